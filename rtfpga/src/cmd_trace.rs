//! `rtfpga trace record|replay`: record the ray-triangle queries of a real render to a trace
//! file (docs/trace.md), replay one into the bit-accurate model and/or the Verilated
//! hardware, and report the first difference or "identical".

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use clap::{Args as ClapArgs, Subcommand, ValueEnum};
use hw_model::ModelIntersector;
use indicatif::{ProgressBar, ProgressStyle};
use sim::hw_intersector::{HwIntersector, Mode};
use sim::trace::{first_difference, read_trace, replay, write_trace, Recorder};
use sw_renderer::intersect::{F32Intersector, Intersector, MtQuery, MtResult};
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

use crate::engine::HwConfig;

#[derive(ClapArgs)]
pub struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene in software (f32) and record every query it asks.
    Record(RecordArgs),
    /// Replay a trace into the model and/or the hardware; report the first difference.
    Replay(ReplayArgs),
}

#[derive(ClapArgs)]
struct RecordArgs {
    /// Scene directory with objects.txt, a .toml scene, or a built-in scene name.
    #[arg(long)]
    scene: String,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    height: Option<u32>,
    /// Output trace file.
    #[arg(long)]
    out: PathBuf,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ReplayEngine {
    Model,
    Hw,
    Both,
}

#[derive(ClapArgs)]
struct ReplayArgs {
    /// The trace file.
    trace: PathBuf,
    #[command(flatten)]
    hw: HwConfig,
    #[arg(long, value_enum, default_value_t = ReplayEngine::Both)]
    engine: ReplayEngine,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

pub fn run(a: Args) -> Result<()> {
    match a.command {
        Command::Record(r) => record(r),
        Command::Replay(r) => replay_trace(r),
    }
}

fn record(a: RecordArgs) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
    let rec = Recorder::new(&F32Intersector);
    let opts = RenderOptions {
        width: a.width,
        height: a.height,
        ..Default::default()
    };
    render(&scene, &rec, &opts)?;
    let queries = rec.into_queries();
    write_trace(&a.out, &queries)?;
    println!(
        "scene={} queries={} file={}",
        scene.name,
        queries.len(),
        a.out.display()
    );
    Ok(())
}

/// Replays `queries` into `isect` with a progress bar; prints and returns the results.
fn timed(isect: &dyn Intersector, queries: &[MtQuery], quiet: bool) -> Result<Vec<MtResult>> {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(queries.len() as u64)
    };
    if let Ok(style) =
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} queries {elapsed}/{eta}")
    {
        bar.set_style(style);
    }
    bar.set_message(isect.name());
    let start = Instant::now();
    let results = replay(isect, queries, &|n| bar.inc(n as u64));
    bar.finish_and_clear();
    let results = results.map_err(|e| anyhow::anyhow!(e).context(isect.name()))?;
    let secs = start.elapsed().as_secs_f64();
    println!(
        "engine=\"{}\" queries={} wall_s={secs:.3} tests_per_s={:.0}",
        isect.name(),
        queries.len(),
        queries.len() as f64 / secs.max(1e-9)
    );
    Ok(results)
}

fn replay_trace(a: ReplayArgs) -> Result<()> {
    let queries = read_trace(&a.trace)?;
    let model = ModelIntersector::new(a.hw.single_format()?);
    let want = if a.engine != ReplayEngine::Hw {
        Some(timed(&model, &queries, a.quiet)?)
    } else {
        None
    };
    if a.engine == ReplayEngine::Model {
        return Ok(());
    }
    let hw = HwIntersector::new(&a.hw.top_config()?, Mode::Stream)?;
    let got = timed(&hw, &queries, a.quiet)?;
    let s = hw.stats();
    println!(
        "cycles={} lane_utilisation={:.4} sim_cycles_per_s={:.0} tests_per_s={:.0} (per core: simulator CPU time {:.2} s, wall time {:.2} s)",
        s.cycles,
        s.lane_utilisation(),
        s.cycles_per_sec(),
        s.tests_per_sec(),
        s.sim_cpu_time.as_secs_f64(),
        s.sim_time.as_secs_f64()
    );
    if let Some(want) = want {
        match first_difference(&got, &want) {
            None => println!("identical ({} queries, hardware = model)", queries.len()),
            Some(d) => {
                println!("first difference: {d} (hardware vs model)");
                bail!("the hardware and the model differ on {}", a.trace.display());
            }
        }
    }
    Ok(())
}
