//! Engine selection shared by the subcommands that render: which `RayEngine` answers the
//! renderer's rays.

use anyhow::{bail, Context, Result};
use clap::builder::TypedValueParser;
use clap::{Args as ClapArgs, ValueEnum};
use hdl::dual::pair::SlotFilter;
use hdl::top::TopConfig;
use hdl::traversal::scene_memory;
use hdl::traversal::unit::UnitConfig;
use hw_model::dual::{
    BoundArith, DualIntersector, Filter, FilterFormat, FilterKind, FormatChoice, PluckerDecisions,
    HW_BOUND_BITS,
};
use hw_model::precision::{auto_scale_exp, SceneRange, SpawnChoice};
use hw_model::traversal::{SceneCapacity, SceneMemory, TraversalEngine, DEFAULT_STACK_DEPTH};
use hw_model::{Advance, Edges, Format, ModelIntersector, NamedChoice};
use sim::dual_pair::{built_pair, PairConfig, PairIntersector};
use sim::hw_intersector::{HwIntersector, Mode};
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::RayEngine;
use sw_renderer::scene::Scene;
use sw_renderer::spawn::SpawnPolicy;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineKind {
    /// The reference Möller-Trumbore in native f32.
    F32,
    /// The bit-accurate model of the hardware arithmetic in `--format`.
    Model,
    /// The Verilated accelerator (co-simulation).
    Hw,
    /// The traversal unit's bit-accurate model: BVH and triangles in the unit's scene
    /// memory, rays in, hits out; Möller-Trumbore in `--format`.
    Traversal,
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
}

/// The hardware configuration: number format, pipeline depth, lanes.
#[derive(ClapArgs, Clone, Debug)]
pub struct HwConfig {
    /// Number format of the datapath: a catalogue name (`rtfpga formats`), or for the model
    /// engine any spelling such as e8m14 or fx<24,8>, or a dual-precision pair
    /// FILTER/FALLBACK such as fp16/fp32 (docs/precision.md; the model engine, and
    /// bfp18/fp32 also in hardware: `--engine hw`, `cosim`).
    #[arg(long, default_value = "fp32")]
    pub format: FormatChoice,
    /// Pipeline registers per operator.
    #[arg(long, default_value_t = 1)]
    pub depth: usize,
    /// Parallel MT lanes (a dual-precision pair in hardware: its filter slots, which share
    /// one fp32 lane).
    #[arg(long, default_value_t = 1)]
    pub lanes: usize,
    /// Ray slots of the traversal unit (`--engine traversal`: its schedule model's cycles).
    #[arg(long, default_value_t = hdl::traversal::timing::DEFAULT_SLOTS as u32,
          value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub slots: u32,
    /// `--unit traversal`: the RTL scene memory as NODES,TRIANGLES (built: 16,32, 512,1024,
    /// 2048,4096, 4096,8192) [default: the one that fits the XC7Z020 beside the lanes:
    /// 4096,8192 beside one, 2048,4096 beside more].
    #[arg(long, value_name = "NODES,TRIANGLES", value_parser = parse_capacity)]
    pub unit_memory: Option<SceneCapacity>,
    /// The filter of a dual-precision pair (docs/precision.md, "Dual precision") [default:
    /// bfp for a bfpW/fp32 pair, else linear].
    #[arg(long, value_enum)]
    pub dual_filter: Option<DualFilter>,
}

/// `--dual-filter`: what a pair's filter computes and how it evaluates its bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DualFilter {
    /// Division-free, its bound on a coarse grid from the subtractors' rounding bound (what
    /// a hardware filter evaluates).
    Linear,
    /// Division-free, its bound exact.
    LinearExact,
    /// A whole lane in the filter format (quotients), its bound exact.
    Quotient,
    /// Block floating point, for a bfpW/FALLBACK pair: exact integers, margins per width.
    Bfp,
    /// Block floating point in Plücker form, for a bfpW/FALLBACK pair: per-ray and
    /// per-triangle blocks, no translation per test, the bfp filter's decisions (the
    /// model of the rust-hdl filter).
    Plucker,
    /// The Plücker filter with sign decisions against short-float margins (model only).
    PluckerSigns,
}

impl DualFilter {
    pub fn kind(self) -> FilterKind {
        match self {
            DualFilter::Linear => FilterKind::Linear(BoundArith::Coarse(HW_BOUND_BITS)),
            DualFilter::LinearExact => FilterKind::Linear(BoundArith::Exact),
            DualFilter::Quotient => FilterKind::Quotient,
            DualFilter::Bfp => FilterKind::Bfp,
            DualFilter::Plucker => FilterKind::Plucker(PluckerDecisions::Table),
            DualFilter::PluckerSigns => FilterKind::Plucker(PluckerDecisions::Signs),
        }
    }
}

