//! Engine selection shared by the subcommands that render: which `RayEngine` answers the
//! renderer's rays.

use anyhow::Result;
use clap::{Args as ClapArgs, ValueEnum};
use hdl::top::TopConfig;
use hw_model::traversal::{TraversalEngine, DEFAULT_STACK_DEPTH};
use hw_model::ModelIntersector;
use sim::hw_intersector::{HwIntersector, Mode};
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::RayEngine;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineKind {
    /// The reference Möller-Trumbore in native f32.
    F32,
    /// The bit-accurate model of the hardware arithmetic in `--format`.
    Model,
    /// The Verilated accelerator (co-simulation).
    Hw,
    /// The traversal unit's bit-accurate model: BVH and triangles in the unit's scene
    /// memory, rays in, hits out; Möller-Trumbore in `--format`.
    Traversal,
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
    /// Ray slots of the traversal unit (`--engine traversal`: its schedule model's cycles).
    #[arg(long, default_value_t = hdl::traversal::timing::DEFAULT_SLOTS as u32,
          value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub slots: u32,
}

pub fn make(kind: EngineKind, hw: &HwConfig) -> Result<Box<dyn RayEngine>> {
    Ok(match kind {
        EngineKind::F32 => Box::new(F32Intersector),
        EngineKind::Model => Box::new(ModelIntersector { format: hw.format }),
        EngineKind::Hw => Box::new(HwIntersector::new(&hw.top_config()?, Mode::Stream)?),
        EngineKind::Traversal => Box::new(hw.traversal_engine()),
    })
}

impl HwConfig {
    /// The traversal unit's model in this configuration; timed by its schedule model when
    /// the format has hardware (any other format has no lane latency to time with).
    pub fn traversal_engine(&self) -> TraversalEngine {
        let timing = hw_model::HwFormat::try_from(self.format).ok().map(|f| {
            hdl::traversal::timing::unit_timing(f, self.depth, self.lanes, self.slots as usize)
        });
        TraversalEngine {
            format: self.format,
            stack_depth: DEFAULT_STACK_DEPTH,
            timing,
        }
    }

    /// The accelerator of this configuration: an error if the format has no hardware.
    pub fn top_config(&self) -> Result<TopConfig, hw_model::FormatError> {
        Ok(TopConfig::new(
            self.format.try_into()?,
            self.depth,
            self.lanes,
        ))
    }
}
