//! The Möller-Trumbore datapath: one lane per format (`formats::<name>::MtLane`, from the
//! [`mt_lane!`] body every format module expands), its timing ([`schedule`]) and the delay
//! lines that balance it ([`delay`]).
//!
//! A lane takes fp32 at its ports, converts into the format, runs the dataflow of
//! `hw_model::mt_model` operator for operator and converts t, u, v back to fp32 (fp32 itself
//! needs neither conversion: `RAW_FP32` in [`formats`]). `depth` is
//! the pipeline registers per operator: every operator is built with
//! `min(depth, its max_stages())`, so depths beyond [`max_depth`] change nothing. Parallel
//! branches are padded with delay lines, so a lane accepts a query every cycle (II = 1) and
//! answers it, with `valid_out`, exactly [`latency`] cycles later.

pub mod delay;
mod lane;
pub mod schedule;

pub(crate) use lane::mt_lane;

use hw_model::{Format, HwFormat, MtQuery, MtResult};
use rust_hdl::prelude::*;

use crate::formats;
use crate::harness::{simulate_cycles, Stepped};
use crate::operator::Op;
use crate::regmap::{self, OPERAND_COUNT};
use crate::top::stream::QUERY_BITS;
use schedule::{OpLatencies, Schedule};

/// The lane's timing in `format` at `depth`.
pub fn schedule(format: HwFormat, depth: usize) -> Schedule {
    let ops = OpLatencies::for_depth(depth, |op| formats::max_stages(format, op));
    Schedule::new(ops.unconverted(formats::raw_fp32(format)))
}

/// Cycles from query to result of a lane in `format` at `depth`.
pub fn latency(format: HwFormat, depth: usize) -> usize {
    schedule(format, depth).latency
}

/// The depth at which every operator of `format` has all its pipeline registers.
pub fn max_depth(format: HwFormat) -> usize {
    Op::ALL
        .into_iter()
        .map(|op| formats::max_stages(format, op))
        .max()
        .unwrap_or(0)
}

/// A query as the lane's input words (the register map's operand order): orig, dir, v0, v1,
/// v2 (x, y, z each), t_min, fp32 bits.
pub fn query_words(q: &MtQuery) -> [u32; OPERAND_COUNT] {
    let mut words = [0; OPERAND_COUNT];
    let fields = [q.orig, q.dir, q.v0, q.v1, q.v2];
    for (w, x) in words.iter_mut().zip(fields.iter().flatten()) {
        *w = x.to_bits();
    }
    words[T_MIN_WORD] = q.t_min.to_bits();
    words
}

/// The query of [`query_words`] (bit for bit, NaN payloads included).
pub fn query_from_words(words: &[u32; OPERAND_COUNT]) -> MtQuery {
    let f = |k: usize| f32::from_bits(words[k]);
    let v = |k: usize| [f(3 * k), f(3 * k + 1), f(3 * k + 2)];
    MtQuery {
        orig: v(0),
        dir: v(1),
        v0: v(2),
        v1: v(3),
        v2: v(4),
        t_min: f(T_MIN_WORD),
    }
}

/// Where t_min is among a query's words (after the 15 coordinates).
pub const T_MIN_WORD: usize = (regmap::T_MIN - regmap::ORIG_X) / 4;
// The lane (`lane.rs`) spells the index as a literal.
const _: () = assert!(T_MIN_WORD == 15 && OPERAND_COUNT == 16);

/// A lane's packed query and its answer, seen from what issues the queries (the traversal
/// unit's leaf ports): the query's words in the register map's operand order
/// ([`query_words`]), one a cycle with `valid`; the answer (t, u, v as fp32 words) a lane's
/// latency later.
#[derive(LogicInterface, Default)]
#[join = "LaneTarget"]
pub struct LanePort {
    pub valid: Signal<Out, Bit>,
    pub query: Signal<Out, Bits<QUERY_BITS>>,
    pub hit: Signal<In, Bit>,
    pub t: Signal<In, Bits<32>>,
    pub u: Signal<In, Bits<32>>,
    pub v: Signal<In, Bits<32>>,
}

/// A lane's side of [`LanePort`].
#[derive(LogicInterface, Default)]
#[join = "LanePort"]
pub struct LaneTarget {
    pub valid: Signal<In, Bit>,
    pub query: Signal<In, Bits<QUERY_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub t: Signal<Out, Bits<32>>,
    pub u: Signal<Out, Bits<32>>,
    pub v: Signal<Out, Bits<32>>,
}

/// What a lane's outputs show in one cycle (t, u, v as fp32 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaneOutput {
    pub valid: bool,
    pub hit: bool,
    pub t: u32,
    pub u: u32,
    pub v: u32,
}

impl LaneOutput {
    pub fn result(&self) -> MtResult {
        MtResult {
            hit: self.hit,
            t: f32::from_bits(self.t),
            u: f32::from_bits(self.u),
            v: f32::from_bits(self.v),
        }
    }
}

/// The port plumbing every format's `MtLane` shares, so tests and drivers are written once.
pub trait Lane: Block + Sized + 'static {
    const NAME: &'static str;
    const HW: HwFormat;
    const FORMAT: Format;
    fn new(depth: usize) -> Self;
    fn latency(depth: usize) -> usize;
    fn clock(&mut self) -> &mut Signal<In, Clock>;
    fn set_inputs(&mut self, valid: bool, query: &[u32; OPERAND_COUNT]);
    fn outputs(&self) -> LaneOutput;
}

impl<L: Lane> Stepped for L {
    /// Valid and the query.
    type Input = (bool, MtQuery);
    type Output = LaneOutput;

    fn idle() -> Self::Input {
        (false, MtQuery::default())
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        self.clock()
    }

    fn apply(&mut self, (valid, query): &Self::Input) {
        self.set_inputs(*valid, &query_words(query));
    }

    fn observe(&self) -> LaneOutput {
        self.outputs()
    }
}

/// Runs a freshly built lane in rust-hdl's simulator for `inputs.len() + flush` cycles,
/// feeding `inputs[c]` (valid, query) in cycle `c` (then invalid all-zero queries) and
/// returning what the outputs show in every cycle.
pub fn simulate_lane<L: Lane>(
    depth: usize,
    inputs: &[(bool, MtQuery)],
    flush: usize,
) -> Vec<LaneOutput> {
    simulate_cycles(move || L::new(depth), inputs, flush)
}
