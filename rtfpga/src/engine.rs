//! The hardware options the subcommands share and what they resolve to: the `RayEngine` that
//! answers a render's rays, the accelerator, pair or traversal unit a command builds. Which
//! option acts where is `options::RULES`; the checks of values are here and in the libraries'
//! configuration types.

use std::time::Duration;

use anyhow::{bail, Context, Result};
use clap::builder::TypedValueParser;
use clap::{Args as ClapArgs, ValueEnum};
use hdl::dual::pair::SlotFilter;
use hdl::top::TopConfig;
use hdl::traversal::config::{
    UnitConfig, BUILT_MEMORY_BITS, BUILT_WIDE_MEMORY_BITS, ZYNQ_WIDE_MEMORY_BITS,
};
use hdl::traversal::scene_memory;
use hw_model::dual::{DualIntersector, Filter, FilterKind, FormatChoice};
use hw_model::precision::{auto_scale_exp, SceneRange, SpawnChoice};
use hw_model::traversal::{
    NodeFormat, SceneCapacity, SceneMemory, TraversalEngine, DEFAULT_STACK_DEPTH,
};
use hw_model::{Advance, Edges, Format, ModelIntersector, NamedChoice};
use sim::dual_pair::{built_pair, PairConfig, PairIntersector};
use sim::hw_intersector::{HwIntersector, Mode};
use sim::verilator::BuiltModel;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::RayEngine;
use sw_renderer::scene::Scene;
use sw_renderer::spawn::SpawnPolicy;

use crate::options::Target;
use crate::report::Line;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineKind {
    /// The reference Möller-Trumbore in native f32 (the golden images').
    F32,
    /// The bit-accurate model of the datapath's arithmetic in --format (no simulation).
    Model,
    /// The Verilated Möller-Trumbore accelerator in --format (co-simulation).
    Hw,
    /// The traversal unit's bit-accurate model: the scene in its memory, rays in, hits out,
    /// Möller-Trumbore in --format; cycles from its schedule model.
    Traversal,
    /// The frame unit's bit-accurate model (render only): ray generation, shading and pixel
    /// sums in the hardware's fp32, rays answered by the traversal unit's model in --format
    /// (docs/frame.md).
    Frame,
}

impl EngineKind {
    /// What this engine is in the options table, answering in `format`.
    pub fn target(self, format: &FormatChoice) -> Target {
        let pair = matches!(format, FormatChoice::Pair(_));
        match self {
            EngineKind::F32 => Target::F32,
            EngineKind::Model if pair => Target::ModelPair,
            EngineKind::Model => Target::Model,
            EngineKind::Hw if pair => Target::HwPair,
            EngineKind::Hw => Target::Accelerator,
            EngineKind::Traversal => Target::UnitModel,
            EngineKind::Frame => Target::FrameModel,
        }
    }
}

/// The error of asking the frame model to answer the software renderer's rays.
pub fn frame_is_not_a_ray_engine() -> anyhow::Error {
    anyhow::anyhow!(
        "--engine frame renders whole frames (ray generation, shading and pixels in the model), not the software renderer's rays: use it with `rtfpga render`"
    )
}

/// Which hardware a co-simulation, Verilog or synthesis command means.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum UnitKind {
    /// The Möller-Trumbore accelerator (`rtfpga_top`): queries in, results out.
    #[default]
    Mt,
    /// The traversal unit: the scene in block RAM, rays in, hits out.
    Traversal,
}

impl UnitKind {
    /// The `render` engine whose hardware this is (`--engine hw` co-simulates the
    /// accelerator; `--engine traversal` is the unit's model).
    pub fn engine(self) -> EngineKind {
        match self {
            UnitKind::Mt => EngineKind::Hw,
            UnitKind::Traversal => EngineKind::Traversal,
        }
    }

