#!/usr/bin/env bash
# Quick start (a): install what is missing, build, run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j2
./build/release/samples/vplkit info
