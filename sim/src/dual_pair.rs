//! The dual-precision pair (`hdl::dual::pair`: bfp18 or Plücker filter slots sharing one
//! fp32 lane), Verilated and driven cycle by cycle as the renderer's [`Intersector`]. A
//! Plücker slot is also given each query's stored vectors (`plucker::datapath`, what the
//! scene memory and a per-ray setup would hold), packed as `hdl::dual::plucker_operands`.
//!
//! A batch is dealt to the slots in turn (query k to slot k mod N, tag k); each slot offers
//! its next query every cycle and keeps it until `ready` takes it. Answers come back out of
//! order, by tag, from the slots' miss ports and the fp32 lane. Every query must be answered
//! exactly once: a doubled or unknown tag is a protocol error, and a pair that stops
//! answering is a timeout, never a silent miss.

use std::sync::{Arc, Mutex};

use hdl::dual::pair::{dual_pair_verilog, SlotFilter, TAG};
use hdl::dual::plucker_operands::{operand_words, OPERAND_BITS, OPERAND_WORDS};
use hdl::dual::WIDTH;
use hdl::mt::query_words;
use hdl::regmap::OPERAND_COUNT;
use hw_model::dual::plucker::datapath;
use hw_model::dual::FormatPair;
use hw_model::{MtQuery, MtResult};
use sw_renderer::intersect::Intersector;
use sw_renderer::rays::EngineError;

use crate::cosim_error::CosimError;
use crate::verilator::{BuiltModel, BuiltModels, Direction};
use crate::{SimError, VerilatedModel};

/// The filter slots a pair is built with (one Verilog per count).
pub const SLOTS: std::ops::RangeInclusive<usize> = 1..=5;

/// The one format pair built in hardware: bfp at `hdl::dual::WIDTH` before fp32 (its filter
/// lane the bfp filter or the Plücker lane, [`PairConfig::filter`]).
pub fn built_pair() -> FormatPair {
    FormatPair::parse(&format!("bfp{WIDTH}/fp32")).expect("hdl::dual::WIDTH is a bfp width")
}

/// A pair's shape: `slots` filters of kind `filter` in front of one fp32 lane at pipeline
/// `depth`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairConfig {
    pub slots: usize,
    pub depth: usize,
    pub filter: SlotFilter,
}

impl std::fmt::Display for PairConfig {
    /// "bfp18/fp32 pair s2 d5", "bfp18/fp32 plucker-signs pair s5 d5".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ", built_pair())?;
        if self.filter != SlotFilter::Bfp {
            write!(f, "{} ", self.filter.model_kind())?;
        }
        write!(f, "pair s{} d{}", self.slots, self.depth)
    }
}

impl PairConfig {
    /// An error unless the slot count is one a pair is built with and its fp32 lane has
    /// `depth`'s pipeline registers.
    pub fn check(&self) -> Result<(), PairError> {
        if !SLOTS.contains(&self.slots) {
            return Err(PairError::Slots(self.slots));
        }
        let max = hdl::mt::max_depth(hw_model::HwFormat::FP32);
        if self.depth > max {
            return Err(PairError::Depth {
                depth: self.depth,
                max,
            });
        }
        Ok(())
    }
}

#[derive(Debug, thiserror::Error)]
pub enum PairError {
    #[error("a dual-precision pair has {} to {} filter slots, not {0}", SLOTS.start(), SLOTS.end())]
    Slots(usize),
    #[error("depth = {depth}: the pair's fp32 lane has pipeline registers for depth 0 to {max}")]
    Depth { depth: usize, max: usize },
    #[error(transparent)]
    Cosim(#[from] CosimError),
}

impl From<SimError> for PairError {
    fn from(e: SimError) -> Self {
        PairError::Cosim(e.into())
    }
}

/// The pair's Verilog (top module `top`).
pub fn pair_verilog(config: &PairConfig) -> Result<String, PairError> {
    config.check()?;
    let (depth, kind) = (config.depth, config.filter);
    Ok(match config.slots {
        1 => dual_pair_verilog::<1>(depth, kind),
        2 => dual_pair_verilog::<2>(depth, kind),
        3 => dual_pair_verilog::<3>(depth, kind),
        4 => dual_pair_verilog::<4>(depth, kind),
        5 => dual_pair_verilog::<5>(depth, kind),
        n => unreachable!("check() admits {SLOTS:?}, not {n}"),
    })
}

/// A built model of a pair and what it was built from.
pub type PairModel = BuiltModel<PairConfig>;

/// The pair of `config`, built (or taken from the builder's cache) once per process.
pub fn pair_model(config: &PairConfig) -> Result<Arc<PairModel>, PairError> {
    static BUILT: BuiltModels<PairConfig> = BuiltModels::new();
    BUILT.get(config, pair_verilog)
}

/// What a pair did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PairStats {
    pub tests: u64,
    /// Tests the filters could not decide, answered by the fp32 lane.
    pub forwarded: u64,
    pub cycles: u64,
    /// Cycles in which a slot offered a query and `ready` held it back.
    pub stall_cycles: u64,
}