    /// What this unit is in the options table, built in `format`.
    pub fn target(self, format: &FormatChoice) -> Target {
        match self {
            UnitKind::Mt => EngineKind::Hw.target(format),
            UnitKind::Traversal => Target::Unit,
        }
    }
}

fn format_help() -> String {
    format!(
        "Number format of the datapath: a catalogue name (`rtfpga formats`); the model engine \
         also takes any spelling such as e8m14 or fx<24,8>, and a dual-precision pair \
         bfpW/FALLBACK such as bfp14/fp32 (docs/precision.md), of which the hardware builds {}",
        built_pair()
    )
}

fn lanes_help() -> String {
    let slots = sim::dual_pair::SLOTS;
    format!(
        "Parallel Möller-Trumbore lanes: the accelerator 1 to {}, the traversal unit 1 to {}, a \
         hardware pair its filter slots ({} to {})",
        hdl::top::MAX_LANES,
        hdl::traversal::config::MAX_LANES,
        slots.start(),
        slots.end()
    )
}

/// `--format`, `--depth`, `--lanes`: the datapath.
#[derive(ClapArgs, Clone, Debug)]
pub struct Datapath {
    #[arg(long, default_value = "fp32", help = format_help())]
    pub format: FormatChoice,
    /// Pipeline registers per operator: 0 to the format's maximum.
    #[arg(long, default_value_t = 1)]
    pub depth: usize,
    #[arg(long, default_value_t = 1, help = lanes_help())]
    pub lanes: usize,
}

/// The scene memory the XC7Z020 holds beside `lanes` lanes for `nodes`.
fn zynq_bits(lanes: usize, nodes: NodeFormat) -> (usize, usize) {
    match nodes.width() {
        Some(_) => ZYNQ_WIDE_MEMORY_BITS,
        None => scene_memory::zynq_address_bits(lanes),
    }
}

fn capacity_text((node_bits, triangle_bits): (usize, usize)) -> String {
    let (nodes, triangles) = scene_memory::capacity_for(node_bits, triangle_bits);
    format!("{nodes},{triangles}")
}

/// The scene memories the RTL is built with, "16,32, 512,1024, … and 4096,8192".
fn built_memories() -> String {
    memories_text(&BUILT_MEMORY_BITS)
}

/// Memories as "16,32, 512,1024 and 4096,8192".
fn memories_text(memories: &[(usize, usize)]) -> String {
    let all: Vec<String> = memories.iter().copied().map(capacity_text).collect();
    match all.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => all.join(""),
    }
}

fn scene_memory_help() -> String {
    let mut wide: Vec<(usize, usize)> = BUILT_WIDE_MEMORY_BITS
        .iter()
        .map(|&(_, nodes, triangles)| (nodes, triangles))
        .collect();
    wide.dedup();
    format!(
        "The traversal unit's scene memory: the inner nodes and triangles it holds. The RTL is \
         built with {} for bvh2-fp32 nodes and {} for wide ones; the model takes any, and \
         renders a larger scene in chunked passes [default: the memory that fits the XC7Z020 \
         beside the lanes: {} beside one lane, {} beside more; {} for wide nodes]",
        built_memories(),
        memories_text(&wide),
        capacity_text(scene_memory::zynq_address_bits(1)),
        capacity_text(scene_memory::zynq_address_bits(2)),
        capacity_text(ZYNQ_WIDE_MEMORY_BITS),
    )
}

/// `--scene-memory NODES,TRIANGLES` (once `--unit-memory` and `--scene-capacity`).
#[derive(ClapArgs, Clone, Debug, Default)]
pub struct SceneMemoryArg {
    #[arg(long = "scene-memory", alias = "unit-memory", alias = "scene-capacity",
          value_name = "NODES,TRIANGLES", value_parser = parse_capacity,
          help = scene_memory_help())]
    pub scene_memory: Option<SceneCapacity>,
}

