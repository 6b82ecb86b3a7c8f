//! The merged results: one row per point and spawn policy with the hardware's lane (advance
//! none; results.csv), one row per format or dual-precision pair, policy, advance and scene
//! (quality.csv), all of it in results.json and as Markdown tables in results.md.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use hw_model::precision::SpawnChoice;
use hw_model::Advance;
use serde::{Deserialize, Serialize};

use super::config::Variant;
use super::dual::DualResult;
use super::layout::parent_dir;
use super::quality::{Psnr, QualityResult};

/// Where a row's resources come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ResourceSource {
    /// yosys synthesised this point.
    Yosys,
    /// Fixed part + lanes × per-lane cost, from the 1- and 2-lane synthesis of the same
    /// format (the fixed part from the pair `Row::fixed_part_from`).
    Estimate,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Row {
    pub id: String,
    pub format: String,
    pub bits: u32,
    pub depth: usize,
    pub lanes: usize,
    /// The spawn policy of the quality columns (none without the quality stage: one row per
    /// point).
    pub policy: Option<SpawnChoice>,
    /// The origin advance of the quality columns: none, the hardware lanes' (none without the
    /// quality stage).
    pub advance: Option<Advance>,
    /// Lane latency in cycles.
    pub latency: usize,
    /// Stream-mode cycles per test of the whole accelerator.
    pub cycles_per_test: f64,
    pub cycles_measured: bool,
    pub lut: Option<u64>,
    pub ff: Option<u64>,
    pub dsp48e1: Option<u64>,
    pub bram18: Option<u64>,
    pub carry4: Option<u64>,
    pub logic_depth: Option<u64>,
    pub resources: Option<ResourceSource>,
    /// Lanes of this format and depth that fit an XC7Z020, and the resource that limits it.
    pub lanes_fit: Option<u64>,
    pub fit_limit: Option<String>,
    /// The format and depth (`fp16_d1`) whose 1- and 2-lane synthesis lent the fixed part of
    /// `lanes_fit` (`merge`'s docs); none when this row's own pair gave it.
    pub fixed_part_from: Option<String>,
    /// Worst scene's PSNR against the f32 reference, under `policy`.
    pub min_psnr_db: Option<Psnr>,
    /// Largest share of differing pixels over the scenes.
    pub max_differing_share: Option<f64>,
    /// Co-simulation gave exactly the model's images (None: not co-simulated).
    pub cosim_identical: Option<bool>,
    pub projected_frame_s: Option<f64>,
    pub speedup_vs_arm: Option<f64>,
}

/// Everything the merge writes to results.json.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Results {
    pub rows: Vec<Row>,
    /// The quality stage's (policy, advance) combinations.
    pub variants: Vec<Variant>,
    /// One per format and variant.
    pub quality: Vec<QualityResult>,
    /// One per dual-precision pair and policy.
    pub dual: Vec<DualResult>,
    /// Formats of `quality` that have no hardware (model engine only).
    pub model_formats: Vec<String>,
    /// Modelled ARM-only time of the projected frame (None without the projection stage).
    pub arm_only_s: Option<f64>,
    pub projected_frame: Option<String>,
    pub scenes: Vec<String>,
    pub image_size: String,
}

pub fn write_csv(rows: &[Row], path: &Path) -> Result<()> {
    parent_dir(path)?;
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("writing {}", path.display()))?;
    for r in rows {
        w.serialize(r)?;
    }
    w.flush()?;
    Ok(())
}

/// One line of quality.csv: a format or pair on one scene under one policy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QualityRow {
    /// A format, or a dual-precision pair (`bfp18/fp32`).
    pub format: String,
    /// `hardware`, `model` (model-only format) or `pair`.
    pub kind: String,
    /// The format's width; a pair's filter width.
    pub bits: u32,
    pub policy: SpawnChoice,
    /// The model lane's origin advance (pairs: none, they have the hardware's lane).
    pub advance: Advance,
    pub scene: String,
    pub psnr_db: Psnr,
    /// Formats only.
    pub differing_share: Option<f64>,
    /// Pairs only: the share of tests forwarded to the fallback.
    pub forwarded_share: Option<f64>,
    /// Pairs only: the image equals the fallback's.
    pub equals_fallback: Option<bool>,
}

