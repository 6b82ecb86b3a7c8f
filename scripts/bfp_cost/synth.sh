#!/usr/bin/env bash
# yosys 0.23 synth_xilinx cost of one block of bfp_blocks.v: scripts/bfp_cost/synth.sh TOP [PARAM=VALUE...]
set -euo pipefail
dir=$(cd "$(dirname "$0")" && pwd)
top=$1; shift
chparam=""
for p in "$@"; do chparam+=" -set ${p%=*} ${p#*=}"; done
yosys -q -p "read_verilog $dir/bfp_blocks.v; chparam$chparam $top; synth_xilinx -family xc7 -flatten -top $top; tee -o /dev/stdout stat" |
    awk -v t="$top $*" '/LUT[1-6] /{l+=$2} /FDRE|FDSE|FDCE|FDPE/{f+=$2} /DSP48E1/{d+=$2} /CARRY4/{c+=$2} /SRL/{s+=$2}
        END {printf "| %s | %d | %d | %d | %d |\n", t, l + s, f, d, c}'
