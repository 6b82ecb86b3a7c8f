//! The `quality/FORMAT` job: every scene through the model engine in one format under each
//! variant (spawn policy and origin advance, `SweepConfig::variants`), against the f32
//! reference: PSNR, share of differing pixels, the renders, error heat-maps and an image grid
//! per variant. The model is bit-accurate to the hardware at every depth and lane count, so
//! quality is a property of the format and the variant alone and is computed once per pair of
//! them. The hardware lanes have no origin advance: only the `advance none` results are the
//! hardware's.

use std::time::Instant;

use anyhow::Result;
use hw_model::precision::SpawnChoice;
use hw_model::{Advance, ModelIntersector};
use serde::{Deserialize, Serialize};
use sw_renderer::compare::{compare, diff_heatmap};
use sw_renderer::render::save_png;

use super::config::{SweepConfig, Variant};
use super::grid::write_grid;
use super::layout::{parent_dir, write_json, Layout};
use super::point::format_bits;
use super::render_job::{reference, render_scene};

/// One scene in one format.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneQuality {
    pub scene: String,
    /// Against the f32 reference; infinite when identical.
    pub psnr_db: Psnr,
    pub differing_pixels: u64,
    /// 0…1.
    pub differing_share: f64,
    pub max_abs_error: u8,
    pub mt_queries: u64,
    pub render_s: f64,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QualityResult {
    pub format: String,
    pub bits: u32,
    pub policy: SpawnChoice,
    /// The model lane's; none is the hardware lanes'.
    pub advance: Advance,
    pub scenes: Vec<SceneQuality>,
}

impl QualityResult {
    pub fn variant(&self) -> Variant {
        Variant {
            policy: self.policy,
            advance: self.advance,
        }
    }

    /// The worst scene's PSNR.
    pub fn min_psnr_db(&self) -> f64 {
        self.scenes
            .iter()
            .map(|s| s.psnr_db.0)
            .fold(f64::INFINITY, f64::min)
    }

    pub fn max_differing_share(&self) -> f64 {
        self.scenes
            .iter()
            .map(|s| s.differing_share)
            .fold(0.0, f64::max)
    }
}

/// Every variant of the sweep in `format`, each written to its result file.
pub fn run(config: &SweepConfig, layout: &Layout, format: &str) -> Result<Vec<QualityResult>> {
    let parsed = hw_model::lookup(format)?;
    let mut results = Vec::new();
    for variant in config.variants() {
        let isect = ModelIntersector {
            advance: variant.advance,
            ..ModelIntersector::new(parsed)
        };
        let spawn = variant.policy.policy(&parsed, 0);
        let mut scenes = Vec::new();
        let mut grid_rows = Vec::new();
        let dir = layout.quality_dir(format, variant);
        for scene in &config.scenes {
            let reference = reference(layout, scene)?;
            let start = Instant::now();
            let out = render_scene(config, scene, &isect, spawn)?;
            let render_s = start.elapsed().as_secs_f64();
            let diff = compare(&out.image, &reference)?;
            let heatmap = diff_heatmap(&out.image, &reference)?;
            let render_path = dir.join(format!("{}.png", scene.label));
            parent_dir(&render_path)?;
            save_png(&out.image, &render_path)?;
            save_png(&heatmap, &dir.join(format!("{}_diff.png", scene.label)))?;
            grid_rows.push([out.image, heatmap]);
            scenes.push(SceneQuality {
                scene: scene.label.clone(),
                psnr_db: Psnr(diff.psnr_db),
                differing_pixels: diff.differing_pixels,
                differing_share: diff.differing_share,
                max_abs_error: diff.max_abs_error,
                mt_queries: out.stats.trace.cast.mt_tests,
                render_s,
            });
        }
        write_grid(&grid_rows, &layout.grid(format, variant))?;
        let result = QualityResult {
            format: format.to_string(),
            bits: format_bits(format),
            policy: variant.policy,
            advance: variant.advance,
            scenes,
        };
        write_json(&layout.quality_result(format, variant), &result)?;
        results.push(result);
    }
    Ok(results)
}

/// A PSNR in dB that serialises infinity (identical images) as the string "inf", which JSON
/// and CSV readers both take, instead of JSON's null.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Psnr(pub f64);

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum PsnrRepr {
    Number(f64),
    Word(String),
}

impl Serialize for Psnr {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0 == f64::INFINITY {
            PsnrRepr::Word("inf".into()).serialize(s)
        } else {
            PsnrRepr::Number(self.0).serialize(s)
        }
    }
}

impl<'de> Deserialize<'de> for Psnr {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Psnr, D::Error> {
        match PsnrRepr::deserialize(d)? {
            PsnrRepr::Number(x) => Ok(Psnr(x)),
            PsnrRepr::Word(w) if w == "inf" => Ok(Psnr(f64::INFINITY)),
            PsnrRepr::Word(w) => Err(serde::de::Error::custom(format!(
                "PSNR `{w}`: expected a number or \"inf\""
            ))),
        }
    }
}

impl std::fmt::Display for Psnr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_infinite() {
            f.write_str("inf")
        } else {
            write!(f, "{:.2}", self.0)
        }
    }
}
