//! The origin advance of a ray's leaf queries in fp32 (docs/precision.md "Advancing the
//! origin", `--advance leaf-box`): `o' = o + t0·d` per axis and `t_min' = t_min − t0`, one
//! ray a cycle (II = 1), bit for bit `hw_model::advance::moved`. t0 is the leaf box's entry
//! distance the unit's box test computed (`hw_model::advance::leaf_start` chooses it); the
//! lane's answer is moved back by one fp32 `Add` (`t + t0`, `hw_model::advance::moved_back`)
//! beside the lane. [`AroundLane`] is that pair around one lane of the traversal unit
//! (`unit_top` builds one per lane with `--advance leaf-box`).
//!
//! The dataflow, with the cycle each value is ready (the operators' latencies at `depth`,
//! see [`AdvanceSchedule`]):
//! ```text
//! scaled_dir    = mul            t0·d_k          (three multipliers)
//! latency       = mul + add      o_k + t0·d_k    (three adders)
//! lowered_t_min = sub            t_min − t0, then delayed to `latency`
//! ```

use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Add, Mul, Sub};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::mt::{LanePort, LaneTarget, T_MIN_WORD};
use crate::operator::Op;
use crate::top::stream::QUERY_BITS;
use crate::traversal::box_test::Tag;

type Word = Bits<32>;

// `AroundLane` spells t_min's place in the query as the literal 480 (hdl_gen would leak a
// named const into the Verilog).
const _: () = assert!(32 * T_MIN_WORD == 480);

/// When each value of the advance is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdvanceSchedule {
    /// Registers per fp32 `Mul`, `Add`, `Sub`: `min(depth, max_stages)`.
    pub mul: usize,
    pub add: usize,
    pub sub: usize,
    /// Inputs (ray, t0, valid, tag) to outputs.
    pub latency: usize,
}

impl AdvanceSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        AdvanceSchedule {
            mul: ops.mul,
            add: ops.add,
            sub: ops.sub,
            latency: ops.mul + ops.add,
        }
    }

    /// The origin to its addition (it skips the multiplication).
    pub fn orig_to_sum(&self) -> usize {
        self.mul
    }

    /// `t_min − t0` to the outputs.
    pub fn lowered_to_out(&self) -> usize {
        self.latency
            .checked_sub(self.sub)
            .expect("a subtraction is never slower than a multiplication and an addition")
    }
}

/// Cycles from a ray at the inputs to its moved origin at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    AdvanceSchedule::new(depth).latency
}

/// Cycles the advance adds to a lane's answer path: the block in front of it, the `t + t0`
/// adder behind it.
pub fn around_lane_latency(depth: usize) -> usize {
    let s = AdvanceSchedule::new(depth);
    s.latency + s.add
}

/// The depth at which every operator of the block has all its pipeline registers.
pub fn max_depth() -> usize {
    [Op::Add, Op::Sub, Op::Mul]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0)
}

/// One ray's advance a cycle: `orig`, `dir` (x, y, z), `t_min`, `t0` (fp32 words),
/// `valid_in` and `tag_in` in; `moved` (x, y, z) and `t_min_out` exactly
/// [`latency`]`(depth)` cycles later with `valid_out` and `tag_out`. `depth` is the pipeline
/// registers per operator, each saturating at its own `max_stages()`. No reset: the valid
/// line holds the flip-flops' power-on zeros.
#[derive(LogicBlock)]
pub struct LeafAdvance {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Tag>,
    pub orig: Vec<Signal<In, Word>>,
    pub dir: Vec<Signal<In, Word>>,
    pub t_min: Signal<In, Word>,
    pub t0: Signal<In, Word>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Tag>,
    pub moved: Vec<Signal<Out, Word>>,
    pub t_min_out: Signal<Out, Word>,
    scaled_dir: Vec<Mul>,
    orig_at_sum: Vec<Delay<Word>>,
    moved_sum: Vec<Add>,
    lowered_t_min: Sub,
    lowered_at_out: Delay<Word>,
    valid_at_out: Delay<Bit>,
    tag_at_out: Delay<Tag>,
}

