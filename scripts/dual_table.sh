#!/usr/bin/env bash
# Forwarded share of dual-precision model renders of the thesis' scenes (docs/precision.md,
# "Dual precision"): per format pair and filter, the share of Möller-Trumbore tests the
# filter could not decide alone, and whether the image equals the fallback's fp32 model
# render. Prints a Markdown table; one row per pair × filter, one column per scene and the
# share over all scenes' tests.
#
#   scripts/dual_table.sh [PAIRS...]
#
# Environment: RTFPGA (the binary, default target/release/rtfpga), RTFPGA_THESIS_SCENES
# (default ../shared/scenes/thesis), SIZE (default 320x180), OUT (work directory, default a
# temporary one), FILTERS (`--dual-filter` values, default "bfp").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${RTFPGA:-$root/target/release/rtfpga}
scenes_dir=${RTFPGA_THESIS_SCENES:-$root/../shared/scenes/thesis}
size=${SIZE:-320x180}
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
read -r -a filters <<< "${FILTERS:-bfp}"
w=${size%x*}
h=${size#*x}
pairs=("$@")
if [ ${#pairs[@]} -eq 0 ]; then
    pairs=(bfp14/fp32 bfp16/fp32 bfp18/fp32 bfp20/fp32)
fi
scenes=(Glass_pen_scene Simple_plane_scene Glasses_scene Glasses_point_scene
    Simple_plane2_scene Utah_teapot_scene All_materials_scene)
render() { "$bin" render --scene "$scenes_dir/$1" --width "$w" --height "$h" --quiet --out "$2" --engine model "${@:3}"; }
field() { grep -o "\b$1=[^ ]*" | head -1 | cut -d= -f2; }

for s in "${scenes[@]}"; do
    [ -f "$out/ref_$s.png" ] || render "$s" "$out/ref_$s.png" --format fp32 >/dev/null
done
printf '| pair | filter |'
for s in "${scenes[@]}"; do printf ' %s |' "${s%_scene}"; done
printf ' all | images = fp32 |\n|---|---|'
for _ in "${scenes[@]}"; do printf -- '---|'; done
printf -- '---|---|\n'
for p in "${pairs[@]}"; do
    for filter in "${filters[@]}"; do
        printf '| %s | %s |' "$p" "$filter"
        tests=0 forwarded=0 same=yes
        for s in "${scenes[@]}"; do
            img="$out/${p//\//_}_${filter}_$s.png"
            line=$(render "$s" "$img" --format "$p" --dual-filter "$filter" | grep '^dual_precision ')
            t=$(field tests <<< "$line")
            f=$(field forwarded <<< "$line")
            printf ' %s |' "$(field forwarded_share <<< "$line")"
            tests=$((tests + t))
            forwarded=$((forwarded + f))
            cmp -s <("$bin" compare "$out/ref_$s.png" "$img" | tail -1) <(echo 'psnr_db=inf') || same=no
        done
        printf ' %s | %s |\n' "$(awk -v f="$forwarded" -v t="$tests" 'BEGIN { printf "%.4f", f / t }')" "$same"
    done
done
