//! `rtfpga project`: the projected frame time of a scene on the ZedBoard for an accelerator
//! design, and (`--calibration`) the model against every time the thesis measured.
//! The model is `sim::projection`; docs/projection.md explains it.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, ValueEnum};
use hw_model::dual::FormatChoice;
use hw_model::frame::schedule::{self, schedule_frame, Stage};
use hw_model::frame::{Frame, FrameLimits};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::{TraversalEngine, TraversalModel};
use hw_model::Advance;
use indicatif::{ProgressBar, ProgressStyle};
use sim::projection::fit_store::{self, StoredFit};
use sim::projection::{
    self, Board, Calibration, Design, Frontend, Role, Setup, Traversal, Workload, Workloads,
};
use sw_renderer::render::RenderOptions;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::engine::{ChunkArgs, Datapath, HwConfig, UnitArgs};
use crate::options::{Given, Target};
use crate::report::{self, Line};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DesignKind {
    /// The thesis' accelerator: one AXI4-Lite call per ray-triangle test.
    Thesis,
    /// The project's: queries streamed by DMA through HP ports into pipelined lanes.
    Stream,
    /// The traversal unit: the scene in the unit, rays in and answers out over HP ports
    /// (cycles from its schedule model on the scene's frame).
    Traversal,
    /// The frame unit: ray generation, traversal, shading and pixels all in the fabric
    /// (cycles from its frame schedule model; a planned design, no ARM, no board constants).
    Frame,
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
    #[arg(long, value_parser = crate::cmd_render::image_side(), requires = "scene")]
    width: Option<u32>,
    /// Override the scene's height (1 to 16384 pixels).
    #[arg(long, value_parser = crate::cmd_render::image_side(), requires = "scene")]
    height: Option<u32>,
    /// The accelerator design projected.
    #[arg(long, value_enum, default_value_t = DesignKind::Stream)]
    design: DesignKind,
    /// How candidates are found [default: brute-force for thesis, bvh for stream].
    #[arg(long, value_enum)]
    traversal: Option<TraversalKind>,
    /// Datapath number format (sets the pipeline latency with --depth).
    #[arg(long, default_value = "fp32")]
    format: hw_model::HwFormat,
    /// Pipeline registers per operator: 0 to the format's maximum.
    #[arg(long, default_value_t = 1)]
    depth: usize,
    /// MT lanes (the traversal unit: 1 to 3); the thesis design: its accelerators.
    #[arg(long, default_value_t = 1)]
    lanes: u32,
    /// The traversal unit's slots, scene memory, node format and box ports.
    #[command(flatten)]
    unit: UnitArgs,
    /// Fabric clock f_PL in MHz.
    #[arg(long, default_value_t = 100.0)]
    fpl_mhz: f64,
    /// Thesis: mean cycles of one call [default: 71, Run 1's 32–110 midpoint];
    /// stream: cycles between queries per lane [default: 1, II = 1].
    #[arg(long)]
    cycles_per_test: Option<f64>,
    /// HP ports the DMA uses (1–4).
    #[arg(long, default_value_t = 1)]
    hp_ports: u32,
    /// Fraction of the HP ports' peak bandwidth the DMA reaches.
    #[arg(long, default_value_t = 0.8)]
    dma_efficiency: f64,
    /// ARM cycles to pack one query into the DMA buffer (the traversal design: to write one
    /// ray and read its answer).
    #[arg(long, default_value_t = 40.0)]
    pack_cycles: f64,
    #[command(flatten)]
    chunks: ChunkArgs,
    /// Shader cores of the frame unit.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=64))]
    shader_cores: u32,
    /// Threads of a shader core, the cycles between a thread's issues (its pipeline latency).
    #[arg(long, default_value_t = schedule::DEFAULT_SHADER_THREADS as u32,
          value_parser = clap::value_parser!(u32).range(1..=256))]
    shader_threads: u32,
    /// Ray-store entries of the frame unit: the rays in flight.
    #[arg(long, default_value_t = schedule::DEFAULT_RAY_STORE as u32,
          value_parser = clap::value_parser!(u32).range(1..=65536))]
    ray_store: u32,
    /// Ray-store entries ray generation leaves for spawned rays [default: a quarter of
    /// --ray-store].
    #[arg(long)]
    spawn_reserve: Option<u32>,
    /// Edge of the renderer's square tiles: one tile's rays per level form a wavefront (a
    /// chunked unit loads every chunk once per wavefront).
    #[arg(long, default_value_t = RenderOptions::default().tile_size,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    tile_size: u32,
    /// Print the calibration table (measured vs modelled thesis times); fits the board's
    /// constants anew and stores them.
    #[arg(long)]
    calibration: bool,
    /// With --calibration: skip the slow scenes (Glass pen, Glasses, All materials).
    #[arg(long, requires = "calibration")]
    quick: bool,
    /// Fit the board's constants on the thesis scenes again instead of using the stored fit.
    #[arg(long)]
    recalibrate: bool,
    /// Directory of the thesis scenes the model is calibrated on [default:
    /// $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis beside the source tree rtfpga was
    /// built from]. Needed once: the fit is stored in the cache ($RTFPGA_CACHE, else the
    /// Cargo target directory's verilator-cache).
    #[arg(long)]
    thesis_scenes: Option<PathBuf>,
}

