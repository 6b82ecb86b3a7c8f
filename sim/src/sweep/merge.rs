//! `sweep-merge`: gathers every job's result file into results.csv, quality.csv,
//! results.json, results.md and the plots, adding what needs several points at once: lanes that fit an
//! XC7Z020 (from the 1- and 2-lane synthesis), estimated resources of the other lane counts,
//! and the projected ZedBoard frame time (one calibration for all points).
//!
//! A format and depth with only its 1-lane design synthesised borrows the fixed part (AXI-Lite
//! slave, stream front end: the same blocks whatever the format) from the nearest 1- and
//! 2-lane pair: the same format at the nearest depth, else the same kind (float or fixed) at
//! the nearest width. Two yosys runs per point would double the sweep's longest stage.

use anyhow::{bail, Result};
use hdl::top::fit::{fit_from, fit_with_fixed, LaneFit, Usage, XC7Z020};
use hw_model::HwFormat;

use super::config::{Stage, SweepConfig, Variant};
use super::dual::DualResult;
use super::hardware::PointResult;
use super::layout::{read_json, write_json, Layout};
use super::plots;
use super::projection::Projector;
use super::quality::{Psnr, QualityResult};
use super::synth_cache::SynthRecord;
use super::table::{self, ResourceSource, Results, Row};

/// Reads the results in `layout`, writes the merged files, returns them.
pub fn merge(layout: &Layout) -> Result<Results> {
    let config: SweepConfig = read_json(&layout.config())?;
    let mut missing = Vec::new();
    let runs_quality = config.runs(Stage::Quality);
    let mut quality: Vec<QualityResult> = Vec::new();
    let mut dual: Vec<DualResult> = Vec::new();
    if runs_quality {
        for f in config.quality_formats() {
            for variant in config.variants() {
                quality.extend(read_or_note(
                    &layout.quality_result(&f, variant),
                    &mut missing,
                ));
            }
        }
        for pair in &config.pairs {
            for &policy in &config.policies {
                dual.extend(read_or_note(
                    &layout.dual_result(pair, policy),
                    &mut missing,
                ));
            }
        }
    }
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
    let projector = if config.runs(Stage::Projection) {
        Some(Projector::new(&config.projection)?)
    } else {
        None
    };

    // One row per point and variant of the hardware's lane (no origin advance), or per point
    // without quality.
    let hardware_variants: Vec<Variant> = config
        .variants()
        .into_iter()
        .filter(|v| v.in_hardware())
        .collect();
    let variants: Vec<Option<Variant>> = if runs_quality && !hardware_variants.is_empty() {
        hardware_variants.into_iter().map(Some).collect()
    } else {
        vec![None]
    };
    let mut rows = Vec::new();
    for p in &points {
        let (fit, fixed_part_from) = lane_fit(&points, p).unzip();
        let cycles_per_test = p.cycles_per_test();
        let projected = match &projector {
            Some(pr) => Some(pr.project(&p.point, p.latency, cycles_per_test)?),
            None => None,
        };
        let (usage, source) = match (&p.synth, &fit) {
            (Some(s), _) => (Some(s.usage()), Some(ResourceSource::Yosys)),
            (None, Some(f)) => (
                Some(Usage::with_lanes(f.fixed, f.per_lane, p.point.lanes as u64)),
                Some(ResourceSource::Estimate),
            ),
            (None, None) => (None, None),
        };
        for &variant in &variants {
            let q = quality
                .iter()
                .find(|q| q.format == p.point.format.name() && Some(q.variant()) == variant);
            rows.push(Row {
                id: p.point.id(),
                format: p.point.format.to_string(),
                bits: p.bits,
                depth: p.point.depth,
                lanes: p.point.lanes,
                policy: variant.map(|v| v.policy),
                advance: variant.map(|v| v.advance),
                latency: p.latency,
                cycles_per_test,
                cycles_measured: !p.cosim.is_empty(),
                lut: usage.map(|u| u.lut),
                ff: usage.map(|u| u.ff),
                dsp48e1: usage.map(|u| u.dsp48e1),
                bram18: usage.map(|u| u.bram18),
                carry4: p.synth.as_ref().map(|s| s.carry4),
                logic_depth: p.synth.as_ref().map(|s| s.logic_depth),
                fmax_mhz_estimate: p.synth.as_ref().and_then(SynthRecord::fmax_mhz_estimate),
                resources: source,
                lanes_fit: fit.map(|f| f.lanes),
                fit_limit: fit.map(|f| f.limit.to_string()),
                fixed_part_from: fixed_part_from.clone().flatten(),
                min_psnr_db: q.map(|q| Psnr(q.min_psnr_db())),
                max_differing_share: q.map(QualityResult::max_differing_share),
                cosim_identical: p.cosim_identical(),
                projected_frame_s: projected.map(|x| x.frame_s),
                speedup_vs_arm: projected.map(|x| x.speedup_vs_arm),
            });
        }
    }
    let results = Results {
        rows,
        variants: config.variants(),
        quality,
        dual,
        model_formats: config.model_formats.clone(),
        arm_only_s: projector.as_ref().map(Projector::arm_only_s),
        projected_frame: projector.as_ref().map(|_| {
            let s = &config.projection;
            format!(
                "{} at {}x{}, f_PL {} MHz",
                s.scene, s.width, s.height, s.fpl_mhz
            )
        }),
        scenes: config.scenes.iter().map(|s| s.label.clone()).collect(),
        image_size: format!("{}x{}", config.width, config.height),
    };
    table::write_csv(&results.rows, &layout.results("csv"))?;
    table::write_quality_csv(&table::quality_rows(&results), &layout.quality_csv())?;
    write_json(&layout.results("json"), &results)?;
    std::fs::write(layout.results("md"), table::markdown(&results)?)?;
    plots::write_all(&results, layout)?;
    Ok(results)
}

