//! `rtfpga cosim`: render a scene through the Verilated accelerator (`--unit mt`) or the
//! Verilated traversal unit (`--unit traversal`), spawning secondary and shadow rays as
//! `render` does (`--spawn`, the same default), render it in software (f32, the thesis'
//! spawn: the golden images') at the same size, report the simulated work and speed, last
//! line `psnr_db=...`.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args as ClapArgs, ValueEnum};
use sim::accel_model::VcdWindow;
use sim::axil_master::Completion;
use sim::dual_pair::{PairConfig, PairIntersector};
use sim::hw_intersector::{HwIntersector, Mode};
use sim::traversal_unit::{Traffic, UnitEngine};
use sw_renderer::compare;
use sw_renderer::intersect::{F32Intersector, Intersector};
use sw_renderer::rays::RayEngine;
use sw_renderer::render::{render, save_png, RenderOptions, RenderOutput};
use sw_renderer::scene::Scene;
use sw_renderer::spawn::SpawnPolicy;

use crate::engine::{AdvanceArg, ChunkArgs, HwConfig, SpawnArgs, UnitKind, Verilated};
use crate::options::Given;
use crate::report::{self, Line};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ModeArg {
    /// AXI4-Stream batches, every lane busy.
    Stream,
    /// The thesis' AXI4-Lite register sequence per test (lane 0), polling ap_done.
    Register,
    /// The register sequence, waiting for the interrupt instead of polling.
    RegisterIrq,
}

#[derive(ClapArgs)]
pub struct Args {
    /// Scene directory with objects.txt, a .toml scene, or a built-in scene name.
    #[arg(long)]
    scene: String,
    /// The hardware: the Möller-Trumbore accelerator, or the traversal unit.
    #[arg(long, value_enum, default_value_t = UnitKind::Mt)]
    unit: UnitKind,
    #[command(flatten)]
    hw: HwConfig,
    #[command(flatten)]
    advance: AdvanceArg,
    #[command(flatten)]
    chunks: ChunkArgs,
    #[command(flatten)]
    spawn: SpawnArgs,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    height: Option<u32>,
    /// How queries reach the accelerator.
    #[arg(long, value_enum, default_value_t = ModeArg::Stream)]
    mode: ModeArg,
    /// Output image of the hardware render (.png; its folder is created).
    #[arg(long, value_name = "OUT.png")]
    out: PathBuf,
    /// Write a VCD waveform of the first simulated instance (builds a trace-enabled model).
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// First cycle of the VCD window (cycles since the instance was created, reset included).
    #[arg(long, default_value_t = 0, requires = "vcd")]
    vcd_from: u64,
    /// Cycles in the VCD window (1 to 100,000,000).
    #[arg(long, default_value_t = 2000, requires = "vcd",
          value_parser = clap::value_parser!(u64).range(1..=100_000_000))]
    vcd_cycles: u64,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The spawn policy by name and the policy itself, as `render --engine hw|traversal` in the
/// same format resolves them. The hardware takes its queries unscaled.
fn spawn(a: &Args) -> (&'static str, SpawnPolicy) {
    let format = a.hw.datapath.answer_format();
    let choice = a.spawn.choice(a.unit.engine(), &format);
    (choice.name(), choice.policy(&format, 0))
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    given.check(a.unit.target(&a.hw.datapath.format))?;
    // The configuration first (an error names it before any scene is read or model built).
    let build = Build::of(&a)?;
    let scene = Scene::load(&a.scene)?;
    report::image_out("--out", &a.out)?;
    if let Some(vcd) = &a.vcd {
        report::file_out(vcd)?;
    }
    match build {
        Build::Accelerator(mode) => run_accelerator(&a, &scene, mode),
        Build::Pair(pair) => run_pair(&a, &scene, &pair),
        Build::Unit(config) => run_traversal(&a, &scene, &config),
    }
}

/// What `cosim` builds.
enum Build {
    Accelerator(Mode),
    Pair(PairConfig),
    Unit(hdl::traversal::config::UnitConfig),
}

