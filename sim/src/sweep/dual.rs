//! The `dual/FILTER/FALLBACK` job: every scene through a dual-precision pair's model under
//! each spawn policy. The pair must answer exactly as its fallback, so each render is compared
//! with the fallback's model render under the same policy (0 differing pixels expected) and
//! with the f32 reference (PSNR); the share of tests the filter forwards is the pair's
//! `DualIntersector::stats`, what `rtfpga render --format FILTER/FALLBACK` prints.
//!
//! The pair built in hardware (`sim::dual_pair`, bfp18/fp32) also gets its hardware: with the
//! `synth` stage yosys' resources of one and two filter slots beside the fp32 lane at fp32's
//! deepest pipeline (what the slot fit needs), with the `cosim` stage the co-simulation
//! scenes through the Verilated pair at every built slot count, whose images must equal
//! the fallback's.

use anyhow::{Context, Result};
use hdl::top::fit::{fit_from, LaneFit, XC7Z020};
use hw_model::dual::{DualIntersector, FormatPair};
use hw_model::precision::SpawnChoice;
use hw_model::{HwFormat, ModelIntersector};
use serde::{Deserialize, Serialize};
use sw_renderer::compare::compare;
use sw_renderer::render::save_png;

use super::config::{Stage, SweepConfig};
use super::layout::{parent_dir, write_json, Layout};
use super::quality::Psnr;
use super::render_job::{reference, render_scene};
use super::synth_cache::{synthesize_cached, SynthRecord};
use hdl::dual::pair::SlotFilter;

use crate::dual_pair::{built_pair, pair_verilog, PairConfig, PairIntersector};

/// The slot counts the sweep co-simulates its bfp pair at: up to four, where the fp32 lane
/// saturates at the thesis scenes' forwarded share (docs/precision.md).
pub const COSIM_SLOTS: std::ops::RangeInclusive<usize> = 1..=4;

/// One scene through one pair.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DualScene {
    pub scene: String,
    /// Möller-Trumbore tests, and those the filter could not decide (answered by the fallback).
    pub tests: u64,
    pub forwarded: u64,
    pub forwarded_share: f64,
    /// Pixels that differ from the fallback's model render (0: the pair is exact).
    pub differing_from_fallback: u64,
    /// Against the f32 reference.
    pub psnr_db: Psnr,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DualResult {
    /// As `FormatPair` prints it (`bfp18/fp32`).
    pub pair: String,
    /// Width of the filter format in bits.
    pub filter_bits: u32,
    pub policy: SpawnChoice,
    pub scenes: Vec<DualScene>,
    /// The pair's hardware, if it is built (`sim::dual_pair`).
    pub hardware: Option<PairHardware>,
}

/// yosys' resources of a pair with `slots` filter slots.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PairSynth {
    pub slots: usize,
    pub synth: SynthRecord,
    pub cached: bool,
}

/// One co-simulation scene through the Verilated pair with `slots` filter slots.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairCosim {
    pub scene: String,
    pub slots: usize,
    pub tests: u64,
    pub forwarded: u64,
    pub cycles: u64,
    pub tests_per_cycle: f64,
    /// Cycles in which `ready` held a slot's query back.
    pub stall_cycles: u64,
    /// Pixels that differ from the fallback's model render (0: the hardware is exact).
    pub differing_from_fallback: u64,
}

/// A built pair's hardware at the fp32 lane's `depth`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairHardware {
    pub depth: usize,
    /// One and two slots (`synth` stage), else empty.
    pub synth: Vec<PairSynth>,
    /// Every built slot count on the co-simulation scenes (`cosim` stage), else empty.
    pub cosim: Vec<PairCosim>,
}

impl PairHardware {
    /// The slots that fit the XC7Z020 beside the fp32 lane, from the one- and two-slot
    /// designs (the fixed part is the fp32 lane and the arbiter).
    pub fn fit(&self) -> Option<LaneFit> {
        let usage = |slots| {
            let s = self.synth.iter().find(|s| s.slots == slots)?;
            Some(s.synth.usage())
        };
        Some(fit_from(usage(1)?, usage(2)?, &XC7Z020))
    }

    /// Tests per cycle over the co-simulated scenes with `slots` slots.
    pub fn tests_per_cycle(&self, slots: usize) -> Option<f64> {
        let runs = self.cosim.iter().filter(|c| c.slots == slots);
        let (tests, cycles) = runs.fold((0, 0), |(t, c), r| (t + r.tests, c + r.cycles));
        (cycles > 0).then(|| tests as f64 / cycles as f64)
    }
}

/// The fp32 lane's depth of the sweep's pair: fp32's deepest pipeline, as the sweep
/// synthesises the formats.
fn pair_depth() -> usize {
    hdl::mt::max_depth(HwFormat::named("fp32"))
}

