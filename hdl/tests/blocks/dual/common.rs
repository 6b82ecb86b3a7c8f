//! What the dual block tests share: each block's Verilog as a (label, Verilog) pair, the
//! one form that both the lint check ([`lint_clean`]) and `hdl::synth::markdown_table` read.

use rust_hdl::prelude::*;

/// The connected block's label, "`name`, `shape`" (`shape` reads the block, e.g. its
/// widths from its type), and its Verilog.
pub(super) fn named<B: Block>(
    mut uut: B,
    name: &str,
    shape: impl FnOnce(&B) -> String,
) -> (String, String) {
    uut.connect_all();
    (format!("{name}, {}", shape(&uut)), generate_verilog(&uut))
}

/// Each Verilog is what Vivado would read: `verilator --lint-only -Wall` passes it with
/// `hdl::verilog`'s waivers and the `extra` ones (`&[]` for none); panics naming the first
/// that fails, with Verilator's complaint.
pub(super) fn lint_clean(verilogs: &[(String, String)], extra: &[&str]) {
    assert!(!verilogs.is_empty(), "no Verilog to lint");
    for (label, verilog) in verilogs {
        if let Err(e) = hdl::verilog::verilator_lint_waiving(verilog, extra) {
            panic!("{label}: verilator lint failed:\n{e}");
        }
    }
}

/// A top whose output nothing drives: Verilator's UNDRIVEN warning, which no waiver of
/// `hdl::verilog` covers.
fn undriven() -> (String, String) {
    let top = hdl::verilog::TOP;
    let verilog = format!("module {top}(input wire a, output wire p);\nendmodule\n");
    ("undriven".into(), verilog)
}

/// The helper fails where Verilator does.
#[test]
#[should_panic(expected = "undriven: verilator lint failed:\n%Warning-UNDRIVEN")]
fn lint_clean_fails_on_a_warning() {
    lint_clean(&[undriven()], &[]);
}

/// It passes the extra waivers on.
#[test]
fn lint_clean_passes_the_extra_waivers() {
    lint_clean(&[undriven()], &["-Wno-UNDRIVEN"]);
}
