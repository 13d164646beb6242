#!/usr/bin/env bash
# Quick start (a): install what is missing, build, run the main job: render the default in-repo
# scene, write out/vplkit.png, print the device used and the GPU time of every stage.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j2
mkdir -p out
./build/release/samples/vplkit render --out out/vplkit.png "$@"