/// `--slots` and `--scene-memory`: the traversal unit's.
#[derive(ClapArgs, Clone, Debug)]
pub struct UnitArgs {
    /// Ray slots of the traversal unit: the RTL has 32 with bvh2-fp32 nodes and 64 with wide
    /// ones; the schedule model times 1 to 1024 [default: the RTL's for --nodes].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub slots: Option<u32>,
    #[command(flatten)]
    pub memory: SceneMemoryArg,
    /// How the scene memory stores the tree's inner nodes: bvh2-fp32 (binary, fp32 boxes), or
    /// wide nodes of 2, 4 or 8 children with 8-bit quantized boxes, all tested in one beat
    /// (docs/wide-nodes.md; the RTL builds 4 and 8).
    #[arg(long, default_value = "bvh2-fp32", value_parser = choice::<NodeFormat>())]
    pub nodes: NodeFormat,
    /// Box ports of the traversal unit (slot s uses port s mod N): the RTL has 1, the
    /// schedule model times 1 to 8.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub box_ports: u32,
}

impl UnitArgs {
    /// `--slots`, else the RTL's for `--nodes`.
    pub fn slots(&self) -> usize {
        (self.slots).map_or(hdl::traversal::config::slots_for(self.nodes), |s| {
            s as usize
        })
    }
}

/// `--no-chunks`.
#[derive(ClapArgs, Clone, Debug, Default)]
pub struct ChunkArgs {
    /// Refuse a scene larger than the traversal unit's scene memory instead of rendering it in
    /// chunked passes.
    #[arg(long)]
    pub no_chunks: bool,
}

/// The hardware configuration: datapath, traversal unit, pair filter.
#[derive(ClapArgs, Clone, Debug)]
pub struct HwConfig {
    #[command(flatten)]
    pub datapath: Datapath,
    #[command(flatten)]
    pub unit: UnitArgs,
    /// The filter of a dual-precision pair (docs/precision.md, "Dual precision") [default:
    /// bfp].
    #[arg(long, value_enum)]
    pub dual_filter: Option<DualFilter>,
}

/// `--dual-filter`: what a pair's filter computes (both are built in hardware).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DualFilter {
    /// Block floating point: the query translated in integers, W-bit blocks, margins from
    /// the bits dropped, decisions on short floats.
    Bfp,
    /// Block floating point in Plücker form: per-ray and per-triangle blocks, no
    /// translation per test, decisions by signs and bit lengths.
    PluckerSigns,
}

impl DualFilter {
    pub fn kind(self) -> FilterKind {
        match self {
            DualFilter::Bfp => FilterKind::Bfp,
            DualFilter::PluckerSigns => FilterKind::Plucker,
        }
    }

    /// The filter lane built in hardware for this filter.
    fn slot_filter(self) -> SlotFilter {
        match self {
            DualFilter::Bfp => SlotFilter::Bfp,
            DualFilter::PluckerSigns => SlotFilter::Plucker,
        }
    }
}

/// A render's engine, with handles on what it reports beside the image.
pub struct Made {
    pub engine: Box<dyn RayEngine>,
    /// Shares the engine's counters (`--format FILTER/FALLBACK`).
    pub dual: Option<DualIntersector>,
    /// The Verilated model behind a hardware engine.
    pub verilated: Option<Verilated>,
}

/// A Verilated model as a command reports it.
pub struct Verilated {
    pub name: String,
    pub cached: bool,
    pub build_time: Duration,
}

impl Verilated {
    pub fn of<C>(name: String, built: &BuiltModel<C>) -> Verilated {
        Verilated {
            name,
            cached: built.model.cached,
            build_time: built.build_time,
        }
    }

    pub fn of_accelerator(hw: &HwIntersector) -> Verilated {
        let m = hw.model();
        Verilated {
            name: sw_renderer::intersect::Intersector::name(hw),
            cached: m.model.cached,
            build_time: m.build_time,
        }
    }

