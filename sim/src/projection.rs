//! A calibrated model of the frame time of a render on the ZedBoard (Zynq-7020: Cortex-A9 at
//! 667 MHz, fabric at f_PL) with a ray-triangle accelerator: the workload of a frame counted
//! from a software render ([`workload`]), the cost terms and designs ([`cost`]), and the fit
//! of the board's constants on the thesis' measured times ([`calibration`]).
//! `docs/projection.md` gives the equations and the calibration table.

pub mod calibration;
pub mod cost;
pub mod fit_store;
pub mod workload;

pub use calibration::{
    calibrate, Calibration, CalibrationRow, Measurement, Role, Setup, Workloads,
    THESIS_MEASUREMENTS,
};
pub use cost::{load_cycles, project, Board, Breakdown, Design, Frontend, ARM_MHZ};
pub use workload::{Traversal, UnitWork, Workload};

/// Why a projection or calibration could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ProjectionError {
    #[error("invalid design: {0}")]
    Invalid(String),
    #[error("scene {0}")]
    Scene(String),
    #[error("rendering the scene to count its work failed: {0}")]
    Render(String),
    #[error("calibration: {0}")]
    Fit(String),
}
