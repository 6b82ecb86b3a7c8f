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

use crate::engine::{Datapath, Verilated};
use crate::options::{Given, Target};
use crate::report::{self, Line};

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
    /// Output trace file (its folder is created).
    #[arg(long)]
    out: PathBuf,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ReplayEngine {
    /// The bit-accurate model of the datapath.
    Model,
    /// The Verilated accelerator.
    Hw,
    /// Both, and the first query where they differ.
    Both,
}

#[derive(ClapArgs)]
struct ReplayArgs {
    /// The trace file (`trace record`).
    trace: PathBuf,
    #[command(flatten)]
    datapath: Datapath,
    /// What answers the queries.
    #[arg(long, value_enum, default_value_t = ReplayEngine::Both)]
    engine: ReplayEngine,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    match a.command {
        Command::Record(r) => record(r),
        Command::Replay(r) => replay_trace(r, given),
    }
}

fn record(a: RecordArgs) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
    report::file_out(&a.out)?;
    let rec = Recorder::new(&F32Intersector);
    let opts = RenderOptions {
        width: a.width,
        height: a.height,
        ..Default::default()
    };
    render(&scene, &rec, &opts)?;
    let queries = rec.into_queries();
    write_trace(&a.out, &queries)?;
    Line::new()
        .kv("scene", &scene.name)
        .kv("queries", queries.len())
        .path("out", &a.out)
        .print();
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
    Line::new()
        .kv("engine", isect.name())
        .kv("queries", queries.len())
        .fixed("wall_s", secs, 3)
        .fixed("tests_per_s", queries.len() as f64 / secs.max(1e-9), 0)
        .print();
    Ok(results)
}

fn replay_trace(a: ReplayArgs, given: &Given) -> Result<()> {
    given.check(match a.engine {
        ReplayEngine::Model => Target::Model,
        ReplayEngine::Hw | ReplayEngine::Both => Target::Accelerator,
    })?;
    let format = a.datapath.single_format()?;
    let config = match a.engine {
        ReplayEngine::Model => None,
        ReplayEngine::Hw | ReplayEngine::Both => Some(a.datapath.top_config()?),
    };
    let queries = read_trace(&a.trace)?;
    let model = ModelIntersector::new(format);
    let want = if a.engine != ReplayEngine::Hw {
        Some(timed(&model, &queries, a.quiet)?)
    } else {
        None
    };
    let Some(config) = config else {
        return Ok(());
    };
    let hw = HwIntersector::new(&config, Mode::Stream)?;
    Verilated::of_accelerator(&hw).line().print();
    let got = timed(&hw, &queries, a.quiet)?;
    let s = hw.stats();
    // Simulator speed per core: its CPU and wall time summed over the threads.
    Line::new()
        .kv("cycles", s.cycles)
        .fixed("lane_utilisation", s.lane_utilisation(), 4)
        .fixed("sim_cycles_per_s", s.cycles_per_sec(), 0)
        .fixed("sim_tests_per_s", s.tests_per_sec(), 0)
        .fixed("sim_cpu_s", s.sim_cpu_time.as_secs_f64(), 2)
        .fixed("sim_wall_s", s.sim_time.as_secs_f64(), 2)
        .print();
    if let Some(want) = want {
        match first_difference(&got, &want) {
            None => println!(
                "identical: the hardware answers as the model on all {} queries",
                queries.len()
            ),
            Some(d) => {
                println!("first difference: {d} (hardware vs model)");
                bail!("the hardware and the model differ on {}", a.trace.display());
            }
        }
    }
    Ok(())
}
