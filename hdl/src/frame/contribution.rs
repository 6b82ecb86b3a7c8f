//! A contribution in fixed point, one a cycle: `hw_model::frame::accumulate::Contribution::of`
//! bit for bit, the values the accumulator ([`super::accumulate`]) sums,
//!
//! ```text
//! t_steps = mul                       v = fl(255·c)        per channel, fp32
//! latency = t_steps + from_f32        v in CONTRIBUTION    fx<28,12>, truncated, saturated
//! ```
//!
//! with the valid bit carried beside the arithmetic by a delay line, so the block takes a
//! colour every cycle (II = 1) and gives its contribution exactly [`latency`]`(depth)` cycles
//! later. `depth` is the pipeline registers per operator, each saturating at its own
//! `max_stages()` (as in [`super::raygen`]).
//!
//! The two steps are the toolkit's operators: fp32's multiplier (a constant word 255.0 on its
//! second input) and the fixed-point conversion `FixedFromF32` in the format
//! [`CONTRIBUTION`], whose truncation and saturation are the model's (NaN → 0, ±Inf and
//! |v| ≥ 2048 to the format's extremes, subnormals and zeros to 0). Why the multiply comes
//! before the conversion and why truncation: `hw_model::frame::accumulate`.

use hw_model::fp32::Fp32;
use hw_model::frame::accumulate::{Contribution, CONTRIBUTION};
use hw_model::{Format, Overflow, Quant};
use rust_hdl::prelude::*;

use crate::fixed::FixedFromF32;
use crate::formats::fp32::{self, Mul};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::operator::Op;
use crate::widths::FixedWidths;

type Word = Bits<32>;

/// [`CONTRIBUTION`]'s integer bits (sign included), and whether it rounds and saturates.
const FORMAT: (usize, bool, bool) = match CONTRIBUTION {
    Format::Fixed {
        int,
        quant,
        overflow,
        ..
    } => (
        int as usize,
        matches!(quant, Quant::Rnd),
        matches!(overflow, Overflow::Sat),
    ),
    Format::Float { .. } => panic!("a contribution is fixed point"),
};
/// The conversion's widths (`crate::widths`).
const WIDTHS: FixedWidths = FixedWidths::of(CONTRIBUTION.width() as usize, FORMAT.0);
/// Bits of a contribution per channel, two's complement.
pub const CONTRIBUTION_BITS: usize = WIDTHS.word;

/// fp32 → [`CONTRIBUTION`].
pub(crate) type ToFixed = FixedFromF32<
    { WIDTHS.word },
    { WIDTHS.frac },
    { WIDTHS.from_f32_aligned },
    { WIDTHS.from_f32_magnitude },
    { FORMAT.1 },
    { FORMAT.2 },
>;

/// When each value is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContributionSchedule {
    /// The multiplier's registers.
    pub mul: usize,
    /// The conversion's registers.
    pub from_f32: usize,
    /// v = fl(255·c).
    pub t_steps: usize,
    /// The contribution (input to output).
    pub latency: usize,
}

impl ContributionSchedule {
    pub fn new(depth: usize) -> Self {
        let mul = depth.min(fp32::max_stages(Op::Mul));
        let from_f32 = depth.min(ToFixed::max_stages());
        let t_steps = mul;
        ContributionSchedule {
            mul,
            from_f32,
            t_steps,
            latency: t_steps + from_f32,
        }
    }
}

/// Cycles from a colour at the inputs to its contribution at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    ContributionSchedule::new(depth).latency
}

/// The depth from which both operators have all their registers (a larger depth builds the
/// same block).
pub fn full_depth() -> usize {
    fp32::max_stages(Op::Mul).max(ToFixed::max_stages())
}

/// A colour (fp32 words) in when `valid`; its contribution out [`latency`]`(depth)` cycles
/// later, with `contribution_valid`.
#[derive(LogicBlock)]
pub struct ToContribution {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    pub c: [Signal<In, Word>; 3],
    pub contribution_valid: Signal<Out, Bit>,
    /// Per channel, two's complement in units of 2^-16 of an 8-bit step.
    pub contribution: [Signal<Out, Bits<CONTRIBUTION_BITS>>; 3],
    steps: [Mul; 3],
    fixed: [ToFixed; 3],
    valid_at_out: Delay<Bit>,
    /// 255.0 in fp32.
    step_count: Constant<Word>,
}

impl ToContribution {
    pub fn new(depth: usize) -> Self {
        let s = ContributionSchedule::new(depth);
        Self {
            clock: Default::default(),
            valid: Default::default(),
            c: Default::default(),
            contribution_valid: Default::default(),
            contribution: Default::default(),
            steps: std::array::from_fn(|_| Mul::new(s.mul)),
            fixed: std::array::from_fn(|_| ToFixed::new(s.from_f32)),
            valid_at_out: Delay::new(s.latency),
            step_count: Constant::new(u64::from(Fp32::new(255.0).bits()).into()),
        }
    }
}

impl Logic for ToContribution {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            clock!(self, clock, steps[k], fixed[k]);
            self.steps[k].a.next = self.c[k].val();
            self.steps[k].b.next = self.step_count.val();
            self.fixed[k].a.next = self.steps[k].y.val();
            self.contribution[k].next = self.fixed[k].y.val();
        }
        clock!(self, clock, valid_at_out);
        self.valid_at_out.d.next = self.valid.val();
        self.contribution_valid.next = self.valid_at_out.q.val();
    }
}

impl Stepped for ToContribution {
    /// A colour's fp32 words, if valid.
    type Input = Option<[u32; 3]>;
    /// The contribution shown, if valid.
    type Output = Option<Contribution>;

    fn idle() -> Option<[u32; 3]> {
        None
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &Option<[u32; 3]>) {
        self.valid.next = input.is_some();
        for (port, &word) in self.c.iter_mut().zip(&input.unwrap_or_default()) {
            port.next = Word::from(u64::from(word));
        }
    }

    fn observe(&self) -> Option<Contribution> {
        let unused = 32 - CONTRIBUTION_BITS;
        self.contribution_valid.val().then(|| {
            Contribution(std::array::from_fn(|k| {
                // Sign-extended from the format's top bit.
                ((self.contribution[k].val().to_u64() as u32) << unused) as i32 >> unused
            }))
        })
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator, one input a cycle, and
/// returns what the outputs show in every cycle (`inputs.len() + flush` of them).
pub fn simulate_contribution(
    depth: usize,
    inputs: &[Option<[u32; 3]>],
    flush: usize,
) -> Vec<Option<Contribution>> {
    simulate_cycles(move || ToContribution::new(depth), inputs, flush)
}

/// Verilog of the block at `depth`, top module `top`.
pub fn contribution_verilog(depth: usize) -> String {
    built_verilog(move || ToContribution::new(depth))
}
