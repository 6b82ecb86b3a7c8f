//! `rtfpga cosim`: render a scene through the Verilated accelerator, render it in software
//! (f32) at the same size, report the simulated work and speed, last line `psnr_db=...`.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args as ClapArgs, ValueEnum};
use sim::accel_model::VcdWindow;
use sim::axil_master::Completion;
use sim::hw_intersector::{HwIntersector, Mode};
use sw_renderer::compare;
use sw_renderer::intersect::{F32Intersector, Intersector};
use sw_renderer::render::{render, save_png, RenderOptions};
use sw_renderer::scene::Scene;

use crate::engine::HwConfig;

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
    #[command(flatten)]
    hw: HwConfig,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    height: Option<u32>,
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

pub fn run(a: Args) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
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
    let opts = RenderOptions {
        width: a.width,
        height: a.height,
        progress: !a.quiet,
        ..Default::default()
    };
    let out = render(&scene, &hw, &opts);
    hw.close_vcd();
    let out = out.with_context(|| format!("co-simulating {}", hw.name()))?;
    save_png(&out.image, &a.out).with_context(|| format!("writing {}", a.out.display()))?;
    let sw = render(
        &scene,
        &F32Intersector,
        &RenderOptions {
            progress: false,
            ..opts
        },
    )?;
    let diff = compare::compare(&out.image, &sw.image)?;

    let s = hw.stats();
    let wall = out.stats.render_time.as_secs_f64();
    println!(
        "scene={} size={}x{} engine=\"{}\" tests={} cycles={} cycles_per_test={:.2} lane_utilisation={:.4} transactions={} instances={}",
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