    /// `verilated engine="…" cache=hit|miss build_s=…`: whether the model came from the cache
    /// and the time spent building or loading it.
    pub fn line(&self) -> Line {
        Line::labelled("verilated")
            .kv("engine", &self.name)
            .kv("cache", if self.cached { "hit" } else { "miss" })
            .fixed("build_s", self.build_time.as_secs_f64(), 1)
    }
}

/// The engine `kind` in `hw`'s configuration, its Möller-Trumbore queries scaled by
/// 2^`scale_exp` (model engines of one format only; a pair answers the queries as given),
/// the model engine's lane options `lane`, a traversal unit's scene memory
/// chunked unless `chunks` says no.
pub fn make(
    kind: EngineKind,
    hw: &HwConfig,
    scale_exp: i32,
    lane: Lane,
    chunks: &ChunkArgs,
) -> Result<Made> {
    let mut made = Made {
        engine: Box::new(F32Intersector),
        dual: None,
        verilated: None,
    };
    match (kind, hw.datapath.format) {
        (EngineKind::F32, _) => {}
        (EngineKind::Model, FormatChoice::Pair(pair)) => {
            let kind = hw
                .dual_filter
                .map_or_else(FilterKind::default, DualFilter::kind);
            let dual = DualIntersector::with_filter(Filter::new(pair, kind));
            made.engine = Box::new(dual.clone());
            made.dual = Some(dual);
        }
        (EngineKind::Model, FormatChoice::Single(format)) => {
            made.engine = Box::new(ModelIntersector {
                format,
                scale_exp,
                edges: lane.edges,
                advance: lane.advance,
            });
        }
        (EngineKind::Hw, FormatChoice::Pair(_)) => {
            let pair = PairIntersector::new(&hw.pair_config()?)?;
            made.verilated = Some(Verilated::of(RayEngine::name(&pair), pair.model()));
            made.engine = Box::new(pair);
        }
        (EngineKind::Hw, FormatChoice::Single(_)) => {
            let accel = HwIntersector::new(&hw.datapath.top_config()?, Mode::Stream)?;
            made.verilated = Some(Verilated::of_accelerator(&accel));
            made.engine = Box::new(accel);
        }
        (EngineKind::Traversal, _) => {
            made.engine = Box::new(hw.traversal_engine(scale_exp, lane.advance, chunks)?);
        }
        (EngineKind::Frame, _) => return Err(frame_is_not_a_ray_engine()),
    }
    Ok(made)
}

/// Power-of-two scaling of the Möller-Trumbore queries (`--scale`, docs/precision.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ScaleKind {
    /// The largest power of two that keeps the scene's intermediates in the format's range.
    Auto,
    /// As given.
    None,
}

/// The parser of a closed list of choices (`--spawn`, `--edges`, `--advance`): its names,
/// listed in the help.
pub(crate) fn choice<T: NamedChoice>() -> impl TypedValueParser<Value = T> {
    clap::builder::PossibleValuesParser::new(T::CHOICES.iter().map(|c| c.choice_name()))
        .try_map(|name| name.parse::<T>())
}

/// `--advance`: where a lane starts a query's ray.
#[derive(ClapArgs, Clone, Debug)]
pub struct AdvanceArg {
    /// Where a lane starts a query's ray: none (at its origin), triangle-box (moved in fp32 to
    /// where it enters the triangle's bounding box) or leaf-box (moved to where it enters the
    /// BVH leaf, as the traversal unit's box test computed it; docs/traversal-unit.md)
    /// [default: triangle-box for a format-aware model render, else none].
    #[arg(long, value_parser = choice::<Advance>())]
    pub advance: Option<Advance>,
}

/// The model lane's options beyond its format (docs/precision.md): the hardware lanes' are
/// the defaults.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Lane {
    pub edges: Edges,
    pub advance: Advance,
}

/// What `PrecisionArgs` resolve to for one render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// The spawn policy by name, and what it is for this format and scale.
    pub choice: SpawnChoice,
    pub spawn: SpawnPolicy,
    pub scale_exp: i32,
    pub lane: Lane,
}