pub fn make(kind: EngineKind, hw: &HwConfig) -> Result<Box<dyn RayEngine>> {
    let memory = MemoryArgs::default().memory(hw.lanes);
    Ok(make_scaled(kind, hw, 0, Lane::default(), memory)?.engine)
}

/// An engine, and for a dual-precision pair a handle on its counters.
pub struct Made {
    pub engine: Box<dyn RayEngine>,
    /// Shares the engine's counters (`--format FILTER/FALLBACK`).
    pub dual: Option<DualIntersector>,
}

/// The engine, its Möller-Trumbore queries scaled by 2^`scale_exp` (model engines only; a
/// pair scales its filter, its fallback answers the queries as given), the model engine's
/// lane options `lane` ([`PrecisionArgs::resolve`] checks that only it gets others than the
/// hardware's), a traversal unit with the scene `memory`.
pub fn make_scaled(
    kind: EngineKind,
    hw: &HwConfig,
    scale_exp: i32,
    lane: Lane,
    memory: SceneMemory,
) -> Result<Made> {
    if let (EngineKind::Model, FormatChoice::Pair(pair)) = (kind, hw.format) {
        let kind = hw
            .dual_filter
            .map_or_else(|| FilterKind::default_for(&pair), DualFilter::kind);
        let dual = DualIntersector::with_filter(Filter::new(pair, scale_exp, kind)?);
        return Ok(Made {
            engine: Box::new(dual.clone()),
            dual: Some(dual),
        });
    }
    if let (EngineKind::Hw, Some(pair)) = (kind, hw.pair_config()?) {
        return Ok(Made {
            engine: Box::new(PairIntersector::new(&pair)?),
            dual: None,
        });
    }
    let engine: Box<dyn RayEngine> = match kind {
        EngineKind::F32 => Box::new(F32Intersector),
        EngineKind::Model => Box::new(ModelIntersector {
            format: hw.single_format()?,
            scale_exp,
            edges: lane.edges,
            advance: lane.advance,
        }),
        EngineKind::Hw => Box::new(HwIntersector::new(&hw.top_config()?, Mode::Stream)?),
        EngineKind::Traversal => Box::new(hw.traversal_engine(scale_exp, lane.advance, memory)?),
    };
    Ok(Made { engine, dual: None })
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
fn choice<T: NamedChoice>() -> impl TypedValueParser<Value = T> {
    clap::builder::PossibleValuesParser::new(T::CHOICES.iter().map(|c| c.choice_name()))
        .try_map(|name| name.parse::<T>())
}

/// `--advance` of the traversal unit's RTL (`verilog`, `synth` and `cosim`).
#[derive(ClapArgs, Clone, Debug)]
pub struct UnitAdvanceArgs {
    /// `--unit traversal`: where the unit's lanes start a leaf's queries: none (at the ray's
    /// origin) or leaf-box (moved to where the box test entered the leaf, the model's
    /// `--engine traversal --advance leaf-box`; docs/traversal-unit.md) [default: none].
    #[arg(long, value_parser = choice::<Advance>())]
    pub advance: Option<Advance>,
}

impl UnitAdvanceArgs {
    /// The advance of `unit`: an error for another than none with the accelerator, whose
    /// lanes start at the query's origin.
    pub fn of(&self, unit: UnitKind) -> Result<Advance> {
        let advance = self.advance.unwrap_or_default();
        if unit == UnitKind::Mt && advance != Advance::None {
            bail!("--advance {advance}: the Möller-Trumbore accelerator's lanes start at the query's origin; the leaf advance is the traversal unit's (--unit traversal)");
        }
        Ok(advance)
    }
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
    /// excluded) [default: thesis for the f32 engine and for fp32, else format-aware].
    #[arg(long, value_parser = choice::<SpawnChoice>())]
    pub spawn: Option<SpawnChoice>,
}

impl SpawnArgs {
    /// The policy asked for, else the default of `kind` answering in `answers`: the thesis'
    /// for the f32 engine and for fp32 (they reproduce the reference), else format-aware.
    pub fn choice(&self, kind: EngineKind, answers: &Format) -> SpawnChoice {
        let thesis = kind == EngineKind::F32 || *answers == Format::FP32;
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
    /// Scaling of the queries into the format's range, model and traversal engines only
    /// [default: none].
    #[arg(long, value_enum)]
    pub scale: Option<ScaleKind>,
    /// The model lane's edge test: exact (the hardware's) or conservative (widened by its
    /// running error bound), model engine with one format only [default: exact].
    #[arg(long, value_parser = choice::<Edges>())]
    pub edges: Option<Edges>,
    /// Where a lane starts a query's ray: none (at its origin), triangle-box (moved in fp32
    /// to where it enters the triangle's bounding box; model engine with one format only) or
    /// leaf-box (moved to where it enters the BVH leaf, as the traversal unit's box test
    /// computed it; traversal engine only) [default: triangle-box for a format-aware model
    /// render, else none].
    #[arg(long, value_parser = choice::<Advance>())]
    pub advance: Option<Advance>,
}

impl PrecisionArgs {
    /// The spawn policy, the scale exponent and the lane options for rendering `scene` with
    /// `kind` in `hw`'s format.
    pub fn resolve(&self, kind: EngineKind, hw: &HwConfig, scene: &Scene) -> Result<Precision> {
        // A pair answers as its fallback (unscaled); only its filter is scaled.
        let (answers, scaled) = match hw.format {
            FormatChoice::Single(f) => (f, f),
            FormatChoice::Pair(p) => match p.filter {
                FilterFormat::Float(filter) => (p.fallback, filter),
                FilterFormat::Bfp(_) if self.scale == Some(ScaleKind::Auto) => {
                    bail!("--format {p} --scale auto: a block-floating-point filter is not scaled (its exponents are per vector)")
                }
                FilterFormat::Bfp(_) => (p.fallback, p.fallback),
            },
        };
        let model = matches!(kind, EngineKind::Model | EngineKind::Traversal);
        // Unscaled unless asked: auto scaling measured no better in any format and worse in
        // e5m14 and the fixed formats (docs/precision.md).
        let scale = self.scale.unwrap_or(ScaleKind::None);
        let scale_exp = match scale {
            ScaleKind::None => 0,
            ScaleKind::Auto if !model => {
                bail!("--scale auto needs the model or traversal engine (the others see fp32 queries as given)")
            }
            ScaleKind::Auto => auto_scale_exp(&scaled, &SceneRange::of(scene)?),
        };
        let answer_scale = if answers == scaled { scale_exp } else { 0 };
        let choice = self.spawn.choice(kind, &answers);
        // The lane options exist in the model of one format only; elsewhere only the
        // hardware's are accepted.
        let single_model =
            kind == EngineKind::Model && matches!(hw.format, FormatChoice::Single(_));
        if single_model && self.advance == Some(Advance::LeafBox) {
            bail!("--advance leaf-box needs the traversal engine (--engine traversal): it starts a leaf's queries where the unit's box test entered the leaf; the model engine has no leaves (--advance triangle-box is its per-triangle form)")
        }
        let lane = if single_model {
            Lane {
                edges: self.edges.unwrap_or_default(),
                advance: self
                    .advance
                    .unwrap_or_else(|| hw_model::advance::default_for(choice)),
            }
        } else {
            let asked = Lane {
                edges: self.edges.unwrap_or_default(),
                advance: self.advance.unwrap_or_default(),
            };
            // The traversal unit also starts a leaf's queries at the leaf's box entry.
            let unit_advance = kind == EngineKind::Traversal && asked.advance == Advance::LeafBox;
            let built = Lane {
                advance: if unit_advance {
                    Advance::LeafBox
                } else {
                    Advance::None
                },
                ..Lane::default()
            };
            if asked != built {
                bail!(
                    "--edges {} --advance {}: not built for --engine {} with --format {}: --edges conservative and --advance triangle-box are model-only so far (--engine model with one format), --advance leaf-box is the traversal unit's (--engine traversal); the hardware lanes, the traversal unit and dual-precision pairs test exact edges",
                    asked.edges,
                    asked.advance,
                    engine_name(kind),
                    hw.format
                )
            }
            asked
        };
        Ok(Precision {
            choice,
            spawn: choice.policy(&answers, answer_scale),
            scale_exp,
            lane,
        })
    }
}

/// `--engine`'s spelling of `kind`.
fn engine_name(kind: EngineKind) -> String {
    kind.to_possible_value()
        .map_or_else(|| format!("{kind:?}"), |v| v.get_name().to_string())
}

/// The traversal unit's scene memory when no `--scene-capacity` is given: the block-RAM
/// memory a unit of `lanes` lanes carries on the XC7Z020.
fn default_capacity(lanes: usize) -> SceneCapacity {
    let (node_bits, triangle_bits) = scene_memory::zynq_address_bits(lanes);
    let (nodes, triangles) = scene_memory::capacity_for(node_bits, triangle_bits);
    SceneCapacity {
        nodes: nodes as u32,
        triangles: triangles as u32,
    }
}

/// `--scene-capacity` and `--no-chunks`: the traversal unit's scene memory.
#[derive(ClapArgs, Clone, Debug, Default)]
pub struct MemoryArgs {
    /// Traversal unit: inner nodes and triangles its scene memory holds, as NODES,TRIANGLES
    /// (e.g. 2048,4096); larger scenes render in chunked passes [default: the unit's block-RAM
    /// memory on the XC7Z020: 4096,8192 beside one lane, 2048,4096 beside more].
    #[arg(long, value_name = "NODES,TRIANGLES", value_parser = parse_capacity)]
    pub scene_capacity: Option<SceneCapacity>,
    /// Traversal unit: refuse a scene larger than --scene-capacity instead of chunking it.
    #[arg(long)]
    pub no_chunks: bool,
}

impl MemoryArgs {
    /// The memory of a unit with `lanes` lanes.
    pub fn memory(&self, lanes: usize) -> SceneMemory {
        let capacity = self
            .scene_capacity
            .unwrap_or_else(|| default_capacity(lanes));
        match self.no_chunks {
            true => SceneMemory::Whole(capacity),
            false => SceneMemory::Chunked(capacity),
        }
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
    Ok(SceneCapacity {
        nodes: count(nodes)?,
        triangles: count(triangles)?,
    })
}

impl HwConfig {
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

    /// The dual-precision pair in hardware (`None` for one format): `--lanes` filter slots
    /// (bfp, or with `--dual-filter plucker-signs` the Plücker lane) sharing one fp32 lane at
    /// `--depth`. Only the pairs built in rust-hdl are: its filter width
    /// (`hdl::dual::WIDTH`), those two filters, 1 to 5 slots.
    pub fn pair_config(&self) -> Result<Option<PairConfig>> {
        let FormatChoice::Pair(pair) = self.format else {
            return Ok(None);
        };
        let built = built_pair();
        let filter = match self.dual_filter.unwrap_or(DualFilter::Bfp) {
            DualFilter::Bfp => Some(SlotFilter::Bfp),
            DualFilter::PluckerSigns => Some(SlotFilter::Plucker),
            _ => None,
        };
        let Some(filter) = filter.filter(|_| pair == built) else {
            let asked = self.dual_filter.and_then(|f| f.to_possible_value());
            let asked = asked.map_or(String::new(), |v| {
                format!(" --dual-filter {}", v.get_name())
            });
            bail!("--format {pair}{asked}: the hardware pairs are {built} with its bfp filter or with plucker-signs; other pairs and filters are model-only (--engine model)");
        };
        let config = PairConfig {
            slots: self.lanes,
            depth: self.depth,
            filter,
        };
        config.check().with_context(|| {
            format!("--format {pair} --lanes {} (its filter slots)", self.lanes)
        })?;
        Ok(Some(config))
    }

    /// The traversal unit's model in this configuration, its Möller-Trumbore queries scaled
    /// by 2^`scale_exp` and started where `advance` says, holding scenes in `memory`; timed by
    /// its schedule model when the format has hardware (any other format has no lane latency
    /// to time with).
    pub fn traversal_engine(
        &self,
        scale_exp: i32,
        advance: Advance,
        memory: SceneMemory,
    ) -> Result<TraversalEngine> {
        let format = self.single_format()?;
        let timing = hw_model::HwFormat::try_from(format).ok().map(|f| {
            let slots = self.slots as usize;
            hdl::traversal::timing::unit_timing(f, self.depth, self.lanes, slots, advance)
        });
        Ok(TraversalEngine {
            format,
            stack_depth: DEFAULT_STACK_DEPTH,
            scale_exp,
            advance,
            timing,
            memory,
        nodes: hw_model::traversal::NodeFormat::Bvh2Fp32,
        })
    }

    /// The traversal unit of this configuration, its scene memory the one that fits the
    /// XC7Z020 beside `lanes` lanes, its lanes started where `advance` says: an error naming
    /// what the RTL does not build.
    pub fn unit_config(&self, advance: Advance) -> Result<UnitConfig> {
        let mut config = UnitConfig::new(self.single_format()?.try_into()?, self.depth, self.lanes);
        config.slots = self.slots as usize;
        config.advance = advance;
        if let Some(c) = self.unit_memory {
            let (node_bits, triangle_bits) =
                scene_memory::address_bits_for(c.nodes as usize, c.triangles as usize);
            config.memory.node_bits = node_bits;
            config.memory.triangle_bits = triangle_bits;
        }
        config.check()?;
        Ok(config)
    }

    /// The accelerator of this configuration: an error if the format has no hardware.
    pub fn top_config(&self) -> Result<TopConfig> {
        Ok(TopConfig::new(
            self.single_format()?.try_into()?,
            self.depth,
            self.lanes,
        ))
    }
}