impl DesignKind {
    fn target(self) -> Target {
        match self {
            DesignKind::Thesis => Target::ThesisDesign,
            DesignKind::Stream => Target::StreamDesign,
            DesignKind::Traversal => Target::TraversalDesign,
            DesignKind::Frame => Target::FrameDesign,
        }
    }
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    given.check(a.design.target())?;
    if a.design == DesignKind::Frame {
        return project_frame(&a);
    }
    if a.scene.is_none() && !a.calibration {
        bail!("nothing to do: give --scene to project a frame and/or --calibration");
    }
    let design = design(&a)?;
    let unit = match a.design {
        DesignKind::Traversal => Some(traversal_engine(&a)?),
        _ => None,
    };
    let scene = a.scene.as_deref().map(Scene::load).transpose()?;
    let thesis = thesis_scenes(&a)?;
    let store = sim::verilator::default_cache_dir().join(fit_store::FILE_NAME);
    let board = if a.calibration {
        let thesis = thesis.with_context(|| {
            format!(
                "--calibration renders the thesis scenes: {} (or give --thesis-scenes)",
                sw_renderer::thesis_scenes::NOT_FOUND
            )
        })?;
        let calibration = fit(&thesis, &store, !a.quick)?;
        print_calibration(&calibration);
        calibration.board
    } else {
        stored_or_fitted(&a, thesis.as_deref(), &store)?
    };
    if let Some(scene) = scene {
        let width = a.width.unwrap_or(scene.options.width);
        let height = a.height.unwrap_or(scene.options.height);
        let mut workload = Workload::measure(&scene, width, height)?;
        if let Some(engine) = &unit {
            workload = workload.with_unit(&scene, engine, a.tile_size)?;
        }
        print_projection(&a, &workload, &design, &board)?;
    }
    Ok(())
}

/// The thesis scenes' directory, if they are here: `--thesis-scenes` (then it must be a
/// directory), else where `sw_renderer::thesis_scenes` finds them.
fn thesis_scenes(a: &Args) -> Result<Option<PathBuf>> {
    match &a.thesis_scenes {
        Some(dir) if dir.is_dir() => Ok(Some(dir.clone())),
        Some(dir) => bail!("--thesis-scenes {}: not a directory", dir.display()),
        None => Ok(sw_renderer::thesis_scenes::locate()?),
    }
}

