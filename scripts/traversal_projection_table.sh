#!/usr/bin/env bash
# Markdown table of the ARM-plus-traversal-unit design's projected frame per thesis scene
# (rtfpga project --design traversal): ARM, accelerator and total seconds, the unit's cycles
# per ray, and the speed-ups over the thesis' brute-force software and over the ARM walking
# the same BVH. The scene is resident whole (--scene-memory 16384,16384: no chunked passes;
# docs/traversal-capacity.md has what smaller memories cost).
# Usage: scripts/traversal_projection_table.sh [SCENES_DIR] [hardware options, e.g. --depth 5]
# SCENES_DIR defaults to $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis; SIZES (default
# "1280x720 1920x1080"), SCENES (default all 7).
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
here=$(dirname "$0")
dir=${1:-${RTFPGA_THESIS_SCENES:-../shared/scenes/thesis}}
shift || true
read -r -a scenes <<< "${SCENES:-Simple_plane_scene Simple_plane2_scene Glasses_scene Glasses_point_scene Glass_pen_scene Utah_teapot_scene All_materials_scene}"
echo "| scene | size | ARM s | accelerator s | total s | cycles/ray | thesis software (modelled) s | speed-up | ARM with BVH walk s | speed-up |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in "${scenes[@]}"; do
  for size in ${SIZES:-1280x720 1920x1080}; do
    "$rtfpga" project --scene "$dir/$scene" --width "${size%x*}" --height "${size#*x}" \
      --design traversal --scene-memory 16384,16384 "$@" 2>/dev/null | PYTHONPATH="$here" python3 -c '
import sys
from rtfpga_output import parse, scene_name
kv = parse(sys.stdin)
print("| %s | %s | %s | %s | **%s** | %s | %s | %s× | %s | %s× |" % (
    scene_name(sys.argv[1]), sys.argv[2], kv["term_ARM"], kv["term_accelerator"], kv["total_s"],
    kv["cycles_per_ray"], kv["arm_software_s"], kv["speedup_vs_arm"], kv["arm_bvh_walk_s"],
    kv["speedup_vs_arm_bvh_walk"]))
' "$scene" "$size"
  done
done
