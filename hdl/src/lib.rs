//! The accelerator in rust-hdl: number-format operators, the Möller-Trumbore pipeline,
//! Verilog generation.

pub mod fixed;
pub mod float;
pub mod formats;
pub mod intmul;
pub mod mt;
pub mod operator;
pub mod pipe;
// The traversal unit's box test (against hw_model::traversal).
pub mod traversal;
pub mod verilog;

// AXI4-Lite slave, register map and C generation (issue 4).
pub mod axil;
pub mod cgen;
pub mod regmap;

// yosys resource and logic-depth reports (issue 3).
pub mod synth;

// The accelerator top (lanes, AXI4-Lite, AXI4-Stream, rtfpga_top wrapper) and the generated
// file set (issue 4).
pub mod generate;
pub mod top;
