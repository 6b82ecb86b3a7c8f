#!/usr/bin/env bash
# Markdown table of the traversal unit's schedule model per thesis scene for several
# configurations side by side (rtfpga render --engine traversal): cycles per ray and, in
# brackets, box tests (node tests) per ray.
# Usage: scripts/node_format_table.sh [SCENES_DIR] "OPTIONS 1" "OPTIONS 2" …
#   e.g. scripts/node_format_table.sh ../shared/scenes/thesis "--nodes bvh2-fp32 --slots 32" \
#        "--nodes bvh8-q8 --slots 64"
# Every configuration also gets COMMON (default: --depth 5 --lanes 1 --scene-memory
# 16384,16384); SIZE (default 320x180), SCENES (default all 7).
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
dir=${1:-${RTFPGA_THESIS_SCENES:-../shared/scenes/thesis}}
shift || true
read -r -a common <<< "${COMMON:---depth 5 --lanes 1 --scene-memory 16384,16384}"
size=${SIZE:-320x180}
read -r -a scenes <<< "${SCENES:-Simple_plane_scene Simple_plane2_scene Glasses_scene Glasses_point_scene Glass_pen_scene Utah_teapot_scene All_materials_scene}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
header="| scene ($size) |"
rule="|---|"
for config in "$@"; do
  header="$header \`$config\` |"
  rule="$rule---:|"
done
echo "$header"
echo "$rule"
for scene in "${scenes[@]}"; do
  row="| $scene |"
  for config in "$@"; do
    read -r -a options <<< "$config"
    cell=$("$rtfpga" render --engine traversal --scene "$dir/$scene" --width "${size%x*}" \
      --height "${size#*x}" "${common[@]}" "${options[@]}" --quiet --out "$out/img.png" \
      | python3 -c '
import sys
for line in sys.stdin:
    if line.startswith("unit_schedule"):
        kv = dict(t.split("=", 1) for t in line.split() if "=" in t)
        print("%.2f (%.2f)" % (float(kv["cycles_per_ray"]), float(kv["box_tests_per_ray"])))
')
    row="$row $cell |"
  done
  echo "$row"
done
