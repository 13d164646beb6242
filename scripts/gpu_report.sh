#!/usr/bin/env bash
# The standard measurements on a GPU, in one command that ends in under 8 minutes there, into one
# Markdown report (out/gpu-report/report.md, with the bench's plots beside it):
#   1. vplkit info: the device and why it was chosen;
#   2. bench tree: keys + sort + leaves + light tree + SST for 4k..1M random VPLs;
#   3. bench bvh: the host's SAH BVH against the GPU LBVH (build, refit, rays per second) on random
#      soups of 50k..4M triangles and on Sponza-lite;
#   4. bench gi on sponza-lite-sun at 1280x720, reduced sweep (samples per pixel for every method,
#      half resolution), 4096 BRSM VPLs;
#   5. the flagship frame (scripts/run.sh's options) on the default scene: per-stage GPU times,
#      median of frames 2..5.
# Needs build/release (a build carried from a Debian 12 machine runs there) and SponzaLite: in
# ../shared/scenes beside the repository, or copied into .scenes/SponzaLite (ignored by git),
# which this script links where the set-ups look for it.
#   scripts/gpu_report.sh [--quick]     (--quick: tiny sizes, to check the script on lavapipe)
# On the device machine of this workplace (see /work/.library/device/README.md): carry .gl,
# build/release and .scenes, unpack the Vulkan loader first, and VK_DRIVER_FILES at the NVIDIA ICD.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[[ ${1:-} == --quick ]] && quick=1
vplkit=build/release/samples/vplkit
out=out/gpu-report
[[ -x $vplkit ]] || { echo "gpu_report: $vplkit not found: build first (cmake --preset release; cmake --build --preset release)" >&2; exit 1; }
if [[ ! -d ../shared/scenes/SponzaLite ]]; then
  [[ -d .scenes/SponzaLite ]] || { echo "gpu_report: SponzaLite not found in ../shared/scenes or .scenes" >&2; exit 1; }
  mkdir -p ../shared/scenes
  ln -s "$PWD/.scenes/SponzaLite" ../shared/scenes/SponzaLite
fi
rm -rf "$out"
mkdir -p "$out"
report=$out/report.md
step() { echo "[gpu_report] $*" >&2; }

if (( quick )); then
  counts=4096,65536; bvh_counts=20000; size=(--width 96 --height 54); spps=(--quick); flagship_size=(--width 64 --height 64)
else
  counts=4096,65536,262144,1048576; bvh_counts=50000,200000,1000000,4000000; size=(--width 1280 --height 720); spps=(); flagship_size=()
fi

step "1/5 device"
"$vplkit" info > "$out/info.txt"

step "2/5 bench tree ($counts VPLs)"
"$vplkit" bench tree --counts "$counts" --runs 3 --csv "$out/tree.csv" > "$out/tree.txt"

step "3/5 bench bvh ($bvh_counts triangles, and sponza-lite-sun)"
# A count past the device's buffer range is refused by name: the report keeps the message.
"$vplkit" bench bvh --counts "$bvh_counts" --runs 3 --csv "$out/bvh.csv" > "$out/bvh.txt" 2> "$out/bvh.err" ||
  step "bench bvh failed: see $out/bvh.err"
"$vplkit" bench bvh --scene sponza-lite-sun --runs 3 --csv "$out/bvh-sponza.csv" > "$out/bvh-sponza.txt" 2> "$out/bvh-sponza.err" ||
  step "bench bvh --scene failed: see $out/bvh-sponza.err"

step "4/5 bench gi on sponza-lite-sun (${size[*]}, spp and resolution sweeps)"
"$vplkit" bench gi --scene sponza-lite-sun "${size[@]}" "${spps[@]}" --sweeps spp,resolution \
  --out "$out/bench-gi" --cache out/bench-cache > "$out/bench-gi.txt"

step "5/5 the flagship frame (BRSM + hybrid, 32 spp, half-resolution GI)"
"$vplkit" render --method hybrid --vpl-source brsm --spp 32 --gi-resolution half --frames 5 "${flagship_size[@]}" \
  --out "$out/flagship.png" > "$out/flagship.txt"

{
  echo "# vplkit on a GPU"
  echo
  echo "Written by \`scripts/gpu_report.sh$( (( quick )) && echo ' --quick')\` on $(date -u +%Y-%m-%d), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)."
  echo
  echo "## Device"
  echo; echo '```'; cat "$out/info.txt"; echo '```'; echo
  echo "## Tree build (\`vplkit bench tree --counts $counts --runs 3\`)"
  echo; echo '```'; cat "$out/tree.txt"; echo '```'; echo
  echo "## BVH build, refit and rays (\`vplkit bench bvh --counts $bvh_counts --runs 3\`, and \`--scene sponza-lite-sun\`)"
  echo; echo '```'; cat "$out/bvh.txt" "$out/bvh-sponza.txt"; echo '```'; echo
  echo "## Accuracy vs time, sponza-lite-sun (\`vplkit bench gi --sweeps spp,resolution\`)"
  echo; echo '```'; cat "$out/bench-gi.txt"; echo '```'; echo
  echo "Full report with plots and images: [bench-gi/report.md](bench-gi/report.md)."
  echo
  echo "![RMSE vs frame time](bench-gi/rmse_vs_time.png)"
  echo
  echo "## The flagship frame (\`vplkit render --method hybrid --vpl-source brsm --spp 32 --gi-resolution half --frames 5\`)"
  echo; echo '```'; cat "$out/flagship.txt"; echo '```'; echo
  echo "![flagship](flagship.png)"
} > "$report"
step "wrote $report"
