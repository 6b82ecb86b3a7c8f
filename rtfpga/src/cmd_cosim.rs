//! `rtfpga cosim`: render a scene through the Verilated accelerator (`--unit mt`) or the
//! Verilated traversal unit (`--unit traversal`), spawning secondary and shadow rays as
//! `render` does (`--spawn`, the same default), render it in software (f32, the thesis'
//! spawn: the golden images') at the same size, report the simulated work and speed, last
//! line `psnr_db=...`.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, ValueEnum};
use sim::accel_model::VcdWindow;
use sim::axil_master::Completion;
use sim::dual_pair::{PairConfig, PairIntersector};
use sim::hw_intersector::{HwIntersector, Mode};
use sim::traversal_unit::{Traffic, UnitEngine};
use sw_renderer::compare;
use sw_renderer::intersect::{F32Intersector, Intersector};
use sw_renderer::render::{render, save_png, RenderOptions, RenderOutput};
use sw_renderer::scene::Scene;
use sw_renderer::spawn::SpawnPolicy;

use crate::engine::{HwConfig, SpawnArgs, UnitAdvanceArgs, UnitKind};

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
    advance: UnitAdvanceArgs,
    #[command(flatten)]
    spawn: SpawnArgs,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    height: Option<u32>,
    /// How queries reach the accelerator (`--unit mt`).
    #[arg(long, value_enum, default_value_t = ModeArg::Stream)]
    mode: ModeArg,
    /// Output PNG of the hardware render.
    #[arg(long)]
    out: PathBuf,
    /// Write a VCD waveform of the first simulated instance (builds a trace-enabled model).
    #[arg(long)]
    vcd: Option<PathBuf>,
    /// First cycle of the VCD window (cycles since the instance was created, reset included).
    #[arg(long, default_value_t = 0, requires = "vcd")]
    vcd_from: u64,
    /// Cycles in the VCD window.
    #[arg(long, default_value_t = 2000, requires = "vcd")]
    vcd_cycles: u64,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The spawn policy by name and the policy itself, as `render --engine hw|traversal` in the
/// same format resolves them. The hardware takes its queries unscaled.
fn spawn(a: &Args) -> Result<(&'static str, SpawnPolicy)> {
    let format = a.hw.answer_format();
    let choice = a.spawn.choice(a.unit.engine(), &format);
    Ok((choice.name(), choice.policy(&format, 0)))
}

pub fn run(a: Args) -> Result<()> {
    a.advance.of(a.unit)?;
    let scene = Scene::load(&a.scene)?;
    if a.unit == UnitKind::Traversal {
        return run_traversal(&a, &scene);
    }
    let (spawn_name, spawn) = spawn(&a)?;
    if let Some(pair) = a.hw.pair_config()? {
        return run_pair(&a, &scene, &pair, spawn_name, spawn);
    }
    let config = a.hw.top_config()?;
    let mode = match a.mode {
        ModeArg::Stream => Mode::Stream,
        ModeArg::Register => Mode::Register(Completion::Poll),
        ModeArg::RegisterIrq => Mode::Register(Completion::Interrupt),
    };
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
    let built = hw.model();
    println!(
        "model {} ({}, {:.1} s)",
        hw.name(),
        if built.model.cached {
            "cached"
        } else {
            "built"
        },
        built.build_time.as_secs_f64()
    );
    let out = render(&scene, &hw, &options(&a, spawn));
    hw.close_vcd();
    let out = out.with_context(|| format!("co-simulating {}", hw.name()))?;
    let sw = save_and_render_software(&a, &scene, &out)?;

    let s = hw.stats();
    let wall = out.stats.render_time.as_secs_f64();
    println!(
        "scene={} size={}x{} engine=\"{}\" spawn={spawn_name} tests={} cycles={} cycles_per_test={:.2} lane_utilisation={:.4} transactions={} instances={}",
        scene.name,
        out.image.width(),
        out.image.height(),
        hw.name(),
        s.tests,
        s.cycles,
        s.cycles_per_test(),
        s.lane_utilisation(),
        s.transactions,
        s.instances
    );
    println!(
        "sim_cycles_per_s={:.0} tests_per_s={:.0} (per core: simulator CPU time {:.2} s, simulator wall time {:.2} s) wall_s={:.2} wall_tests_per_s={:.0}",
        s.cycles_per_sec(),
        s.tests_per_sec(),
        s.sim_cpu_time.as_secs_f64(),
        s.sim_time.as_secs_f64(),
        wall,
        s.tests as f64 / wall.max(1e-9)
    );
    if let Some(path) = &a.vcd {
        println!(
            "vcd={} (cycles {}..{})",
            path.display(),
            a.vcd_from,
            a.vcd_from + a.vcd_cycles
        );
    }
    print_comparison(&out, &sw)
}

