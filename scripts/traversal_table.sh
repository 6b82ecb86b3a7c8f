#!/usr/bin/env bash
# Markdown table of the traversal unit per thesis scene and size: its bit-accurate model's
# work per ray and its schedule model's cycles (rtfpga render --engine traversal), plus the
# model engine's own speed on this machine.
# Usage: scripts/traversal_table.sh [SCENES_DIR] [rtfpga render options, e.g. --slots 32 --lanes 1]
# SCENES_DIR defaults to $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis; SIZES
# (default "320x180 1280x720") the image sizes.
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
dir=${1:-${RTFPGA_THESIS_SCENES:-../shared/scenes/thesis}}
shift || true
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | size | rays | node visits/ray | box tests/ray | MT tests/ray | cycles/ray | box unit | lanes | Mrays/s at 100 MHz | model Mrays/s |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in Simple_plane_scene Simple_plane2_scene Glasses_scene Glasses_point_scene Glass_pen_scene Utah_teapot_scene All_materials_scene; do
  for size in ${SIZES:-320x180 1280x720}; do
    w=${size%x*} h=${size#*x}
    "$rtfpga" render --scene "$dir/$scene" --width "$w" --height "$h" --engine traversal "$@" \
      --quiet --out "$out/img.png" | python3 -c '
import sys
kv = {}
for line in sys.stdin:
    for tok in line.split():
        if "=" in tok:
            k, v = tok.split("=", 1); kv[k] = v
r = int(kv["rays"])
print("| %s | %sx%s | %d | %.2f | %.2f | %.2f | %.2f | %.0f %% | %.0f %% | %.2f | %.2f |" % (
    sys.argv[1], sys.argv[2], sys.argv[3], r, int(kv["node_visits"]) / r, int(kv["box_tests"]) / r,
    int(kv["mt_queries"]) / r, float(kv["cycles_per_ray"]), 100 * float(kv["box_utilisation"]),
    100 * float(kv["lane_utilisation"]), float(kv["mrays_per_s_at_100mhz"]), float(kv["mrays_per_s"])))
' "$scene" "$w" "$h"
  done
done