/// quality.csv's lines: every format's scenes, then every pair's.
pub fn quality_rows(results: &Results) -> Vec<QualityRow> {
    let formats = results.quality.iter().flat_map(|q| {
        let kind = if results.model_formats.contains(&q.format) {
            "model"
        } else {
            "hardware"
        };
        q.scenes.iter().map(move |s| QualityRow {
            format: q.format.clone(),
            kind: kind.into(),
            bits: q.bits,
            policy: q.policy,
            advance: q.advance,
            scene: s.scene.clone(),
            psnr_db: s.psnr_db,
            differing_share: Some(s.differing_share),
            forwarded_share: None,
            equals_fallback: None,
        })
    });
    let pairs = results.dual.iter().flat_map(|d| {
        d.scenes.iter().map(move |s| QualityRow {
            format: d.pair.clone(),
            kind: "pair".into(),
            bits: d.filter_bits,
            policy: d.policy,
            advance: Advance::None,
            scene: s.scene.clone(),
            psnr_db: s.psnr_db,
            differing_share: None,
            forwarded_share: Some(s.forwarded_share),
            equals_fallback: Some(s.differing_from_fallback == 0),
        })
    });
    formats.chain(pairs).collect()
}

pub fn write_quality_csv(rows: &[QualityRow], path: &Path) -> Result<()> {
    parent_dir(path)?;
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("writing {}", path.display()))?;
    for r in rows {
        w.serialize(r)?;
    }
    w.flush()?;
    Ok(())
}

fn opt<T: std::fmt::Display>(v: &Option<T>) -> String {
    v.as_ref().map_or_else(|| "—".to_string(), T::to_string)
}

/// The smallest format (fewest bits) whose worst scene reaches `db` under `variant`.
pub fn smallest_format_above<'q>(
    quality: impl IntoIterator<Item = &'q QualityResult>,
    variant: Variant,
    db: f64,
) -> Option<&'q QualityResult> {
    quality
        .into_iter()
        .filter(|q| q.variant() == variant && q.min_psnr_db() >= db)
        .min_by(|a, b| (a.bits, &a.format).cmp(&(b.bits, &b.format)))
}

/// The header and alignment rows of a table with a column per scene: the leading and trailing
/// columns (header cells, alignment cells) around one `scene_align` cell per scene.
fn scene_table_head(
    s: &mut String,
    lead: (&str, &str),
    scenes: &[String],
    scene_align: &str,
    tail: (&str, &str),
) -> std::fmt::Result {
    write!(s, "{}", lead.0)?;
    for scene in scenes {
        write!(s, " {scene} |")?;
    }
    writeln!(s, "{}", tail.0)?;
    writeln!(
        s,
        "{}{}{}",
        lead.1,
        scene_align.repeat(scenes.len()),
        tail.1
    )
}

