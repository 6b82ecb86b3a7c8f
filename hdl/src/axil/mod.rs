//! AXI4-Lite: the register-mode control slave of the accelerator.
//!
//! The register layout comes from [`crate::regmap`]; `slave` is the bus protocol and the
//! `ap_ctrl_hs` block-control logic in rust-hdl.

pub mod slave;

pub use slave::{AxiLiteSlave, AxiLiteSlavePort};
