//! AXI4-Lite: the bus protocol of a register slave (`bus`) and the accelerator's
//! register-mode control slave on it (`slave`).
//!
//! The register layouts come from [`crate::regmap`]; `slave` is the `ap_ctrl_hs`
//! block-control logic in rust-hdl; the traversal unit's slave is `traversal::unit_axil`.

pub mod bus;
pub mod slave;

pub use bus::AxiLiteBus;
pub use slave::{AxiLiteSlave, AxiLiteSlavePort};