/// `--format bfp18/fp32`: the render's queries through the Verilated dual-precision pair,
/// the share the filters forwarded to the fp32 lane and the tests per cycle.
fn run_pair(
    a: &Args,
    scene: &Scene,
    pair: &PairConfig,
    spawn_name: &str,
    spawn: SpawnPolicy,
) -> Result<()> {
    if a.mode != ModeArg::Stream || a.vcd.is_some() {
        bail!("--format {}: the dual-precision pair is driven at its ports (no AXI bus: --mode stream, no --vcd)", a.hw.format);
    }
    let hw = PairIntersector::new(pair)?;
    println!(
        "model {} ({:.1} s)",
        hw.name(),
        hw.build_time().as_secs_f64()
    );
    let out = render(scene, &hw, &options(a, spawn))
        .with_context(|| format!("co-simulating {}", hw.name()))?;
    let sw = save_and_render_software(a, scene, &out)?;
    let s = hw.stats();
    println!(
        "scene={} size={}x{} engine=\"{}\" spawn={spawn_name} tests={} forwarded={} forwarded_share={:.4} cycles={} tests_per_cycle={:.4} stall_cycles={}",
        scene.name,
        out.image.width(),
        out.image.height(),
        hw.name(),
        s.tests,
        s.forwarded,
        s.forwarded_share(),
        s.cycles,
        s.tests_per_cycle(),
        s.stall_cycles
    );
    print_comparison(&out, &sw)
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
    save_png(&hw.image, &a.out).with_context(|| format!("writing {}", a.out.display()))?;
    let opts = RenderOptions {
        progress: false,
        ..options(a, SpawnPolicy::Thesis)
    };
    Ok(render(scene, &F32Intersector, &opts)?)
}

/// `differing_pixels=…` and, last, `psnr_db=…` of the hardware render against the software.
fn print_comparison(hw: &RenderOutput, sw: &RenderOutput) -> Result<()> {
    let diff = compare::compare(&hw.image, &sw.image)?;
    println!(
        "differing_pixels={} max_abs_error={}",
        diff.differing_pixels, diff.max_abs_error
    );
    let psnr = if diff.psnr_db.is_infinite() {
        "inf".to_string()
    } else {
        format!("{:.4}", diff.psnr_db)
    };
    println!("psnr_db={psnr}");
    Ok(())
}

/// `--unit traversal`: the render's rays through the Verilated traversal unit (chunked
/// passes when the scene exceeds its memory), its counters and cycles per render ray.
fn run_traversal(a: &Args, scene: &Scene) -> Result<()> {
    if a.mode != ModeArg::Stream || a.vcd.is_some() {
        bail!("--mode register/register-irq and --vcd are options of --unit mt: the traversal unit takes its rays over its own stream");
    }
    let config = a.hw.unit_config(a.advance.of(a.unit)?)?;
    let (spawn_name, spawn) = spawn(a)?;
    let engine = UnitEngine::new(&config, Traffic::FULL_SPEED, true)?;
    let name = sw_renderer::rays::RayEngine::name(&engine);
    let built = engine.model();
    println!(
        "model {} ({}, {:.1} s)",
        name,
        if built.model.cached {
            "cached"
        } else {
            "built"
        },
        built.build_time.as_secs_f64()
    );
    let out = render(scene, &engine, &options(a, spawn))
        .with_context(|| format!("co-simulating {}", name))?;
    let sw = save_and_render_software(a, scene, &out)?;
    let c = out.stats.trace.cast;
    let s = engine.stats();
    let rays = out.stats.trace.rays();
    let per_ray = |n: u64| n as f64 / rays.max(1) as f64;
    let cycles = c.cycles.max(1) as f64;
    println!(
        "scene={} size={}x{} engine=\"{}\" spawn={spawn_name} rays={rays} cycles={} cycles_per_ray={:.2} node_visits_per_ray={:.2} box_tests_per_ray={:.2} mt_tests_per_ray={:.2} box_utilisation={:.4} lane_utilisation={:.4} busy_cycles={} instances={}",
        scene.name,
        out.image.width(),
        out.image.height(),
        name,
        c.cycles,
        per_ray(c.cycles),
        per_ray(c.node_visits),
        per_ray(c.box_tests),
        per_ray(c.mt_tests),
        c.box_tests as f64 / cycles,
        c.mt_tests as f64 / (cycles * config.lanes as f64),
        s.runs.busy_cycles,
        s.instances
    );
    println!(
        "unit_memory passes={} ray_passes={} chunk_loads={} loaded_bytes={} loads={} load_cycles={}",
        c.passes, c.ray_passes, c.chunk_loads, c.loaded_bytes, s.loads, s.load_cycles
    );
    let sim_s = s.sim_time.as_secs_f64().max(1e-9);
    println!(
        "sim_cycles_per_s={:.0} rays_per_s={:.0} (per core: {} simulated cycles in {:.2} s of simulator wall time, summed over threads) wall_s={:.2}",
        s.sim_cycles as f64 / sim_s,
        rays as f64 / sim_s,
        s.sim_cycles,
        sim_s,
        out.stats.render_time.as_secs_f64()
    );
    print_comparison(&out, &sw)
}
