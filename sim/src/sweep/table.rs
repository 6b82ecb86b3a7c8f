//! The merged results: one row per point, written as CSV, JSON and a Markdown table.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};

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
    /// Worst scene's PSNR against the f32 reference.
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
    pub quality: Vec<QualityResult>,
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

fn opt<T: std::fmt::Display>(v: &Option<T>) -> String {
    v.as_ref().map_or_else(|| "—".to_string(), T::to_string)
}

/// The smallest format (fewest bits) whose worst scene reaches `db`.
pub fn smallest_format_above(quality: &[QualityResult], db: f64) -> Option<&QualityResult> {
    quality
        .iter()
        .filter(|q| q.min_psnr_db() >= db)
        .min_by(|a, b| (a.bits, &a.format).cmp(&(b.bits, &b.format)))
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
    writeln!(s, "Resources: `yosys` synthesised, `estimate` = fixed + lanes × per-lane from the 1- and 2-lane synthesis; lanes fit = lanes of the format and depth that fit an XC7Z020 (limit; †fp16_d1 = this point's 1-lane synthesis with the fixed part (AXI-Lite slave, stream front end) of that 1- and 2-lane pair). Cycles/test: `*` measured in co-simulation.\n")?;
    writeln!(s, "| point | bits | depth | lanes | latency | cycles/test | LUT | FF | DSP | BRAM18 | CARRY4 | logic depth | resources | lanes fit | min PSNR dB | max diff px | cosim = model | frame s | × ARM |")?;
    writeln!(s, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---:|---|---:|---:|")?;
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
            "| {} | {} | {} | {} | {} | {:.3}{} | {} | {} | {} | {} | {} | {} | {res} | {fit} | {} | {} | {} | {} | {} |",
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
        write!(s, "| format | bits |")?;
        for scene in &results.scenes {
            write!(s, " {scene} |")?;
        }
        writeln!(s, " min PSNR |")?;
        writeln!(s, "|---|---:|{}---:|", "---|".repeat(results.scenes.len()))?;
        for q in &results.quality {
            let tag = if results.model_formats.contains(&q.format) {
                " (model only)"
            } else {
                ""
            };
            write!(s, "| {}{tag} | {} |", q.format, q.bits)?;
            for sq in &q.scenes {
                write!(s, " {} / {:.2} % |", sq.psnr_db, 100.0 * sq.differing_share)?;
            }
            writeln!(s, " {} |", Psnr(q.min_psnr_db()))?;
        }
        let (hardware, model): (Vec<QualityResult>, Vec<QualityResult>) = results
            .quality
            .iter()
            .cloned()
            .partition(|q| !results.model_formats.contains(&q.format));
        for (what, list) in [
            ("hardware format", &hardware),
            ("model-only format", &model),
        ] {
            if list.is_empty() {
                continue;
            }
            match smallest_format_above(list, 40.0) {
                Some(q) => writeln!(s, "\nSmallest {what} with PSNR ≥ 40 dB on every scene: **{}** ({} bits, worst {} dB).", q.format, q.bits, Psnr(q.min_psnr_db()))?,
                None => writeln!(s, "\nNo {what} reaches PSNR ≥ 40 dB on every scene.")?,
            }
        }
    }
    Ok(s)
}
