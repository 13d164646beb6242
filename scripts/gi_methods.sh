#!/usr/bin/env bash
# The sampling methods against the exact ground truth on one standard set-up, at a few sample
# budgets: RMSE and SSIM of the tonemapped frame (sRGB / 255, as the thesis compares images) and
# the relative RMSE of the linear indirect light (rmse / the reference's mean), GI time (GPU
# timestamps of the sampling passes, with downsampling and upsampling for hybrid-half; the tree
# build separately; medians of frames 2-3) and tree levels per traversal. Writes
# OUT/SCENE-WxH.csv, the frames and their x10 difference pictures.
#   scripts/gi_methods.sh SCENE [OUT] [WIDTHxHEIGHT] [SPP list] [extra render options...]
# e.g. scripts/gi_methods.sh sponza-sun out/gi 320x180 "4 8 16 32" --vpl-source brsm --vpls 4096
# The exact frame is rendered once per scene and size (the slow part) and reused if present.
# VPLKIT=PATH: the vplkit binary (default build/release/samples/vplkit; a copy lets the tree
# rebuild meanwhile).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1
out=${2:-out/gi}
size=${3:-320x180}
spps=${4:-"4 8 16 32"}
shift $(( $# < 4 ? $# : 4 ))
extra=("$@")
width=${size%x*}
height=${size#*x}
vplkit=${VPLKIT:-build/release/samples/vplkit}
mkdir -p "$out"
base="$out/$scene-${width}x$height"
if [[ ! -f "$base-exact.png" ]]; then
  echo "[$scene] exact ground truth (every VPL at every pixel; minutes on lavapipe)" >&2
  # --exposure 1 here and below: every PNG of a scene at one fixed exposure, as the RMSE column
  # compares them (the automatic exposure differs by about 1% between methods' images, and in
  # Sponza it scales the image 3.8x, which doubles every RMSE against the thesis' protocol).
  "$vplkit" render --scene "$scene" --method exact --width "$width" --height "$height" --exposure 1 "${extra[@]}" \
    --out "$base-exact.png" --out-indirect "$base-exact.pfm" > "$base-exact.log"
fi
csv="$out/$scene-${width}x$height.csv"
echo "scene,method,spp,gi_ms,tree_ms,levels_per_traversal,mock_cut_pixels,rmse,ssim,indirect_relative_rmse" > "$csv"
# hybrid-half: the hybrid method at half GI resolution, upsampled. hybrid-lightcuts: hybrid's cuts
# and blending with rtslc's traversal to a leaf (the thesis' sec. 7.1 protocol).
for variant in sst rtslc hybrid hybrid-half hybrid-lightcuts; do
  method=${variant%-half}
  method=${method%-lightcuts}
  resolution=full
  [[ $variant == *-half ]] && resolution=half
  variant_options=()
  [[ $variant == *-lightcuts ]] && variant_options=(--traversal lightcuts)
  for spp in $spps; do
    name="$base-$variant-$spp"
    echo "[$scene] $variant, $spp spp" >&2
    # 3 frames: the times are the medians of frames 2 and 3 (the first compiles the shaders);
    # --no-antialias keeps every frame at the pixel centres with the same samples, so the image is
    # one frame at $spp, as exact's (several frames would be averaged, at sub-pixel offsets).
    "$vplkit" render --scene "$scene" --method "$method" --spp "$spp" --width "$width" --height "$height" \
      --gi-resolution "$resolution" --frames 3 --no-antialias --no-reuse --exposure 1 "${variant_options[@]}" "${extra[@]}" --out "$name.png" --out-indirect "$name.pfm" > "$name.log" 2>/dev/null
    gi_ms=$(awk '/^  (sst gi|rtslc cuts|rtslc gi|hybrid cuts|hybrid gi|gbuffer downsample|upsample)/ { sum += $(NF-1) } END { printf "%.1f", sum }' "$name.log")
    tree_ms=$(awk '/^  (vpl bounds|morton keys|sort|gather leaves|light tree|sst clear|build sst)/ { sum += $(NF-1) } END { printf "%.1f", sum }' "$name.log")
    levels=$(sed -n 's/.* \([0-9.]*\) tree levels per traversal.*/\1/p' "$name.log")
    mock=$(sed -n 's/.* \([0-9]*\) mock-cut pixels.*/\1/p' "$name.log")
    "$vplkit" compare "$name.png" "$base-exact.png" --diff "$name-diff.png" > "$name-compare.txt"
    rmse=$(awk '/^rmse:/ { print $2 }' "$name-compare.txt")
    ssim=$(awk '/^ssim:/ { print $2 }' "$name-compare.txt")
    rel=$("$vplkit" compare "$name.pfm" "$base-exact.pfm" | awk '/^relative rmse:/ { print $3 }')
    echo "$scene,$variant,$spp,$gi_ms,$tree_ms,$levels,${mock:-},$rmse,$ssim,$rel" >> "$csv"
  done
done
column -s, -t "$csv"