/// `--spawn` (`render` and `cosim`): how secondary and shadow rays are spawned.
#[derive(ClapArgs, Clone, Debug)]
pub struct SpawnArgs {
    /// Spawn policy of secondary and shadow rays: thesis (origin offset by the scene's bias)
    /// or format-aware (also a t_min from the format's rounding error, the triangle left
    /// excluded) [default: thesis for the f32 and frame engines and for fp32, else
    /// format-aware].
    #[arg(long, value_parser = choice::<SpawnChoice>())]
    pub spawn: Option<SpawnChoice>,
}

impl SpawnArgs {
    /// The policy asked for, else the default of `kind` answering in `answers`: the thesis'
    /// for the f32 engine and for fp32 (they reproduce the reference) and for the frame
    /// engine (the only one it has), else format-aware.
    pub fn choice(&self, kind: EngineKind, answers: &Format) -> SpawnChoice {
        let thesis =
            matches!(kind, EngineKind::F32 | EngineKind::Frame) || *answers == Format::FP32;
        self.spawn.unwrap_or(if thesis {
            SpawnChoice::Thesis
        } else {
            SpawnChoice::FormatAware
        })
    }
}

/// `--spawn`, `--scale`, `--edges` and `--advance`: reduced precision that renders
/// (docs/precision.md).
#[derive(ClapArgs, Clone, Debug)]
pub struct PrecisionArgs {
    #[command(flatten)]
    pub spawn: SpawnArgs,
    /// Scaling of the queries into the format's range [default: none].
    #[arg(long, value_enum)]
    pub scale: Option<ScaleKind>,
    /// The model lane's edge test: exact (the hardware's) or conservative (widened by its
    /// running error bound) [default: exact].
    #[arg(long, value_parser = choice::<Edges>())]
    pub edges: Option<Edges>,
    #[command(flatten)]
    pub advance: AdvanceArg,
}

impl PrecisionArgs {
    /// The spawn policy, the scale exponent and the lane options for rendering `scene` with
    /// `kind` in `hw`'s format (`options::RULES` has checked which of them act on it).
    pub fn resolve(&self, kind: EngineKind, hw: &HwConfig, scene: &Scene) -> Result<Precision> {
        let format = hw.datapath.format;
        // A pair answers as its fallback, on the queries as given (`--scale` does not act on
        // it: its filter's exponents are per vector).
        let answers = match format {
            FormatChoice::Single(f) => f,
            FormatChoice::Pair(p) => p.fallback,
        };
        // Unscaled unless asked: auto scaling measured no better in any format and worse in
        // e5m14 and the fixed formats (docs/precision.md).
        let scale_exp = match self.scale.unwrap_or(ScaleKind::None) {
            ScaleKind::None => 0,
            ScaleKind::Auto => auto_scale_exp(&answers, &SceneRange::of(scene)?),
        };
        let choice = self.spawn.choice(kind, &answers);
        let single_model = kind.target(&format) == Target::Model;
        let lane = Lane {
            edges: self.edges.unwrap_or_default(),
            advance: self.advance.advance.unwrap_or(if single_model {
                hw_model::advance::default_for(choice)
            } else {
                Advance::None
            }),
        };
        Ok(Precision {
            choice,
            spawn: choice.policy(&answers, scale_exp),
            scale_exp,
            lane,
        })
    }
}

/// `NODES,TRIANGLES` as a capacity.
fn parse_capacity(s: &str) -> Result<SceneCapacity, String> {
    let expected = || format!("`{s}`: expected NODES,TRIANGLES, two counts such as 2048,4096");
    let (nodes, triangles) = s.split_once(',').ok_or_else(expected)?;
    let count = |x: &str| {
        x.trim()
            .parse::<u32>()
            .map_err(|e| format!("{}: {e}", expected()))
    };
    let capacity = SceneCapacity {
        nodes: count(nodes)?,
        triangles: count(triangles)?,
    };
    if capacity.triangles == 0 {
        return Err(format!(
            "`{s}`: a scene memory holds at least one triangle (a scene without inner nodes: 0 nodes)"
        ));
    }
    Ok(capacity)
}

