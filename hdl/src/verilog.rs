//! Verilog of one operator as a top module (`top`), with what a harness needs to drive it.

use rust_hdl::prelude::*;

use crate::operator::Operator;

/// A generated operator: Verilog whose top module is `top` with ports `clock`, `a`
/// (`b` when `b_width > 0`) and `y`; `y` answers the inputs of `latency` clocks earlier.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OperatorRtl {
    pub verilog: String,
    pub a_width: usize,
    /// 0 for a unary operator (no `b` port).
    pub b_width: usize,
    pub y_width: usize,
    pub latency: usize,
}

/// Name of the top module in [`OperatorRtl::verilog`].
pub const TOP: &str = "top";

/// Verilator warnings rust-hdl's generated code cannot avoid, to pass as `-Wno-…` flags next
/// to `-Wall`:
/// - WIDTH: `bit_cast` is emitted as `(x) & N'hmask`, literals as 32-bit constants and
///   struct fields as 64-bit indices, so operand widths differ although the values fit.
/// - DECLFILENAME: one file holds all the modules of a design (`top`, `top$sub`, …).
/// - UNUSEDSIGNAL: shared blocks (the unpacker's class flags, the flip-flop of a pipe built
///   as a wire, the divisor after the last division row) have outputs some operators never
///   read; synthesis removes them.
pub const VERILATOR_WAIVERS: &[&str] = &["-Wno-WIDTH", "-Wno-DECLFILENAME", "-Wno-UNUSEDSIGNAL"];

/// Verilator warnings waived for the accelerator's top, on top of [`VERILATOR_WAIVERS`]:
/// - VARHIDDEN: rust-hdl declares a block's local signals and its submodule instances by
///   their field names, so a local `sum` in a sub-block "hides" an instance `sum` of the
///   parent (the MT lane's dot products); each module has its own scope, nothing is hidden.
/// - SYMRSVDWORD: the port `interrupt` (the Vitis name Vivado infers the interrupt from) is
///   a common C++ word; Verilator renames it in its C++ and says so.
pub const TOP_VERILATOR_WAIVERS: &[&str] = &["-Wno-VARHIDDEN", "-Wno-SYMRSVDWORD"];

/// Verilator warnings waived for the traversal unit, on top of [`VERILATOR_WAIVERS`]:
/// - UNOPTFLAT: the unit's kernel is one `always` block that reads its blocks' outputs and
///   drives their inputs, and a block at a low depth passes some signals through zero-cycle
///   delay lines, so Verilator sees a loop between always blocks where every real path
///   crosses a register (the rust-hdl simulation settles every cycle, and the Verilated unit
///   equals the model). The shader core (`frame::shader::core`) is waived for the same
///   reason: its kernel reads the write-back delay lines' outputs and drives their inputs;
///   so are ray generation and its normalisation (`frame::raygen`, `frame::normalise`: a
///   shared operator's input multiplexer reads a register its own result feeds) and the
///   frame engine (`frame::engine`), which holds all three.
pub const UNIT_VERILATOR_WAIVERS: &[&str] = &["-Wno-UNOPTFLAT"];

/// `verilator --lint-only -Wall` with [`VERILATOR_WAIVERS`] on a generated block whose top
/// module is [`TOP`]: `Err` with the first 20 lines of Verilator's complaint.
pub fn verilator_lint(verilog: &str) -> Result<(), String> {
    verilator_lint_waiving(verilog, &[])
}

/// [`verilator_lint`] with the `extra` waivers too.
pub fn verilator_lint_waiving(verilog: &str, extra: &[&str]) -> Result<(), String> {
    let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
    let path = dir.path().join("block.v");
    std::fs::write(&path, verilog).map_err(|e| e.to_string())?;
    let out = std::process::Command::new("verilator")
        .args(["--lint-only", "-Wall"])
        .args(VERILATOR_WAIVERS)
        .args(extra)
        .args(["--top-module", TOP])
        .arg(&path)
        .output()
        .map_err(|e| format!("cannot run verilator (make setup installs it): {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&out.stderr)
            .lines()
            .take(20)
            .collect::<Vec<_>>()
            .join("\n"))
    }
}

/// Builds `T` with `stages` pipeline registers and generates its Verilog.
///
/// Panics if `stages > T::max_stages()` (see [`crate::formats::rtl`] for a checked entry).
pub fn operator_verilog<T: Operator>(stages: usize) -> OperatorRtl {
    let mut uut = T::new(stages);
    uut.connect_all();
    OperatorRtl {
        verilog: generate_verilog(&uut),
        a_width: T::A_WIDTH,
        b_width: T::B_WIDTH,
        y_width: T::Y_WIDTH,
        latency: stages,
    }
}
