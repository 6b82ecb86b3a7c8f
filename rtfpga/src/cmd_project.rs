//! `rtfpga project`: the projected frame time of a scene on the ZedBoard for an accelerator
//! design, and (`--calibration`) the model against every time the thesis measured.
//! The model is `sim::projection`; docs/projection.md explains it.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, ValueEnum};
use hw_model::traversal::{TraversalEngine, DEFAULT_STACK_DEPTH};
use hw_model::Advance;
use sim::projection::{
    self, Board, Calibration, Design, Frontend, Role, Setup, Traversal, Workload, Workloads,
};
use sw_renderer::render::RenderOptions;
use sw_renderer::scene::Scene;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DesignKind {
    /// The thesis' accelerator: one AXI4-Lite call per ray-triangle test.
    Thesis,
    /// The project's: queries streamed by DMA through HP ports into pipelined lanes.
    Stream,
    /// The traversal unit: the scene in the unit, rays in and answers out over HP ports
    /// (cycles from its schedule model on the scene's frame).
    Traversal,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TraversalKind {
    /// Every ray against every triangle, as the thesis' renderer.
    BruteForce,
    /// Only the BVH's candidates, as the project's renderer.
    Bvh,
}

/// Mean latency of the thesis' HLS unit (Run 1): the midpoint of its 32–110 cycles.
const THESIS_CYCLES_PER_TEST: f64 = 71.0;

#[derive(ClapArgs)]
pub struct Args {
    /// Scene directory, .toml scene or built-in name (not needed with --calibration alone).
    #[arg(long)]
    scene: Option<String>,
    /// Override the scene's width (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side())]
    height: Option<u32>,
    #[arg(long, value_enum, default_value_t = DesignKind::Stream)]
    design: DesignKind,
    /// How candidates are found [default: brute-force for thesis, bvh for stream].
    #[arg(long, value_enum)]
    traversal: Option<TraversalKind>,
    /// Datapath number format of the stream design (sets its pipeline latency with --depth).
    #[arg(long, default_value = "fp32")]
    format: hw_model::HwFormat,
    /// Pipeline registers per operator of the stream design.
    #[arg(long, default_value_t = 1)]
    depth: usize,
    /// Stream, traversal: MT lanes; thesis: accelerators.
    #[arg(long, default_value_t = 1)]
    lanes: u32,
    /// Traversal: ray slots of the unit.
    #[arg(long, default_value_t = hdl::traversal::timing::DEFAULT_SLOTS as u32,
          value_parser = clap::value_parser!(u32).range(1..=1024))]
    slots: u32,
    /// Fabric clock f_PL in MHz.
    #[arg(long, default_value_t = 100.0)]
    fpl_mhz: f64,
    /// Thesis: mean cycles of one call [default: 71, Run 1's 32–110 midpoint];
    /// stream: cycles between queries per lane [default: 1, II = 1].
    #[arg(long)]
    cycles_per_test: Option<f64>,
    /// Stream, traversal: HP ports the DMA uses (1–4).
    #[arg(long, default_value_t = 1)]
    hp_ports: u32,
    /// Stream, traversal: fraction of the HP ports' peak bandwidth the DMA reaches.
    #[arg(long, default_value_t = 0.8)]
    dma_efficiency: f64,
    /// Stream: ARM cycles to pack one query into the DMA buffer; traversal: to write one
    /// ray and read its answer.
    #[arg(long, default_value_t = 40.0)]
    pack_cycles: f64,
    /// Traversal: the unit's scene memory.
    #[command(flatten)]
    memory: crate::engine::MemoryArgs,
    /// Edge of the renderer's square tiles: one tile's rays per level form a wavefront (a
    /// chunked unit loads every chunk once per wavefront).
    #[arg(long, default_value_t = RenderOptions::default().tile_size,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    tile_size: u32,
    /// Print the calibration table (measured vs modelled thesis times).
    #[arg(long)]
    calibration: bool,
    /// With --calibration: skip the slow scenes (Glass pen, Glasses, All materials).
    #[arg(long)]
    quick: bool,
    /// Directory of the thesis scenes the model is calibrated on [default:
    /// $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis beside the source tree rtfpga was
    /// built from].
    #[arg(long)]
    thesis_scenes: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<()> {
    if a.scene.is_none() && !a.calibration {
        bail!("nothing to do: give --scene to project a frame and/or --calibration");
    }
    let design = design(&a)?;
    if a.design != DesignKind::Traversal
        && (a.memory.scene_capacity.is_some() || a.memory.no_chunks)
    {
        bail!("--scene-capacity and --no-chunks describe the traversal unit: use them with --design traversal");
    }
    let thesis_scenes = match &a.thesis_scenes {
        Some(dir) => dir.clone(),
        None => sw_renderer::thesis_scenes::locate()?.with_context(|| {
            format!(
                "{} (looked for {}); or give --thesis-scenes",
                sw_renderer::thesis_scenes::NOT_FOUND,
                sw_renderer::thesis_scenes::fallback_dir().display()
            )
        })?,
    };
    if !thesis_scenes.is_dir() {
        bail!(
            "thesis scenes: {} is not a directory (set --thesis-scenes)",
            thesis_scenes.display()
        );
    }
    let mut workloads = Workloads::new(&thesis_scenes);
    let quick = a.quick;
    let calibration = projection::calibrate(&mut workloads, |m| {
        !quick
            || [
                "Simple_plane_scene",
                "Simple_plane2_scene",
                "Utah_teapot_scene",
            ]
            .contains(&m.scene)
    })
    .context("calibrating the model on the thesis' measurements")?;
    if a.calibration {
        print_calibration(&calibration);
    }
    if let Some(spec) = &a.scene {
        let scene = Scene::load(spec)?;
        let width = a.width.unwrap_or(scene.options.width);
        let height = a.height.unwrap_or(scene.options.height);
        let mut workload = Workload::measure(&scene, width, height)?;
        if a.design == DesignKind::Traversal {
            let engine = TraversalEngine {
                format: a.format.format(),
                stack_depth: DEFAULT_STACK_DEPTH,
                scale_exp: 0,
                advance: Advance::None,
                timing: Some(hdl::traversal::timing::unit_timing(
                    a.format,
                    a.depth,
                    a.lanes as usize,
                    a.slots as usize,
                    Advance::None,
                )),
                memory: a.memory.memory(a.lanes as usize),
        nodes: hw_model::traversal::NodeFormat::Bvh2Fp32,
            };
            workload = workload.with_unit(&scene, &engine, a.tile_size)?;
        }
        print_projection(&workload, &design, &calibration.board)?;
    }
    Ok(())
}

