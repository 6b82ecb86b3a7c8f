#!/usr/bin/env bash
# Markdown table of the Verilated traversal unit per thesis scene (rtfpga cosim --unit
# traversal): rays, cycles and work per ray, utilisation of the box unit and the lane, the
# simulation's speed, the image against the software's, and beside it the schedule model's
# cycles per ray for the same configuration (rtfpga render --engine traversal).
# Usage: scripts/unit_cosim_table.sh [SCENES_DIR] [hardware options, e.g. --depth 5]
# SCENES_DIR defaults to $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis; SIZE (default
# 320x180), SCENES (default all 7).
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
dir=${1:-${RTFPGA_THESIS_SCENES:-../shared/scenes/thesis}}
shift || true
size=${SIZE:-320x180}
w=${size%x*}
h=${size#*x}
read -r -a scenes <<< "${SCENES:-Simple_plane_scene Simple_plane2_scene Glasses_scene Glasses_point_scene Glass_pen_scene Utah_teapot_scene All_materials_scene}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | size | rays | cycles/ray | schedule model cycles/ray | node visits/ray | box tests/ray | MT tests/ray | box unit | lane | chunk loads | sim cycles/s | sim rays/s | PSNR |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
for scene in "${scenes[@]}"; do
  cosim=$("$rtfpga" cosim --unit traversal --scene "$dir/$scene" --width "$w" --height "$h" "$@" \
    --quiet --out "$out/unit.png")
  schedule=$("$rtfpga" render --engine traversal --scene "$dir/$scene" --width "$w" --height "$h" "$@" \
    --quiet --out "$out/model.png" | grep '^unit_schedule ')
  printf '%s\n%s\n' "$cosim" "$schedule" | python3 -c '
import sys
kv, schedule = {}, None
for line in sys.stdin:
    for tok in line.split():
        if "=" in tok:
            k, v = tok.split("=", 1)
            if line.startswith("unit_schedule"):
                if k == "cycles_per_ray": schedule = float(v)
            else:
                kv.setdefault(k, v)
print("| %s | %sx%s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f %% | %.0f %% | %s | %.0f | %.0f | %s |" % (
    sys.argv[1], sys.argv[2], sys.argv[3], kv["rays"], float(kv["cycles_per_ray"]), schedule,
    float(kv["node_visits_per_ray"]), float(kv["box_tests_per_ray"]), float(kv["mt_tests_per_ray"]),
    100 * float(kv["box_utilisation"]), 100 * float(kv["lane_utilisation"]), kv["chunk_loads"],
    float(kv["sim_cycles_per_s"]), float(kv["rays_per_s"]), kv["psnr_db"]))
' "$scene" "$w" "$h"
done