/// yosys' resources of the one- and two-slot pairs (cached by their Verilog).
fn synthesise_pair(layout: &Layout, depth: usize) -> Result<Vec<PairSynth>> {
    [1, 2]
        .into_iter()
        .map(|slots| {
            let config = PairConfig {
                slots,
                depth,
                filter: SlotFilter::Bfp,
            };
            let verilog = pair_verilog(&config)?;
            let id = format!(
                "pair_{}_d{depth}_s{slots}",
                built_pair().to_string().replace('/', "_")
            );
            let (synth, cached) = synthesize_cached(layout, &id, hdl::verilog::TOP, &verilog)
                .with_context(|| format!("synthesising {config}"))?;
            Ok(PairSynth {
                slots,
                synth,
                cached,
            })
        })
        .collect()
}

impl DualResult {
    /// Forwarded tests over all scenes' tests.
    pub fn forwarded_share(&self) -> f64 {
        let tests: u64 = self.scenes.iter().map(|s| s.tests).sum();
        let forwarded: u64 = self.scenes.iter().map(|s| s.forwarded).sum();
        forwarded as f64 / tests.max(1) as f64
    }

    /// Every image equals the fallback's.
    pub fn exact(&self) -> bool {
        self.scenes.iter().all(|s| s.differing_from_fallback == 0)
    }

    pub fn min_psnr_db(&self) -> f64 {
        self.scenes
            .iter()
            .map(|s| s.psnr_db.0)
            .fold(f64::INFINITY, f64::min)
    }
}

/// Whether `pair` (as the sweep file spells it) is the pair built in hardware, whose job
/// also synthesises and co-simulates it.
pub fn has_hardware(pair: &str) -> bool {
    FormatPair::parse(pair).is_ok_and(|p| p == built_pair())
}

/// Every policy of the sweep through `pair`, each written to its result file.
pub fn run(config: &SweepConfig, layout: &Layout, pair: &str) -> Result<Vec<DualResult>> {
    let parsed = FormatPair::parse(pair)?;
    let fallback = ModelIntersector::new(parsed.fallback);
    let hardware = has_hardware(pair);
    let depth = pair_depth();
    let synth = if hardware && config.runs(Stage::Synth) {
        synthesise_pair(layout, depth)?
    } else {
        Vec::new()
    };
    let mut results = Vec::new();
    for &policy in &config.policies {
        // The pair answers as its fallback, so it spawns as the fallback does.
        let spawn = policy.policy(&parsed.fallback, 0);
        let dir = layout.dual_dir(pair, policy);
        let mut scenes = Vec::new();
        for scene in &config.scenes {
            // One intersector per scene: its counters are the scene's.
            let dual = DualIntersector::new(parsed);
            let out = render_scene(config, scene, &dual, spawn)?;
            let stats = dual.stats();
            let expected = render_scene(config, scene, &fallback, spawn)?;
            let exact = compare(&out.image, &expected.image).with_context(|| {
                format!("comparing {pair} with its fallback on {}", scene.label)
            })?;
            let against_f32 = compare(&out.image, &reference(layout, scene)?)?;
            let path = dir.join(format!("{}.png", scene.label));
            parent_dir(&path)?;
            save_png(&out.image, &path)?;
            scenes.push(DualScene {
                scene: scene.label.clone(),
                tests: stats.tests,
                forwarded: stats.forwarded(),
                forwarded_share: stats.forwarded_share(),
                differing_from_fallback: exact.differing_pixels,
                psnr_db: Psnr(against_f32.psnr_db),
            });
        }
        let cosim = if hardware && config.runs(Stage::Cosim) {
            cosimulate(config, depth, spawn, &fallback)?
        } else {
            Vec::new()
        };
        let result = DualResult {
            pair: pair.to_string(),
            filter_bits: parsed.filter_width,
            policy,
            scenes,
            hardware: hardware.then(|| PairHardware {
                depth,
                synth: synth.clone(),
                cosim,
            }),
        };
        write_json(&layout.dual_result(pair, policy), &result)?;
        results.push(result);
    }
    Ok(results)
}

/// The co-simulation scenes through the Verilated pair at every built slot count, each
/// image compared with the fallback's model render.
fn cosimulate(
    config: &SweepConfig,
    depth: usize,
    spawn: sw_renderer::spawn::SpawnPolicy,
    fallback: &ModelIntersector,
) -> Result<Vec<PairCosim>> {
    let mut records = Vec::new();
    for slots in COSIM_SLOTS {
        let pair = PairConfig {
            slots,
            depth,
            filter: SlotFilter::Bfp,
        };
        let hw = PairIntersector::new(&pair)
            .with_context(|| format!("building the Verilated {pair}"))?;
        for scene in &config.cosim_scenes {
            let before = hw.stats();
            let out = render_scene(config, scene, &hw, spawn)?;
            let s = hw.stats();
            let expected = render_scene(config, scene, fallback, spawn)?;
            let diff = compare(&out.image, &expected.image)?;
            let (tests, cycles) = (s.tests - before.tests, s.cycles - before.cycles);
            records.push(PairCosim {
                scene: scene.label.clone(),
                slots,
                tests,
                forwarded: s.forwarded - before.forwarded,
                cycles,
                tests_per_cycle: tests as f64 / cycles.max(1) as f64,
                stall_cycles: s.stall_cycles - before.stall_cycles,
                differing_from_fallback: diff.differing_pixels,
            });
        }
    }
    Ok(records)
}