fn design(a: &Args) -> Result<Design> {
    let traversal = match a.traversal {
        Some(TraversalKind::BruteForce) => Traversal::BruteForce,
        Some(TraversalKind::Bvh) => Traversal::Bvh,
        None if a.design == DesignKind::Thesis => Traversal::BruteForce,
        None => Traversal::Bvh,
    };
    let frontend = match a.design {
        DesignKind::Thesis => {
            if a.format != hw_model::HwFormat::FP32 {
                bail!(
                    "--format {}: the thesis design is the fp32 HLS unit",
                    a.format
                );
            }
            Frontend::Thesis {
                units: a.lanes,
                cycles_per_test: a.cycles_per_test.unwrap_or(THESIS_CYCLES_PER_TEST),
            }
        }
        DesignKind::Traversal => {
            if a.cycles_per_test.is_some() {
                bail!(
                    "--cycles-per-test: the traversal design's cycles come from its schedule model"
                );
            }
            Frontend::Traversal {
                hp_ports: a.hp_ports,
                dma_efficiency: a.dma_efficiency,
                pack_arm_cycles: a.pack_cycles,
            }
        }
        DesignKind::Stream => {
            let latency = hdl::mt::latency(a.format, a.depth);
            Frontend::Stream {
                lanes: a.lanes,
                cycles_per_test: a.cycles_per_test.unwrap_or(1.0),
                pipeline_latency: u32::try_from(latency).context("pipeline latency")?,
                hp_ports: a.hp_ports,
                dma_efficiency: a.dma_efficiency,
                pack_arm_cycles: a.pack_cycles,
            }
        }
    };
    let d = Design {
        frontend,
        traversal,
        fpl_mhz: a.fpl_mhz,
    };
    d.validate()?;
    Ok(d)
}

