#!/usr/bin/env bash
# The converged residue of hybrid, hybrid-lightcuts and rtslc against exact over the same VPLs:
# each method's raw frames (new samples per frame, the same VPLs, a static
# camera, no filter) averaged by scripts/pfm_residue.py; block error and the brightest pixel at
# each frame count, then the block error expected after that many
# frames, from all of them (scripts/block_noise.py: disjoint windows and the per-frame variance).
# rtslc is unbiased: its block error is the noise left at that many samples, the yardstick for
# the others.
#
# usage: scripts/hybrid_residue.sh [OUT_DIR]      (default out/hybrid_residue)
# environment: VPLKIT (binary, default build/release/samples/vplkit), SCENE (sponza-lite-sun),
#   SIZE (96x54), SPP (8), VPLS (4096), SOURCE (the --vpl-source, brsm), FRAMES (largest count rendered, 256), COUNTS (64,256),
#   BLOCK (6), METHODS ("hybrid hybrid-lightcuts rtslc"), EXTRA (more render options for the sampled
#   methods, e.g. "--nu-min 2": no substitutes); a folder already holding its frames is not rendered again
#
# Sponza-lite (the issue's set-up):   scripts/hybrid_residue.sh
# The default Cornell box:            SCENE=cornell SIZE=64x64 VPLS=1024 scripts/hybrid_residue.sh out/cornell_residue
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/hybrid_residue}
vplkit=${VPLKIT:-build/release/samples/vplkit}
scene=${SCENE:-sponza-lite-sun}
size=${SIZE:-96x54}
spp=${SPP:-8}
vpls=${VPLS:-4096}
source=${SOURCE:-brsm}
frames=${FRAMES:-256}
counts=${COUNTS:-64,256}
block=${BLOCK:-6}
methods=${METHODS:-hybrid hybrid-lightcuts rtslc}
read -r -a extra <<<"${EXTRA:-}"
common=(--scene "$scene" --width "${size%x*}" --height "${size#*x}" --orbit-degrees 0 --pfm)
indirect=(--vpl-source "$source" --vpls "$vpls" --denoise off)
mkdir -p "$out"
run() {  # name, frames, method options...
    local name=$1 n=$2
    shift 2
    if [ ! -f "$out/$name/frame_$(printf %04d $((n - 1))).pfm" ]; then
        echo "[hybrid_residue] $name: $n frames" >&2
        rm -rf "${out:?}/$name"
        "$vplkit" sequence --out "$out/$name" --frames "$n" "${common[@]}" "$@" >"$out/$name.log"
    fi
}
run direct 1 --method direct
run exact 1 --method exact "${indirect[@]}"
dirs=()
for m in $methods; do
    case $m in
    hybrid-lightcuts) run "$m" "$frames" --method hybrid --traversal lightcuts --spp "$spp" "${indirect[@]}" "${extra[@]}" ;;
    *) run "$m" "$frames" --method "$m" --spp "$spp" "${indirect[@]}" "${extra[@]}" ;;
    esac
    dirs+=("$m=$out/$m")
done
python3 scripts/pfm_residue.py --direct "$out/direct/frame_0000.pfm" --exact "$out/exact/frame_0000.pfm" \
    --block "$block" --frames "$counts" "${dirs[@]}" | tee "$out/residue.txt"
# One draw of N frames is a poor yardstick under heavy tails: the expectation from all frames.
python3 scripts/block_noise.py --direct "$out/direct/frame_0000.pfm" --exact "$out/exact/frame_0000.pfm" \
    --block "$block" --frames "$counts" "${dirs[@]}" | tee -a "$out/residue.txt"