impl PairStats {
    pub fn forwarded_share(&self) -> f64 {
        self.forwarded as f64 / self.tests.max(1) as f64
    }

    pub fn tests_per_cycle(&self) -> f64 {
        self.tests as f64 / self.cycles.max(1) as f64
    }

    fn add(&mut self, other: &PairStats) {
        self.tests += other.tests;
        self.forwarded += other.forwarded;
        self.cycles += other.cycles;
        self.stall_cycles += other.stall_cycles;
    }
}

/// Word offsets of one slot's ports in the packed cycle buffers.
struct SlotPorts {
    valid: usize,
    query: usize,
    tag: usize,
    /// A Plücker slot's operands.
    operands: Option<usize>,
    miss_valid: usize,
    miss_tag: usize,
}

/// Word offsets of the fp32 lane's answer.
struct LanePorts {
    valid: usize,
    tag: usize,
    hit: usize,
    t: usize,
    u: usize,
    v: usize,
}

/// One simulated pair.
pub struct VerilatedPair {
    sim: VerilatedModel,
    slots: Vec<SlotPorts>,
    ready: usize,
    lane: LanePorts,
    input: Vec<u32>,
    output: Vec<u32>,
}

/// Cycles without an answer after which a pair with queries outstanding has failed: far
/// beyond the longest wait (every slot's queue ahead, then the fp32 lane).
const WATCHDOG: u64 = 10_000;

impl VerilatedPair {
    pub fn new(model: &PairModel) -> Result<VerilatedPair, SimError> {
        let sim = model.model.instantiate();
        let iface = sim.interface().clone();
        let input = |name: &str, bits| iface.word_offset(Direction::Input, name, bits);
        let output = |name: &str, bits| iface.word_offset(Direction::Output, name, bits);
        let plucker = model.config.filter == SlotFilter::Plucker;
        let slots = (0..model.config.slots)
            .map(|s| {
                let operands = format!("operands${s}");
                Ok(SlotPorts {
                    valid: input(&format!("valid${s}"), None)?,
                    query: input(&format!("query${s}"), Some(32 * OPERAND_COUNT as u32))?,
                    tag: input(&format!("tag${s}"), None)?,
                    operands: match plucker {
                        true => Some(input(&operands, Some(OPERAND_BITS as u32))?),
                        false => None,
                    },
                    miss_valid: output(&format!("miss_valid${s}"), None)?,
                    miss_tag: output(&format!("miss_tag${s}"), None)?,
                })
            })
            .collect::<Result<_, SimError>>()?;
        let lane = LanePorts {
            valid: output("fp_valid", None)?,
            tag: output("fp_tag", None)?,
            hit: output("fp_hit", None)?,
            t: output("fp_t", None)?,
            u: output("fp_u", None)?,
            v: output("fp_v", None)?,
        };
        Ok(VerilatedPair {
            ready: output("ready", None)?,
            input: vec![0; iface.in_words()],
            output: vec![0; iface.out_words()],
            sim,
            slots,
            lane,
        })
    }

    /// Answers `queries` into `results` (one each, by position).
    pub fn run_batch(
        &mut self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<PairStats, CosimError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        let mut stats = PairStats::default();
        // Tags are query indices: a batch goes in chunks the tag can name.
        let chunk = 1 << TAG;
        for (qs, rs) in queries.chunks(chunk).zip(results.chunks_mut(chunk)) {
            stats.add(&self.run_chunk(qs, rs)?);
        }
        Ok(stats)
    }

