//! The traversal unit's ray setup in fp32: a ray's box-test words from its origin, direction
//! and bound, one ray a cycle (II = 1), bit for bit `hw_model::traversal::box_test::ray_setup`.
//!
//! The dataflow, with the cycle each value is ready (the operators' latencies at `depth`,
//! see [`SetupSchedule`]):
//! ```text
//! t_magnitude = 3·lt              magnitude = larger of 0, |o_x|, |o_y|, |o_z|, one lt and
//!                                 one mux per axis
//! t_pad       = t_magnitude + mul pad = PAD·magnitude
//! t_orig_lo   = t_pad + add       orig_lo = o + pad
//! t_orig_hi   = t_pad + sub       orig_hi = o − pad
//! t_inv       = recip             inv_dir = 1/d, ±HUGE_SLOPE (sign of d) where not finite
//! t_hi        = t_bound + far     t_hi = (bound + |bound|·PAD) + pad, a FarEnd whose bound
//!                                 enters at t_bound and whose pad joins it when ready
//! latency     = the latest of them
//! ```
//! The magnitude fold is sequential (x, then y, then z) as the model's is: a NaN component
//! loses its lt and is ignored, a tie keeps the running value (bit for bit is the spec).
//! The far end takes its pad up to [`FarSchedule::pad_slack`] cycles after its bound, so the
//! bound enters it at `t_bound = t_pad − min(t_pad, pad_slack)` and `|bound|·PAD` overlaps the
//! fold. Every other path (the origin to the add and sub, d's sign to the slope's mux, the
//! bound, valid and the tag, and each output to the latest) is padded with flip-flop delay
//! lines; valid and the tag ride through the far end with the bound.
//!
//! Latency at depth 0..=5: 0, 5, 7, 9, 11, 13 (5 = [`max_depth`]). yosys xc7 (Yosys 0.23,
//! `cargo test --release -p hdl --test integration -- --ignored --nocapture ray_setup::ray_setup_resources`):
//! depth 1: 8598 LUT, 1137 FF, 148 SRL, 19 DSP48E1, logic depth 37; depth 5: 5246 LUT,
//! 2673 FF, 533 SRL, 19 DSP48E1, logic depth 8.
//!
//! Per-axis things are arrays indexed by the axis; the magnitude fold's running value before
//! step k is `running[k]` (k = 3: the magnitude).

use hw_model::traversal::box_test::{RaySetup, HUGE_SLOPE, PAD};
use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Add, Lt, Mul, Recip, Sub};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::operator::Op;
use crate::traversal::box_test::Tag;
use crate::traversal::far_end::{self, FarEnd, FarSchedule};

type Word = Bits<32>;

/// When each value of the ray setup is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SetupSchedule {
    /// Registers per fp32 `Lt`, `Mul`, `Add`, `Sub`, `Recip`: `min(depth, max_stages)`.
    pub lt: usize,
    pub mul: usize,
    pub add: usize,
    pub sub: usize,
    pub recip: usize,
    /// The larger of 0 and the three |o|.
    pub t_magnitude: usize,
    /// PAD·magnitude.
    pub t_pad: usize,
    /// o + pad, o − pad.
    pub t_orig_lo: usize,
    pub t_orig_hi: usize,
    /// The slopes (1/d or the huge slope).
    pub t_inv: usize,
    /// The far end's timing, and the cycle the bound (with valid and the tag) enters it.
    pub far: FarSchedule,
    pub t_bound: usize,
    /// t_hi.
    pub t_hi: usize,
    /// Inputs to outputs.
    pub latency: usize,
}

impl SetupSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let (lt, mul, add, sub, recip) = (ops.lt, ops.mul, ops.add, ops.sub, ops.recip);
        let t_magnitude = 3 * lt;
        let t_pad = t_magnitude + mul;
        let t_orig_lo = t_pad + add;
        let t_orig_hi = t_pad + sub;
        let t_inv = recip;
        let far = far_end::schedule(depth);
        let t_bound = t_pad - t_pad.min(far.pad_slack());
        let t_hi = t_bound + far.latency;
        let latency = [t_pad, t_orig_lo, t_orig_hi, t_inv, t_hi]
            .into_iter()
            .max()
            .unwrap_or(0);
        SetupSchedule {
            lt,
            mul,
            add,
            sub,
            recip,
            t_magnitude,
            t_pad,
            t_orig_lo,
            t_orig_hi,
            t_inv,
            far,
            t_bound,
            t_hi,
            latency,
        }
    }

    /// |o_k| to fold step `k` (the steps before it).
    pub fn axis_to_step(&self, k: usize) -> usize {
        k * self.lt
    }

    /// The origin (an input) to the add and sub.
    pub fn orig_to_pad(&self) -> usize {
        self.t_pad
    }

    /// d's sign (an input) to the slope's mux.
    pub fn sign_to_inv(&self) -> usize {
        self.t_inv
    }

    /// Cycles `pad` reaches the far end after its bound.
    pub fn pad_after_bound(&self) -> usize {
        self.t_pad - self.t_bound
    }

    /// A value ready at cycle `t` to the outputs.
    pub fn to_out(&self, t: usize) -> usize {
        self.latency - t
    }
}

