//! What the dual block tests share: each block's Verilog as a (label, Verilog) pair, the
//! one form that both the lint check ([`lint_clean`]) and `hdl::synth::markdown_table` read.

use rand::rngs::StdRng;
use rand::Rng;
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

/// A direction nearly in the plane of triangle `v`: e1 scaled, plus up to 2^-40 of the
/// normal, so det is tiny against its terms (the filter's near-parallel case).
pub(super) fn near_parallel(rng: &mut StdRng, v: [[f32; 3]; 3]) -> [f32; 3] {
    let [v0, v1, v2] = v;
    let e1: [f32; 3] = std::array::from_fn(|k| v1[k] - v0[k]);
    let e2: [f32; 3] = std::array::from_fn(|k| v2[k] - v0[k]);
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let off = rng.gen_range(-1.0f32..1.0) * 2f32.powi(-rng.gen_range(0..40));
    std::array::from_fn(|k| e1[k] * rng.gen_range(0.5..2.0) + n[k] * off)
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
