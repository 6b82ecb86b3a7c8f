#!/usr/bin/env bash
# Markdown table of every operator of the given formats at 0 and at the maximum number of
# pipeline stages: latency and yosys synth_xilinx resources / logic depth.
# Usage: scripts/operator_table.sh [FORMAT...]   (default: fp32 fp24 bf16 fp16 fx16_10 fx32_16)
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
formats=("$@")
[ ${#formats[@]} -gt 0 ] || formats=(fp32 fp24 bf16 fp16 fx16_10 fx32_16)
echo "| format | op | stages = latency | LUT | FF | DSP48E1 | CARRY4 | logic depth |"
echo "|---|---|---|---|---|---|---|---|"
for f in "${formats[@]}"; do
  for op in add sub mul recip lt from_f32 to_f32; do
    # The operator's maximum stage count, from the error message of an impossible request.
    max=$({ "$rtfpga" synth --format "$f" --op "$op" --stages 100000 2>&1 || true; } | sed -n 's/.*at most \([0-9]*\).*/\1/p')
    [ -n "$max" ] || { echo "operator_table: cannot read max stages of $f $op" >&2; exit 1; }
    for s in 0 "$max"; do
      "$rtfpga" synth --format "$f" --op "$op" --stages "$s" --json | python3 -c '
import json, sys
d = json.load(sys.stdin); r = d["report"]
print("| %s | %s | %s | %d | %d | %d | %d | %d |" % (sys.argv[1], sys.argv[2], d["latency"], r["lut"], r["ff"], r["dsp48e1"], r["carry4"], r["logic_depth"]))
' "$f" "$op"
    done
  done
done
