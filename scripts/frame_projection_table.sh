#!/usr/bin/env bash
# Markdown table of the frame schedule model per thesis scene (rtfpga project --design
# frame), one and two shader cores: rays, frame cycles or seconds at 100 MHz, fps, the
# bounding stage and utilisations. At 320x180 (the default SIZE) beside it how 8 and 32
# threads change the one-core frame and the most rays in flight; at any other size beside it
# the ARM-plus-unit design's frame (rtfpga project --design traversal, the scene resident
# whole as the frame design holds it: no chunked passes) and the speed-ups.
# Usage: scripts/frame_projection_table.sh [SCENES_DIR] [hardware options, e.g. --depth 5]
# SCENES_DIR defaults to $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis; SIZE (default
# 320x180), SCENES (default all 7).
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
here=$(dirname "$0")
dir=${1:-${RTFPGA_THESIS_SCENES:-../shared/scenes/thesis}}
shift || true
size=${SIZE:-320x180}
w=${size%x*}
h=${size#*x}
read -r -a scenes <<< "${SCENES:-Simple_plane_scene Simple_plane2_scene Glasses_scene Glasses_point_scene Glass_pen_scene Utah_teapot_scene All_materials_scene}"
project() { "$rtfpga" project --scene "$dir/$scene" --width "$w" --height "$h" "$@" 2>/dev/null; }
if [ "$size" = 320x180 ]; then
  echo "| scene | rays | instructions | K=1 cycles | fps | bound | box | issue | K=2 cycles | fps | bound | box | issue | T=8 / T=32 | peak |"
  echo "|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|"
else
  echo "| scene | rays | K=1 s | fps | bound | K=2 s | fps | bound | ARM + unit s (unit alone) | speed-up K=1 / K=2 |"
  echo "|---|---:|---:|---:|---|---:|---:|---|---:|---:|"
fi
for scene in "${scenes[@]}"; do
  {
    echo "== k1"; project --design frame "$@" --shader-cores 1
    echo "== k2"; project --design frame "$@" --shader-cores 2
    if [ "$size" = 320x180 ]; then
      echo "== t8"; project --design frame "$@" --shader-cores 1 --shader-threads 8
      echo "== t32"; project --design frame "$@" --shader-cores 1 --shader-threads 32
    else
      echo "== arm"; project --design traversal "$@" --scene-memory 16384,16384
    fi
  } | PYTHONPATH="$here" python3 -c '
import sys
from rtfpga_output import parse, scene_name
runs, run = {}, None
for line in sys.stdin:
    if line.startswith("== "):
        run = runs[line.split()[1]] = []
    else:
        run.append(line)
runs = {name: parse(lines) for name, lines in runs.items()}
k1, k2 = runs["k1"], runs["k2"]
cycles = lambda r: int(r["frame_cycles"])
pct = lambda x: "%.0f %%" % (100 * float(x))
bound = lambda r: r["bound"].replace("_", " ")
name = scene_name(sys.argv[1])
if "t8" in runs:
    print("| %s | {:,} | {:,} | {:,} | %s | %s | %s | %s | {:,} | %s | %s | %s | %s | %.3f / %.3f | %s |".format(
        int(k1["rays"]), int(k1["instructions"]), cycles(k1), cycles(k2)) % (
        name, k1["fps_at_100mhz"], bound(k1), pct(k1["box_port"]), pct(k1["shader_issue"]),
        k2["fps_at_100mhz"], bound(k2), pct(k2["box_port"]), pct(k2["shader_issue"]),
        cycles(runs["t8"]) / cycles(k1), cycles(runs["t32"]) / cycles(k1), k1["peak_in_flight"]))
else:
    arm = runs["arm"]
    s1, s2, total = cycles(k1) / 1e8, cycles(k2) / 1e8, float(arm["total_s"])
    print("| %s | {:,} | %.4f | %s | %s | %.4f | %s | %s | %.4f (%.4f) | %.2f× / %.2f× |".format(int(k1["rays"])) % (
        name, s1, k1["fps_at_100mhz"], bound(k1), s2, k2["fps_at_100mhz"], bound(k2),
        total, float(arm["term_accelerator"]), total / s1, total / s2))
' "$scene"
done