impl LeafAdvance {
    pub fn new(depth: usize) -> Self {
        let s = AdvanceSchedule::new(depth);
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            orig: (0..3).map(|_| Default::default()).collect(),
            dir: (0..3).map(|_| Default::default()).collect(),
            t_min: Default::default(),
            t0: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            moved: (0..3).map(|_| Default::default()).collect(),
            t_min_out: Default::default(),
            scaled_dir: (0..3).map(|_| Mul::new(s.mul)).collect(),
            orig_at_sum: (0..3).map(|_| Delay::new(s.orig_to_sum())).collect(),
            moved_sum: (0..3).map(|_| Add::new(s.add)).collect(),
            lowered_t_min: Sub::new(s.sub),
            lowered_at_out: Delay::new(s.lowered_to_out()),
            valid_at_out: Delay::new(s.latency),
            tag_at_out: Delay::new(s.latency),
        }
    }
}

impl Stepped for LeafAdvance {
    type Input = AdvanceInput;
    type Output = AdvanceOutput;

    fn idle() -> AdvanceInput {
        AdvanceInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, x: &Self::Input) {
        let word = |x: f32| Word::from(u64::from(x.to_bits()));
        self.valid_in.next = x.valid;
        self.tag_in.next = u64::from(x.tag).into();
        for k in 0..3 {
            self.orig[k].next = word(x.orig[k]);
            self.dir[k].next = word(x.dir[k]);
        }
        self.t_min.next = word(x.t_min);
        self.t0.next = word(x.t0);
    }

    fn observe(&self) -> Self::Output {
        let bits = |w: Word| w.to_u64() as u32;
        AdvanceOutput {
            valid: self.valid_out.val(),
            tag: self.tag_out.val().to_u64() as u16,
            moved: [0, 1, 2].map(|k| bits(self.moved[k].val())),
            t_min: bits(self.t_min_out.val()),
        }
    }
}

impl Logic for LeafAdvance {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            clock!(self, clock, scaled_dir[k], orig_at_sum[k], moved_sum[k]);
            // o + t0·d, in the model's operand order.
            self.scaled_dir[k].a.next = self.t0.val();
            self.scaled_dir[k].b.next = self.dir[k].val();
            self.orig_at_sum[k].d.next = self.orig[k].val();
            self.moved_sum[k].a.next = self.orig_at_sum[k].q.val();
            self.moved_sum[k].b.next = self.scaled_dir[k].y.val();
            self.moved[k].next = self.moved_sum[k].y.val();
        }
        clock!(
            self,
            clock,
            lowered_t_min,
            lowered_at_out,
            valid_at_out,
            tag_at_out
        );
        self.lowered_t_min.a.next = self.t_min.val();
        self.lowered_t_min.b.next = self.t0.val();
        self.lowered_at_out.d.next = self.lowered_t_min.y.val();
        self.t_min_out.next = self.lowered_at_out.q.val();
        self.valid_at_out.d.next = self.valid_in.val();
        self.tag_at_out.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_at_out.q.val();
        self.tag_out.next = self.tag_at_out.q.val();
    }
}

/// One ray at the inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AdvanceInput {
    pub valid: bool,
    pub tag: u16,
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    pub t_min: f32,
    pub t0: f32,
}

/// What the block's outputs show in one cycle (fp32 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AdvanceOutput {
    pub valid: bool,
    pub tag: u16,
    pub moved: [u32; 3],
    pub t_min: u32,
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator for `inputs.len() + flush`
/// cycles, feeding `inputs[c]` in cycle `c` (then idle, all-zero inputs) and returning what
/// the outputs show in every cycle.
pub fn simulate_leaf_advance(
    depth: usize,
    inputs: &[AdvanceInput],
    flush: usize,
) -> Vec<AdvanceOutput> {
    simulate_cycles(move || LeafAdvance::new(depth), inputs, flush)
}

/// Verilog of the block at `depth`, top module `top`.
pub fn leaf_advance_verilog(depth: usize) -> String {
    built_verilog(move || LeafAdvance::new(depth))
}

