//! The far end of a ray's slab interval in fp32: `t_hi = (bound + |bound|·PAD) + pad`, one
//! bound a cycle (II = 1), bit for bit `hw_model::traversal::box_test::t_hi`. The unit
//! computes it when a ray enters (inside [`crate::traversal::ray_setup::RaySetupUnit`]) and
//! again whenever a closest-hit ray's nearest hit shrinks its bound.
//!
//! The dataflow, with the cycle each value is ready (the operators' latencies at `depth`,
//! see [`FarSchedule`]):
//! ```text
//! scaled   = mul                 |bound|·PAD
//! loosened = scaled + add        bound + scaled
//! latency  = loosened + add      loosened + pad
//! ```
//! `pad` is needed only by the last addition: it waits for it in a delay line, so a caller
//! that has `pad` later than the bound (the ray setup, whose pad comes out of a fold and a
//! multiplication) can give it up to [`FarSchedule::pad_slack`] cycles late
//! ([`FarEnd::with_late_pad`]) instead of delaying the bound.
//!
//! Latency at depth 0..=5: 0, 3, 6, 9, 11, 13 (5 = [`max_depth`]); yosys xc7 resources of
//! the whole ray setup, which holds one, are in its module doc.

use hw_model::traversal::box_test::PAD;
use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Add, Mul};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::operator::Op;
use crate::traversal::box_test::Tag;

type Word = Bits<32>;

/// When each value of the far end is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FarSchedule {
    /// Registers per fp32 `Mul`, `Add`: `min(depth, max_stages)`.
    pub mul: usize,
    pub add: usize,
    /// |bound|·PAD.
    pub scaled: usize,
    /// bound + |bound|·PAD.
    pub loosened: usize,
    /// Inputs (bound, valid, tag) to outputs.
    pub latency: usize,
}

impl FarSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let (mul, add) = (ops.mul, ops.add);
        let scaled = mul;
        let loosened = scaled + add;
        FarSchedule {
            mul,
            add,
            scaled,
            loosened,
            latency: loosened + add,
        }
    }

    /// The bound to the first addition (it skips the multiplication).
    pub fn bound_to_sum(&self) -> usize {
        self.scaled
    }

    /// The most cycles `pad` may arrive after the bound: when the last addition needs it.
    pub fn pad_slack(&self) -> usize {
        self.loosened
    }

    /// `pad`, arriving `pad_after` cycles after the bound, to the last addition.
    pub fn pad_to_sum(&self, pad_after: usize) -> usize {
        assert!(
            pad_after <= self.pad_slack(),
            "pad {pad_after} cycles after the bound: at most {} at this depth",
            self.pad_slack()
        );
        self.loosened - pad_after
    }
}

/// The block's timing at `depth`.
pub fn schedule(depth: usize) -> FarSchedule {
    FarSchedule::new(depth)
}

/// Cycles from a bound at the inputs to its `t_hi` at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    schedule(depth).latency
}

/// The depth at which every operator of the block has all its pipeline registers.
pub fn max_depth() -> usize {
    [Op::Add, Op::Mul]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0)
}

/// The far end of one ray a cycle: `bound`, `pad` (fp32 words), `valid_in` and `tag_in` in,
/// `t_hi` out exactly [`latency`]`(depth)` cycles later with `valid_out` and `tag_out`.
/// `depth` is the pipeline registers per operator, each saturating at its own
/// `max_stages()`. Built with [`FarEnd::with_late_pad`], `pad` belongs to the bound given
/// that many cycles earlier. No reset: the valid line holds the flip-flops' power-on zeros.
#[derive(LogicBlock)]
pub struct FarEnd {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Tag>,
    pub bound: Signal<In, Word>,
    pub pad: Signal<In, Word>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Tag>,
    pub t_hi: Signal<Out, Word>,
    scaled: Mul,
    bound_at_sum: Delay<Word>,
    loosened: Add,
    pad_at_sum: Delay<Word>,
    sum: Add,
    valid_at_out: Delay<Bit>,
    tag_at_out: Delay<Tag>,
    /// PAD (the model's constant) and the mask that clears a word's sign.
    pad_factor: Constant<Word>,
    abs_mask: Constant<Word>,
}

