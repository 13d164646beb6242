# vplkit_add_test_suite(<name>
#     SOURCES <test .cpp files...>
#     [LIBS <libraries...>]           e.g. a shader library, a reference implementation
#     [INCLUDE_DIRS <dirs...>])
#
# Builds the test program <name>_tests from SOURCES (no main: vplkit_test_support provides it)
# linked with vplkit_test_support and vplkit_runtime, and registers each doctest case as its own
# ctest test named "<name>/<case>" (so `ctest -R '^<name>/'` runs one suite), labeled <name>.
# Every case runs in its own process on the validated test context; a validation message fails
# the case. Avoid '*', '?' and ',' in case names: ctest passes the name to --test-case=,
# which treats them as wildcards and separators.

include(doctest)

function(vplkit_add_test_suite name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;LIBS;INCLUDE_DIRS")
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "vplkit_add_test_suite(${name}): SOURCES is required")
  endif()
  set(target ${name}_tests)
  add_executable(${target} ${arg_SOURCES})
  target_link_libraries(${target} PRIVATE vplkit_test_support vplkit_runtime ${arg_LIBS})
  target_include_directories(${target} PRIVATE ${arg_INCLUDE_DIRS})
  # `VkXxx info{VK_STRUCTURE_TYPE_XXX};` (the rest zero) is the idiom, not a mistake.
  target_compile_options(${target} PRIVATE -Wno-missing-field-initializers)
  doctest_discover_tests(${target}
    TEST_PREFIX "${name}/"
    # A case name with ',' '*' or '?' becomes a filter that selects no case, and doctest exits 0
    # when it ran nothing: make that a failure, not a silent pass.
    PROPERTIES LABELS ${name} TIMEOUT 300 FAIL_REGULAR_EXPRESSION "test cases: *0 [|]")
endfunction()