pub fn markdown(results: &Results) -> Result<String> {
    let mut s = String::new();
    writeln!(s, "# Sweep results\n")?;
    writeln!(
        s,
        "Scenes ({}): {}\n",
        results.image_size,
        results.scenes.join(", ")
    )?;
    if let Some(arm) = results.arm_only_s {
        writeln!(
            s,
            "Projected frame: {} (stream design, BVH); modelled ARM-only time {arm:.3} s.\n",
            results.projected_frame.as_deref().unwrap_or("?")
        )?;
    }
    writeln!(s, "## Points\n")?;
    writeln!(s, "Resources: `yosys` synthesised, `estimate` = fixed + lanes × per-lane from the 1- and 2-lane synthesis; lanes fit = lanes of the format and depth that fit an XC7Z020 (limit; †fp16_d1 = this point's 1-lane synthesis with the fixed part (AXI-Lite slave, stream front end) of that 1- and 2-lane pair). Cycles/test: `*` measured in co-simulation. Quality: the hardware's lane (advance none).\n")?;
    writeln!(s, "| point | bits | depth | lanes | latency | cycles/test | LUT | FF | DSP | BRAM18 | CARRY4 | logic depth | resources | lanes fit | policy | advance | min PSNR dB | max diff px | cosim = model | frame s | × ARM |")?;
    writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|---:|---:|---|---:|---:|")?;
    for r in &results.rows {
        let res = match r.resources {
            Some(ResourceSource::Yosys) => "yosys",
            Some(ResourceSource::Estimate) => "estimate",
            None => "—",
        };
        let borrowed = r
            .fixed_part_from
            .as_ref()
            .map_or(String::new(), |from| format!(" †{from}"));
        let fit = match (&r.lanes_fit, &r.fit_limit) {
            (Some(n), Some(l)) => format!("{n} ({l}){borrowed}"),
            _ => "—".into(),
        };
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.3}{} | {} | {} | {} | {} | {} | {} | {res} | {fit} | {} | {} | {} | {} | {} | {} | {} |",
            r.id,
            r.bits,
            r.depth,
            r.lanes,
            r.latency,
            r.cycles_per_test,
            if r.cycles_measured { "*" } else { "" },
            opt(&r.lut),
            opt(&r.ff),
            opt(&r.dsp48e1),
            opt(&r.bram18),
            opt(&r.carry4),
            opt(&r.logic_depth),
            opt(&r.policy),
            opt(&r.advance),
            opt(&r.min_psnr_db),
            opt(&r.max_differing_share.map(|x| format!("{:.2} %", 100.0 * x))),
            opt(&r.cosim_identical.map(|b| if b { "yes" } else { "NO" })),
            opt(&r.projected_frame_s.map(|x| format!("{x:.3}"))),
            opt(&r.speedup_vs_arm.map(|x| format!("{x:.2}"))),
        )?;
    }
    if !results.quality.is_empty() {
        writeln!(
            s,
            "\n## Quality per scene (model engine vs f32; PSNR dB / differing pixels)\n"
        )?;
        scene_table_head(
            &mut s,
            ("| format | policy | advance | bits |", "|---|---|---|---:|"),
            &results.scenes,
            "---|",
            (" min PSNR |", "---:|"),
        )?;
        for q in &results.quality {
            let tag = if results.model_formats.contains(&q.format) {
                " (model only)"
            } else {
                ""
            };
            write!(
                s,
                "| {}{tag} | {} | {} | {} |",
                q.format, q.policy, q.advance, q.bits
            )?;
            for sq in &q.scenes {
                write!(s, " {} / {:.2} % |", sq.psnr_db, 100.0 * sq.differing_share)?;
            }
            writeln!(s, " {} |", Psnr(q.min_psnr_db()))?;
        }
        writeln!(s)?;
        let (hardware, model): (Vec<&QualityResult>, Vec<&QualityResult>) = results
            .quality
            .iter()
            .partition(|q| !results.model_formats.contains(&q.format));
        for &variant in &results.variants {
            // An advanced origin exists in the model lane only.
            let lane = if variant.in_hardware() {
                ""
            } else {
                "; model lane only: the hardware lanes do not advance the origin"
            };
            for (what, list) in [
                ("hardware format", &hardware),
                ("model-only format", &model),
            ] {
                if list.is_empty() {
                    continue;
                }
                match smallest_format_above(list.iter().copied(), variant, 40.0) {
                    Some(q) => writeln!(s, "- Smallest {what} with PSNR ≥ 40 dB on every scene ({variant}{lane}): **{}** ({} bits, worst {} dB).", q.format, q.bits, Psnr(q.min_psnr_db()))?,
                    None => writeln!(s, "- No {what} reaches PSNR ≥ 40 dB on every scene ({variant}{lane}).")?,
                }
            }
        }
    }
    if !results.dual.is_empty() {
        writeln!(
            s,
            "\n## Dual precision (the model; the pair built in hardware below; the hardware's lane, advance none)\n"
        )?;
        writeln!(s, "Share of each scene's Möller-Trumbore tests the filter forwards to the fallback; all = over every scene's tests; = fallback: every image equals the fallback format's model render under the same policy; min PSNR against f32.\n")?;
        scene_table_head(
            &mut s,
            ("| pair | policy |", "|---|---|"),
            &results.scenes,
            "---:|",
            (" all | = fallback | min PSNR |", "---:|---|---:|"),
        )?;
        for d in &results.dual {
            write!(s, "| {} | {} |", d.pair, d.policy)?;
            for sc in &d.scenes {
                write!(s, " {:.4} |", sc.forwarded_share)?;
            }
            writeln!(
                s,
                " {:.4} | {} | {} |",
                d.forwarded_share(),
                if d.exact() { "yes" } else { "NO" },
                Psnr(d.min_psnr_db())
            )?;
        }
        pair_hardware(&mut s, results)?;
    }
    Ok(s)
}

