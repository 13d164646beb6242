# Runs vplkit-codegen on shaders it must refuse (see CMakeLists.txt) and prints
# "REJECTED: <its message>" only if it
#   - exits non-zero,
#   - writes exactly one line to stderr and nothing to stdout,
#   - leaves the output tree as it found it: a header already there (from an earlier good
#     run) keeps its content, and no other file appears.
# Otherwise it prints what went wrong and fails, so PASS_REGULAR_EXPRESSION cannot match.
#
#   cmake -DCODEGEN=<exe> -DOUT=<dir> -DSHADER_ARGS=<--shader|name|file|...> -P expect_codegen_failure.cmake

string(REPLACE "|" ";" shader_args "${SHADER_ARGS}")
set(header_dir "${OUT}/h")
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${header_dir}")
set(stale_text "// stale header from an earlier run\n")
file(WRITE "${header_dir}/types.hpp" "${stale_text}")

execute_process(
  COMMAND "${CODEGEN}" --namespace expect::failure --header-dir h --out "${OUT}" ${shader_args}
  RESULT_VARIABLE rc
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)

set(problems "")
if(rc EQUAL 0)
  string(APPEND problems "codegen exited with 0; ")
endif()
if(NOT out STREQUAL "")
  string(APPEND problems "codegen wrote to stdout: ${out}; ")
endif()
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines newline_count)
if(NOT newline_count EQUAL 1 OR NOT err MATCHES "\n$")
  string(APPEND problems "expected exactly one line on stderr, got: ${err}; ")
endif()
file(GLOB_RECURSE files RELATIVE "${OUT}" "${OUT}/*")
if(NOT files STREQUAL "h/types.hpp")
  string(APPEND problems "output tree changed, now holds: ${files}; ")
endif()
file(READ "${header_dir}/types.hpp" types_text)
if(NOT types_text STREQUAL stale_text)
  string(APPEND problems "types.hpp was rewritten; ")
endif()

if(problems)
  message(FATAL_ERROR "codegen did not fail cleanly: ${problems}")
endif()
string(STRIP "${err}" err)
message("REJECTED: ${err}")
