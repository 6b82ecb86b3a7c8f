#!/usr/bin/env bash
# Markdown table of where the traversal unit's resources go: yosys synth_xilinx (xc7) of the
# unit under AXI4-Lite control with the hierarchy kept at its blocks (the core's ports,
# slots, stacks, setup, box stage, leaf ports, scene memory, counters; the lanes; the register
# slave) and everything inside a block flattened. Keeping the boundaries stops optimisation
# across them, so the sum is near, not equal to, the flattened unit's (`rtfpga synth --unit
# traversal`). Takes about as long as that synthesis (13-21 CPU-min for the fp32 d5 units).
# Usage: scripts/unit_blocks_table.sh [rtfpga verilog --unit traversal options, e.g.
#        --format fp32 --depth 5 --lanes 1 --nodes bvh8-q8]
set -euo pipefail
rtfpga=${RTFPGA:-target/release/rtfpga}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$rtfpga" verilog --unit traversal "$@" --out "$out" > /dev/null
v="$out/traversal_unit.v"
# The blocks: the control, the lanes, the core's children and, inside the ports and the
# setup, the box test or wide box stage, the stacks and the fp32 setup.
blocks=$(grep -o '^module top\$\(control\|unit\$lanes\$[0-9]*\|unit\$core\(\$[a-z_]*\(\$[0-9]*\)\?\)\?\|unit\$core\$\(box_port\$\(boxes\|stage\)\|stack_port\$stacks\|entry\$setup\)\)\b[ (]' "$v" |
  sed 's/^module //; s/[ (]$//' | sort -u)
{
  echo "read_verilog $v"
  echo "hierarchy -top top"
  for b in $blocks; do echo "setattr -mod -set keep_hierarchy 1 $b"; done
  echo "synth_xilinx -family xc7 -top top -flatten -noiopad -noclkbuf"
  echo "tee -q -o $out/stat.txt stat"
} > "$out/blocks.ys"
yosys -q -s "$out/blocks.ys" > "$out/yosys.log" 2>&1 || { tail -n 30 "$out/yosys.log" >&2; exit 1; }
python3 - "$out/stat.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
parts = re.split(r"\n=== (.*?) ===\n", text)
rows = []
for name, body in zip(parts[1::2], parts[2::2]):
    if name == "design hierarchy":
        continue
    cells = {m[1]: int(m[2]) for m in re.finditer(r"^\s+(\S+)\s+(\d+)$", body, re.M)}
    count = lambda pred: sum(n for c, n in cells.items() if pred(c))
    lut = count(lambda c: re.fullmatch(r"LUT[1-6]", c))
    srl = count(lambda c: c.startswith("SRL"))
    # LUTs a LUT RAM occupies: RAM32M, RAM64M 4; RAM32X1D, RAM64X1D 2; RAM128X1D 4;
    # RAM32X1S, RAM64X1S 1; RAM128X1S 2; RAM256X1S 4.
    luts = {"RAM32M": 4, "RAM64M": 4, "RAM32X1D": 2, "RAM64X1D": 2, "RAM128X1D": 4,
            "RAM32X1S": 1, "RAM64X1S": 1, "RAM128X1S": 2, "RAM256X1S": 4}
    lutram = sum(n * cells.get(c, 0) for c, n in luts.items())
    rows.append((lut + srl + lutram, name, lut, srl, lutram, count(lambda c: c.startswith("FD")),
                 cells.get("DSP48E1", 0), cells.get("RAMB18E1", 0) + 2 * cells.get("RAMB36E1", 0)))
total = sum(r[0] for r in rows)
print("| block | LUT-eq | share | LUT | SRL | LUT RAM (LUTs) | FF | DSP48E1 | RAMB18 halves |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in sorted(rows, reverse=True):
    if r[0] or r[5] or r[7]:
        print(f"| {r[1]} | {r[0]:,} | {100 * r[0] / total:.0f} % | {r[2]:,} | {r[3]:,} | {r[4]:,} | {r[5]:,} | {r[6]} | {r[7]} |")
s = [sum(r[k] for r in rows) for k in range(8) if k != 1]
print(f"| **sum** | {s[0]:,} | 100 % | {s[1]:,} | {s[2]:,} | {s[3]:,} | {s[4]:,} | {s[5]} | {s[6]} |")
PY
