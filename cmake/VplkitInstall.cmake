# cmake --install: the libraries, their headers (runtime, stages and the generated shader headers),
# the GLSL sources and lib/cmake/vplkit/vplkitConfig.cmake, so that a project can
#   find_package(vplkit CONFIG REQUIRED)                     # or COMPONENTS stages: no TinyGLTF needed
#   target_link_libraries(app PRIVATE vplkit::runtime)   # or vplkit::stages, vplkit::shaders
# The same vplkit:: names are aliases in the build tree (add_subdirectory, FetchContent).
include(CMakePackageConfigHelpers)

set(VPLKIT_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/vplkit")
set(VPLKIT_INSTALL_SHADERDIR "${CMAKE_INSTALL_DATADIR}/vplkit/shaders")

# Embedded with add_subdirectory/FetchContent: the GLSL is used in place (the installed config
# sets the same variable to its copy).
if(NOT vplkit_IS_TOP_LEVEL)
  set(vplkit_SHADER_DIR "${PROJECT_SOURCE_DIR}/shaders" PARENT_SCOPE)
endif()

# Two export sets, so that a caller of the stages alone needs neither TinyGLTF nor Threads (the
# runtime's own dependencies): vplkitConfig.cmake loads the runtime's only when asked or found.
install(TARGETS vplkit_shaders vplkit_stages EXPORT vplkitStagesTargets)
install(TARGETS vplkit_runtime EXPORT vplkitRuntimeTargets)
# Not part of the package's targets; installed for users who generate headers for their own shaders.
install(TARGETS vplkit-codegen)

# Whole directories, not file lists: stage headers are moving between stages/ and runtime/, and
# both trees contribute to include/vplkit/stages/.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/stages/include/" "${PROJECT_SOURCE_DIR}/runtime/include/"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" FILES_MATCHING PATTERN "*.hpp")
# The generated shader headers (vplkit/shaders/*.hpp): where vplkit_add_shader_library() writes them.
install(DIRECTORY "${CMAKE_BINARY_DIR}/generated/vplkit_shaders/"
        DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" FILES_MATCHING PATTERN "*.hpp")
# GLSL sources and their includes (include/vplkit/*.glsl), for users who compile them into their
# own pipelines: the folder structure is kept, so the shaders' #include paths still resolve.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/shaders/" DESTINATION "${VPLKIT_INSTALL_SHADERDIR}"
        FILES_MATCHING PATTERN "*.comp" PATTERN "*.vert" PATTERN "*.frag" PATTERN "*.glsl")

install(EXPORT vplkitStagesTargets NAMESPACE vplkit:: DESTINATION "${VPLKIT_INSTALL_CMAKEDIR}")
install(EXPORT vplkitRuntimeTargets NAMESPACE vplkit:: DESTINATION "${VPLKIT_INSTALL_CMAKEDIR}")
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/vplkitConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/vplkitConfig.cmake"
  INSTALL_DESTINATION "${VPLKIT_INSTALL_CMAKEDIR}"
  PATH_VARS VPLKIT_INSTALL_SHADERDIR)
# find_package(vplkit X.Y) accepts any installed X.y that is at least X.Y.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/vplkitConfigVersion.cmake"
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/vplkitConfig.cmake" "${PROJECT_BINARY_DIR}/vplkitConfigVersion.cmake"
        DESTINATION "${VPLKIT_INSTALL_CMAKEDIR}")
