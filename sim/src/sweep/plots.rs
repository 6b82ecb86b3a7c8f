//! The sweep's plots (plotters, PNG and SVG): per variant (spawn policy and origin advance) the
//! worst-scene PSNR against the format's bits, and per variant of the hardware's lane the
//! Pareto front of quality against DSP48E1; LUT and DSP48E1 against lanes.

use std::collections::BTreeMap;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::config::Variant;
use super::layout::{parent_dir, Layout};
use super::quality::QualityResult;
use super::table::{Results, Row};

const SIZE: (u32, u32) = (900, 600);

fn err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing a plot: {e}")
}

/// Where an infinite PSNR (identical images) is drawn: above every finite value.
fn psnr_ceiling(values: impl Iterator<Item = f64>) -> f64 {
    let finite = values.filter(|v| v.is_finite()).fold(40.0_f64, f64::max);
    (finite / 10.0).ceil() * 10.0 + 10.0
}

fn capped(v: f64, ceiling: f64) -> f64 {
    v.min(ceiling)
}

pub fn write_all(results: &Results, layout: &Layout) -> Result<()> {
    for &variant in &results.variants {
        let quality: Vec<&QualityResult> = results
            .quality
            .iter()
            .filter(|q| q.variant() == variant)
            .collect();
        if !quality.is_empty() {
            save(
                layout,
                &format!("psnr_vs_bits_{}", variant.name()),
                |a| psnr_vs_bits(a, results, &quality, variant),
                |a| psnr_vs_bits(a, results, &quality, variant),
            )?;
        }
        let rows: Vec<&Row> = results
            .rows
            .iter()
            .filter(|r| r.policy == Some(variant.policy) && r.advance == Some(variant.advance))
            .collect();
        if rows
            .iter()
            .any(|r| r.min_psnr_db.is_some() && r.dsp48e1.is_some())
        {
            save(
                layout,
                &format!("pareto_psnr_dsp_{}", variant.name()),
                |a| pareto(a, &rows, variant),
                |a| pareto(a, &rows, variant),
            )?;
        }
    }
    if results.rows.iter().any(|r| r.lut.is_some()) {
        save(
            layout,
            "resources_vs_lanes",
            |a| resources_vs_lanes(a, &results.rows),
            |a| resources_vs_lanes(a, &results.rows),
        )?;
    }
    Ok(())
}

fn save(
    layout: &Layout,
    name: &str,
    png: impl FnOnce(&DrawingArea<BitMapBackend, Shift>) -> Result<()>,
    svg: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<()>,
) -> Result<()> {
    let png_path = layout.plot(name, "png");
    parent_dir(&png_path)?;
    {
        let area = BitMapBackend::new(&png_path, SIZE).into_drawing_area();
        area.fill(&WHITE).map_err(err)?;
        png(&area)?;
        area.present().map_err(err)?;
    }
    let svg_path = layout.plot(name, "svg");
    let area = SVGBackend::new(&svg_path, SIZE).into_drawing_area();
    area.fill(&WHITE).map_err(err)?;
    svg(&area)?;
    area.present().map_err(err)?;
    Ok(())
}

fn psnr_vs_bits<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    r: &Results,
    quality: &[&QualityResult],
    variant: Variant,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let ceiling = psnr_ceiling(quality.iter().map(|q| q.min_psnr_db()));
    let max_bits = quality.iter().map(|q| q.bits).max().unwrap_or(32) + 2;
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "Worst-scene PSNR vs format width, {} ({} scenes, {})",
                variant.name(),
                r.scenes.len(),
                r.image_size
            ),
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(8u32..max_bits, 0.0..ceiling + 5.0)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("format width (bits)")
        .y_desc("min PSNR over scenes (dB)")
        .draw()
        .map_err(err)?;
    identical_line(&mut chart, 8, max_bits, ceiling)?;
    chart
        .draw_series(LineSeries::new([(8, 40.0), (max_bits, 40.0)], RED.mix(0.5)))
        .map_err(err)?
        .label("40 dB")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 15, y)], RED.mix(0.5)));
    // Formats of equal width get staggered labels.
    let mut seen: BTreeMap<u32, i32> = BTreeMap::new();
    for q in quality {
        let y = capped(q.min_psnr_db(), ceiling);
        let n = seen.entry(q.bits).or_insert(0);
        // Fixed point blue, floating point green; model-only formats hollow.
        let colour = if q.format.starts_with("fx") {
            BLUE
        } else {
            RGBColor(0, 150, 0)
        };
        let style = if r.model_formats.contains(&q.format) {
            colour.stroke_width(2)
        } else {
            colour.filled()
        };
        let offset = (5, -12 - 12 * *n);
        *n += 1;
        chart
            .draw_series([EmptyElement::at((q.bits, y))
                + Circle::new((0, 0), 4, style)
                + Text::new(q.format.clone(), offset, ("sans-serif", 12))])
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE)
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    Ok(())
}

