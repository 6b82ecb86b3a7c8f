//! `sweep-merge`: gathers every job's result file into results.csv, results.json,
//! results.md and the plots, adding what needs several points at once: lanes that fit an
//! XC7Z020 (from the 1- and 2-lane synthesis), estimated resources of the other lane counts,
//! and the projected ZedBoard frame time (one calibration for all points).

use anyhow::{bail, Result};
use hdl::top::fit::{fit_from, LaneFit, XC7Z020};

use super::config::{Stage, SweepConfig};
use super::hardware::PointResult;
use super::layout::{read_json, write_json, Layout};
use super::plots;
use super::projection::Projector;
use super::quality::{Psnr, QualityResult};
use super::table::{self, ResourceSource, Results, Row};

/// Reads the results in `layout`, writes the merged files, returns them.
pub fn merge(layout: &Layout) -> Result<Results> {
    let config: SweepConfig = read_json(&layout.config())?;
    let mut missing = Vec::new();
    let quality: Vec<QualityResult> = if config.runs(Stage::Quality) {
        config
            .quality_formats()
            .iter()
            .filter_map(|f| read_or_note(&layout.quality_result(f), &mut missing))
            .collect()
    } else {
        Vec::new()
    };
    let points: Vec<PointResult> = config
        .points
        .iter()
        .filter_map(|p| read_or_note(&layout.point_result(&p.id()), &mut missing))
        .collect();
    if !missing.is_empty() {
        bail!(
            "{} result file(s) missing, run their jobs first (manifest.json lists them): {}",
            missing.len(),
            missing.join(", ")
        );
    }
    let projector = if config.runs(Stage::Projection) { Some(Projector::new(&config.projection)?) } else { None };

    let mut rows = Vec::new();
    for p in &points {
        let fit = lane_fit(&points, p);
        let q = quality.iter().find(|q| q.format == p.point.format);
        let cycles_per_test = p.cycles_per_test();
        let projected = match &projector {
            Some(pr) => Some(pr.project(&p.point, p.latency, cycles_per_test)?),
            None => None,
        };
        let (usage, source) = match (&p.synth, &fit) {
            (Some(s), _) => (Some(s.usage()), Some(ResourceSource::Yosys)),
            (None, Some(f)) => {
                let n = p.point.lanes as u64;
                let u = hdl::top::fit::Usage {
                    lut: f.fixed.lut + n * f.per_lane.lut,
                    ff: f.fixed.ff + n * f.per_lane.ff,
                    dsp48e1: f.fixed.dsp48e1 + n * f.per_lane.dsp48e1,
                    bram18: f.fixed.bram18 + n * f.per_lane.bram18,
                };
                (Some(u), Some(ResourceSource::Estimate))
            }
            (None, None) => (None, None),
        };
        rows.push(Row {
            id: p.point.id(),
            format: p.point.format.clone(),
            bits: p.bits,
            depth: p.point.depth,
            lanes: p.point.lanes,
            latency: p.latency,
            cycles_per_test,
            cycles_measured: !p.cosim.is_empty(),
            lut: usage.map(|u| u.lut),
            ff: usage.map(|u| u.ff),
            dsp48e1: usage.map(|u| u.dsp48e1),
            bram18: usage.map(|u| u.bram18),
            carry4: p.synth.as_ref().map(|s| s.carry4),
            logic_depth: p.synth.as_ref().map(|s| s.logic_depth),
            resources: source,
            lanes_fit: fit.map(|f| f.lanes),
            fit_limit: fit.map(|f| f.limit.to_string()),
            min_psnr_db: q.map(|q| Psnr(q.min_psnr_db())),
            max_differing_share: q.map(QualityResult::max_differing_share),
            cosim_identical: p.cosim_identical(),
            projected_frame_s: projected.map(|x| x.frame_s),
            speedup_vs_arm: projected.map(|x| x.speedup_vs_arm),
        });
    }
    let results = Results {
        rows,
        quality,
        model_formats: config.model_formats.clone(),
        arm_only_s: projector.as_ref().map(Projector::arm_only_s),
        projected_frame: projector.as_ref().map(|_| {
            let s = &config.projection;
            format!("{} at {}x{}, f_PL {} MHz", s.scene, s.width, s.height, s.fpl_mhz)
        }),
        scenes: config.scenes.iter().map(|s| s.label.clone()).collect(),
        image_size: format!("{}x{}", config.width, config.height),
    };
    table::write_csv(&results.rows, &layout.results("csv"))?;
    write_json(&layout.results("json"), &results)?;
    std::fs::write(layout.results("md"), table::markdown(&results)?)?;
    plots::write_all(&results, layout)?;
    Ok(results)
}

fn read_or_note<T: serde::de::DeserializeOwned>(path: &std::path::Path, missing: &mut Vec<String>) -> Option<T> {
    if !path.exists() {
        missing.push(path.display().to_string());
        return None;
    }
    match read_json(path) {
        Ok(v) => Some(v),
        Err(e) => {
            missing.push(format!("{} ({e:#})", path.display()));
            None
        }
    }
}

/// The XC7Z020 lane fit of `p`'s format and depth, when both its 1- and 2-lane designs were
/// synthesised.
fn lane_fit(points: &[PointResult], p: &PointResult) -> Option<LaneFit> {
    let usage = |lanes: usize| {
        points
            .iter()
            .find(|o| o.point.format == p.point.format && o.point.depth == p.point.depth && o.point.lanes == lanes)
            .and_then(|o| o.synth.as_ref())
            .map(|s| s.usage())
    };
    Some(fit_from(usage(1)?, usage(2)?, &XC7Z020))
}
