//! The accelerator in rust-hdl: number-format operators, the Möller-Trumbore pipeline,
//! Verilog generation.

pub mod fixed;
pub mod float;
pub mod formats;
pub mod harness;
pub mod intmul;
pub(crate) mod macros;
pub mod mt;
pub mod operator;
pub mod pipe;
pub mod verilog;
pub mod widths;

// AXI4-Lite slave, register map and C generation (issue 4).
pub mod axil;
pub mod cgen;
pub mod regmap;

// yosys resource and logic-depth reports (issue 3), and the Fmax estimate (issue 41).
pub mod synth;
pub mod timing;

// The accelerator top (lanes, AXI4-Lite, AXI4-Stream, rtfpga_top wrapper) and the generated
// file set (issue 4).
pub mod generate;
pub mod top;

// The traversal unit's parts (issue 16).
pub mod traversal;

// The block-floating-point dual-precision filter (issue 17).
pub mod dual;

// The frame unit's blocks: ray generation, shading (issue 40).
pub mod frame;

/// `n` default values: the blocks or signals of a `Vec` field, one per lane or slot.
pub(crate) fn defaults<T: Default>(n: usize) -> Vec<T> {
    (0..n).map(|_| T::default()).collect()
}
