#!/bin/sh
# Checks of the Vivado collateral that need no Vivado (tclsh, and yosys when real Verilog
# is at hand). Exits non-zero on any problem.
#   1. every .tcl/.xdc file is complete Tcl (`info complete` on the whole file);
#   2. test/run_tests.tcl: helpers, port names against docs/architecture.md, XDC files in an
#      XDC-only interpreter, dry runs of the three flow scripts against a Vivado mock;
#   3. with generated Verilog, the ports of rtfpga_top (yosys portlist) and the register
#      offsets of the generated C header against the architecture.
# Environment: ARCH_DOC (architecture.md; default the repository's docs/architecture.md),
# VERILOG_DIR (output of `rtfpga verilog`), else RTFPGA (default
# target/release/rtfpga) is asked to generate it when it has a `verilog` command.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
arch_doc=${ARCH_DOC:-$root/docs/architecture.md}
rtfpga=${RTFPGA:-$root/target/release/rtfpga}

if [ ! -f "$arch_doc" ]; then
    echo "check.sh: $arch_doc not found (set ARCH_DOC to an architecture.md)" >&2
    exit 1
fi

for f in "$here"/*.tcl "$here"/*.xdc "$here"/test/*.tcl; do
    tclsh <<TCL || { echo "check.sh: $f is not complete Tcl (unbalanced braces, brackets or quotes)" >&2; exit 1; }
set fd [open {$f} r]
set text [read \$fd]
close \$fd
exit [expr {![info complete \$text]}]
TCL
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

verilog_dir=${VERILOG_DIR:-}
if [ -z "$verilog_dir" ] && [ -x "$rtfpga" ] && "$rtfpga" verilog --help 2>&1 | grep -q -- --out; then
    verilog_dir=$tmp/verilog
    "$rtfpga" verilog --out "$verilog_dir" >/dev/null
fi

header=
if [ -n "$verilog_dir" ]; then
    header=$verilog_dir/xrtfpga_hw.h
    [ -f "$header" ] || { echo "check.sh: $header missing" >&2; exit 1; }
    yosys -Q -T -q -p "read_verilog -noblackbox $verilog_dir/*.v; hierarchy -top rtfpga_top; tee -q -o $tmp/ports.txt portlist rtfpga_top"
    tclsh "$here/test/check_top_ports.tcl" "$tmp/ports.txt"
else
    echo "check.sh: no generated Verilog (set VERILOG_DIR or build rtfpga with its verilog command): rtfpga_top's ports not checked"
fi

TMPDIR=$tmp tclsh "$here/test/run_tests.tcl" "$arch_doc" "$header"