impl SceneMemoryArg {
    /// The model's scene memory for a unit of `lanes` lanes holding `nodes`: `--scene-memory`,
    /// else the one the XC7Z020 holds beside them; chunked unless `chunks` says no.
    pub fn model_memory(&self, lanes: usize, nodes: NodeFormat, chunks: &ChunkArgs) -> SceneMemory {
        let capacity = self.scene_memory.unwrap_or_else(|| {
            let (node_bits, triangle_bits) = zynq_bits(lanes, nodes);
            let (nodes, triangles) = scene_memory::capacity_for(node_bits, triangle_bits);
            SceneCapacity {
                nodes: nodes as u32,
                triangles: triangles as u32,
            }
        });
        match chunks.no_chunks {
            true => SceneMemory::Whole(capacity),
            false => SceneMemory::Chunked(capacity),
        }
    }

    /// The RTL's scene memory as address bits: `--scene-memory` must name one of the memories
    /// built (in the units typed) for `nodes`, else the one the XC7Z020 holds beside `lanes`
    /// lanes.
    pub fn rtl_bits(&self, lanes: usize, nodes: NodeFormat) -> Result<(usize, usize)> {
        let Some(c) = self.scene_memory else {
            return Ok(zynq_bits(lanes, nodes));
        };
        let built: Vec<(usize, usize)> = match nodes.width() {
            None => BUILT_MEMORY_BITS.to_vec(),
            Some(width) => (BUILT_WIDE_MEMORY_BITS.iter())
                .filter(|(k, _, _)| *k == width)
                .map(|&(_, n, t)| (n, t))
                .collect(),
        };
        built
            .iter()
            .copied()
            .find(|&bits| capacity_text(bits) == format!("{},{}", c.nodes, c.triangles))
            .with_context(|| {
                format!(
                    "--scene-memory {},{}: the traversal unit's RTL for {} nodes is built with scene memories of {} (NODES,TRIANGLES)",
                    c.nodes,
                    c.triangles,
                    nodes.name(),
                    memories_text(&built)
                )
            })
    }
}

impl Datapath {
    /// The datapath's one format: a pair is an error here (the model engine and the
    /// Möller-Trumbore hardware take one, [`HwConfig::pair_config`]).
    pub fn single_format(&self) -> Result<Format> {
        match self.format {
            FormatChoice::Single(format) => Ok(format),
            FormatChoice::Pair(pair) => bail!(
                "--format {pair}: one format only here; dual-precision pairs are model-only (--engine model) but for {}, which the Möller-Trumbore hardware also builds (render --engine hw, cosim, synth)",
                built_pair()
            ),
        }
    }

    /// The format the answers are in: the one format, or a pair's fallback.
    pub fn answer_format(&self) -> Format {
        match self.format {
            FormatChoice::Single(format) => format,
            FormatChoice::Pair(pair) => pair.fallback,
        }
    }

    /// The accelerator of this configuration: an error if the format has no hardware or the
    /// depth or lanes are not built.
    pub fn top_config(&self) -> Result<TopConfig> {
        let config = TopConfig::new(self.single_format()?.try_into()?, self.depth, self.lanes);
        config.validate()?;
        Ok(config)
    }
}

