#!/usr/bin/env bash
# The integration check: install the kit from this build tree into a fresh prefix,
# build samples/dropin as a separate project against that prefix (find_package(vplkit)), and run
# it. Usage: dropin_from_install.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build_dir=$1 source_dir=$2 work_dir=$3
rm -rf "$work_dir"
mkdir -p "$work_dir"
cmake --install "$build_dir" --prefix "$work_dir/prefix" >/dev/null
# The sample links vplkit::stages only: its package must configure without the runtime's
# dependencies (TinyGLTF, Threads), as in a renderer that never installed them.
cmake -S "$source_dir/samples/dropin" -B "$work_dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work_dir/prefix" -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_Threads=ON >/dev/null
# A plain find_package(vplkit) where TinyGLTF is installed still loads vplkit::runtime.
mkdir -p "$work_dir/runtime_consumer"
cat >"$work_dir/runtime_consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(runtime_consumer LANGUAGES CXX)
find_package(vplkit CONFIG REQUIRED)
if(NOT TARGET vplkit::runtime OR NOT TARGET vplkit::stages)
  message(FATAL_ERROR "runtime consumer: vplkit::runtime not loaded")
endif()
CMAKE
cmake -S "$work_dir/runtime_consumer" -B "$work_dir/runtime_consumer/build" \
  -DCMAKE_PREFIX_PATH="$work_dir/prefix" >/dev/null
# A renderer with its own glm (a glm::glm target of its own, find_package(glm) made to fail)
# links vplkit::stages alone, without TinyGLTF or Threads, and builds against the kit's headers.
mkdir -p "$work_dir/stages_consumer/own_glm"
cp -r "$(dirname "$(find /usr/include /usr/local/include -maxdepth 2 -name glm.hpp -path '*glm/glm.hpp' | head -1)")" \
  "$work_dir/stages_consumer/own_glm/"
cat >"$work_dir/stages_consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(stages_consumer LANGUAGES CXX)
add_library(glm::glm INTERFACE IMPORTED)
target_include_directories(glm::glm INTERFACE "${CMAKE_CURRENT_SOURCE_DIR}/own_glm")
find_package(vplkit CONFIG REQUIRED COMPONENTS stages)
if(TARGET vplkit::runtime)
  message(FATAL_ERROR "stages consumer: vplkit::runtime loaded though only stages was asked for")
endif()
add_executable(stages_consumer main.cpp)
target_link_libraries(stages_consumer PRIVATE vplkit::stages)
target_compile_features(stages_consumer PRIVATE cxx_std_20)
CMAKE
cat >"$work_dir/stages_consumer/main.cpp" <<'CPP'
#include "vplkit/stages/device_requirements.hpp"
#include "vplkit/stages/gi_chain.hpp"
#include "vplkit/stages/renderer_scene.hpp"
#include <cstdio>
int main() {
    const glm::vec3 triangle[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const auto scene = vplkit::stages::renderer_scene({}, {}, {triangle, {}, glm::vec3(0.5f)});
    std::printf("stages consumer: %zu extensions, scene block %llu bytes\n",
                vplkit::stages::required_device_features().extensions.size(), (unsigned long long)scene.bytes());
}
CPP
cmake -S "$work_dir/stages_consumer" -B "$work_dir/stages_consumer/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work_dir/prefix" -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_Threads=ON -DCMAKE_DISABLE_FIND_PACKAGE_glm=ON >/dev/null
cmake --build "$work_dir/stages_consumer/build" >/dev/null
"$work_dir/stages_consumer/build/stages_consumer"
cmake --build "$work_dir/build" >/dev/null
cd "$work_dir"
"$work_dir/build/vplkit_dropin"
