# Finds every dependency vplkit builds with: Debian 12 packages, none vendored.
# A missing one stops configuration here, naming the package that provides it,
# rather than failing halfway through the build.

set(_vplkit_install_hint "run scripts/install-deps.sh (Debian 12) to install it")

macro(vplkit_require_package name debian_package)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR "vplkit: ${name} not found (Debian package '${debian_package}'); ${_vplkit_install_hint}")
  endif()
endmacro()

find_program(GLSLANG_VALIDATOR glslangValidator)
if(NOT GLSLANG_VALIDATOR)
  message(FATAL_ERROR "vplkit: glslangValidator not found (Debian package 'glslang-tools'); ${_vplkit_install_hint}")
endif()

find_package(Vulkan QUIET)
vplkit_require_package(Vulkan libvulkan-dev)

find_package(Threads REQUIRED)
find_package(glslang CONFIG QUIET)
vplkit_require_package(glslang glslang-dev)

# SPIRV-Cross: the core component must be found before the others.
find_package(spirv_cross_core CONFIG QUIET)
vplkit_require_package(spirv_cross_core libspirv-cross-c-shared-dev)

find_package(glm CONFIG QUIET)
vplkit_require_package(glm libglm-dev)

find_package(TinyGLTF CONFIG QUIET)
vplkit_require_package(TinyGLTF libtinygltf-dev)

find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
if(NOT STB_INCLUDE_DIR)
  message(FATAL_ERROR "vplkit: stb_image_write.h not found (Debian package 'libstb-dev'); ${_vplkit_install_hint}")
endif()

if(VPLKIT_BUILD_TESTS)
  find_package(doctest CONFIG QUIET)
  vplkit_require_package(doctest doctest-dev)
  # Tests run on lavapipe with the validation layer: check the runtime pieces exist too.
  find_file(VPLKIT_LAVAPIPE_ICD lvp_icd.x86_64.json lvp_icd.aarch64.json PATHS /usr/share/vulkan/icd.d NO_DEFAULT_PATH)
  if(NOT VPLKIT_LAVAPIPE_ICD)
    message(WARNING "vplkit: lavapipe ICD not found (Debian package 'mesa-vulkan-drivers'); tests need a Vulkan device")
  endif()
  find_file(VPLKIT_VALIDATION_LAYER VkLayer_khronos_validation.json PATHS /usr/share/vulkan/explicit_layer.d NO_DEFAULT_PATH)
  if(NOT VPLKIT_VALIDATION_LAYER)
    message(FATAL_ERROR "vplkit: Vulkan validation layer not found (Debian package 'vulkan-validationlayers'); ${_vplkit_install_hint}")
  endif()
endif()
