#!/usr/bin/env bash
# The Verilated dual-precision pair (bfp18 or Plücker filter slots sharing one fp32 lane) on the thesis'
# scenes (docs/precision.md, "The pair in hardware"): per slot count, per scene the share of
# tests forwarded to the fp32 lane and the tests per cycle, over all scenes both again and
# whether every image equals the software fp32 render. Prints a Markdown table.
#
#   scripts/pair_cosim_table.sh [SLOTS...]      (default: 1 2 3 4)
#
# Environment: RTFPGA (the binary, default target/release/rtfpga), RTFPGA_THESIS_SCENES
# (default ../shared/scenes/thesis), SIZE (default 320x180), DEPTH (the fp32 lane's, default
# 5), FILTER (the slots' filter, `--dual-filter`: bfp or plucker-signs, default bfp), SPAWN
# (`--spawn`: thesis or format-aware, default cosim's: thesis for this fp32 pair), OUT (work
# directory, default a temporary one).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${RTFPGA:-$root/target/release/rtfpga}
scenes_dir=${RTFPGA_THESIS_SCENES:-$root/../shared/scenes/thesis}
size=${SIZE:-320x180}
depth=${DEPTH:-5}
filter=${FILTER:-bfp}
spawn=${SPAWN:-thesis}
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
w=${size%x*}
h=${size#*x}
slot_counts=("$@")
if [ ${#slot_counts[@]} -eq 0 ]; then
    slot_counts=(1 2 3 4)
fi
scenes=(Glass_pen_scene Simple_plane_scene Glasses_scene Glasses_point_scene
    Simple_plane2_scene Utah_teapot_scene All_materials_scene)
field() { grep -o "\b$1=[^ ]*" | head -1 | cut -d= -f2; }

printf '| slots | value |'
for s in "${scenes[@]}"; do printf ' %s |' "${s%_scene}"; done
printf ' all | images = fp32 |\n|---|---|'
for _ in "${scenes[@]}"; do printf -- '---|'; done
printf -- '---|---|\n'
for n in "${slot_counts[@]}"; do
    shares="" rates="" tests=0 forwarded=0 cycles=0 exact=yes
    for s in "${scenes[@]}"; do
        log="$out/s${n}_$s.log"
        "$bin" cosim --scene "$scenes_dir/$s" --width "$w" --height "$h" --format bfp18/fp32 \
            --dual-filter "$filter" --spawn "$spawn" --lanes "$n" --depth "$depth" --quiet --out "$out/s${n}_$s.png" > "$log"
        shares+=" $(field forwarded_share < "$log") |"
        rates+=" $(field tests_per_cycle < "$log") |"
        tests=$((tests + $(field tests < "$log")))
        forwarded=$((forwarded + $(field forwarded < "$log")))
        cycles=$((cycles + $(field cycles < "$log")))
        [ "$(field psnr_db < "$log")" = inf ] || exact=no
    done
    share=$(awk -v f="$forwarded" -v t="$tests" 'BEGIN { printf "%.4f", f / t }')
    rate=$(awk -v t="$tests" -v c="$cycles" 'BEGIN { printf "%.4f", t / c }')
    printf '| %s | forwarded |%s %s | %s |\n' "$n" "$shares" "$share" "$exact"
    printf '| %s | tests/cycle |%s %s | %s |\n' "$n" "$rates" "$rate" "$exact"
done
