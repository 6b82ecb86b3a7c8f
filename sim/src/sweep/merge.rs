//! `sweep-merge`: gathers every job's result file into results.csv, results.json,
//! results.md and the plots, adding what needs several points at once: lanes that fit an
//! XC7Z020 (from the 1- and 2-lane synthesis), estimated resources of the other lane counts,
//! and the projected ZedBoard frame time (one calibration for all points).
//!
//! A format and depth with only its 1-lane design synthesised borrows the fixed part (AXI-Lite
//! slave, stream front end) from the same format's 1- and 2-lane pair at the nearest depth:
//! two yosys runs per depth would double the sweep's longest stage.

use anyhow::{bail, Result};
use hdl::top::fit::{fit_from, fit_with_fixed, LaneFit, Usage, XC7Z020};

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
        let (fit, fixed_part_depth) = match lane_fit(&points, p) {
            Some((fit, depth)) => (Some(fit), Some(depth)),
            None => (None, None),
        };
        let q = quality.iter().find(|q| q.format == p.point.format);
        let cycles_per_test = p.cycles_per_test();
        let projected = match &projector {
            Some(pr) => Some(pr.project(&p.point, p.latency, cycles_per_test)?),
            None => None,
        };
        let (usage, source) = match (&p.synth, &fit) {
            (Some(s), _) => (Some(s.usage()), Some(ResourceSource::Yosys)),
            (None, Some(f)) => {
                (Some(Usage::with_lanes(f.fixed, f.per_lane, p.point.lanes as u64)), Some(ResourceSource::Estimate))
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
            fixed_part_depth,
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

/// The XC7Z020 lane fit of `p`'s format and depth and the depth its fixed part comes from:
/// its own when both its 1- and 2-lane designs were synthesised, else the nearest depth of the
/// same format that has both (with this depth's 1-lane design).
fn lane_fit(points: &[PointResult], p: &PointResult) -> Option<(LaneFit, usize)> {
    let usage = |depth: usize, lanes: usize| {
        points
            .iter()
            .find(|o| o.point.format == p.point.format && o.point.depth == depth && o.point.lanes == lanes)
            .and_then(|o| o.synth.as_ref())
            .map(|s| s.usage())
    };
    let depth = p.point.depth;
    let one = usage(depth, 1)?;
    if let Some(two) = usage(depth, 2) {
        return Some((fit_from(one, two, &XC7Z020), depth));
    }
    let mut depths: Vec<usize> = points.iter().filter(|o| o.point.format == p.point.format).map(|o| o.point.depth).collect();
    depths.sort_by_key(|&d| (d.abs_diff(depth), d));
    depths.dedup();
    depths.into_iter().find_map(|d| {
        let fixed = fit_from(usage(d, 1)?, usage(d, 2)?, &XC7Z020).fixed;
        Some((fit_with_fixed(one, fixed, &XC7Z020), d))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::point::Point;
    use crate::sweep::synth_cache::SynthRecord;

    fn synthesised(format: &str, depth: usize, lanes: usize, lut: u64, dsp48e1: u64) -> PointResult {
        PointResult {
            point: Point::new(format, depth, lanes),
            bits: 32,
            latency: 0,
            stream_latency: None,
            verilog_bytes: None,
            synth: Some(SynthRecord {
                lut,
                ff: 1000 * lanes as u64,
                dsp48e1,
                carry4: 0,
                bram18: 4 * lanes as u64,
                logic_depth: 9,
                seconds: 0,
                verilog_sha256: String::new(),
            }),
            synth_cached: false,
            cosim: Vec::new(),
            seconds: 0.0,
        }
    }

    #[test]
    fn a_depth_without_its_two_lane_design_borrows_the_nearest_fixed_part() {
        // Depth 1: fixed 2000 LUT + 10000 per lane; depth 6: 2000 LUT + 9000 per lane, no 2-lane
        // design; depth 9 (farther) would give another fixed part.
        let points = vec![
            synthesised("fp32", 1, 1, 12_000, 54),
            synthesised("fp32", 1, 2, 22_000, 108),
            synthesised("fp32", 6, 1, 11_000, 54),
            synthesised("fp32", 9, 1, 10_000, 54),
            synthesised("fp32", 9, 2, 15_000, 108),
            synthesised("fp16", 6, 1, 5_000, 27),
            synthesised("fp16", 6, 2, 9_000, 54),
        ];
        let (own, own_depth) = lane_fit(&points, &points[0]).unwrap();
        assert_eq!((own.fixed.lut, own.per_lane.lut, own_depth), (2000, 10_000, 1));
        let (borrowed, from) = lane_fit(&points, &points[2]).unwrap();
        assert_eq!(from, 9, "depth 9 is nearer to 6 than depth 1");
        assert_eq!((borrowed.fixed.lut, borrowed.per_lane.lut), (5000, 6000));
        // fp16's pair at depth 6 is another format's: never borrowed across formats.
        let lone = synthesised("fp24", 6, 1, 8000, 27);
        assert!(lane_fit(&[lone.clone()], &lone).is_none());
        // A point whose 1-lane design was not synthesised has no fit.
        let mut unsynthesised = points[2].clone();
        unsynthesised.synth = None;
        assert!(lane_fit(&[unsynthesised.clone(), points[0].clone(), points[1].clone()], &unsynthesised).is_none());
    }
}
