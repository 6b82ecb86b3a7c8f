//! Engine selection shared by the subcommands that render: which `Intersector` answers the
//! renderer's ray-triangle queries.

use anyhow::Result;
use clap::{Args as ClapArgs, ValueEnum};
use hdl::top::TopConfig;
use sim::hw_intersector::{HwIntersector, Mode};
use sw_renderer::intersect::{F32Intersector, Intersector, MtQuery, MtResult};
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
    /// Number format of the datapath: a catalogue name (`rtfpga formats`), or for the model
    /// engine any spelling such as e8m14 or fx<24,8>.
    #[arg(long, default_value = "fp32")]
    pub format: hw_model::Format,
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
        EngineKind::Model => Box::new(ModelIntersector { format: hw.format }),
        EngineKind::Hw => Box::new(FailFast(HwIntersector::new(
            &hw.top_config()?,
            Mode::Stream,
        )?)),
    })
}

impl HwConfig {
    /// The accelerator of this configuration: an error if the format has no hardware.
    pub fn top_config(&self) -> Result<TopConfig, hw_model::FormatError> {
        Ok(TopConfig::new(
            self.format.try_into()?,
            self.depth,
            self.lanes,
        ))
    }
}

/// The hardware engine for commands that only see an `Intersector`: a simulation error
/// (which the trait cannot return) ends the process with the error instead of letting the
/// render finish with misses in its place.
struct FailFast(HwIntersector);

impl Intersector for FailFast {
    fn name(&self) -> String {
        self.0.name()
    }

    fn intersect_batch(&self, queries: &[MtQuery], results: &mut [MtResult]) {
        self.0.intersect_batch(queries, results);
        if let Some(e) = self.0.take_error() {
            eprintln!("error: hardware co-simulation ({}): {e}", self.0.name());
            std::process::exit(1);
        }
    }
}
