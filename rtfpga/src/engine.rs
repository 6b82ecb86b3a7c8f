//! Engine selection shared by the subcommands that render: which `Intersector` answers the
//! renderer's ray-triangle queries.

use anyhow::{bail, Result};
use clap::{Args as ClapArgs, ValueEnum};
use sw_renderer::intersect::{F32Intersector, Intersector};
use sw_renderer::model_engine::ModelIntersector;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineKind {
    /// The reference Möller-Trumbore in native f32.
    F32,
    /// The bit-accurate model of the hardware arithmetic in `--format`.
    Model,
    /// The Verilated accelerator (co-simulation).
    Hw,
}

/// The hardware configuration: number format, pipeline depth, lanes.
#[derive(ClapArgs, Clone, Debug)]
pub struct HwConfig {
    /// Number format of the datapath (`rtfpga formats` lists them).
    #[arg(long, default_value = "fp32")]
    pub format: String,
    /// Pipeline registers per operator.
    #[arg(long, default_value_t = 1)]
    pub depth: usize,
    /// Parallel MT lanes.
    #[arg(long, default_value_t = 1)]
    pub lanes: usize,
}

pub fn make(kind: EngineKind, hw: &HwConfig) -> Result<Box<dyn Intersector>> {
    Ok(match kind {
        EngineKind::F32 => Box::new(F32Intersector),
        EngineKind::Model => Box::new(ModelIntersector { format: hw_model::lookup(&hw.format)? }),
        EngineKind::Hw => bail!("the hardware engine is not available yet: co-simulation is issue 5"),
    })
}