impl Build {
    fn of(a: &Args) -> Result<Build> {
        let advance = a.advance.advance.unwrap_or_default();
        if a.unit == UnitKind::Traversal {
            return Ok(Build::Unit(a.hw.unit_config(advance)?));
        }
        if matches!(a.hw.datapath.format, hw_model::dual::FormatChoice::Pair(_)) {
            return Ok(Build::Pair(a.hw.pair_config()?));
        }
        a.hw.datapath.top_config()?;
        Ok(Build::Accelerator(match a.mode {
            ModeArg::Stream => Mode::Stream,
            ModeArg::Register => Mode::Register(Completion::Poll),
            ModeArg::RegisterIrq => Mode::Register(Completion::Interrupt),
        }))
    }
}

fn run_accelerator(a: &Args, scene: &Scene, mode: Mode) -> Result<()> {
    let config = a.hw.datapath.top_config()?;
    let hw = match &a.vcd {
        Some(path) => HwIntersector::with_vcd(
            &config,
            mode,
            VcdWindow {
                path: path.clone(),
                from: a.vcd_from,
                cycles: a.vcd_cycles,
            },
        )?,
        None => HwIntersector::new(&config, mode)?,
    };
    Verilated::of_accelerator(&hw).line().print();
    let (spawn_name, spawn) = spawn(a);
    let out = render(scene, &hw, &options(a, spawn));
    hw.close_vcd();
    let out = out.with_context(|| format!("co-simulating {}", Intersector::name(&hw)))?;
    let sw = save_and_render_software(a, scene, &out)?;

    let s = hw.stats();
    let wall = out.stats.render_time.as_secs_f64();
    Line::new()
        .kv("scene", &scene.name)
        .kv(
            "size",
            format_args!("{}x{}", out.image.width(), out.image.height()),
        )
        .kv("engine", Intersector::name(&hw))
        .kv("spawn", spawn_name)
        .kv("tests", s.tests)
        .kv("cycles", s.cycles)
        .fixed("cycles_per_test", s.cycles_per_test(), 2)
        .fixed("lane_utilisation", s.lane_utilisation(), 4)
        .kv("transactions", s.transactions)
        .kv("instances", s.instances)
        .print();
    // Simulator speed per core: its CPU and wall time summed over the threads.
    Line::new()
        .fixed("sim_cycles_per_s", s.cycles_per_sec(), 0)
        .fixed("tests_per_s", s.tests_per_sec(), 0)
        .fixed("sim_cpu_s", s.sim_cpu_time.as_secs_f64(), 2)
        .fixed("sim_wall_s", s.sim_time.as_secs_f64(), 2)
        .fixed("wall_s", wall, 2)
        .fixed("wall_tests_per_s", s.tests as f64 / wall.max(1e-9), 0)
        .print();
    if let Some(path) = &a.vcd {
        Line::new()
            .path("vcd", path)
            .kv("vcd_from", a.vcd_from)
            .kv("vcd_to", a.vcd_from + a.vcd_cycles)
            .print();
    }
    print_comparison(a, &out, &sw)
}

/// `--format bfp18/fp32`: the render's queries through the Verilated dual-precision pair,
/// the share the filters forwarded to the fp32 lane and the tests per cycle.
fn run_pair(a: &Args, scene: &Scene, pair: &PairConfig) -> Result<()> {
    let hw = PairIntersector::new(pair)?;
    Verilated::of(Intersector::name(&hw), hw.model())
        .line()
        .print();
    let (spawn_name, spawn) = spawn(a);
    let out = render(scene, &hw, &options(a, spawn))
        .with_context(|| format!("co-simulating {}", Intersector::name(&hw)))?;
    let sw = save_and_render_software(a, scene, &out)?;
    let s = hw.stats();
    Line::new()
        .kv("scene", &scene.name)
        .kv(
            "size",
            format_args!("{}x{}", out.image.width(), out.image.height()),
        )
        .kv("engine", Intersector::name(&hw))
        .kv("spawn", spawn_name)
        .kv("tests", s.tests)
        .kv("forwarded", s.forwarded)
        .fixed("forwarded_share", s.forwarded_share(), 4)
        .kv("cycles", s.cycles)
        .fixed("tests_per_cycle", s.tests_per_cycle(), 4)
        .kv("stall_cycles", s.stall_cycles)
        .print();
    print_comparison(a, &out, &sw)
}

