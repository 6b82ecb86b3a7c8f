//! `rtfpga render`: one scene, one engine, one PNG.

use std::path::PathBuf;

use std::time::Instant;

use anyhow::Result;
use clap::Args as ClapArgs;
use hw_model::frame::{Frame, FrameLimits, WAVEFRONT};
use hw_model::traversal::TraversalEngine;
use indicatif::{ProgressBar, ProgressStyle};
use sw_renderer::rays::{CastStats, RayEngine};
use sw_renderer::render::{render, save_png, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::engine::{self, ChunkArgs, EngineKind, HwConfig, Precision, PrecisionArgs};
use crate::options::Given;
use crate::report::{self, Line};

#[derive(ClapArgs)]
pub struct Args {
    /// Scene directory with objects.txt, a .toml scene, or a built-in scene name.
    #[arg(long)]
    scene: String,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = image_side())]
    height: Option<u32>,
    /// What answers the rays.
    #[arg(long, value_enum, default_value_t = EngineKind::F32)]
    engine: EngineKind,
    #[command(flatten)]
    hw: HwConfig,
    #[command(flatten)]
    precision: PrecisionArgs,
    #[command(flatten)]
    chunks: ChunkArgs,
    /// Output image (.png; its folder is created).
    #[arg(long, value_name = "OUT.png")]
    out: PathBuf,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The largest image side the command line accepts: beyond any display (8K is 7680 wide),
/// small enough that a typo such as `--width 100000` is refused instead of rendering for hours.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Parser of `--width`/`--height`: 1 to [`MAX_IMAGE_SIDE`] pixels.
pub fn image_side() -> clap::builder::RangedI64ValueParser<u32> {
    clap::value_parser!(u32).range(1..=i64::from(MAX_IMAGE_SIDE))
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    given.check(a.engine.target(&a.hw.datapath.format))?;
    let scene = Scene::load(&a.scene)?;
    let precision = a.precision.resolve(a.engine, &a.hw, &scene)?;
    let (scale_exp, lane) = (precision.scale_exp, precision.lane);
    report::image_out("--out", &a.out)?;
    if a.engine == EngineKind::Frame {
        return render_frame(&a, &scene, &precision);
    }
    let made = engine::make(a.engine, &a.hw, scale_exp, lane, &a.chunks)?;
    if let Some(v) = &made.verilated {
        v.line().print();
    }
    let engine = made.engine;
    let opts = RenderOptions {
        width: a.width,
        height: a.height,
        progress: !a.quiet,
        spawn: precision.spawn,
        ..Default::default()
    };
    let out = render(&scene, engine.as_ref(), &opts)?;
    save_png(&out.image, &a.out)?;
    let s = &out.stats;
    let secs = s.render_time.as_secs_f64();
    Line::new()
        .kv("scene", &scene.name)
        .kv("engine", engine.name())
        .kv("spawn", precision.choice.name())
        .kv("scale_exp", scale_exp)
        .kv("edges", lane.edges)
        .kv("advance", lane.advance)
        .kv(
            "size",
            format_args!("{}x{}", out.image.width(), out.image.height()),
        )
        .kv("triangles", scene.triangle_count())
        .kv("rays", s.trace.rays())
        .kv("mt_queries", s.trace.cast.mt_tests)
        .kv("box_tests", s.trace.cast.box_tests)
        .kv("node_visits", s.trace.cast.node_visits)
        .fixed("prepare_s", s.prepare_time.as_secs_f64(), 3)
        .fixed("render_s", secs, 3)
        .fixed(
            "mrays_per_s",
            s.trace.rays() as f64 / secs.max(1e-9) / 1e6,
            2,
        )
        .print();
    Line::new().path("out", &a.out).print();
    if let Some(dual) = &made.dual {
        let d = dual.stats();
        Line::labelled("dual_precision")
            .kv("pair", dual.filter.pair)
            .kv("filter", dual.filter.kind)
            .kv("tests", d.tests)
            .kv("certain_misses", d.certain_misses)
            .kv("forwarded", d.forwarded())
            .fixed("forwarded_share", d.forwarded_share(), 4)
            .print();
    }
    let c = s.trace.cast;
    unit_memory(&c);
    if c.cycles > 0 {
        // The traversal unit's schedule model (not a co-simulation).
        let rays = s.trace.rays().max(1) as f64;
        let lanes = a.hw.datapath.lanes as f64;
        let box_ports = a.hw.unit.box_ports as f64;
        Line::labelled("unit_schedule")
            .kv("nodes", a.hw.unit.nodes.name())
            .kv("slots", a.hw.unit.slots())
            .kv("box_ports", a.hw.unit.box_ports)
            .kv("lanes", a.hw.datapath.lanes)
            .kv("cycles", c.cycles)
            .fixed("cycles_per_ray", c.cycles as f64 / rays, 2)
            .fixed("box_tests_per_ray", c.box_tests as f64 / rays, 2)
            .fixed("mt_tests_per_ray", c.mt_tests as f64 / rays, 2)
            .fixed("node_visits_per_ray", c.node_visits as f64 / rays, 2)
            .fixed(
                "box_utilisation",
                c.box_tests as f64 / (c.cycles as f64 * box_ports),
                3,
            )
            .fixed(
                "lane_utilisation",
                c.mt_tests as f64 / (c.cycles as f64 * lanes),
                3,
            )
            .fixed("mrays_per_s_at_100mhz", rays / c.cycles as f64 * 100.0, 2)
            .print();
    }
    Ok(())
}

