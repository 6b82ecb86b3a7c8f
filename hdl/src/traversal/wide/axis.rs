//! One axis of a node as intervals on its grid (docs/wide-nodes.md, step 3): the offsets
//! `α − τ` lowered and raised by the margins, and the steps `r = 2^e/d` lowered and raised
//! by the reciprocal's rounding, each possibly infinite (saturated the sound way), exactly the
//! model's `Axis`. With `q ≥ 0` the plane of code `q` is `offset + q·step`.
//!
//! From the grid-scaled magnitudes of `α` (floor, ceiling), of `pad_t` (ceiling) and of the
//! reciprocal (floor and ceiling at the node's exponent): with `sat = 2^45`,
//! ```text
//! α ≥ 0:  A_lo = min(⌊α⌋, sat)             A_hi = ⌈α⌉   (+∞ from sat)
//! α < 0:  A_lo = −⌈|α|⌉   (−∞ from −sat)   A_hi = −min(⌊|α|⌋, sat)
//! margin = (min(⌈|α|⌉, sat) >> 22) + 3 + pad + (pad >> 22)        pad = ⌈|pad_t|⌉
//! offset_lo = A_lo − τ − margin            offset_hi = A_hi − τ + 255 + margin
//! L = ⌊|r|⌋ − (⌊|r|⌋ >> 23) − 1            H = ⌈|r|⌉ + (⌈|r|⌉ >> 23) + 1
//! d > 0:  step_lo = min(L, STEP_MAX)       step_hi = H   (+∞ from STEP_MAX)
//! d < 0:  step_lo = −H    (−∞ from STEP_MAX)   step_hi = −min(L, STEP_MAX)
//! ```
//! The axis bounds nothing (both offsets infinite) when the reciprocal is flushed or not
//! finite, when the grid is so fine that a flushing error could reach a quarter unit
//! (`max(inv_b, 126) + s ≥ 251`), when `α` or `pad_t` is NaN, or when `pad ≥ sat`.
//!
//! Cut points ([`AxisBounds::CUTS`]), one carry chain each:
//!   0. after `A_lo`, `A_hi + 255`, the margin's parts, `L` and `H`
//!   1. after `A − τ`, the margin, the steps' saturation
//!   2. the results, after the margins are applied and the steps negated

use rust_hdl::prelude::*;

use super::{Magnitude, Offset, Shift, Step, Word};
use crate::pipe::{placement, Pipe};
use hw_model::traversal::wide::box_test::{FRAC_BITS, OFFSET_SAT, STEP_MAX};

