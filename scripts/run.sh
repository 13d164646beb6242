#!/usr/bin/env bash
# Quick start (a): install what is missing, build, run the main job: render the default in-repo
# scene with the flagship pipeline (BRSM VPLs, hybrid sampling at 32 samples per pixel on a
# half-resolution G-buffer, upsampled: cleaner than 8 at full resolution for less time; 4 frames
# accumulated on the static camera, anti-aliased and filtered: --denoise svgf), write
# out/vplkit.png, print the device used and the GPU time of every stage.
#
# Arguments go to `vplkit render` after the main job's options: they add to them, and an option
# given here replaces the main job's of the same name (e.g. scripts/run.sh --scene sponza-sun
# renders Sponza with the flagship options; --frames 8 accumulates 8 frames). Another --method
# drops the flagship's method options (--vpl-source, --spp, --gi-resolution, --denoise), which
# belong to hybrid: that method's own defaults apply, and anything given here.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j2
mkdir -p out

main_job=(--method hybrid --vpl-source brsm --spp 32 --gi-resolution half --denoise svgf --frames 4 --out out/vplkit.png)
method_options=" --vpl-source --spp --gi-resolution --denoise "
# The options the arguments name (--name VALUE or --name=VALUE).
given=" "
for arg in "$@"; do
  [[ $arg == --* ]] && given+="${arg%%=*} "
done
options=()
for ((i = 0; i < ${#main_job[@]}; i += 2)); do
  name=${main_job[i]}
  [[ $given == *" $name "* ]] && continue
  [[ $given == *" --method "* && $method_options == *" $name "* ]] && continue
  options+=("$name" "${main_job[i + 1]}")
done
./build/release/samples/vplkit render "${options[@]}" "$@"