fn print_projection(w: &Workload, d: &Design, b: &Board) -> Result<()> {
    let p = projection::project(w, d, b)?;
    // The thesis' software on the ARM, and the same with the BVH (traversal not counted).
    let arm = b.arm_only_s(w, Traversal::BruteForce);
    let arm_bvh = b.arm_only_s(w, Traversal::Bvh);
    println!("scene: {} at {}x{}", w.scene, w.width, w.height);
    println!(
        "design: {:?}, traversal {:?}, f_PL {} MHz",
        d.frontend, d.traversal, d.fpl_mhz
    );
    println!(
        "rays: {} (primary {}, reflection {}, refraction {}, shadow {}); tests: {}",
        w.rays(),
        w.primary_rays,
        w.reflection_rays,
        w.refraction_rays,
        w.shadow_rays,
        p.tests
    );
    println!("\n| term | seconds |\n|---|---|");
    println!("| ARM | {:.4} |", p.arm_s);
    println!("| bus (AXI4-Lite) | {:.4} |", p.bus_s);
    println!("| accelerator | {:.4} |", p.accel_s);
    println!("| total | {:.4} |", p.total_s());
    if let Some(u) = &w.unit {
        let rays = w.rays().max(1) as f64;
        println!(
            "\nunit (schedule model): cycles_per_ray={:.2} box_tests_per_ray={:.2} mt_tests_per_ray={:.2} image_bytes={}",
            u.cycles as f64 / rays,
            u.box_tests as f64 / rays,
            u.mt_tests as f64 / rays,
            u.image_bytes
        );
        println!(
            "scene memory: wavefronts={} passes={} ray_passes={} chunk_loads={} loaded_bytes={} load_cycles_per_ray={:.2}",
            u.wavefronts,
            u.passes,
            u.ray_passes,
            u.chunk_loads,
            u.loaded_bytes,
            projection::load_cycles(u, d).unwrap_or(0.0) / rays
        );
    }
    println!(
        "\narm_software_s={arm:.4} arm_bvh_software_s={arm_bvh:.4} total_s={:.4} speedup_vs_arm={:.2} speedup_vs_arm_bvh={:.2}",
        p.total_s(),
        arm / p.total_s(),
        arm_bvh / p.total_s()
    );
    if let Some(walk) = b.arm_bvh_walk_s(w) {
        println!(
            "arm_bvh_walk_s={walk:.4} speedup_vs_arm_bvh_walk={:.2}",
            walk / p.total_s()
        );
    }
    Ok(())
}

fn print_calibration(c: &Calibration) {
    let b = &c.board;
    println!("fitted constants (4, from the 4 `fit` rows; all other rows are held-out checks):");
    println!("  ARM per ray (non-MT work)  {:.1} ns", b.arm_ray_ns);
    println!(
        "  ARM per MT test            {:.1} ns ({:.1} cycles at 667 MHz)",
        b.arm_test_ns,
        b.arm_test_ns * projection::ARM_MHZ / 1e3
    );
    println!("  AXI4-Lite access, fixed    {:.1} ns", b.access_fixed_ns);
    println!(
        "  AXI4-Lite access, fabric   {:.2} cycles ({:.0} ns at 100 MHz, {:.0} ns at 214 MHz)",
        b.access_pl_cycles,
        b.access_ns(100.0),
        b.access_ns(214.0)
    );
    println!("\n| measurement | source | scene | size | setup | role | measured s | modelled s | error % |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in &c.rows {
        let m = &r.measurement;
        let setup = match m.setup {
            Setup::Arm => "ARM 667 MHz".to_string(),
            Setup::Accelerator {
                fpl_mhz,
                units,
                latency,
            } => {
                format!(
                    "{units}× HLS {}–{} cyc @ {fpl_mhz} MHz",
                    latency.0, latency.1
                )
            }
        };
        let role = if m.role == Role::Fit { "fit" } else { "check" };
        println!(
            "| {} | {} | {} | {}x{} | {setup} | {role} | {} | {:.3} | {:+.1} |",
            m.label,
            m.source,
            m.scene,
            m.width,
            m.height,
            m.seconds,
            r.modelled_s,
            r.error_pct()
        );
    }
}