#[derive(LogicBlock)]
pub struct AxisBounds {
    pub clock: Signal<In, Clock>,
    pub alpha_floor: Signal<In, Magnitude>,
    pub alpha_ceil: Signal<In, Magnitude>,
    pub alpha_negative: Signal<In, Bit>,
    pub alpha_nan: Signal<In, Bit>,
    pub pad_ceil: Signal<In, Magnitude>,
    pub pad_nan: Signal<In, Bit>,
    /// The reciprocal scaled by `2^(e + s)`.
    pub step_floor: Signal<In, Magnitude>,
    pub step_ceil: Signal<In, Magnitude>,
    pub inv_dir: Signal<In, Word>,
    pub shift: Signal<In, Shift>,
    /// `τ`, below `sat` (when it is not, the node's children are all entered anyway).
    pub tau: Signal<In, Magnitude>,
    pub offset_lo: Signal<Out, Offset>,
    pub offset_hi: Signal<Out, Offset>,
    pub step_lo: Signal<Out, Step>,
    pub step_hi: Signal<Out, Step>,
    /// `offset_lo` is −∞, `offset_hi` +∞, `step_lo` −∞, `step_hi` +∞.
    pub lo_inf: Signal<Out, Bit>,
    pub hi_inf: Signal<Out, Bit>,
    pub step_lo_inf: Signal<Out, Bit>,
    pub step_hi_inf: Signal<Out, Bit>,
    /// The direction is positive: entries are the lower planes.
    pub positive: Signal<Out, Bit>,
    inv_exp: Signal<Local, Bits<8>>,
    fine_exp: Signal<Local, Bits<12>>,
    shift_wide: Signal<Local, Bits<12>>,
    /// `max(inv_b, 126) + s − 251`: non-negative when the grid is too fine.
    fine_sum: Signal<Local, Bits<12>>,
    no_bound: Signal<Local, Bit>,
    alpha_huge: Signal<Local, Bit>,
    alpha_floor_sat: Signal<Local, Offset>,
    rounding: Signal<Local, Offset>,
    /// Cut 0.
    a_lo: Pipe<Offset>,
    a_hi: Pipe<Offset>,
    rounding_part: Pipe<Offset>,
    pad_part: Pipe<Offset>,
    step_down: Pipe<Offset>,
    step_up: Pipe<Offset>,
    tau_0: Pipe<Offset>,
    lo_inf_0: Pipe<Bit>,
    hi_inf_0: Pipe<Bit>,
    positive_0: Pipe<Bit>,
    step_down_clamped: Signal<Local, Step>,
    /// Cut 1.
    from_tau_lo: Pipe<Offset>,
    from_tau_hi: Pipe<Offset>,
    margin: Pipe<Offset>,
    step_down_1: Pipe<Step>,
    step_up_1: Pipe<Step>,
    step_up_inf_1: Pipe<Bit>,
    lo_inf_1: Pipe<Bit>,
    hi_inf_1: Pipe<Bit>,
    positive_1: Pipe<Bit>,
    /// Cut 2.
    offset_lo_out: Pipe<Offset>,
    offset_hi_out: Pipe<Offset>,
    step_lo_out: Pipe<Step>,
    step_hi_out: Pipe<Step>,
    lo_inf_out: Pipe<Bit>,
    hi_inf_out: Pipe<Bit>,
    step_lo_inf_out: Pipe<Bit>,
    step_hi_inf_out: Pipe<Bit>,
    positive_out: Pipe<Bit>,
    sat: Constant<Offset>,
    rounding_sat: Constant<Offset>,
    margin_base: Constant<Offset>,
    exit_round: Constant<Offset>,
    fine_floor: Constant<Bits<12>>,
    fine_bias: Constant<Bits<12>>,
    shift_sign: Constant<Bits<12>>,
    step_max: Constant<Offset>,
    step_max_short: Constant<Step>,
    zero: Constant<Offset>,
}

impl AxisBounds {
    pub const CUTS: usize = 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            alpha_floor: Default::default(),
            alpha_ceil: Default::default(),
            alpha_negative: Default::default(),
            alpha_nan: Default::default(),
            pad_ceil: Default::default(),
            pad_nan: Default::default(),
            step_floor: Default::default(),
            step_ceil: Default::default(),
            inv_dir: Default::default(),
            shift: Default::default(),
            tau: Default::default(),
            offset_lo: Default::default(),
            offset_hi: Default::default(),
            step_lo: Default::default(),
            step_hi: Default::default(),
            lo_inf: Default::default(),
            hi_inf: Default::default(),
            step_lo_inf: Default::default(),
            step_hi_inf: Default::default(),
            positive: Default::default(),
            inv_exp: Default::default(),
            fine_exp: Default::default(),
            shift_wide: Default::default(),
            fine_sum: Default::default(),
            no_bound: Default::default(),
            alpha_huge: Default::default(),
            alpha_floor_sat: Default::default(),
            rounding: Default::default(),
            a_lo: Pipe::new(cut[0]),
            a_hi: Pipe::new(cut[0]),
            rounding_part: Pipe::new(cut[0]),
            pad_part: Pipe::new(cut[0]),
            step_down: Pipe::new(cut[0]),
            step_up: Pipe::new(cut[0]),
            tau_0: Pipe::new(cut[0]),
            lo_inf_0: Pipe::new(cut[0]),
            hi_inf_0: Pipe::new(cut[0]),
            positive_0: Pipe::new(cut[0]),
            step_down_clamped: Default::default(),
            from_tau_lo: Pipe::new(cut[1]),
            from_tau_hi: Pipe::new(cut[1]),
            margin: Pipe::new(cut[1]),
            step_down_1: Pipe::new(cut[1]),
            step_up_1: Pipe::new(cut[1]),
            step_up_inf_1: Pipe::new(cut[1]),
            lo_inf_1: Pipe::new(cut[1]),
            hi_inf_1: Pipe::new(cut[1]),
            positive_1: Pipe::new(cut[1]),
            offset_lo_out: Pipe::new(cut[2]),
            offset_hi_out: Pipe::new(cut[2]),
            step_lo_out: Pipe::new(cut[2]),
            step_hi_out: Pipe::new(cut[2]),
            lo_inf_out: Pipe::new(cut[2]),
            hi_inf_out: Pipe::new(cut[2]),
            step_lo_inf_out: Pipe::new(cut[2]),
            step_hi_inf_out: Pipe::new(cut[2]),
            positive_out: Pipe::new(cut[2]),
            sat: Constant::new((OFFSET_SAT as u64).into()),
            rounding_sat: Constant::new(((OFFSET_SAT >> 22) as u64).into()),
            // The fp32 rounding's 2 units and the padding's 1.
            margin_base: Constant::new(3.into()),
            exit_round: Constant::new(((1u64 << FRAC_BITS) - 1).into()),
            fine_floor: Constant::new(126.into()),
            // max(inv_b, 126) + s − 251 ≥ 0, modulo 2^12.
            fine_bias: Constant::new(((1u64 << 12) - 251).into()),
            shift_sign: Constant::new(0x800.into()),
            step_max: Constant::new((STEP_MAX as u64).into()),
            step_max_short: Constant::new((STEP_MAX as u64).into()),
            zero: Constant::new(0.into()),
        }
    }
}