/// The block's timing at `depth`.
pub fn schedule(depth: usize) -> SetupSchedule {
    SetupSchedule::new(depth)
}

/// Cycles from a ray at the inputs to its setup at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    schedule(depth).latency
}

/// The depth at which every operator of the block has all its pipeline registers.
pub fn max_depth() -> usize {
    [Op::Add, Op::Sub, Op::Mul, Op::Recip, Op::Lt]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0)
}

/// The ray setup of one ray a cycle: `orig`, `dir`, `bound` (fp32 words), `valid_in` and
/// `tag_in` in, the ray's [`RaySetup`] words out exactly [`latency`]`(depth)` cycles later
/// with `valid_out` and `tag_out`. `depth` is the pipeline registers per operator, each
/// saturating at its own `max_stages()` (as in the MT lane and the box test). No reset: the
/// valid line holds the flip-flops' power-on zeros until the first ray passes.
///
/// Named `RaySetupUnit` so as not to clash with the model's [`RaySetup`] (its result).
#[derive(LogicBlock)]
pub struct RaySetupUnit {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Tag>,
    pub orig: [Signal<In, Word>; 3],
    pub dir: [Signal<In, Word>; 3],
    pub bound: Signal<In, Word>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Tag>,
    pub orig_lo: [Signal<Out, Word>; 3],
    pub orig_hi: [Signal<Out, Word>; 3],
    pub inv_dir: [Signal<Out, Word>; 3],
    pub pad: Signal<Out, Word>,
    pub t_hi: Signal<Out, Word>,
    /// Per fold step k: |o_k| waiting for its step, the step's lt(running, |o_k|) …
    abs_at_step: [Delay<Word>; 3],
    magnitude_step: [Lt; 3],
    /// … and both candidates waiting for it, to be selected.
    abs_at_keep: [Delay<Word>; 3],
    running_at_keep: [Delay<Word>; 3],
    /// The running magnitude before step k (k = 3: the magnitude).
    running: [Signal<Local, Word>; 4],
    scale: Mul,
    orig_at_pad: [Delay<Word>; 3],
    lo: [Add; 3],
    hi: [Sub; 3],
    recip: [Recip; 3],
    sign_at_inv: [Delay<Bit>; 3],
    slope: [Signal<Local, Word>; 3],
    bound_at_far: Delay<Word>,
    valid_at_far: Delay<Bit>,
    tag_at_far: Delay<Tag>,
    far: FarEnd,
    orig_lo_at_out: [Delay<Word>; 3],
    orig_hi_at_out: [Delay<Word>; 3],
    inv_at_out: [Delay<Word>; 3],
    pad_at_out: Delay<Word>,
    t_hi_at_out: Delay<Word>,
    valid_at_out: Delay<Bit>,
    tag_at_out: Delay<Tag>,
    zero: Constant<Word>,
    abs_mask: Constant<Word>,
    exp_mask: Constant<Word>,
    pad_factor: Constant<Word>,
    huge: Constant<Word>,
    minus_huge: Constant<Word>,
}

