//! Errors of co-simulating the accelerator top: its configuration, the model build, and the
//! bus protocols the drivers check while they run.

use crate::SimError;
use hdl::top::TopError;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum CosimError {
    /// The requested accelerator configuration does not exist.
    #[error("accelerator configuration: {0}")]
    Config(#[from] TopError),

    /// Building, loading or stepping the Verilated model failed.
    #[error(transparent)]
    Sim(#[from] SimError),

    /// The hardware broke a bus rule or answered something the driver cannot match.
    #[error("{bus} protocol, cycle {cycle}: {message}")]
    Protocol {
        bus: &'static str,
        cycle: u64,
        message: String,
    },

    /// The hardware did not answer within the cycle budget (instead of hanging).
    #[error("{what}: no progress after {cycles} cycles (the hardware does not answer)")]
    Timeout { what: String, cycles: u64 },

    /// A trace file could not be read or written.
    #[error("trace {}: {message}", path.display())]
    Trace { path: PathBuf, message: String },
}