/// The per-lane LUTs (with SRL) of fp32 at `depth` from its synthesised 1- and 2-lane points.
fn fp32_lane_lut(results: &Results, depth: usize) -> Option<u64> {
    let lut = |lanes: usize| {
        let id = format!("fp32_d{depth}_l{lanes}");
        let row = results.rows.iter().find(|r| r.id == id)?;
        (row.resources == Some(ResourceSource::Yosys)).then_some(row.lut?)
    };
    Some(lut(2)? - lut(1)?)
}

/// The pairs built in hardware: resources, the slots that fit, tests per cycle and per LUT
/// against fp32 lanes.
fn pair_hardware(s: &mut String, results: &Results) -> Result<()> {
    let built: Vec<&DualResult> = results
        .dual
        .iter()
        .filter(|d| d.hardware.is_some())
        .collect();
    let Some(first) = built.first() else {
        return Ok(());
    };
    let hw = first.hardware.as_ref().expect("filtered");
    writeln!(
        s,
        "\n### {} in hardware: filter slots sharing one fp32 lane (depth {})\n",
        first.pair, hw.depth
    )?;
    if hw.synth.is_empty() {
        writeln!(s, "Not synthesised (no `synth` stage).")?;
    } else {
        writeln!(
            s,
            "| slots | LUT | FF | DSP | BRAM18 | CARRY4 | logic depth | yosys s |"
        )?;
        writeln!(s, "|---:|---:|---:|---:|---:|---:|---:|---:|")?;
        for p in &hw.synth {
            let r = &p.synth;
            writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {}{} |",
                p.slots,
                r.lut,
                r.ff,
                r.dsp48e1,
                r.bram18,
                r.carry4,
                r.logic_depth,
                r.seconds,
                if p.cached { " (cached)" } else { "" }
            )?;
        }
        if let Some(f) = hw.fit() {
            writeln!(
                s,
                "\nPer slot {} LUT, {} FF, {} DSP48E1; fixed part (the fp32 lane, the arbiter) {} LUT, {} DSP48E1: **{} slots fit an XC7Z020** (limited by {}).",
                f.per_lane.lut, f.per_lane.ff, f.per_lane.dsp48e1, f.fixed.lut, f.fixed.dsp48e1, f.lanes, f.limit
            )?;
        }
    }
    if hw.cosim.is_empty() {
        return Ok(writeln!(s, "\nNot co-simulated (no `cosim` stage).")?);
    }
    let lane_lut = fp32_lane_lut(results, hw.depth);
    writeln!(s, "\nCo-simulated on the co-simulation scenes: tests per cycle; per LUT against fp32 lanes at depth {} (1 test per cycle per lane; their per-lane LUTs from the fp32 1- and 2-lane synthesis; – without it or the pair's).\n", hw.depth)?;
    writeln!(s, "| policy | slots | tests/cycle | forwarded | stall cycles | = fallback | LUT | tests/cycle/LUT vs fp32 |")?;
    writeln!(s, "|---|---:|---:|---:|---:|---|---:|---:|")?;
    for d in &built {
        let hw = d.hardware.as_ref().expect("filtered");
        let fit = hw.fit();
        for slots in super::dual::COSIM_SLOTS {
            let runs: Vec<_> = hw.cosim.iter().filter(|c| c.slots == slots).collect();
            let Some(rate) = hw.tests_per_cycle(slots) else {
                continue;
            };
            let tests: u64 = runs.iter().map(|c| c.tests).sum();
            let forwarded: u64 = runs.iter().map(|c| c.forwarded).sum();
            let stalls: u64 = runs.iter().map(|c| c.stall_cycles).sum();
            let exact = runs.iter().all(|c| c.differing_from_fallback == 0);
            let lut = fit.map(|f| f.fixed.lut + slots as u64 * f.per_lane.lut);
            let versus = match (lut, lane_lut) {
                (Some(lut), Some(lane)) => format!("{:.2}×", rate / lut as f64 * lane as f64),
                _ => "–".into(),
            };
            writeln!(
                s,
                "| {} | {slots} | {rate:.3} | {:.4} | {stalls} | {} | {} | {versus} |",
                d.policy,
                forwarded as f64 / tests.max(1) as f64,
                if exact { "yes" } else { "NO" },
                lut.map_or("–".into(), |l| l.to_string()),
            )?;
        }
    }
    Ok(())
}