fn read_or_note<T: serde::de::DeserializeOwned>(
    path: &std::path::Path,
    missing: &mut Vec<String>,
) -> Option<T> {
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

/// The XC7Z020 lane fit of `p`'s format and depth, and the pair (`format_dD`) whose fixed part
/// it borrowed: none when both its own 1- and 2-lane designs were synthesised, else the
/// nearest pair (see the module docs), with this point's 1-lane design.
fn lane_fit(points: &[PointResult], p: &PointResult) -> Option<(LaneFit, Option<String>)> {
    let usage = |format: HwFormat, depth: usize, lanes: usize| {
        points
            .iter()
            .find(|o| o.point.format == format && o.point.depth == depth && o.point.lanes == lanes)
            .and_then(|o| o.synth.as_ref())
            .map(|s| s.usage())
    };
    let (format, depth) = (p.point.format, p.point.depth);
    let one = usage(format, depth, 1)?;
    let is_float = |f: HwFormat| matches!(f.format(), hw_model::Format::Float { .. });
    // Every synthesised 1-/2-lane pair, with both usages; the nearest first.
    let mut pairs: Vec<(&PointResult, Usage, Usage)> = points
        .iter()
        .filter(|o| o.point.lanes == 1)
        .filter_map(|o| {
            Some((
                o,
                o.synth.as_ref()?.usage(),
                usage(o.point.format, o.point.depth, 2)?,
            ))
        })
        .collect();
    pairs.sort_by_cached_key(|(o, _, _)| {
        (
            o.point.format != format,
            is_float(o.point.format) != is_float(format),
            o.bits.abs_diff(p.bits),
            o.point.depth.abs_diff(depth),
            o.point.format.name(),
            o.point.depth,
        )
    });
    let &(pair, pair_one, two) = pairs.first()?;
    let (f, d) = (pair.point.format, pair.point.depth);
    if (f, d) == (format, depth) {
        return Some((fit_from(one, two, &XC7Z020), None));
    }
    let fixed = fit_from(pair_one, two, &XC7Z020).fixed;
    Some((
        fit_with_fixed(one, fixed, &XC7Z020),
        Some(format!("{f}_d{d}")),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::point::Point;

    fn synthesised(
        format: &str,
        depth: usize,
        lanes: usize,
        lut: u64,
        dsp48e1: u64,
    ) -> PointResult {
        let point = Point::new(format.parse().unwrap(), depth, lanes);
        PointResult {
            bits: point.bits(),
            point,
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
                critical_path: None,
                seconds: 0,
                verilog_sha256: String::new(),
                routing_model: String::new(),
            }),
            synth_cached: false,
            cosim: Vec::new(),
            seconds: 0.0,
        }
    }

    #[test]
    fn a_point_without_its_two_lane_design_borrows_the_nearest_fixed_part() {
        // fp32 depth 1: fixed 2000 LUT + 10000 per lane; depth 6 has no 2-lane design; depth 9
        // (nearer to 6) gives another fixed part; fp16's and fx16_10's pairs are other formats'.
        let points = vec![
            synthesised("fp32", 1, 1, 12_000, 54),
            synthesised("fp32", 1, 2, 22_000, 108),
            synthesised("fp32", 6, 1, 11_000, 54),
            synthesised("fp32", 9, 1, 10_000, 54),
            synthesised("fp32", 9, 2, 15_000, 108),
            synthesised("fp16", 6, 1, 5_000, 27),
            synthesised("fp16", 6, 2, 9_000, 54),
            synthesised("fx16_10", 1, 1, 4_500, 27),
            synthesised("fx16_10", 1, 2, 8_500, 54),
            synthesised("bf16", 2, 1, 6_000, 27),
            synthesised("fx21_12", 3, 1, 7_000, 54),
        ];
        let fit = |i: usize| lane_fit(&points, &points[i]).unwrap();
        let (own, from) = fit(0);
        assert_eq!(
            (own.fixed.lut, own.per_lane.lut, from),
            (2000, 10_000, None)
        );
        let (borrowed, from) = fit(2);
        assert_eq!(
            from.as_deref(),
            Some("fp32_d9"),
            "depth 9 is nearer to 6 than depth 1"
        );
        assert_eq!((borrowed.fixed.lut, borrowed.per_lane.lut), (5000, 6000));
        // No bf16 pair: the float of the same width (fp16, fixed part 1000) before the fixed
        // format of the same width.
        let (borrowed, from) = fit(9);
        assert_eq!(
            (from.as_deref(), borrowed.fixed.lut, borrowed.per_lane.lut),
            (Some("fp16_d6"), 1000, 5000)
        );
        let (_, from) = fit(10);
        assert_eq!(
            from.as_deref(),
            Some("fx16_10_d1"),
            "a fixed format borrows from a fixed format"
        );
        // A point whose 1-lane design was not synthesised has no fit, nor one without any pair.
        let mut unsynthesised = points[2].clone();
        unsynthesised.synth = None;
        assert!(lane_fit(
            &[unsynthesised.clone(), points[0].clone(), points[1].clone()],
            &unsynthesised
        )
        .is_none());
        assert!(lane_fit(&points[9..10], &points[9]).is_none());
        // A 2-lane design without its 1-lane one is no pair: the next one is taken.
        let mut lone_two = points.clone();
        lone_two[7].synth = None;
        assert_eq!(
            lane_fit(&lone_two, &lone_two[10]).unwrap().1.as_deref(),
            Some("fp16_d6"),
            "fx16_10 has no pair left"
        );
    }
}
