//! `rtfpga bench`: render scenes at several sizes and print a Markdown table of wall times
//! and ray throughput (what BENCHMARKS.md records).

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

use crate::engine::{self, EngineKind, HwConfig};

#[derive(ClapArgs)]
pub struct Args {
    /// Scenes (directories, .toml files or built-in names).
    #[arg(required = true)]
    scenes: Vec<String>,
    /// Comma-separated WxH sizes.
    #[arg(long, default_value = "320x180,1280x720")]
    sizes: String,
    /// Best of this many runs per point.
    #[arg(long, default_value_t = 3)]
    repeat: u32,
    #[arg(long, value_enum, default_value_t = EngineKind::F32)]
    engine: EngineKind,
    #[command(flatten)]
    hw: HwConfig,
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

pub fn run(a: Args) -> Result<()> {
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
    let engine = engine::make(a.engine, &a.hw)?;
    println!(
        "engine: {}, threads: {}, best of {}",
        engine.name(),
        rayon::current_num_threads(),
        a.repeat.max(1)
    );
    println!("\n| scene | triangles | size | time (s) | rays | Mrays/s | MT tests |\n|---|---|---|---|---|---|---|");
    for scene in &scenes {
        for &(w, h) in &sizes {
            let opts = RenderOptions {
                width: Some(w),
                height: Some(h),
                ..Default::default()
            };
            let mut best = None::<sw_renderer::render::RenderStats>;
            for _ in 0..a.repeat.max(1) {
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