impl FarEnd {
    /// `bound` and `pad` of a ray in the same cycle.
    pub fn new(depth: usize) -> Self {
        Self::with_late_pad(depth, 0)
    }

    /// `pad` arriving `pad_after` cycles after its bound (at most
    /// [`FarSchedule::pad_slack`]); the latency still counts from the bound.
    pub fn with_late_pad(depth: usize, pad_after: usize) -> Self {
        let s = schedule(depth);
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            bound: Default::default(),
            pad: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            t_hi: Default::default(),
            scaled: Mul::new(s.mul),
            bound_at_sum: Delay::new(s.bound_to_sum()),
            loosened: Add::new(s.add),
            pad_at_sum: Delay::new(s.pad_to_sum(pad_after)),
            sum: Add::new(s.add),
            valid_at_out: Delay::new(s.latency),
            tag_at_out: Delay::new(s.latency),
            pad_factor: Constant::new(u64::from(PAD.to_bits()).into()),
            abs_mask: Constant::new(0x7FFF_FFFFu64.into()),
        }
    }

    /// Cycles from a bound at the inputs to its `t_hi` at the outputs ([`latency`]).
    pub fn latency(depth: usize) -> usize {
        latency(depth)
    }
}

impl Stepped for FarEnd {
    type Input = FarInput;
    type Output = FarOutput;

    fn idle() -> FarInput {
        FarInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, x: &Self::Input) {
        let word = |x: f32| Word::from(u64::from(x.to_bits()));
        self.valid_in.next = x.valid;
        self.tag_in.next = u64::from(x.tag).into();
        self.bound.next = word(x.bound);
        self.pad.next = word(x.pad);
    }

    fn observe(&self) -> Self::Output {
        FarOutput {
            valid: self.valid_out.val(),
            tag: self.tag_out.val().to_u64() as u16,
            t_hi: self.t_hi.val().to_u64() as u32,
        }
    }
}

impl Logic for FarEnd {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            scaled,
            bound_at_sum,
            loosened,
            pad_at_sum,
            sum,
            valid_at_out,
            tag_at_out
        );
        // (bound + |bound|·PAD) + pad, in the model's operand order.
        self.scaled.a.next = self.bound.val() & self.abs_mask.val();
        self.scaled.b.next = self.pad_factor.val();
        self.bound_at_sum.d.next = self.bound.val();
        self.loosened.a.next = self.bound_at_sum.q.val();
        self.loosened.b.next = self.scaled.y.val();
        self.pad_at_sum.d.next = self.pad.val();
        self.sum.a.next = self.loosened.y.val();
        self.sum.b.next = self.pad_at_sum.q.val();
        self.t_hi.next = self.sum.y.val();
        self.valid_at_out.d.next = self.valid_in.val();
        self.tag_at_out.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_at_out.q.val();
        self.tag_out.next = self.tag_at_out.q.val();
    }
}

/// One bound at the inputs: valid, tag, the bound and the ray's pad.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FarInput {
    pub valid: bool,
    pub tag: u16,
    pub bound: f32,
    pub pad: f32,
}

/// What the block's outputs show in one cycle (t_hi as fp32 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FarOutput {
    pub valid: bool,
    pub tag: u16,
    pub t_hi: u32,
}

/// Runs a freshly built block at `depth` (bound and pad together) in rust-hdl's simulator for
/// `inputs.len() + flush` cycles, feeding `inputs[c]` in cycle `c` (then idle, all-zero
/// inputs) and returning what the outputs show in every cycle.
pub fn simulate_far_end(depth: usize, inputs: &[FarInput], flush: usize) -> Vec<FarOutput> {
    simulate_cycles(move || FarEnd::new(depth), inputs, flush)
}

/// Verilog of the block at `depth` (bound and pad together), top module `top`.
pub fn far_end_verilog(depth: usize) -> String {
    built_verilog(move || FarEnd::new(depth))
}
