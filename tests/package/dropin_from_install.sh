#!/usr/bin/env bash
# The integration check of issue 18: install the kit from this build tree into a fresh prefix,
# build samples/dropin as a separate project against that prefix (find_package(vplkit)), and run
# it. Usage: dropin_from_install.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build_dir=$1 source_dir=$2 work_dir=$3
rm -rf "$work_dir"
mkdir -p "$work_dir"
cmake --install "$build_dir" --prefix "$work_dir/prefix" >/dev/null
cmake -S "$source_dir/samples/dropin" -B "$work_dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work_dir/prefix" >/dev/null
cmake --build "$work_dir/build" >/dev/null
cd "$work_dir"
"$work_dir/build/vplkit_dropin"
