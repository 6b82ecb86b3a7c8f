//! Verilator co-simulation: the model builder and cache, the FFI to Verilated models, and
//! helpers that drive them.

pub mod error;
pub mod projection;
pub mod verilator;

pub use error::SimError;
pub use verilator::{build, run_pipelined, BuildOptions, Model, ModelSpec, VerilatedModel};