impl RaySetupUnit {
    pub fn new(depth: usize) -> Self {
        let s = schedule(depth);
        let word = |x: f32| Word::from(u64::from(x.to_bits()));
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            orig: Default::default(),
            dir: Default::default(),
            bound: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            orig_lo: Default::default(),
            orig_hi: Default::default(),
            inv_dir: Default::default(),
            pad: Default::default(),
            t_hi: Default::default(),
            abs_at_step: std::array::from_fn(|k| Delay::new(s.axis_to_step(k))),
            magnitude_step: std::array::from_fn(|_| Lt::new(s.lt)),
            abs_at_keep: Delay::lines(s.lt),
            running_at_keep: Delay::lines(s.lt),
            running: Default::default(),
            scale: Mul::new(s.mul),
            orig_at_pad: Delay::lines(s.orig_to_pad()),
            lo: std::array::from_fn(|_| Add::new(s.add)),
            hi: std::array::from_fn(|_| Sub::new(s.sub)),
            recip: std::array::from_fn(|_| Recip::new(s.recip)),
            sign_at_inv: Delay::lines(s.sign_to_inv()),
            slope: Default::default(),
            bound_at_far: Delay::new(s.t_bound),
            valid_at_far: Delay::new(s.t_bound),
            tag_at_far: Delay::new(s.t_bound),
            far: FarEnd::with_late_pad(depth, s.pad_after_bound()),
            orig_lo_at_out: Delay::lines(s.to_out(s.t_orig_lo)),
            orig_hi_at_out: Delay::lines(s.to_out(s.t_orig_hi)),
            inv_at_out: Delay::lines(s.to_out(s.t_inv)),
            pad_at_out: Delay::new(s.to_out(s.t_pad)),
            t_hi_at_out: Delay::new(s.to_out(s.t_hi)),
            valid_at_out: Delay::new(s.to_out(s.t_hi)),
            tag_at_out: Delay::new(s.to_out(s.t_hi)),
            zero: Constant::new(0.into()),
            abs_mask: Constant::new(0x7FFF_FFFFu64.into()),
            exp_mask: Constant::new(0x7F80_0000u64.into()),
            pad_factor: Constant::new(word(PAD)),
            huge: Constant::new(word(HUGE_SLOPE)),
            minus_huge: Constant::new(word(-HUGE_SLOPE)),
        }
    }

    /// Cycles from a ray at the inputs to its setup at the outputs ([`latency`]).
    pub fn latency(depth: usize) -> usize {
        latency(depth)
    }
}

impl Stepped for RaySetupUnit {
    type Input = SetupInput;
    type Output = SetupOutput;

    fn idle() -> SetupInput {
        SetupInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, x: &Self::Input) {
        let word = |x: f32| Word::from(u64::from(x.to_bits()));
        self.valid_in.next = x.valid;
        self.tag_in.next = u64::from(x.tag).into();
        for a in 0..3 {
            self.orig[a].next = word(x.orig[a]);
            self.dir[a].next = word(x.dir[a]);
        }
        self.bound.next = word(x.bound);
    }

    fn observe(&self) -> Self::Output {
        let word = |s: &Signal<Out, Word>| s.val().to_u64() as u32;
        SetupOutput {
            valid: self.valid_out.val(),
            tag: self.tag_out.val().to_u64() as u16,
            orig_lo: std::array::from_fn(|a| word(&self.orig_lo[a])),
            orig_hi: std::array::from_fn(|a| word(&self.orig_hi[a])),
            inv_dir: std::array::from_fn(|a| word(&self.inv_dir[a])),
            pad: word(&self.pad),
            t_hi: word(&self.t_hi),
        }
    }
}