/// The render options of `a`, spawning with `spawn`.
fn options(a: &Args, spawn: SpawnPolicy) -> RenderOptions {
    RenderOptions {
        width: a.width,
        height: a.height,
        progress: !a.quiet,
        spawn,
        ..Default::default()
    }
}

/// The hardware render saved, the software render (f32, the thesis' spawn) at the same size.
fn save_and_render_software(a: &Args, scene: &Scene, hw: &RenderOutput) -> Result<RenderOutput> {
    save_png(&hw.image, &a.out)?;
    let opts = RenderOptions {
        progress: false,
        ..options(a, SpawnPolicy::Thesis)
    };
    Ok(render(scene, &F32Intersector, &opts)?)
}

/// `out=…`, `differing_pixels=…` and, last, `psnr_db=…` of the hardware render against the
/// software.
fn print_comparison(a: &Args, hw: &RenderOutput, sw: &RenderOutput) -> Result<()> {
    let diff = compare::compare(&hw.image, &sw.image)?;
    Line::new().path("out", &a.out).print();
    Line::new()
        .kv("differing_pixels", diff.differing_pixels)
        .kv("max_abs_error", diff.max_abs_error)
        .print();
    Line::new()
        .kv("psnr_db", report::psnr(diff.psnr_db))
        .print();
    Ok(())
}

/// `--unit traversal`: the render's rays through the Verilated traversal unit (chunked
/// passes when the scene exceeds its memory, unless `--no-chunks`), its counters and cycles
/// per render ray.
fn run_traversal(
    a: &Args,
    scene: &Scene,
    config: &hdl::traversal::config::UnitConfig,
) -> Result<()> {
    let engine = UnitEngine::new(config, Traffic::FULL_SPEED, !a.chunks.no_chunks)?;
    let name = RayEngine::name(&engine);
    Verilated::of(name.clone(), engine.model()).line().print();
    let (spawn_name, spawn) = spawn(a);
    let out = render(scene, &engine, &options(a, spawn))
        .with_context(|| format!("co-simulating {name}"))?;
    let sw = save_and_render_software(a, scene, &out)?;
    let c = out.stats.trace.cast;
    let s = engine.stats();
    let rays = out.stats.trace.rays();
    let per_ray = |n: u64| n as f64 / rays.max(1) as f64;
    let cycles = c.cycles.max(1) as f64;
    Line::new()
        .kv("scene", &scene.name)
        .kv(
            "size",
            format_args!("{}x{}", out.image.width(), out.image.height()),
        )
        .kv("engine", &name)
        .kv("spawn", spawn_name)
        .kv("rays", rays)
        .kv("cycles", c.cycles)
        .fixed("cycles_per_ray", per_ray(c.cycles), 2)
        .fixed("node_visits_per_ray", per_ray(c.node_visits), 2)
        .fixed("box_tests_per_ray", per_ray(c.box_tests), 2)
        .fixed("mt_tests_per_ray", per_ray(c.mt_tests), 2)
        .fixed("box_utilisation", c.box_tests as f64 / cycles, 4)
        .fixed(
            "lane_utilisation",
            c.mt_tests as f64 / (cycles * config.lanes as f64),
            4,
        )
        .kv("busy_cycles", s.runs.busy_cycles)
        .kv("instances", s.instances)
        .print();
    Line::labelled("unit_memory")
        .kv("passes", c.passes)
        .kv("ray_passes", c.ray_passes)
        .kv("chunk_loads", c.chunk_loads)
        .kv("loaded_bytes", c.loaded_bytes)
        .kv("loads", s.loads)
        .kv("load_cycles", s.load_cycles)
        .print();
    // Simulator speed per core: simulated cycles over the simulating threads' CPU time.
    let core_s = s.core_seconds();
    Line::new()
        .fixed("sim_cycles_per_s", s.sim_cycles as f64 / core_s, 0)
        .fixed("rays_per_s", rays as f64 / core_s, 0)
        .kv("sim_cycles", s.sim_cycles)
        .fixed("sim_cpu_s", s.sim_cpu_time.as_secs_f64(), 2)
        .fixed("sim_wall_s", s.sim_time.as_secs_f64(), 2)
        .fixed("wall_s", out.stats.render_time.as_secs_f64(), 2)
        .print();
    print_comparison(a, &out, &sw)
}
