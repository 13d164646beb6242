#!/usr/bin/env bash
# |E| and |E'| (the SMC paper, Reinhard-tonemapped indirect luminance against an exact gather over many
# IR light paths) of hybrid GI along a short orbit, with the filter off and with svgf
# (`vplkit sequence` defaults to svgf), on the in-repo Cornell box and SponzaLite with the sun.
# Writes OUT/<scene>-<denoise>/ and OUT/table.md.
#   scripts/denoise_table.sh [OUT] [WxH] [FRAMES] [extra sequence options...]
set -euo pipefail
out=${1:-out/denoise-table}
size=${2:-64x48}
frames=${3:-8}
shift $(( $# < 3 ? $# : 3 ))
vplkit=${VPLKIT:-build/release/samples/vplkit}
width=${size%x*}
height=${size#*x}
common=(--width "$width" --height "$height" --frames "$frames" --orbit-degrees 6 --method hybrid --spp 16
        --vpls 1024 --reference --reference-paths 2048 --cache "$out/cache" "$@")
mkdir -p "$out"
table="$out/table.md"
printf '| scene | --denoise | average \\|E\\| | average \\|E'"'"'\\| |\n| --- | --- | --- | --- |\n' > "$table"
for scene in cornell sponza-lite-sun; do
  for denoise in off svgf; do
    dir="$out/$scene-$denoise"
    echo "== $scene $denoise" >&2
    log=$("$vplkit" sequence --scene "$scene" "${common[@]}" --denoise "$denoise" --out "$dir" 2>"$dir.log")
    echo "$log" >&2
    e=$(echo "$log" | sed -n 's/.*average |E| \([0-9.]*\), average |E.| \([0-9.]*\).*/\1/p')
    de=$(echo "$log" | sed -n 's/.*average |E| \([0-9.]*\), average |E.| \([0-9.]*\).*/\2/p')
    printf '| %s | %s | %s | %s |\n' "$scene" "$denoise" "$e" "$de" >> "$table"
  done
done
cat "$table"