/// Fits the board's constants on the thesis scenes in `thesis` (every check row too when
/// `all`, else the quick scenes' only) and stores the fit at `store`.
fn fit(thesis: &Path, store: &Path, all: bool) -> Result<Calibration> {
    let mut workloads = Workloads::new(thesis);
    let (calibration, took) = report::spinner(
        &format!("calibrating on the thesis scenes in {}", thesis.display()),
        || {
            projection::calibrate(&mut workloads, |m| {
                all || [
                    "Simple_plane_scene",
                    "Simple_plane2_scene",
                    "Utah_teapot_scene",
                ]
                .contains(&m.scene)
            })
        },
    );
    let calibration = calibration.context("calibrating the model on the thesis' measurements")?;
    fit_store::save(
        store,
        &StoredFit {
            program: fit_store::program_key()?,
            scenes: fit_store::scenes_key(thesis)?,
            board: calibration.board,
        },
    )?;
    eprintln!(
        "calibration: fitted on the thesis scenes in {} in {:.1} s, stored at {}",
        thesis.display(),
        took.as_secs_f64(),
        store.display()
    );
    Ok(calibration)
}

/// The board's constants: the stored fit when this program made it on these scenes (or the
/// scenes are not here to check), else fitted now on the scenes (the four fit rows only),
/// saying on stderr which.
fn stored_or_fitted(a: &Args, thesis: Option<&Path>, store: &Path) -> Result<Board> {
    let program = fit_store::program_key()?;
    let scenes = thesis.map(fit_store::scenes_key).transpose()?;
    let stored = fit_store::load(store);
    if let Some(f) = fit_store::usable(stored, &program, scenes.as_deref(), a.recalibrate) {
        let on = match thesis {
            Some(dir) => format!("on the thesis scenes in {}", dir.display()),
            None => "on thesis scenes that are not here now".to_string(),
        };
        eprintln!(
            "calibration: the fit stored at {} (made {on}; --recalibrate fits again)",
            store.display()
        );
        return Ok(f.board);
    }
    let Some(thesis) = thesis else {
        bail!(
            "the projection's board constants are fitted once on the thesis scenes, and no fit is stored at {}: {} (or give --thesis-scenes) and run this again",
            store.display(),
            sw_renderer::thesis_scenes::NOT_FOUND
        );
    };
    Ok(fit(thesis, store, false)?.board)
}

/// The traversal design's unit: the traversal engine `render --engine traversal` makes in
/// this configuration (its checks of depth, lanes, slots and box ports included).
fn traversal_engine(a: &Args) -> Result<TraversalEngine> {
    let hw = HwConfig {
        datapath: Datapath {
            format: FormatChoice::Single(a.format.format()),
            depth: a.depth,
            lanes: a.lanes as usize,
        },
        unit: a.unit.clone(),
        dual_filter: None,
    };
    hw.traversal_engine(0, Advance::None, &a.chunks)
}