/// A dashed-looking grey line at the ceiling, labelled, where identical images are drawn.
fn identical_line<DB: DrawingBackend, XC: Ranged>(
    chart: &mut ChartContext<DB, Cartesian2d<XC, plotters::coord::types::RangedCoordf64>>,
    from: XC::ValueType,
    to: XC::ValueType,
    ceiling: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
    XC::ValueType: Clone + 'static,
{
    chart
        .draw_series(LineSeries::new(
            [(from.clone(), ceiling), (to, ceiling)],
            BLACK.mix(0.3),
        ))
        .map_err(err)?;
    chart
        .draw_series([Text::new(
            "identical to f32 (PSNR = inf)",
            (from, ceiling + 3.0),
            ("sans-serif", 12),
        )])
        .map_err(err)?;
    Ok(())
}

fn resources_vs_lanes<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, rows: &[Row]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let mut series: BTreeMap<String, Vec<&Row>> = BTreeMap::new();
    for row in rows.iter().filter(|r| r.lut.is_some()) {
        // Rows repeat per spawn policy with the same hardware: one point each.
        let points = series
            .entry(format!("{} d{}", row.format, row.depth))
            .or_default();
        if !points.iter().any(|p| p.id == row.id) {
            points.push(row);
        }
    }
    let max_lanes = rows.iter().map(|r| r.lanes).max().unwrap_or(1) as u32;
    let (left, right) = area.split_horizontally(SIZE.0 / 2);
    // (area, resource, its value in a row, the XC7Z020's total)
    type Panel<'a, DB> = (
        &'a DrawingArea<DB, Shift>,
        &'a str,
        fn(&Row) -> Option<u64>,
        u64,
    );
    let panels: [Panel<DB>; 2] = [
        (&left, "LUT", |r| r.lut, hdl::top::fit::XC7Z020.lut),
        (
            &right,
            "DSP48E1",
            |r| r.dsp48e1,
            hdl::top::fit::XC7Z020.dsp48e1,
        ),
    ];
    for (panel, name, value, device) in panels {
        let top = rows
            .iter()
            .filter_map(value)
            .max()
            .unwrap_or(1)
            .max(device / 4);
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("{name} vs lanes (XC7Z020: {device})"),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(60)
            .build_cartesian_2d(0u32..max_lanes + 1, 0u64..top + top / 10)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("lanes")
            .y_desc(name)
            .draw()
            .map_err(err)?;
        for (i, (label, points)) in series.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let mut pts: Vec<(u32, u64)> = points
                .iter()
                .filter_map(|r| Some((r.lanes as u32, value(r)?)))
                .collect();
            pts.sort();
            chart
                .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
                .map_err(err)?
                .label(label.clone())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 15, y)], colour));
            chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, colour.filled())))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

/// Points with both quality and DSP48E1, and the front: no other point has at least the
/// PSNR for fewer DSP48E1 (ties in DSP: the better PSNR).
pub fn pareto_front<'r>(rows: &[&'r Row]) -> Vec<&'r Row> {
    let mut candidates: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| r.min_psnr_db.is_some() && r.dsp48e1.is_some())
        .collect();
    candidates.sort_by(|a, b| {
        a.dsp48e1.cmp(&b.dsp48e1).then(
            b.min_psnr_db
                .partial_cmp(&a.min_psnr_db)
                .unwrap_or(std::cmp::Ordering::Equal),
        )
    });
    let mut front: Vec<&Row> = Vec::new();
    for r in candidates {
        if front.last().is_none_or(|f| r.min_psnr_db > f.min_psnr_db) {
            front.push(r);
        }
    }
    front
}

fn pareto<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    rows: &[&Row],
    variant: Variant,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let with: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| r.min_psnr_db.is_some() && r.dsp48e1.is_some())
        .collect();
    let psnr = |r: &Row| r.min_psnr_db.map_or(0.0, |p| p.0);
    let ceiling = psnr_ceiling(with.iter().map(|r| psnr(r)));
    let max_dsp = with.iter().filter_map(|r| r.dsp48e1).max().unwrap_or(1);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "Quality vs DSP48E1, {}: Pareto front in red",
                variant.name()
            ),
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(0u64..max_dsp + max_dsp / 10 + 1, 0.0..ceiling + 5.0)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("DSP48E1")
        .y_desc("min PSNR over scenes (dB)")
        .draw()
        .map_err(err)?;
    identical_line(&mut chart, 0u64, max_dsp + max_dsp / 10 + 1, ceiling)?;
    chart
        .draw_series(with.iter().map(|r| {
            Circle::new(
                (r.dsp48e1.unwrap_or(0), capped(psnr(r), ceiling)),
                3,
                BLUE.mix(0.5).filled(),
            )
        }))
        .map_err(err)?;
    let front = pareto_front(rows);
    let line: Vec<(u64, f64)> = front
        .iter()
        .map(|r| (r.dsp48e1.unwrap_or(0), capped(psnr(r), ceiling)))
        .collect();
    chart
        .draw_series(LineSeries::new(line.clone(), RED.stroke_width(2)))
        .map_err(err)?;
    for (r, p) in front.iter().zip(line) {
        chart
            .draw_series([EmptyElement::at(p)
                + Circle::new((0, 0), 5, RED.filled())
                + Text::new(r.id.clone(), (6, -14), ("sans-serif", 12))])
            .map_err(err)?;
    }
    Ok(())
}
