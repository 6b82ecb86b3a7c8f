//! `rtfpga render`: one scene, one engine, one PNG.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use sw_renderer::render::{render, save_png, RenderOptions};
use sw_renderer::scene::Scene;

use crate::engine::{self, EngineKind, HwConfig, MemoryArgs, PrecisionArgs};

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
    #[arg(long, value_enum, default_value_t = EngineKind::F32)]
    engine: EngineKind,
    #[command(flatten)]
    hw: HwConfig,
    #[command(flatten)]
    precision: PrecisionArgs,
    #[command(flatten)]
    memory: MemoryArgs,
    /// Output PNG.
    #[arg(long)]
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

pub fn run(a: Args) -> Result<()> {
    if a.engine != EngineKind::Traversal
        && (a.memory.scene_capacity.is_some() || a.memory.no_chunks)
    {
        bail!("--scene-capacity and --no-chunks describe the traversal unit: use them with --engine traversal");
    }
    let scene = Scene::load(&a.scene)?;
    let precision = a.precision.resolve(a.engine, &a.hw, &scene)?;
    let (spawn, scale_exp, lane) = (precision.spawn, precision.scale_exp, precision.lane);
    // The model's memory is the RTL's when --unit-memory names it.
    let memory = MemoryArgs {
        scene_capacity: a.memory.scene_capacity.or(a.hw.unit_memory),
        ..a.memory.clone()
    };
    let made = engine::make_scaled(a.engine, &a.hw, scale_exp, lane, memory.memory(a.hw.lanes))?;
    let engine = made.engine;
    let opts = RenderOptions {
        width: a.width,
        height: a.height,
        progress: !a.quiet,
        spawn,
        ..Default::default()
    };
    let out = render(&scene, engine.as_ref(), &opts)?;
    save_png(&out.image, &a.out).with_context(|| format!("writing {}", a.out.display()))?;
    let s = &out.stats;
    let secs = s.render_time.as_secs_f64();
    println!(
        "scene={} engine={} spawn={} scale_exp={} edges={} advance={} size={}x{} triangles={} rays={} mt_queries={} box_tests={} node_visits={} prepare_s={:.3} render_s={:.3} mrays_per_s={:.2}",
        scene.name,
        engine.name(),
        precision.choice.name(),
        scale_exp,
        lane.edges,
        lane.advance,
        out.image.width(),
        out.image.height(),
        scene.triangle_count(),
        s.trace.rays(),
        s.trace.cast.mt_tests,
        s.trace.cast.box_tests,
        s.trace.cast.node_visits,
        s.prepare_time.as_secs_f64(),
        secs,
        s.trace.rays() as f64 / secs.max(1e-9) / 1e6
    );
    if let Some(dual) = &made.dual {
        let d = dual.stats();
        println!(
            "dual_precision pair={} filter={} tests={} certain_misses={} forwarded={} forwarded_share={:.4}",
            dual.filter.pair,
            dual.filter.kind,
            d.tests,
            d.certain_misses,
            d.forwarded(),
            d.forwarded_share()
        );
    }
    let c = s.trace.cast;
    if c.passes > 0 {
        // The traversal unit's scene memory: one pass per wavefront and loaded chunk.
        println!(
            "unit_memory passes={} ray_passes={} chunk_loads={} loaded_bytes={}",
            c.passes, c.ray_passes, c.chunk_loads, c.loaded_bytes
        );
    }
    if c.cycles > 0 {
        // The traversal unit's schedule model (not a co-simulation).
        let rays = s.trace.rays().max(1) as f64;
        println!(
            "unit_schedule slots={} lanes={} cycles={} cycles_per_ray={:.2} box_tests_per_ray={:.2} mt_tests_per_ray={:.2} node_visits_per_ray={:.2} box_utilisation={:.3} lane_utilisation={:.3} mrays_per_s_at_100mhz={:.2}",
            a.hw.slots,
            a.hw.lanes,
            c.cycles,
            c.cycles as f64 / rays,
            c.box_tests as f64 / rays,
            c.mt_tests as f64 / rays,
            c.node_visits as f64 / rays,
            c.box_tests as f64 / c.cycles as f64,
            c.mt_tests as f64 / (c.cycles as f64 * a.hw.lanes as f64),
            rays / c.cycles as f64 * 100.0
        );
    }
    Ok(())
}