/// `--design frame`: the frame's cycles on the planned frame unit, from its schedule model
/// (the scene whole in the traversal unit's memory).
fn project_frame(a: &Args) -> Result<()> {
    let Some(name) = &a.scene else {
        bail!("--design frame times a frame: give --scene");
    };
    let scene = Scene::load(name)?;
    let width = a.width.unwrap_or(scene.options.width);
    let height = a.height.unwrap_or(scene.options.height);
    let engine = traversal_engine(a)?;
    let timing = engine
        .timing
        .context("the frame unit's traversal unit is timed in fp32 only")?;
    let prepared = PreparedScene::new(&scene)?;
    let frame = Frame::new(&scene, &prepared, &engine, width, height, &FrameLimits::HW)?;
    let model = TraversalModel::new(
        engine.format,
        engine.stack_depth,
        SceneImage::new(&prepared),
    )
    .with_nodes(engine.nodes)?;
    let ray_store = a.ray_store as usize;
    let unit = hdl::frame::schedule_unit(
        timing,
        a.depth,
        ray_store,
        a.spawn_reserve.map_or(ray_store / 4, |r| r as usize),
        a.shader_cores as usize,
        a.shader_threads as usize,
    );
    let bar = ProgressBar::new(u64::from(width) * u64::from(height));
    if let Ok(style) =
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} pixels {elapsed}/{eta}")
    {
        bar.set_style(style);
    }
    bar.set_message(format!("{} (frame schedule)", scene.name));
    let start = Instant::now();
    let s = schedule_frame(frame.constants(), frame.program(), &model, &unit, &|n| {
        bar.set_position(n)
    });
    let took = start.elapsed();
    bar.finish_and_clear();
    let s = s.with_context(|| format!("scene `{}` at {width}x{height}", scene.name))?;
    Line::new()
        .kv("scene", &scene.name)
        .kv("size", format_args!("{width}x{height}"))
        .print();
    Line::new()
        .kv("design", "frame")
        .kv("format", a.format)
        .kv("depth", a.depth)
        .kv("lanes", a.lanes)
        .kv("slots", a.unit.slots())
        .kv("nodes", a.unit.nodes.name())
        .kv("box_ports", a.unit.box_ports)
        .kv("shader_cores", unit.shader_cores)
        .kv("shader_threads", unit.threads)
        .kv("ray_store", unit.ray_store)
        .kv("spawn_reserve", unit.spawn_reserve)
        .kv("pixel_slots", unit.pixel_slots)
        .kv("raygen_latency", unit.raygen_latency)
        .kv("accumulate_latency", unit.accumulate_latency)
        .print();
    let mut rays = Line::new().kv("rays", s.rays.iter().sum::<u64>());
    for (kind, n) in ["primary", "reflection", "refraction", "shadow"]
        .iter()
        .zip(s.rays)
    {
        rays = rays.kv(&format!("{kind}_rays"), n);
    }
    rays.kv("threads", s.threads.iter().map(|l| l.threads).sum::<u64>())
        .kv("instructions", s.instructions())
        .kv("peak_in_flight", s.peak_in_flight)
        .print();
    let mut line = Line::labelled("frame_schedule")
        .kv("frame_cycles", s.cycles)
        .fixed("fps_at_100mhz", s.fps(100.0), 2)
        .fixed("fps", s.fps(a.fpl_mhz), 2)
        .kv("fpl_mhz", a.fpl_mhz)
        .kv("bound", s.busiest().name());
    for stage in Stage::ALL {
        line = line.fixed(stage.name(), s.utilisation(stage), 3);
    }
    line.fixed("schedule_s", took.as_secs_f64(), 1).print();
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
        DesignKind::Thesis => Frontend::Thesis {
            units: a.lanes,
            cycles_per_test: a.cycles_per_test.unwrap_or(THESIS_CYCLES_PER_TEST),
        },
        DesignKind::Traversal => Frontend::Traversal {
            hp_ports: a.hp_ports,
            dma_efficiency: a.dma_efficiency,
            pack_arm_cycles: a.pack_cycles,
        },
        DesignKind::Frame => unreachable!("--design frame is timed by project_frame"),
        DesignKind::Stream => {
            // The lane's depth as the accelerator checks it.
            hdl::top::TopConfig::new(a.format, a.depth, 1).validate()?;
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

/// The design as `key=value` fields: what `a` chose and what it set.
fn design_line(a: &Args, d: &Design) -> Line {
    let traversal = match d.traversal {
        Traversal::BruteForce => "brute-force",
        Traversal::Bvh => "bvh",
    };
    let line = Line::new()
        .kv(
            "design",
            a.design
                .to_possible_value()
                .map_or_else(String::new, |v| v.get_name().to_string()),
        )
        .kv("traversal", traversal)
        .kv("fpl_mhz", d.fpl_mhz);
    match d.frontend {
        Frontend::Thesis {
            units,
            cycles_per_test,
        } => line
            .kv("accelerators", units)
            .kv("cycles_per_test", cycles_per_test),
        Frontend::Stream {
            lanes,
            cycles_per_test,
            pipeline_latency,
            hp_ports,
            dma_efficiency,
            pack_arm_cycles,
        } => line
            .kv("format", a.format)
            .kv("depth", a.depth)
            .kv("lanes", lanes)
            .kv("cycles_per_test", cycles_per_test)
            .kv("pipeline_latency", pipeline_latency)
            .kv("hp_ports", hp_ports)
            .kv("dma_efficiency", dma_efficiency)
            .kv("pack_cycles", pack_arm_cycles),
        Frontend::Traversal {
            hp_ports,
            dma_efficiency,
            pack_arm_cycles,
        } => line
            .kv("format", a.format)
            .kv("depth", a.depth)
            .kv("lanes", a.lanes)
            .kv("slots", a.unit.slots())
            .kv("nodes", a.unit.nodes.name())
            .kv("box_ports", a.unit.box_ports)
            .kv("hp_ports", hp_ports)
            .kv("dma_efficiency", dma_efficiency)
            .kv("pack_cycles", pack_arm_cycles),
    }
}

fn print_projection(a: &Args, w: &Workload, d: &Design, b: &Board) -> Result<()> {
    let p = projection::project(w, d, b)?;
    // The thesis' software on the ARM, and the same with the BVH (traversal not counted).
    let arm = b.arm_only_s(w, Traversal::BruteForce);
    let arm_bvh = b.arm_only_s(w, Traversal::Bvh);
    Line::new()
        .kv("scene", &w.scene)
        .kv("size", format_args!("{}x{}", w.width, w.height))
        .print();
    design_line(a, d).print();
    Line::new()
        .kv("rays", w.rays())
        .kv("primary_rays", w.primary_rays)
        .kv("reflection_rays", w.reflection_rays)
        .kv("refraction_rays", w.refraction_rays)
        .kv("shadow_rays", w.shadow_rays)
        .kv("tests", p.tests)
        .print();
    println!("\n| term | seconds |\n|---|---|");
    println!("| ARM | {:.4} |", p.arm_s);
    println!("| bus (AXI4-Lite) | {:.4} |", p.bus_s);
    println!("| accelerator | {:.4} |", p.accel_s);
    println!("| total | {:.4} |\n", p.total_s());
    if let Some(u) = &w.unit {
        let rays = w.rays().max(1) as f64;
        // The unit's schedule model on the frame, and its scene memory's loads.
        Line::labelled("unit_schedule")
            .fixed("cycles_per_ray", u.cycles as f64 / rays, 2)
            .fixed("box_tests_per_ray", u.box_tests as f64 / rays, 2)
            .fixed("mt_tests_per_ray", u.mt_tests as f64 / rays, 2)
            .kv("image_bytes", u.image_bytes)
            .print();
        Line::labelled("unit_memory")
            .kv("wavefronts", u.wavefronts)
            .kv("passes", u.passes)
            .kv("ray_passes", u.ray_passes)
            .kv("chunk_loads", u.chunk_loads)
            .kv("loaded_bytes", u.loaded_bytes)
            .fixed(
                "load_cycles_per_ray",
                projection::load_cycles(u, d).unwrap_or(0.0) / rays,
                2,
            )
            .print();
    }
    let mut line = Line::new()
        .fixed("arm_software_s", arm, 4)
        .fixed("arm_bvh_software_s", arm_bvh, 4)
        .fixed("total_s", p.total_s(), 4)
        .fixed("speedup_vs_arm", arm / p.total_s(), 2)
        .fixed("speedup_vs_arm_bvh", arm_bvh / p.total_s(), 2);
    if let Some(walk) = b.arm_bvh_walk_s(w) {
        line = line.fixed("arm_bvh_walk_s", walk, 4).fixed(
            "speedup_vs_arm_bvh_walk",
            walk / p.total_s(),
            2,
        );
    }
    line.print();
    Ok(())
}

fn print_calibration(c: &Calibration) {
    let b = &c.board;
    // The four fitted constants (from the four `fit` rows; every other row is a held-out
    // check): ARM ns per ray and per MT test, AXI4-Lite access ns (fixed) and fabric cycles.
    Line::labelled("fitted")
        .fixed("arm_ray_ns", b.arm_ray_ns, 1)
        .fixed("arm_test_ns", b.arm_test_ns, 1)
        .fixed(
            "arm_test_cycles",
            b.arm_test_ns * projection::ARM_MHZ / 1e3,
            1,
        )
        .fixed("access_fixed_ns", b.access_fixed_ns, 1)
        .fixed("access_pl_cycles", b.access_pl_cycles, 2)
        .fixed("access_ns_at_100mhz", b.access_ns(100.0), 0)
        .fixed("access_ns_at_214mhz", b.access_ns(214.0), 0)
        .print();
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
    println!();
}
