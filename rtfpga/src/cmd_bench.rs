//! `rtfpga bench`: render scenes at several sizes and print a Markdown table of wall times
//! and ray throughput (what BENCHMARKS.md records).

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

use crate::engine::{self, ChunkArgs, EngineKind, HwConfig, Lane};
use crate::options::Given;
use crate::report::Line;

#[derive(ClapArgs)]
pub struct Args {
    /// Scenes (directories, .toml files or built-in names).
    #[arg(required = true)]
    scenes: Vec<String>,
    /// Comma-separated WxH sizes.
    #[arg(long, default_value = "320x180,1280x720")]
    sizes: String,
    /// Best of this many runs per point (1 to 1000).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeat: u32,
    /// What answers the rays.
    #[arg(long, value_enum, default_value_t = EngineKind::F32)]
    engine: EngineKind,
    #[command(flatten)]
    hw: HwConfig,
    #[command(flatten)]
    chunks: ChunkArgs,
}

fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once('x')
        .with_context(|| format!("size `{s}`: expected WxH, e.g. 320x180"))?;
    let (w, h): (u32, u32) = (
        w.parse()
            .with_context(|| format!("size `{s}`: bad width"))?,
        h.parse()
            .with_context(|| format!("size `{s}`: bad height"))?,
    );
    let max = crate::cmd_render::MAX_IMAGE_SIDE;
    if !(1..=max).contains(&w) || !(1..=max).contains(&h) {
        bail!("size `{s}`: width and height must be 1 to {max} pixels");
    }
    Ok((w, h))
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    if a.engine == EngineKind::Frame {
        return Err(engine::frame_is_not_a_ray_engine());
    }
    given.check(a.engine.target(&a.hw.datapath.format))?;
    let sizes = a
        .sizes
        .split(',')
        .map(parse_size)
        .collect::<Result<Vec<_>>>()?;
    let scenes = a
        .scenes
        .iter()
        .map(|s| Scene::load(s))
        .collect::<Result<Vec<_>, _>>()?;
    let made = engine::make(a.engine, &a.hw, 0, Lane::default(), &a.chunks)?;
    if let Some(v) = &made.verilated {
        v.line().print();
    }
    let engine = made.engine;
    Line::new()
        .kv("engine", engine.name())
        .kv("threads", rayon::current_num_threads())
        .kv("best_of", a.repeat)
        .print();
    println!("\n| scene | triangles | size | time (s) | rays | Mrays/s | MT tests |\n|---|---|---|---|---|---|---|");
    for scene in &scenes {
        for &(w, h) in &sizes {
            let opts = RenderOptions {
                width: Some(w),
                height: Some(h),
                ..Default::default()
            };
            let mut best = None::<sw_renderer::render::RenderStats>;
            for _ in 0..a.repeat {
                let stats = render(scene, engine.as_ref(), &opts)?.stats;
                let total = stats.prepare_time + stats.render_time;
                if best.is_none_or(|b| total < b.prepare_time + b.render_time) {
                    best = Some(stats);
                }
            }
            let s = best.expect("at least one run");
            let secs = (s.prepare_time + s.render_time).as_secs_f64();
            println!(
                "| {} | {} | {w}×{h} | {secs:.3} | {} | {:.2} | {} |",
                scene.name,
                scene.triangle_count(),
                s.trace.rays(),
                s.trace.rays() as f64 / secs / 1e6,
                s.trace.cast.mt_tests
            );
        }
    }
    Ok(())
}
