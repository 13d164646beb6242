#!/usr/bin/env bash
# The exact one-bounce gather against an independent path tracer: vplkit's per-pixel
# indirect / direct ratio on ../shared/reference/Sponza-sun (Blender Cycles, one diffuse bounce,
# 160x90; see its README) against Cycles' own, printed by scripts/cycles_ratio.py.
#   scripts/compare_cycles.sh [PATHS] [OUT] [extra render options...]
# PATHS: instant-radiosity light paths per render (default 65536: 36,988 VPLs on Sponza-sun, the
# rest leave the scene); the gather is every VPL at every pixel (about 150 s per render on a
# shared 2-core lavapipe). Environment:
#   SEEDS="0 1 2"  one render per seed, averaged pixel by pixel before the ratios (default "0");
#                  the median ratio is biased low by VPL noise (see cycles_ratio.py) and rises
#                  towards the truth only with more VPLs.
#   MIPMAPS=1      render the file as it is (mipmapped textures) instead of as Cycles samples it.
#   VPLKIT=PATH    the vplkit binary (default build/release/samples/vplkit; a copy lets the tree
#                  rebuild meanwhile).
# Set as Cycles rendered it: `--brdf lambert` (every material a Lambertian of its base colour),
# and, unless MIPMAPS=1, every texture read from its full-resolution level (a copy of the glTF
# whose one sampler has a non-mipmapped minification filter). Cycles reads textures without
# mipmaps at the pixel centre; at 160x90 the kit's mip chain averages the normal maps flat,
# which lights the receivers' direct more than Cycles' bumpy normals: vplkit's ratio on Cycles'
# direct went from -10.4% (mipmapped) to -3.9% (full resolution) at 16384 paths, seed 0.
# The 1/d^2 clamp (vpl_eval.glsl: d >= 1% of the scene scale, 0.27 m on Sponza) is the kit's
# design: every method loses the same light, so `exact` stays their fair reference, but against
# Cycles it is a bias, largest on the sunlit pixels beside other sunlit surfaces (those the
# median is taken over). Pass `--exact-clamp 0` to sum every VPL unclamped, as Cycles does:
#   scripts/compare_cycles.sh 65536 out/cycles-unclamped --exact-clamp 0
set -euo pipefail
cd "$(dirname "$0")/.."
paths=${1:-65536}
out=${2:-out/cycles}
shift $(( $# < 2 ? $# : 2 ))
vplkit=${VPLKIT:-build/release/samples/vplkit}
reference=../shared/reference/Sponza-sun
[[ -d $reference ]] || { echo "compare_cycles: $reference not found (../shared beside the repository)" >&2; exit 1; }
mkdir -p "$out"
scene="$reference/scene/Sponza-sun.gltf"
if [[ ${MIPMAPS:-0} != 1 ]]; then
  # The copy's buffer and image URIs point back at the file's own, wherever $out is.
  python3 - "$scene" "$out/Sponza-sun-level0.gltf" <<'EOF'
import json, os, sys
source, copy = sys.argv[1:]
gltf = json.load(open(source))
base = os.path.relpath(os.path.dirname(os.path.abspath(source)), os.path.dirname(os.path.abspath(copy)))
for item in gltf.get("buffers", []) + gltf.get("images", []):
    if "uri" in item and not item["uri"].startswith("data:"):
        item["uri"] = os.path.join(base, item["uri"])
if any("sampler" in t for t in gltf.get("textures", [])):
    raise SystemExit("compare_cycles: the file has its own samplers; set MIPMAPS=1 or extend this copy")
gltf["samplers"] = [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}]  # LINEAR, REPEAT
for texture in gltf.get("textures", []):
    texture["sampler"] = 0
json.dump(gltf, open(copy, "w"))
EOF
  scene="$out/Sponza-sun-level0.gltf"
fi
pairs=()
for seed in ${SEEDS:-0}; do
  "$vplkit" render --scene "$scene" --camera 0 --width 160 --height 90 --brdf lambert \
    --method exact --vpl-source ir --bounces 1 --vpls "$paths" --seed "$seed" "$@" \
    --out "$out/vplkit-$seed.png" --out-direct "$out/direct-$seed.pfm" --out-indirect "$out/indirect-$seed.pfm" \
    > "$out/render-$seed.log"
  grep -E "^indirect:" "$out/render-$seed.log" || true
  pairs+=("$out/direct-$seed.pfm" "$out/indirect-$seed.pfm")
done
python3 scripts/cycles_ratio.py "$reference/b1" "${pairs[@]}"
