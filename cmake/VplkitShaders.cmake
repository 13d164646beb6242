# vplkit_add_shader_library(<target>
#     NAMESPACE <c++ namespace>      e.g. vplkit::shaders
#     HEADER_DIR <relative dir>      e.g. vplkit/shaders  (headers land in <build>/generated/<target>/<dir>)
#     SOURCES <glsl files...>        .comp / .vert / .frag, one entry point each
#     [INCLUDE_DIRS <dirs...>])      searched by #include (GL_GOOGLE_include_directive)
#
# Compiles every source with glslangValidator (GLSL 460, Vulkan 1.2 target) with a depfile, so
# editing an included header recompiles exactly the shaders that include it. The SPIR-V keeps its
# OpName debug names (no optimizing pass): codegen reflects struct and member names from it, and
# the same words are embedded (drivers optimize at pipeline creation anyway).
# Then one vplkit-codegen run over all modules writes <dir>/types.hpp and <dir>/<name>.hpp.
# The result is an INTERFACE target to link against.

function(vplkit_add_shader_library target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "NAMESPACE;HEADER_DIR" "SOURCES;INCLUDE_DIRS")
  if(NOT arg_NAMESPACE OR NOT arg_HEADER_DIR OR NOT arg_SOURCES)
    message(FATAL_ERROR "vplkit_add_shader_library(${target}): NAMESPACE, HEADER_DIR and SOURCES are required")
  endif()

  set(spv_dir "${CMAKE_CURRENT_BINARY_DIR}/${target}_spv")
  set(gen_root "${CMAKE_BINARY_DIR}/generated/${target}")
  set(include_flags "")
  foreach(dir IN LISTS arg_INCLUDE_DIRS)
    get_filename_component(dir "${dir}" ABSOLUTE)
    list(APPEND include_flags "-I${dir}")
  endforeach()

  set(spv_files "")
  set(codegen_args "")
  set(headers "${gen_root}/${arg_HEADER_DIR}/types.hpp")
  set(seen_names "")
  foreach(src IN LISTS arg_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME_WLE)
    get_filename_component(ext "${src}" LAST_EXT)
    if(NOT ext MATCHES "^\\.(comp|vert|frag)$")
      message(FATAL_ERROR "vplkit_add_shader_library(${target}): ${src}: expected .comp, .vert or .frag")
    endif()
    if(name IN_LIST seen_names)
      message(FATAL_ERROR "vplkit_add_shader_library(${target}): two shaders are named '${name}'; generated headers are named after the file, so names must be unique")
    endif()
    list(APPEND seen_names "${name}")

    set(spv "${spv_dir}/${name}.spv")
    file(RELATIVE_PATH rel_src "${CMAKE_SOURCE_DIR}" "${src}")
    add_custom_command(
      OUTPUT "${spv}"
      COMMAND "${CMAKE_COMMAND}" -E make_directory "${spv_dir}"
      COMMAND "${GLSLANG_VALIDATOR}" -V --quiet --target-env vulkan1.2 ${include_flags}
              --depfile "${spv}.d" -o "${spv}" "${src}"
      MAIN_DEPENDENCY "${src}"
      DEPFILE "${spv}.d"
      COMMENT "glslang ${rel_src}"
      VERBATIM)
    list(APPEND spv_files "${spv}")
    list(APPEND codegen_args --shader "${name}" "${spv}")
    list(APPEND headers "${gen_root}/${arg_HEADER_DIR}/${name}.hpp")
  endforeach()

  # Headers are byproducts of a stamp: codegen rewrites a header only when its text changes,
  # so a shader edit that leaves a layout unchanged does not rebuild the C++ that includes it.
  set(stamp "${CMAKE_CURRENT_BINARY_DIR}/${target}.codegen.stamp")
  add_custom_command(
    OUTPUT "${stamp}"
    BYPRODUCTS ${headers}
    COMMAND vplkit-codegen --namespace "${arg_NAMESPACE}" --header-dir "${arg_HEADER_DIR}"
            --out "${gen_root}" ${codegen_args}
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS ${spv_files} vplkit-codegen
    COMMENT "vplkit-codegen ${target}"
    VERBATIM)
  add_custom_target(${target}_codegen DEPENDS "${stamp}")

  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_codegen)
  target_include_directories(${target} INTERFACE
    "$<BUILD_INTERFACE:${gen_root}>" "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  target_link_libraries(${target} INTERFACE Vulkan::Headers)
  set_property(TARGET ${target} PROPERTY VPLKIT_SPIRV_FILES "${spv_files}")
endfunction()
