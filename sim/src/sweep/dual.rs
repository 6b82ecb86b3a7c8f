//! The `dual/FILTER/FALLBACK` job: every scene through a dual-precision pair's model under
//! each spawn policy. The pair must answer exactly as its fallback, so each render is compared
//! with the fallback's model render under the same policy (0 differing pixels expected) and
//! with the f32 reference (PSNR); the share of tests the filter forwards is the pair's
//! `DualIntersector::stats`, what `rtfpga render --format FILTER/FALLBACK` prints. There is no
//! dual-precision hardware, so a pair has no points.

use anyhow::{Context, Result};
use hw_model::dual::{DualIntersector, FormatPair};
use hw_model::precision::SpawnChoice;
use hw_model::ModelIntersector;
use serde::{Deserialize, Serialize};
use sw_renderer::compare::compare;
use sw_renderer::render::save_png;

use super::config::SweepConfig;
use super::layout::{parent_dir, write_json, Layout};
use super::quality::Psnr;
use super::render_job::{reference, render_scene};

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
    /// As `FormatPair` prints it (`fp16/fp32`).
    pub pair: String,
    /// Width of the filter format in bits.
    pub filter_bits: u32,
    pub policy: SpawnChoice,
    pub scenes: Vec<DualScene>,
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

/// Every policy of the sweep through `pair`, each written to its result file.
pub fn run(config: &SweepConfig, layout: &Layout, pair: &str) -> Result<Vec<DualResult>> {
    let parsed = FormatPair::parse(pair)?;
    let fallback = ModelIntersector::new(parsed.fallback);
    let mut results = Vec::new();
    for &policy in &config.policies {
        // The pair answers as its fallback, so it spawns as the fallback does.
        let spawn = policy.policy(&parsed.fallback, 0);
        let dir = layout.dual_dir(pair, policy);
        let mut scenes = Vec::new();
        for scene in &config.scenes {
            // One intersector per scene: its counters are the scene's.
            let dual = DualIntersector::new(parsed, 0)?;
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
        let result = DualResult {
            pair: pair.to_string(),
            filter_bits: parsed.filter.width(),
            policy,
            scenes,
        };
        write_json(&layout.dual_result(pair, policy), &result)?;
        results.push(result);
    }
    Ok(results)
}
