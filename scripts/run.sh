#!/usr/bin/env bash
# Quick start (a): install what is missing, build, run the main job: render the default in-repo
# scene with the flagship pipeline (BRSM VPLs, hybrid sampling at 32 samples per pixel on a
# half-resolution G-buffer, upsampled: cleaner than 8 at full resolution for less time; 4 frames
# accumulated on the static camera and filtered: --denoise svgf), write
# out/vplkit.png, print the device used and the GPU time of every stage. Arguments replace the
# flagship options and go to `vplkit render` as they are (e.g. scripts/run.sh --scene sponza-sun
# --method rtslc).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j2
mkdir -p out
if [[ $# -eq 0 ]]; then
  set -- --method hybrid --vpl-source brsm --spp 32 --gi-resolution half --denoise svgf --frames 4
fi
# out/vplkit.png unless the arguments name their own --out.
out=(--out out/vplkit.png)
for arg in "$@"; do
  [[ $arg == --out || $arg == --out=* ]] && out=()
done
./build/release/samples/vplkit render "${out[@]}" "$@"
