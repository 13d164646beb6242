#!/usr/bin/env bash
# format/cpp: every C++ source of the kit follows .clang-format (clang-format prints each
# difference; fix with `clang-format -i FILE`). Usage: check_format.sh CLANG_FORMAT SOURCE_DIR
set -euo pipefail
clang_format=$1 source_dir=$2
cd "$source_dir"
mapfile -t files < <(find codegen runtime stages samples tests -name '*.cpp' -o -name '*.hpp' | sort)
"$clang_format" --dry-run --Werror "${files[@]}"
echo "format: ${#files[@]} files follow .clang-format"
