#!/usr/bin/env bash
# The exact one-bounce gather against an independent path tracer: vplkit's per-pixel
# indirect / direct ratio on ../shared/reference/Sponza-sun (Blender Cycles, one diffuse bounce,
# 160x90; see its README) against Cycles' own, printed by scripts/cycles_ratio.py.
#   scripts/compare_cycles.sh [PATHS] [OUT] [extra render options...]
# PATHS: instant-radiosity light paths (default 16384; one bounce, so about that many VPLs less
# those that leave the scene); the gather is every VPL at every pixel (minutes on lavapipe).
set -euo pipefail
cd "$(dirname "$0")/.."
paths=${1:-16384}
out=${2:-out/cycles}
shift $(( $# < 2 ? $# : 2 ))
reference=../shared/reference/Sponza-sun
[[ -d $reference ]] || { echo "compare_cycles: $reference not found (../shared beside the repository)" >&2; exit 1; }
mkdir -p "$out"
build/release/samples/vplkit render --scene "$reference/scene/Sponza-sun.gltf" --camera 0 --width 160 --height 90 \
  --method exact --vpl-source ir --bounces 1 --vpls "$paths" "$@" \
  --out "$out/vplkit.png" --out-direct "$out/direct.pfm" --out-indirect "$out/indirect.pfm" > "$out/render.log"
grep -E "^indirect:" "$out/render.log" || true
python3 scripts/cycles_ratio.py "$reference/b1" "$out/direct.pfm" "$out/indirect.pfm"