    fn run_chunk(
        &mut self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<PairStats, CosimError> {
        let n = self.slots.len();
        let mut answered = vec![false; queries.len()];
        // Each slot's next query: s, s + n, s + 2n, …
        let mut next: Vec<usize> = (0..n).collect();
        let (mut left, mut quiet) = (queries.len(), 0);
        let mut stats = PairStats {
            tests: queries.len() as u64,
            ..PairStats::default()
        };
        while left > 0 {
            for (s, port) in self.slots.iter().enumerate() {
                let offer = queries.get(next[s]);
                self.input[port.valid] = u32::from(offer.is_some());
                let words = query_words(offer.unwrap_or(&MtQuery::default()));
                self.input[port.query..port.query + OPERAND_COUNT].copy_from_slice(&words);
                self.input[port.tag] = next[s] as u32;
                if let Some(at) = port.operands {
                    let ops = offer.and_then(|q| datapath(q, WIDTH)).map(|(ops, _)| ops);
                    self.input[at..at + OPERAND_WORDS]
                        .copy_from_slice(&operand_words(ops.as_ref()));
                }
            }
            self.sim.step(&self.input, &mut self.output)?;
            let cycle = self.sim.cycles();
            stats.cycles += 1;
            // `ready` comes from registers: what this cycle showed decided its edge.
            let offered = next.iter().any(|&k| k < queries.len());
            if self.output[self.ready] != 0 {
                for k in &mut next {
                    if *k < queries.len() {
                        *k += n;
                    }
                }
            } else if offered {
                stats.stall_cycles += 1;
            }
            let before = left;
            let mut answer = |tag: u32, result: MtResult| -> Result<(), CosimError> {
                let k = tag as usize;
                let taken = k < queries.len() && k < next[k % n];
                if !taken || std::mem::replace(&mut answered[k], true) {
                    return Err(CosimError::Protocol {
                        bus: "dual pair",
                        cycle,
                        message: format!(
                            "answer for tag {k}, which is {} (batch of {})",
                            if taken {
                                "answered already"
                            } else {
                                "not taken"
                            },
                            queries.len()
                        ),
                    });
                }
                results[k] = result;
                left -= 1;
                Ok(())
            };
            for port in &self.slots {
                if self.output[port.miss_valid] != 0 {
                    answer(self.output[port.miss_tag], MtResult::default())?;
                }
            }
            let lane = &self.lane;
            if self.output[lane.valid] != 0 {
                let f = |offset: usize| f32::from_bits(self.output[offset]);
                let result = MtResult {
                    hit: self.output[lane.hit] != 0,
                    t: f(lane.t),
                    u: f(lane.u),
                    v: f(lane.v),
                };
                answer(self.output[lane.tag], result)?;
                stats.forwarded += 1;
            }
            quiet = if left < before { 0 } else { quiet + 1 };
            if quiet > WATCHDOG {
                return Err(CosimError::Timeout {
                    what: format!("dual pair, {left} of {} queries unanswered", queries.len()),
                    cycles: quiet,
                });
            }
        }
        Ok(stats)
    }
}

/// The Verilated pair as an [`Intersector`]: each calling thread takes an instance from a
/// pool (creating one when none is free).
pub struct PairIntersector {
    model: Arc<PairModel>,
    pool: Mutex<Vec<VerilatedPair>>,
    stats: Mutex<PairStats>,
}

impl PairIntersector {
    pub fn new(config: &PairConfig) -> Result<PairIntersector, PairError> {
        let model = pair_model(config)?;
        let first = VerilatedPair::new(&model)?;
        Ok(PairIntersector {
            model,
            pool: Mutex::new(vec![first]),
            stats: Mutex::default(),
        })
    }

    pub fn config(&self) -> PairConfig {
        self.model.config
    }

    /// The Verilated model: whether it came from the cache, the time spent on it.
    pub fn model(&self) -> &PairModel {
        &self.model
    }

    pub fn stats(&self) -> PairStats {
        *self.stats.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn simulate(&self, queries: &[MtQuery], results: &mut [MtResult]) -> Result<(), CosimError> {
        let taken = self.pool.lock().unwrap_or_else(|p| p.into_inner()).pop();
        let mut pair = match taken {
            Some(pair) => pair,
            None => VerilatedPair::new(&self.model)?,
        };
        let batch = pair.run_batch(queries, results)?;
        (self.stats.lock().unwrap_or_else(|p| p.into_inner())).add(&batch);
        self.pool
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(pair);
        Ok(())
    }
}

impl Intersector for PairIntersector {
    /// "hw bfp18/fp32 pair s2 d5".
    fn name(&self) -> String {
        format!("hw {}", self.model.config)
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        Ok(self.simulate(queries, results)?)
    }
}