/// The traversal unit's scene memory, when a unit answered: one pass per wavefront and loaded
/// chunk.
fn unit_memory(c: &CastStats) {
    if c.passes > 0 {
        Line::labelled("unit_memory")
            .kv("passes", c.passes)
            .kv("ray_passes", c.ray_passes)
            .kv("chunk_loads", c.chunk_loads)
            .kv("loaded_bytes", c.loaded_bytes)
            .print();
    }
}

/// `render --engine frame`: the frame unit's model (docs/frame.md), its rays answered by the
/// traversal unit's model in `--format` (untimed: the frame model has no cycles) with its
/// scene memory as `--engine traversal` has it (chunked passes change no answer).
fn render_frame(a: &Args, scene: &Scene, precision: &Precision) -> Result<()> {
    let unit = TraversalEngine {
        timing: None,
        ..a.hw
            .traversal_engine(precision.scale_exp, precision.lane.advance, &a.chunks)?
    };
    let width = a.width.unwrap_or(scene.options.width);
    let height = a.height.unwrap_or(scene.options.height);
    let start = Instant::now();
    let prepared = PreparedScene::new(scene)?;
    let frame = Frame::new(scene, &prepared, &unit, width, height, &FrameLimits::HW)?;
    let prepare_s = start.elapsed().as_secs_f64();
    let tile_size = RenderOptions::default().tile_size;
    let bar = match a.quiet {
        true => ProgressBar::hidden(),
        false => ProgressBar::new(frame.tile_count(tile_size) as u64),
    };
    if let Ok(style) =
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} tiles {elapsed}/{eta}")
    {
        bar.set_style(style);
    }
    bar.set_message(format!("{} (frame)", scene.name));
    let start = Instant::now();
    let out = frame.render(tile_size, WAVEFRONT, &|| bar.inc(1));
    bar.finish_and_clear();
    let out = out?;
    let render_s = start.elapsed().as_secs_f64();
    save_png(&out.image, &a.out)?;
    let s = &out.stats;
    Line::new()
        .kv("scene", &scene.name)
        .kv("engine", "frame")
        .kv("traversal", unit.name())
        .kv("spawn", precision.choice.name())
        .kv("scale_exp", precision.scale_exp)
        .kv("advance", precision.lane.advance)
        .kv("size", format_args!("{width}x{height}"))
        .kv("triangles", scene.triangle_count())
        .kv("rays", s.rays())
        .kv("mt_queries", s.cast.mt_tests)
        .kv("box_tests", s.cast.box_tests)
        .kv("node_visits", s.cast.node_visits)
        .fixed("prepare_s", prepare_s, 3)
        .fixed("render_s", render_s, 3)
        .fixed("mrays_per_s", s.rays() as f64 / render_s.max(1e-9) / 1e6, 2)
        .print();
    Line::new().path("out", &a.out).print();
    Line::labelled("frame")
        .kv("primary_rays", s.primary_rays)
        .kv("reflection_rays", s.reflection_rays)
        .kv("refraction_rays", s.refraction_rays)
        .kv("shadow_rays", s.shadow_rays)
        .kv("hits", s.hits)
        .kv("occluded", s.occluded)
        .kv("zero_shadows", s.zero_shadows)
        .kv("past_depth", s.past_depth)
        .kv("total_internal", s.total_internal)
        .kv("contributions", s.contributions())
        .print();
    unit_memory(&s.cast);
    Ok(())
}