impl HwConfig {
    /// The dual-precision pair in hardware: `--lanes` filter slots (bfp, or with
    /// `--dual-filter plucker-signs` the Plücker lane) sharing one fp32 lane at `--depth`.
    /// Only the pair built in rust-hdl is: its filter width (`hdl::dual::WIDTH`), 1 to 5
    /// slots.
    pub fn pair_config(&self) -> Result<PairConfig> {
        let format = self.datapath.format;
        let built = built_pair();
        let filter = self.dual_filter.unwrap_or(DualFilter::Bfp).slot_filter();
        let FormatChoice::Pair(pair) = format else {
            bail!("--format {format}: the hardware pair is {built}; other pairs are model-only (--engine model)");
        };
        if pair != built {
            bail!("--format {pair}: the hardware pair is {built}; other pairs are model-only (--engine model)");
        }
        let config = PairConfig {
            slots: self.datapath.lanes,
            depth: self.datapath.depth,
            filter,
        };
        config.check().with_context(|| {
            format!(
                "--format {pair} --lanes {} --depth {}",
                self.datapath.lanes, self.datapath.depth
            )
        })?;
        Ok(config)
    }

    /// The traversal unit's model in this configuration, its Möller-Trumbore queries scaled
    /// by 2^`scale_exp` and started where `advance` says; timed by its schedule model when
    /// the format has hardware (any other format has no lane latency to time with). Its depth
    /// and lanes are the RTL's (1 to 3 lanes); its slots any the schedule model takes.
    pub fn traversal_engine(
        &self,
        scale_exp: i32,
        advance: Advance,
        chunks: &ChunkArgs,
    ) -> Result<TraversalEngine> {
        let d = &self.datapath;
        let format = d.single_format()?;
        let timing = match hw_model::HwFormat::try_from(format) {
            Ok(f) => {
                // The RTL's checks of depth and lanes, not of its slots and memory: the
                // schedule model times any slot count, the model holds any memory.
                let rtl = UnitConfig {
                    advance,
                    ..UnitConfig::new(f, d.depth, d.lanes)
                };
                rtl.check()?;
                let slots = self.unit.slots();
                let t = hdl::traversal::timing::unit_timing(f, d.depth, d.lanes, slots, advance);
                let t = hdl::traversal::timing::node_timing(
                    t,
                    self.unit.nodes,
                    d.depth,
                    self.unit.box_ports as usize,
                );
                t.check()?;
                Some(t)
            }
            Err(_) => None,
        };
        Ok(TraversalEngine {
            format,
            stack_depth: DEFAULT_STACK_DEPTH,
            scale_exp,
            advance,
            timing,
            memory: (self.unit.memory).model_memory(d.lanes, self.unit.nodes, chunks),
            nodes: self.unit.nodes,
        })
    }

    /// The traversal unit's RTL in this configuration, its lanes started where `advance`
    /// says: an error naming what the RTL does not build.
    pub fn unit_config(&self, advance: Advance) -> Result<UnitConfig> {
        let d = &self.datapath;
        let mut config = UnitConfig::new(d.single_format()?.try_into()?, d.depth, d.lanes)
            .with_nodes(self.unit.nodes);
        config.slots = self.unit.slots();
        config.advance = advance;
        (config.memory.node_bits, config.memory.triangle_bits) =
            self.unit.memory.rtl_bits(d.lanes, self.unit.nodes)?;
        config.check()?;
        Ok(config)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_memories_are_named_in_the_units_typed() {
        assert_eq!(built_memories(), "16,32, 512,1024, 2048,4096 and 4096,8192");
        let arg = |nodes, triangles| SceneMemoryArg {
            scene_memory: Some(SceneCapacity { nodes, triangles }),
        };
        assert_eq!(
            arg(2048, 4096).rtl_bits(1, NodeFormat::Bvh2Fp32).unwrap(),
            (11, 12)
        );
        let e = arg(100, 100)
            .rtl_bits(1, NodeFormat::Bvh2Fp32)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--scene-memory 100,100: "), "{e}");
        assert_eq!(
            SceneMemoryArg::default()
                .rtl_bits(1, NodeFormat::Bvh2Fp32)
                .unwrap(),
            scene_memory::zynq_address_bits(1)
        );
    }
}