/// The leaf advance around one MT lane of `lane_latency` cycles: a packed query (the
/// accelerator's operand order: orig, dir, v0, v1, v2, t_min) and the leaf's entry distance
/// in, the moved query out to the lane; the lane's answer in, `t + t0` (and hit, u, v
/// beside it) out. t0 is `hw_model::advance::leaf_start` of the entry: the entry if finite,
/// positive and normal, else 0 (a subnormal t0 moves nothing through the flushing
/// operators, so it is 0 either way). Query to answer: [`around_lane_latency`] plus the lane's.
#[derive(LogicBlock)]
pub struct AroundLane {
    pub clock: Signal<In, Clock>,
    /// The leaf port's side: its query in, the moved-back answer out; the entry distance
    /// beside the query.
    pub core: LaneTarget,
    pub entry: Signal<In, Word>,
    /// The lane's side: the moved query out, the lane's answer in.
    pub lane: LanePort,
    advance: LeafAdvance,
    /// The query's other words (dir, vertices) wait for the moved origin.
    query_at: Delay<Bits<QUERY_BITS>>,
    /// t0 travels beside the advance and the lane to the adder.
    t0_at: Delay<Word>,
    moved_back: Add,
    hit_at: Delay<Bit>,
    u_at: Delay<Word>,
    v_at: Delay<Word>,
    t0: Signal<Local, Word>,
    exponent: Signal<Local, Bits<8>>,
}

impl AroundLane {
    pub fn new(depth: usize, lane_latency: usize) -> Self {
        let s = AdvanceSchedule::new(depth);
        Self {
            clock: Default::default(),
            core: Default::default(),
            entry: Default::default(),
            lane: Default::default(),
            advance: LeafAdvance::new(depth),
            query_at: Delay::new(s.latency),
            t0_at: Delay::new(s.latency + lane_latency),
            moved_back: Add::new(s.add),
            hit_at: Delay::new(s.add),
            u_at: Delay::new(s.add),
            v_at: Delay::new(s.add),
            t0: Default::default(),
            exponent: Default::default(),
        }
    }
}

impl Logic for AroundLane {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, advance, query_at, t0_at, moved_back, hit_at, u_at, v_at);
        // leaf_start: only a finite, positive, normal entry moves the ray.
        self.exponent.next = self.entry.val().get_bits::<8>(23);
        self.t0.next = 0.into();
        if !self.entry.val().get_bit(31) & self.exponent.val().any() & !self.exponent.val().all() {
            self.t0.next = self.entry.val();
        }
        self.advance.valid_in.next = self.core.valid.val();
        self.advance.tag_in.next = 0.into();
        for k in 0..3 {
            self.advance.orig[k].next = self.core.query.val().get_bits::<32>(32 * k);
            self.advance.dir[k].next = self.core.query.val().get_bits::<32>(32 * (3 + k));
        }
        self.advance.t_min.next = self.core.query.val().get_bits::<32>(480);
        self.advance.t0.next = self.t0.val();
        self.query_at.d.next = self.core.query.val();
        // The moved origin (words 0-2) and t_min (word 15) around the delayed words 3-14.
        self.lane.valid.next = self.advance.valid_out.val();
        self.lane.query.next = bit_cast::<QUERY_BITS, 32>(self.advance.moved[0].val())
            | (bit_cast::<QUERY_BITS, 32>(self.advance.moved[1].val()) << 32)
            | (bit_cast::<QUERY_BITS, 32>(self.advance.moved[2].val()) << 64)
            | (((self.query_at.q.val() << 32) >> 128) << 96)
            | (bit_cast::<QUERY_BITS, 32>(self.advance.t_min_out.val()) << 480);
        // The answer: t + t0 in fp32, the rest delayed beside the adder.
        self.t0_at.d.next = self.t0.val();
        self.moved_back.a.next = self.lane.t.val();
        self.moved_back.b.next = self.t0_at.q.val();
        self.hit_at.d.next = self.lane.hit.val();
        self.u_at.d.next = self.lane.u.val();
        self.v_at.d.next = self.lane.v.val();
        self.core.hit.next = self.hit_at.q.val();
        self.core.t.next = self.moved_back.y.val();
        self.core.u.next = self.u_at.q.val();
        self.core.v.next = self.v_at.q.val();
    }
}
