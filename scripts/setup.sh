#!/usr/bin/env bash
# Installs the system tools the project drives: Verilator and clang (co-simulation), Yosys (resource
# reports), Icarus Verilog (a second compiler check), Tcl (checks of the Vivado scripts). Debian/Ubuntu, run as root or with sudo.
# Then FuseSoC (pip) for the lint target of rtfpga.core; without pip it says so and goes on
# (hdl/tests/integration/fusesoc_core.rs then skips its fusesoc run).
set -euo pipefail

install_fusesoc() {
  command -v fusesoc >/dev/null 2>&1 && return 0
  local log
  log=$(mktemp)
  if command -v pipx >/dev/null 2>&1; then
    echo "setup: installing fusesoc with pipx" >&2
    pipx install fusesoc >"$log" 2>&1 || true
  elif python3 -m pip --version >/dev/null 2>&1; then
    echo "setup: installing fusesoc with pip" >&2
    python3 -m pip install --quiet fusesoc >"$log" 2>&1 ||
      python3 -m pip install --quiet --user fusesoc >"$log" 2>&1 || true
  else
    echo "setup: no pip or pipx: fusesoc not installed; the FuseSoC lint test is skipped (pip install fusesoc to run it)" >&2
    rm -f "$log"
    return 0
  fi
  if ! command -v fusesoc >/dev/null 2>&1; then
    if grep -q externally-managed "$log"; then
      echo "setup: fusesoc not installed: this Python is externally managed (PEP 668); use pipx install fusesoc or a venv. The FuseSoC lint test is skipped until fusesoc is on PATH" >&2
    else
      echo "setup: fusesoc not installed or not on PATH (pip's script directory, e.g. ~/.local/bin?); the FuseSoC lint test is skipped. Installer output:" >&2
      tail -n 5 "$log" >&2
    fi
  fi
  rm -f "$log"
  return 0
}

# make test runs rustfmt and clippy: rustup's default profile has them, a minimal one not.
if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
  echo "setup: adding the rustfmt and clippy components (rustup)" >&2
  rustup component add rustfmt clippy
fi

need=()
command -v verilator >/dev/null 2>&1 || need+=(verilator)
command -v yosys >/dev/null 2>&1 || need+=(yosys)
command -v iverilog >/dev/null 2>&1 || need+=(iverilog)
command -v g++ >/dev/null 2>&1 || need+=(g++)
# The Verilated models are compiled with clang++ when it is there: their code runs about a
# quarter faster than g++'s (BENCHMARKS "Traversal unit, co-simulated").
command -v clang++ >/dev/null 2>&1 || need+=(clang)
command -v tclsh >/dev/null 2>&1 || need+=(tcl)
command -v make >/dev/null 2>&1 || need+=(make)
if [ ${#need[@]} -eq 0 ]; then
  install_fusesoc
  exit 0
fi
echo "setup: installing ${need[*]} with apt-get" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "setup: need root or sudo to apt-get install ${need[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
install_fusesoc
