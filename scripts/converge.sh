#!/usr/bin/env bash
# Does accumulation converge to the ground truth? Renders `exact` once and each method accumulated
# over each frame count (`--denoise temporal --frames F` on the static camera, the firefly clamp at
# its default), all over the same BRSM VPLs, and prints per image: relative RMSE, mean over
# exact's, the KxK-block error and the brightest pixel over exact's (scripts/pfm_error.py).
# An unbiased method's block error falls like 1/sqrt(F) (halves from 64 to 256 frames) and its
# mean tends to 1; a bias shows as a floor.
#   scripts/converge.sh [OUT] [FRAMES...]
# Environment: VPLKIT (binary; default build/release/samples/vplkit), SCENE (sponza-lite-sun),
# SIZE (96x54), SPP (8), VPLS (4096), BLOCK (6), METHODS ("rtslc hybrid hybrid-lightcuts"),
# EXTRA (more render options for every method, e.g. "--firefly-sigma 0"), COMMON (options for
# every render, exact included, e.g. "--brdf lambert").
# The flagship-image measurement's set-up: scripts/converge.sh out/converge 64 256
set -euo pipefail
out=${1:-out/converge}
shift $(( $# < 1 ? $# : 1 ))
frames=("$@")
[ ${#frames[@]} -gt 0 ] || frames=(64 256)
vplkit=${VPLKIT:-build/release/samples/vplkit}
scene=${SCENE:-sponza-lite-sun}
size=${SIZE:-96x54}
methods=${METHODS:-rtslc hybrid hybrid-lightcuts}
read -r -a extra <<< "${EXTRA:-}"
common=(--scene "$scene" --width "${size%x*}" --height "${size#*x}" --vpl-source brsm --vpls "${VPLS:-4096}")
read -r -a more_common <<< "${COMMON:-}"
common+=("${more_common[@]}")
mkdir -p "$out"
here=$(cd "$(dirname "$0")" && pwd)
if [ ! -f "$out/exact.pfm" ]; then
  echo "== exact" >&2
  "$vplkit" render "${common[@]}" --method exact --out "$out/exact.png" --out-indirect "$out/exact.pfm" \
    > "$out/exact.log" 2>&1
fi
images=()
for method in $methods; do
  case $method in
    hybrid-lightcuts) options=(--method hybrid --traversal lightcuts) ;;
    *) options=(--method "$method") ;;
  esac
  for f in "${frames[@]}"; do
    name="$method-$f"
    echo "== $name" >&2
    # --no-antialias: every frame at the pixel centres, as exact's one frame (with the sub-pixel
    # offsets the mean is the pixel's area average, which is not what exact computes).
    "$vplkit" render "${common[@]}" "${options[@]}" --spp "${SPP:-8}" --denoise temporal --frames "$f" --no-antialias \
      "${extra[@]}" --out "$out/$name.png" --out-indirect "$out/$name.pfm" > "$out/$name.log" 2> "$out/$name.err"
    grep -h "firefly clamp" "$out/$name.log" >&2 || true
    images+=("$out/$name.pfm")
  done
done
python3 "$here/pfm_error.py" --block "${BLOCK:-6}" "$out/exact.pfm" "${images[@]}"
