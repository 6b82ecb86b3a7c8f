#!/usr/bin/env bash
# Every block row of docs/precision.md "Tests per cycle per LUT (estimate)" for the bfp18
# filter, and the Plücker filter's blocks ("The Plücker filter"; yosys 0.23
# synth_xilinx; LUT counts LUT + SRL): scripts/bfp_cost/table.sh
set -euo pipefail
dir=$(cd "$(dirname "$0")" && pwd)
echo "| block | LUT | FF | DSP48E1 | CARRY4 |"
echo "|---|---:|---:|---:|---:|"
while read -r row; do
    # shellcheck disable=SC2086
    "$dir/synth.sh" $row
done <<'ROWS'
bfp_translate G=3
bfp_block IW=25 W=18
bfp_block IW=29 W=18
bfp_block IW=29 W=25
bfp_mul A=18 B=18
bfp_mul A=25 B=18
bfp_mul A=25 B=11
bfp_add N=37
bfp_add N=44
bfp_add N=38
bfp_add N=45
bfp_cut IW=37 W=18
bfp_cut IW=44 W=25
bfp_margin N=38 MW=30 K=33
bfp_margin N=45 MW=36 K=40
bfp_round IW=40 M=10 UP=1
bfp_round IW=40 M=10 UP=0
bfp_round IW=47 M=10 UP=1
bfp_round IW=47 M=10 UP=0
bfp_round IW=36 M=10 UP=0
bfp_scmp M=11
bfp_sadd M=11
bfp_mul A=25 B=25
bfp_align_add N=38
bfp_align_add N=52
bfp_round IW=45 M=6 UP=1
bfp_round IW=39 M=6 UP=1
bfp_round IW=53 M=6 UP=1
bfp_sadd M=5
bfp_scmp M=6
bfp_add N=10
bfp_mul A=6 B=6
plucker_s_bound
ROWS
