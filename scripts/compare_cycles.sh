#!/usr/bin/env bash
# The exact one-bounce gather against an independent path tracer: vplkit's per-pixel
# indirect / direct ratio on ../shared/reference/Sponza-sun (Blender Cycles, one diffuse bounce,
# 160x90; see its README) against Cycles' own, printed by scripts/cycles_ratio.py.
#   scripts/compare_cycles.sh [PATHS] [OUT] [extra render options...]
# PATHS: instant-radiosity light paths per render (default 65536: about 37,000 VPLs on
# Sponza-sun, the rest leave the scene); the gather is every VPL at every pixel (~15 minutes per
# render on lavapipe). Environment:
#   SEEDS="0 1 2"  one render per seed, averaged pixel by pixel before the ratios (default "0");
#                  the median ratio is biased low by VPL noise (see cycles_ratio.py) and falls
#                  towards the truth only with more VPLs.
#   MIPMAPS=1      render the file as it is (mipmapped textures) instead of as Cycles samples it.
#   CLAMP_SCALE=K  (K >= 1) renders the scene moved along +x so that its scale, the largest
#                  coordinate magnitude of its box, and with it the 1/d^2 clamp's d_min, is K
#                  times the file's: with the same seed (the same light paths), the ratio's
#                  change from K = 1 to 2 measures what the clamp removes (see below).
#   VPLKIT=PATH    the vplkit binary (default build/release/samples/vplkit; a copy lets the tree
#                  rebuild meanwhile).
# Set as Cycles rendered it: `--brdf lambert` (every material a Lambertian of its base colour),
# and, unless MIPMAPS=1, every texture read from its full-resolution level (a copy of the glTF
# whose one sampler has a non-mipmapped minification filter). Cycles reads textures without
# mipmaps at the pixel centre; at 160x90 the kit's mip chain averages the normal maps flat,
# which lights the receivers' direct more than Cycles' bumpy normals and moved vplkit's ratio on
# Cycles' direct by 6 points (-10.4% mipmapped, -3.9% full resolution, 16384 paths, seed 0).
# The 1/d^2 clamp (vpl_eval.glsl: d >= 1% of the scene scale, 0.27 m on Sponza) is the kit's
# design and stays on: every method loses the same light, so `exact` stays their fair reference,
# but against Cycles it is a bias, concentrated on the sunlit pixels whose neighbouring surfaces
# are sunlit too (the pixels the median is taken over). The kit has no switch for it; it is
# measured by moving the scene (CLAMP_SCALE). Translation changes nothing else but the rays'
# origin offsets, which also scale with the scene scale.
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
clamp_scale=${CLAMP_SCALE:-1}
if [[ ${MIPMAPS:-0} != 1 || $clamp_scale != 1 ]]; then
  # The copy's buffer and image URIs point back at the file's own, wherever $out is.
  python3 - "$scene" "$out/Sponza-sun-copy.gltf" "${MIPMAPS:-0}" "$clamp_scale" <<'EOF'
import json, os, sys
source, copy, mipmaps, clamp_scale = sys.argv[1], sys.argv[2], sys.argv[3] == "1", float(sys.argv[4])
gltf = json.load(open(source))
base = os.path.relpath(os.path.dirname(os.path.abspath(source)), os.path.dirname(os.path.abspath(copy)))
for item in gltf.get("buffers", []) + gltf.get("images", []):
    if "uri" in item and not item["uri"].startswith("data:"):
        item["uri"] = os.path.join(base, item["uri"])
if not mipmaps:
    if any("sampler" in t for t in gltf.get("textures", [])):
        raise SystemExit("compare_cycles: the file has its own samplers; set MIPMAPS=1 or extend this copy")
    gltf["samplers"] = [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}]  # LINEAR, REPEAT
    for texture in gltf.get("textures", []):
        texture["sampler"] = 0
if clamp_scale != 1:
    if clamp_scale < 1:
        raise SystemExit("compare_cycles: CLAMP_SCALE below 1 cannot be made by moving the scene")
    # The box around the mesh nodes' accessor boxes, each rotated and translated (Sponza-sun's
    # nodes are roots without scale or matrix: checked; a slightly loose box only moves d_min by
    # as much), then a parent node that moves everything, camera and sun too.
    def rotate(q, v):  # unit quaternion (x, y, z, w) applied to v
        x, y, z, w = q
        t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])]
        return [v[0] + w * t[0] + y * t[2] - z * t[1], v[1] + w * t[1] + z * t[0] - x * t[2],
                v[2] + w * t[2] + x * t[1] - y * t[0]]
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for node in gltf["nodes"]:
        if "children" in node or "matrix" in node or "scale" in node:
            raise SystemExit("compare_cycles: CLAMP_SCALE handles root nodes with translation and rotation only")
        if "mesh" not in node:
            continue
        t = node.get("translation", [0, 0, 0])
        q = node.get("rotation", [0, 0, 0, 1])
        for primitive in gltf["meshes"][node["mesh"]]["primitives"]:
            accessor = gltf["accessors"][primitive["attributes"]["POSITION"]]
            a, b = accessor["min"], accessor["max"]
            for corner in ([x, y, z] for x in (a[0], b[0]) for y in (a[1], b[1]) for z in (a[2], b[2])):
                p = rotate(q, corner)
                for k in range(3):
                    lo[k] = min(lo[k], p[k] + t[k])
                    hi[k] = max(hi[k], p[k] + t[k])
    scale = max(max(abs(v) for v in lo), max(abs(v) for v in hi))
    shift = [clamp_scale * scale - hi[0], 0.0, 0.0]  # the box's +x side then at clamp_scale x scale
    gltf["nodes"].append({"name": "compare_cycles shift", "translation": shift, "children": gltf["scenes"][0]["nodes"]})
    gltf["scenes"][0]["nodes"] = [len(gltf["nodes"]) - 1]
    print(f"compare_cycles: scene scale {scale:.3f} -> {clamp_scale * scale:.3f}, d_min {0.01 * clamp_scale * scale:.3f}")
json.dump(gltf, open(copy, "w"))
EOF
  scene="$out/Sponza-sun-copy.gltf"
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
