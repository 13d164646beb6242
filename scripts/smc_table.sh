#!/usr/bin/env bash
# the SMC paper Table 1 on the kit's scenes: IR, BRSM and SMC VPLs at about equal counts, one gather
# (exact: every VPL with a shadow ray, so the VPLs alone differ), no temporal filtering, a short
# orbit per scene; |E| and |E'| (Reinhard-tonemapped indirect luminance) against the exact gather
# over many IR light paths. IR and BRSM draw new VPLs every frame (--fresh-vpls), as the paper's
# comparison methods do; SMC carries its set over. Writes OUT/<scene>-<source>/ and OUT/table.md.
#   scripts/smc_table.sh [OUT] [WxH] [FRAMES] [extra sequence options...]
set -euo pipefail
out=${1:-out/smc-table}
size=${2:-64x36}
frames=${3:-6}
shift $(( $# < 3 ? $# : 3 ))
vplkit=${VPLKIT:-build/release/samples/vplkit}
width=${size%x*}
height=${size#*x}
common=(--width "$width" --height "$height" --frames "$frames" --orbit-degrees 6 --method exact
        --reference --reference-paths 2048 --cache "$out/cache" "$@")
mkdir -p "$out"
table="$out/table.md"
printf '| scene | source | VPLs | average \\|E\\| | average \\|E'"'"'\\| |\n| --- | --- | --- | --- | --- |\n' > "$table"
for scene in cornell-shared sponza-sun breakfast-sun; do
  for source in ir brsm smc; do
    # Light paths for about 1000 IR VPLs (2 bounces; paths that leave the scene leave none).
    case $scene in
      cornell-shared) paths=820 ;;
      sponza-sun) paths=1760 ;;
      *) paths=1024 ;;
    esac
    case $source in
      ir) opts=(--vpl-source ir --vpls "$paths" --bounces 2 --fresh-vpls) ;;
      brsm) opts=(--vpl-source brsm --vpls 1024 --fresh-vpls) ;;  # one bounce, punctual lights only
      smc) opts=(--vpl-source smc --vpls 1024 --bounces 2 --smc-warmup 30) ;;
    esac
    if [[ $source == brsm && $scene == cornell-shared ]]; then
      printf '| %s | brsm | - | (no punctual light) | |\n' "$scene" >> "$table"
      continue
    fi
    dir="$out/$scene-$source"
    echo "== $scene $source" >&2
    log=$("$vplkit" sequence --scene "$scene" "${common[@]}" "${opts[@]}" --out "$dir" 2>"$dir.log")
    echo "$log" >&2
    vpls=$(grep -o 'frame [0-9]*/[0-9]*: [0-9.]* ms GPU, [0-9]* VPLs' "$dir.log" | awk '{s += $6; n++} END {printf "%.0f", s / n}')
    e=$(echo "$log" | sed -n 's/.*average |E| \([0-9.]*\), average |E.| \([0-9.]*\).*/\1/p')
    de=$(echo "$log" | sed -n 's/.*average |E| \([0-9.]*\), average |E.| \([0-9.]*\).*/\2/p')
    printf '| %s | %s | %s | %s | %s |\n' "$scene" "$source" "$vpls" "$e" "$de" >> "$table"
  done
done
cat "$table"