impl Logic for RaySetupUnit {
    #[hdl_gen]
    fn update(&mut self) {
        // magnitude: from +0, step k keeps |o_k| when lt(running, |o_k|); a NaN loses its lt
        // and a tie keeps the running value, as in the model.
        self.running[0].next = self.zero.val();
        for k in 0..3 {
            clock!(
                self,
                clock,
                abs_at_step[k],
                magnitude_step[k],
                abs_at_keep[k],
                running_at_keep[k]
            );
            self.abs_at_step[k].d.next = self.orig[k].val() & self.abs_mask.val();
            self.magnitude_step[k].a.next = self.running[k].val();
            self.magnitude_step[k].b.next = self.abs_at_step[k].q.val();
            self.abs_at_keep[k].d.next = self.abs_at_step[k].q.val();
            self.running_at_keep[k].d.next = self.running[k].val();
            if self.magnitude_step[k].y.val() {
                self.running[k + 1].next = self.abs_at_keep[k].q.val();
            } else {
                self.running[k + 1].next = self.running_at_keep[k].q.val();
            }
        }
        // pad = PAD·magnitude; orig_lo = o + pad, orig_hi = o − pad.
        clock!(self, clock, scale);
        self.scale.a.next = self.pad_factor.val();
        self.scale.b.next = self.running[3].val();
        for a in 0..3 {
            clock!(
                self,
                clock,
                orig_at_pad[a],
                lo[a],
                hi[a],
                orig_lo_at_out[a],
                orig_hi_at_out[a]
            );
            self.orig_at_pad[a].d.next = self.orig[a].val();
            self.lo[a].a.next = self.orig_at_pad[a].q.val();
            self.lo[a].b.next = self.scale.y.val();
            self.hi[a].a.next = self.orig_at_pad[a].q.val();
            self.hi[a].b.next = self.scale.y.val();
            self.orig_lo_at_out[a].d.next = self.lo[a].y.val();
            self.orig_hi_at_out[a].d.next = self.hi[a].y.val();
            self.orig_lo[a].next = self.orig_lo_at_out[a].q.val();
            self.orig_hi[a].next = self.orig_hi_at_out[a].q.val();
        }
        // inv_dir = 1/d, or the huge slope with d's sign where that has an all-ones exponent
        // (±Inf from ±0 or a flushed subnormal, NaN from a NaN).
        for a in 0..3 {
            clock!(self, clock, recip[a], sign_at_inv[a], inv_at_out[a]);
            self.recip[a].a.next = self.dir[a].val();
            self.sign_at_inv[a].d.next = self.dir[a].val().get_bit(31);
            if (self.recip[a].y.val() & self.exp_mask.val()) != self.exp_mask.val() {
                self.slope[a].next = self.recip[a].y.val();
            } else if self.sign_at_inv[a].q.val() {
                self.slope[a].next = self.minus_huge.val();
            } else {
                self.slope[a].next = self.huge.val();
            }
            self.inv_at_out[a].d.next = self.slope[a].val();
            self.inv_dir[a].next = self.inv_at_out[a].q.val();
        }
        clock!(self, clock, pad_at_out);
        self.pad_at_out.d.next = self.scale.y.val();
        self.pad.next = self.pad_at_out.q.val();
        // t_hi: the bound (with valid and the tag) enters the far end at t_bound, pad joins
        // it at t_pad.
        clock!(
            self,
            clock,
            bound_at_far,
            valid_at_far,
            tag_at_far,
            far,
            t_hi_at_out,
            valid_at_out,
            tag_at_out
        );
        self.bound_at_far.d.next = self.bound.val();
        self.valid_at_far.d.next = self.valid_in.val();
        self.tag_at_far.d.next = self.tag_in.val();
        self.far.bound.next = self.bound_at_far.q.val();
        self.far.valid_in.next = self.valid_at_far.q.val();
        self.far.tag_in.next = self.tag_at_far.q.val();
        self.far.pad.next = self.scale.y.val();
        self.t_hi_at_out.d.next = self.far.t_hi.val();
        self.valid_at_out.d.next = self.far.valid_out.val();
        self.tag_at_out.d.next = self.far.tag_out.val();
        self.t_hi.next = self.t_hi_at_out.q.val();
        self.valid_out.next = self.valid_at_out.q.val();
        self.tag_out.next = self.tag_at_out.q.val();
    }
}

/// One ray at the inputs: valid, tag, origin, direction and bound.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SetupInput {
    pub valid: bool,
    pub tag: u16,
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    pub bound: f32,
}

/// What the block's outputs show in one cycle (fp32 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SetupOutput {
    pub valid: bool,
    pub tag: u16,
    pub orig_lo: [u32; 3],
    pub orig_hi: [u32; 3],
    pub inv_dir: [u32; 3],
    pub pad: u32,
    pub t_hi: u32,
}

impl SetupOutput {
    pub fn result(&self) -> RaySetup {
        let f = |w: [u32; 3]| w.map(f32::from_bits);
        RaySetup {
            orig_lo: f(self.orig_lo),
            orig_hi: f(self.orig_hi),
            inv_dir: f(self.inv_dir),
            pad: f32::from_bits(self.pad),
            t_hi: f32::from_bits(self.t_hi),
        }
    }

    /// Whether the setup is `want` bit for bit (every word compared as bits, not as floats).
    pub fn same_bits(&self, want: &RaySetup) -> bool {
        let b = |w: [f32; 3]| w.map(f32::to_bits);
        self.orig_lo == b(want.orig_lo)
            && self.orig_hi == b(want.orig_hi)
            && self.inv_dir == b(want.inv_dir)
            && self.pad == want.pad.to_bits()
            && self.t_hi == want.t_hi.to_bits()
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator for `inputs.len() + flush`
/// cycles, feeding `inputs[c]` in cycle `c` (then idle, all-zero inputs) and returning what
/// the outputs show in every cycle.
pub fn simulate_ray_setup(depth: usize, inputs: &[SetupInput], flush: usize) -> Vec<SetupOutput> {
    simulate_cycles(move || RaySetupUnit::new(depth), inputs, flush)
}

/// Verilog of the block at `depth`, top module `top` (built on a thread with room for it).
pub fn ray_setup_verilog(depth: usize) -> String {
    built_verilog(move || RaySetupUnit::new(depth))
}
