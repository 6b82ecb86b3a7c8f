//! Verilator co-simulation: the model builder and cache, the FFI to Verilated models, and
//! helpers that drive them.

pub mod accel_model;
pub mod axil_master;
pub mod cosim_error;
pub mod dual_pair;
pub mod error;
pub mod frame_unit;
pub mod hw_intersector;
pub mod projection;
pub mod sim_clock;
pub mod stream_driver;
pub mod sweep;
pub mod trace;
pub mod traversal_unit;
pub mod verilator;

pub use error::SimError;
pub use verilator::{build, run_pipelined, BuildOptions, Model, ModelSpec, VerilatedModel};
