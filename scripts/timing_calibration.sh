#!/usr/bin/env bash
# Calibrates the timing estimate's routing model (hdl::timing, docs/timing.md "Calibration"):
# fetches the PicoRV32 and VexRiscv Verilog from PyPI into a temporary venv, synthesises them
# with yosys (hdl::synth, as `rtfpga synth` does), and prints the fitted constants and the
# residuals against the published Vivado results as Markdown. None of the fetched code is
# kept in the repository: it goes to DIR (default target/timing-calibration), with the
# mapped netlists, which a second run reuses.
# Usage: scripts/timing_calibration.sh [DIR]
set -euo pipefail
dir=${1:-target/timing-calibration}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

python3 -m venv "$tmp/venv"
"$tmp/venv/bin/pip" download --quiet --no-deps -d "$tmp/wheels" \
  pythondata-cpu-picorv32==1.0.post218 pythondata-cpu-vexriscv==1.0.1.post407
for wheel in "$tmp"/wheels/*.whl; do
  python3 -m zipfile -e "$wheel" "$tmp/src"
done

picorv32=$tmp/src/pythondata_cpu_picorv32/verilog
vexriscv=$tmp/src/pythondata_cpu_vexriscv/verilog
mkdir -p "$dir/picorv32" "$dir/vexriscv_min" "$dir/vexriscv_full"
cp "$picorv32/picorv32.v" "$picorv32/scripts/vivado/tabtest.v" "$dir/picorv32/"
cp "$vexriscv/VexRiscv_Min.v" "$dir/vexriscv_min/"
cp "$vexriscv/VexRiscv_Full.v" "$dir/vexriscv_full/"

nice cargo run --release -p hdl --example timing_calibration -- "$dir"
