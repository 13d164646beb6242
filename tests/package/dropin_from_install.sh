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
cmake --build "$work_dir/build" >/dev/null
cd "$work_dir"
"$work_dir/build/vplkit_dropin"
