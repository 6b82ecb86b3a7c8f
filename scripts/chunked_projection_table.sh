#!/usr/bin/env bash
# Markdown table of what chunked passes cost the ARM-plus-traversal-unit design's projected
# frame (rtfpga project --design traversal --scene-memory NODES,TRIANGLES): chunks, passes,
# bytes loaded, the unit's and the loads' cycles per ray, and the frame's terms, one row per
# image size and scene-memory capacity ("unbounded": the scene resident whole).
# Usage: scripts/chunked_projection_table.sh SCENE_DIR [hardware options, e.g. --depth 5]
# ROWS: "SIZE:CAPACITY[:TILE]" items (default: the Utah teapot rows of BENCHMARKS.md);
# TILE (default 256) the tile size where a row names none.
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
here=$(dirname "$0")
scene=$1
shift
rows=${ROWS:-1280x720:unbounded 1280x720:4096,5120 1280x720:3072,4096 1280x720:2048,2560 1280x720:3072,4096:32 1920x1080:unbounded 1920x1080:3072,4096}
echo "| size | capacity | tile | chunks | passes | ray passes / ray | bytes loaded | unit cycles/ray | load cycles/ray | ARM s | accelerator s | total s |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for row in $rows; do
  IFS=: read -r size capacity tile <<< "$row"
  memory=$capacity
  [ "$capacity" = unbounded ] && memory=16384,16384
  "$rtfpga" project --scene "$scene" --width "${size%x*}" --height "${size#*x}" --design traversal \
    --tile-size "${tile:-${TILE:-256}}" --scene-memory "$memory" "$@" 2>/dev/null | PYTHONPATH="$here" python3 -c '
import sys
from rtfpga_output import parse
kv = parse(sys.stdin)
rays = int(kv["rays"])
# Chunks: passes per wavefront, rounded up (a wavefront takes at most a pass per chunk).
chunks = -(-int(kv["passes"]) // int(kv["wavefronts"]))
print("| %s | %s | %s | %d | {:,} | %.2f | {:,} | %s | %s | %s | %s | **%s** |".format(
    int(kv["passes"]), int(kv["loaded_bytes"])) % (
    sys.argv[1], sys.argv[2], sys.argv[3], chunks,
    int(kv["ray_passes"]) / rays, kv["cycles_per_ray"], kv["load_cycles_per_ray"],
    kv["term_ARM"], kv["term_accelerator"], kv["total_s"]))
' "$size" "$capacity" "${tile:-${TILE:-256}}"
done