impl Logic for AxisBounds {
    #[hdl_gen]
    fn update(&mut self) {
        self.a_lo.clock.next = self.clock.val();
        self.a_hi.clock.next = self.clock.val();
        self.rounding_part.clock.next = self.clock.val();
        self.pad_part.clock.next = self.clock.val();
        self.step_down.clock.next = self.clock.val();
        self.step_up.clock.next = self.clock.val();
        self.tau_0.clock.next = self.clock.val();
        self.lo_inf_0.clock.next = self.clock.val();
        self.hi_inf_0.clock.next = self.clock.val();
        self.positive_0.clock.next = self.clock.val();
        self.from_tau_lo.clock.next = self.clock.val();
        self.from_tau_hi.clock.next = self.clock.val();
        self.margin.clock.next = self.clock.val();
        self.step_down_1.clock.next = self.clock.val();
        self.step_up_1.clock.next = self.clock.val();
        self.step_up_inf_1.clock.next = self.clock.val();
        self.lo_inf_1.clock.next = self.clock.val();
        self.hi_inf_1.clock.next = self.clock.val();
        self.positive_1.clock.next = self.clock.val();
        self.offset_lo_out.clock.next = self.clock.val();
        self.offset_hi_out.clock.next = self.clock.val();
        self.step_lo_out.clock.next = self.clock.val();
        self.step_hi_out.clock.next = self.clock.val();
        self.lo_inf_out.clock.next = self.clock.val();
        self.hi_inf_out.clock.next = self.clock.val();
        self.step_lo_inf_out.clock.next = self.clock.val();
        self.step_hi_inf_out.clock.next = self.clock.val();
        self.positive_out.clock.next = self.clock.val();
        // Whether the axis bounds anything.
        self.inv_exp.next = self.inv_dir.val().get_bits::<8>(23);
        self.fine_exp.next = bit_cast::<12, 8>(self.inv_exp.val());
        if self.inv_exp.val() < bit_cast::<8, 12>(self.fine_floor.val()) {
            self.fine_exp.next = self.fine_floor.val();
        }
        self.shift_wide.next = bit_cast::<12, 11>(self.shift.val());
        if self.shift.val().get_bit(10) {
            self.shift_wide.next = self.shift_wide.val() | self.shift_sign.val();
        }
        self.fine_sum.next = self.fine_exp.val() + self.shift_wide.val() + self.fine_bias.val();
        self.no_bound.next = !self.inv_exp.val().any()
            | self.inv_exp.val().all()
            | !self.fine_sum.val().get_bit(11)
            | self.alpha_nan.val()
            | self.pad_nan.val()
            | (bit_cast::<48, 47>(self.pad_ceil.val()) >= self.sat.val());
        // The offsets before τ and the margins, and whether they are infinite.
        self.alpha_huge.next = bit_cast::<48, 47>(self.alpha_ceil.val()) >= self.sat.val();
        self.alpha_floor_sat.next = bit_cast::<48, 47>(self.alpha_floor.val());
        if self.alpha_floor_sat.val() >= self.sat.val() {
            self.alpha_floor_sat.next = self.sat.val();
        }
        if self.alpha_negative.val() {
            self.a_lo.d.next = self.zero.val() - bit_cast::<48, 47>(self.alpha_ceil.val());
            self.a_hi.d.next = self.exit_round.val() - self.alpha_floor_sat.val();
        } else {
            self.a_lo.d.next = self.alpha_floor_sat.val();
            self.a_hi.d.next = bit_cast::<48, 47>(self.alpha_ceil.val()) + self.exit_round.val();
        }
        self.lo_inf_0.d.next =
            self.no_bound.val() | (self.alpha_negative.val() & self.alpha_huge.val());
        self.hi_inf_0.d.next =
            self.no_bound.val() | (!self.alpha_negative.val() & self.alpha_huge.val());
        self.rounding.next = bit_cast::<48, 47>(self.alpha_ceil.val() >> 22);
        if self.alpha_huge.val() {
            self.rounding.next = self.rounding_sat.val();
        }
        self.rounding_part.d.next = self.rounding.val() + self.margin_base.val();
        self.pad_part.d.next =
            bit_cast::<48, 47>(self.pad_ceil.val()) + bit_cast::<48, 47>(self.pad_ceil.val() >> 22);
        // L = ⌊r⌋ − (⌊r⌋ >> 23) − 1 = ⌊r⌋ + ~(⌊r⌋ >> 23).
        self.step_down.d.next = bit_cast::<48, 47>(self.step_floor.val())
            + !bit_cast::<48, 47>(self.step_floor.val() >> 23);
        self.step_up.d.next = bit_cast::<48, 47>(self.step_ceil.val())
            + bit_cast::<48, 47>(self.step_ceil.val() >> 23)
            + 1;
        self.positive_0.d.next = !self.inv_dir.val().get_bit(31);
        self.tau_0.d.next = bit_cast::<48, 47>(self.tau.val());
        // Stage 1: relative to τ; the margin; the steps' saturation.
        self.from_tau_lo.d.next = self.a_lo.q.val() - self.tau_0.q.val();
        self.from_tau_hi.d.next = self.a_hi.q.val() - self.tau_0.q.val();
        self.margin.d.next = self.rounding_part.q.val() + self.pad_part.q.val();
        // min(L, STEP_MAX) (L ≥ −1); H ≥ STEP_MAX is infinite.
        self.step_down_clamped.next = bit_cast::<25, 48>(self.step_down.q.val());
        if !self.step_down.q.val().get_bit(47) & (self.step_down.q.val() >= self.step_max.val()) {
            self.step_down_clamped.next = self.step_max_short.val();
        }
        self.step_down_1.d.next = self.step_down_clamped.val();
        self.step_up_1.d.next = bit_cast::<25, 48>(self.step_up.q.val());
        self.step_up_inf_1.d.next = self.step_up.q.val() >= self.step_max.val();
        self.lo_inf_1.d.next = self.lo_inf_0.q.val();
        self.hi_inf_1.d.next = self.hi_inf_0.q.val();
        self.positive_1.d.next = self.positive_0.q.val();
        // Stage 2: the margins applied; a negative direction's steps negated and swapped.
        self.offset_lo_out.d.next = self.from_tau_lo.q.val() - self.margin.q.val();
        self.offset_hi_out.d.next = self.from_tau_hi.q.val() + self.margin.q.val();
        if self.positive_1.q.val() {
            self.step_lo_out.d.next = self.step_down_1.q.val();
            self.step_hi_out.d.next = self.step_up_1.q.val();
            self.step_lo_inf_out.d.next = false;
            self.step_hi_inf_out.d.next = self.step_up_inf_1.q.val();
        } else {
            self.step_lo_out.d.next = bit_cast::<25, 48>(self.zero.val()) - self.step_up_1.q.val();
            self.step_hi_out.d.next =
                bit_cast::<25, 48>(self.zero.val()) - self.step_down_1.q.val();
            self.step_lo_inf_out.d.next = self.step_up_inf_1.q.val();
            self.step_hi_inf_out.d.next = false;
        }
        self.lo_inf_out.d.next = self.lo_inf_1.q.val();
        self.hi_inf_out.d.next = self.hi_inf_1.q.val();
        self.positive_out.d.next = self.positive_1.q.val();
        self.offset_lo.next = self.offset_lo_out.q.val();
        self.offset_hi.next = self.offset_hi_out.q.val();
        self.step_lo.next = self.step_lo_out.q.val();
        self.step_hi.next = self.step_hi_out.q.val();
        self.lo_inf.next = self.lo_inf_out.q.val();
        self.hi_inf.next = self.hi_inf_out.q.val();
        self.step_lo_inf.next = self.step_lo_inf_out.q.val();
        self.step_hi_inf.next = self.step_hi_inf_out.q.val();
        self.positive.next = self.positive_out.q.val();
    }
}
