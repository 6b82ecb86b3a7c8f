//! The `point/ID` job: one accelerator configuration. Its Verilog, its latency, yosys'
//! resources and logic depth (if the config selects it) and co-simulation of the configured
//! scenes (if selected), which must give exactly the model engine's images.

use std::time::Instant;

use anyhow::{Context, Result};
use hdl::generate::{generate, VERILOG_FILE};
use hw_model::precision::SpawnChoice;
use hw_model::ModelIntersector;
use serde::{Deserialize, Serialize};
use sw_renderer::compare::compare;
use sw_renderer::render::save_png;

use crate::hw_intersector::{HwIntersector, Mode};

use super::config::{Stage, SweepConfig};
use super::layout::{parent_dir, write_json, Layout};
use super::point::Point;
use super::render_job::render_scene;
use super::synth_cache::{synthesize_cached, SynthRecord};

/// Co-simulation of one scene under one spawn policy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CosimRecord {
    pub scene: String,
    pub policy: SpawnChoice,
    pub tests: u64,
    /// Simulated clock cycles (stream mode).
    pub cycles: u64,
    pub cycles_per_test: f64,
    /// Pixels where the hardware's image differs from the model engine's (0 = identical).
    pub differing_from_model: u64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    pub point: Point,
    pub bits: u32,
    /// Cycles from a query entering a lane to its result.
    pub latency: usize,
    /// Cycles from an accepted stream beat to its results (when the Verilog was generated).
    pub stream_latency: Option<usize>,
    /// Size of the generated rtfpga_top.v (when generated).
    pub verilog_bytes: Option<u64>,
    pub synth: Option<SynthRecord>,
    /// Whether the synthesis came from the cache.
    pub synth_cached: bool,
    pub cosim: Vec<CosimRecord>,
    pub seconds: f64,
}

impl PointResult {
    /// Stream-mode cycles per test: measured where co-simulated, else the pipelined ideal
    /// (every lane takes a query each cycle).
    pub fn cycles_per_test(&self) -> f64 {
        let tests: u64 = self.cosim.iter().map(|c| c.tests).sum();
        if tests == 0 {
            return 1.0 / self.point.lanes as f64;
        }
        self.cosim.iter().map(|c| c.cycles).sum::<u64>() as f64 / tests as f64
    }

    /// None when not co-simulated.
    pub fn cosim_identical(&self) -> Option<bool> {
        (!self.cosim.is_empty()).then(|| self.cosim.iter().all(|c| c.differing_from_model == 0))
    }
}

pub fn run(config: &SweepConfig, layout: &Layout, point: &Point) -> Result<PointResult> {
    let start = Instant::now();
    let top = point.top_config();
    let id = point.id();
    let latency = top.lane_latency()?;
    let mut verilog_bytes = None;
    let mut stream_latency = None;
    let mut synth = None;
    let mut synth_cached = false;
    if config.runs(Stage::Verilog) || config.synthesises(point) {
        let generated =
            generate(&top).with_context(|| format!("generating the Verilog of {id}"))?;
        let verilog = generated
            .file(VERILOG_FILE)
            .context("generated files lack the Verilog")?;
        verilog_bytes = Some(verilog.len() as u64);
        stream_latency = Some(generated.summary.stream_latency);
        if config.keep_verilog {
            generated.write_to(&layout.point_dir(&id).join("verilog"))?;
        }
        if config.synthesises(point) {
            let (record, cached) = synthesize_cached(layout, &id, hdl::top::wrapper::TOP, verilog)
                .with_context(|| format!("synthesising {id}"))?;
            synth = Some(record);
            synth_cached = cached;
        }
    }
    let cosim = if config.cosimulates(point) {
        cosimulate(config, layout, point)?
    } else {
        Vec::new()
    };
    let result = PointResult {
        point: point.clone(),
        bits: point.bits(),
        latency,
        stream_latency,
        verilog_bytes,
        synth,
        synth_cached,
        cosim,
        seconds: start.elapsed().as_secs_f64(),
    };
    write_json(&layout.point_result(&id), &result)?;
    Ok(result)
}

/// Every co-simulated scene under every policy of the sweep (the format-aware policy's
/// t_min and excluded triangle travel in the stream packet).
fn cosimulate(config: &SweepConfig, layout: &Layout, point: &Point) -> Result<Vec<CosimRecord>> {
    let hw = HwIntersector::new(&point.top_config(), Mode::Stream)
        .with_context(|| format!("building the Verilated model of {}", point.id()))?;
    let format = point.format.format();
    // The hardware lanes do not advance the origin: they equal the plain model lane.
    let model = ModelIntersector::new(format);
    let mut records = Vec::new();
    for &policy in &config.policies {
        let spawn = policy.policy(&format, 0);
        for scene in &config.cosim_scenes {
            let before = hw.stats();
            let out = render_scene(config, scene, &hw, spawn).with_context(|| {
                format!("co-simulating {} on {} ({policy})", point.id(), scene.label)
            })?;
            let after = hw.stats();
            let png = layout.point_dir(&point.id()).join(format!(
                "cosim_{}_{}.png",
                scene.label,
                policy.name()
            ));
            parent_dir(&png)?;
            save_png(&out.image, &png)?;
            let expected = render_scene(config, scene, &model, spawn)?;
            let diff = compare(&out.image, &expected.image)?;
            let tests = after.tests - before.tests;
            let cycles = after.cycles - before.cycles;
            records.push(CosimRecord {
                scene: scene.label.clone(),
                policy,
                tests,
                cycles,
                cycles_per_test: cycles as f64 / tests.max(1) as f64,
                differing_from_model: diff.differing_pixels,
            });
        }
    }
    Ok(records)
}
