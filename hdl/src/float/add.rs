//! Float addition and subtraction `y = a ± b` (RNE, FTZ, see the SPEC in `hw_model::format`).
//!
//! The operand of larger magnitude is x, the other y; y's significand (with 3 extra low
//! bits: guard, round and a sticky bit that collects everything shifted out) is aligned to
//! x, added or subtracted, normalized by the position of the leading one and rounded.
//!
//! The leading zeros of a difference are anticipated from the two addends beside the add
//! (a leading-zero anticipator, LZA: Schmookler and Nowka's indicator string, whose leading
//! one is at the sum's or one place above it), so counting them costs no stage of its own; a
//! one-place correction after the normalizing shift fixes the anticipation's error.
//!
//! The stages are cut so that no register-to-register path holds two wide carry chains or a
//! carry chain and a wide shifter:
//!   0. after comparing: exponents (both differences, clamped to the alignment range) and
//!      fractions are compared separately, an exact cancellation is detected there, and
//!      each significand's trailing zeros are counted (for the sticky bit)
//!   1. after ordering and aligning y (shifter and sticky comparison side by side); y is already
//!      inverted for a subtraction and x carries the +1, so the next stage is one adder
//!   2. after the add and, beside it, the anticipated leading-zero count
//!   3. after the normalizing shift, its one-place correction and the exponent adjust
//!   4. the result, after rounding and packing
//!
//! Registers are spread over them by `pipe::placement`; max_stages() = 5.

use rust_hdl::prelude::*;

use super::leading_zeros::LeadingZeros;
use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// E, M: the format; W = 1+E+M; S = M+1; X = exponent width (≥ E+2);
/// A = S+3 (aligned significand); A1 = A+1 (sum) ([`crate::widths::FloatWidths`]); SUB:
/// subtract instead of add.
#[derive(LogicBlock)]
pub struct FloatAdd<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const X: usize,
    const A: usize,
    const A1: usize,
    const SUB: bool,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    unpack_a: Unpack<E, M, W, S>,
    unpack_b: Unpack<E, M, W, S>,
    sign_b: Signal<Local, Bit>,
    diff_ab: Signal<Local, Bits<E>>,
    diff_ba: Signal<Local, Bits<E>>,
    compared_sig_a: Pipe<Bits<S>>,
    compared_sig_b: Pipe<Bits<S>>,
    compared_exp_a: Pipe<Bits<E>>,
    compared_exp_b: Pipe<Bits<E>>,
    compared_shift_ab: Pipe<Bits<5>>,
    compared_shift_ba: Pipe<Bits<5>>,
    compared_exp_greater: Pipe<Bit>,
    compared_exp_equal: Pipe<Bit>,
    compared_frac_not_less: Pipe<Bit>,
    compared_sign_a: Pipe<Bit>,
    compared_sign_b: Pipe<Bit>,
    compared_nan: Pipe<Bit>,
    compared_inf: Pipe<Bit>,
    compared_cancel: Pipe<Bit>,
    reversed_a: Signal<Local, Bits<32>>,
    reversed_b: Signal<Local, Bits<32>>,
    trailing_a: LeadingZeros,
    trailing_b: LeadingZeros,
    compared_zeros_a: Pipe<Bits<5>>,
    compared_zeros_b: Pipe<Bits<5>>,
    a_larger: Signal<Local, Bit>,
    subtract_now: Signal<Local, Bit>,
    x_sig: Signal<Local, Bits<S>>,
    y_sig: Signal<Local, Bits<S>>,
    shift: Signal<Local, Bits<5>>,
    category: Signal<Local, ResultClass>,
    y_wide: Signal<Local, Bits<A>>,
    y_shifted: Signal<Local, Bits<A>>,
    y_sticky: Signal<Local, Bit>,
    y_aligned: Signal<Local, Bits<A>>,
    aligned_x: Pipe<Bits<A>>,
    aligned_y: Pipe<Bits<A>>,
    aligned_exp: Pipe<Bits<E>>,
    aligned_subtract: Pipe<Bit>,
    aligned_category: Pipe<ResultClass>,
    lza_t: Signal<Local, Bits<A>>,
    lza_g: Signal<Local, Bits<A>>,
    lza_z: Signal<Local, Bits<A>>,
    indicator: Signal<Local, Bits<A>>,
    anticipated: LeadingZeros,
    summed: Pipe<Bits<A1>>,
    summed_zeros: Pipe<Bits<8>>,
    summed_exp: Pipe<Bits<X>>,
    summed_exp_below: Pipe<Bits<X>>,
    summed_category: Pipe<ResultClass>,
    shifted: Signal<Local, Bits<A1>>,
    normalized: Signal<Local, Bits<A1>>,
    exp_select: Signal<Local, Bits<X>>,
    normal_sig: Pipe<Bits<S>>,
    normal_round: Pipe<Bit>,
    normal_sticky: Pipe<Bit>,
    normal_exp: Pipe<Bits<X>>,
    normal_category: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, X>,
    result: Pipe<Bits<W>>,
    subtract: Constant<Bit>,
    frac_mask: Constant<Bits<W>>,
    extra_bits: Constant<Bits<8>>,
    align_limit: Constant<Bits<E>>,
    all_zeros: Constant<Bits<5>>,
    reversed_bits: Vec<Constant<Bits<32>>>,
    carry_in: Constant<Bits<A>>,
    lza_top: Constant<Bits<A>>,
    left_align: Constant<Bits<8>>,
    exp_one: Constant<Bits<X>>,
    exp_all_ones: Constant<Bits<X>>,
    sig_shift: Constant<Bits<8>>,
    top_bit: Constant<Bits<A1>>,
    round_bit: Constant<Bits<A1>>,
    sticky_bits: Constant<Bits<A1>>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const A: usize,
        const A1: usize,
        const SUB: bool,
    > FloatAdd<E, M, W, S, X, A, A1, SUB>
{
    pub const CUTS: usize = 5;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            A == S + 3 && A1 == A + 1 && X >= E + 2,
            "FloatAdd: inconsistent widths"
        );
        // The alignment shift (at most A) is held in 5 bits: a narrow shift is a shallow shifter.
        assert!(
            (A as u64) < (1 << E) && A < 32,
            "FloatAdd: the format is too narrow or too wide"
        );
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            unpack_a: Default::default(),
            unpack_b: Default::default(),
            sign_b: Default::default(),
            diff_ab: Default::default(),
            diff_ba: Default::default(),
            compared_sig_a: Pipe::new(cut[0]),
            compared_sig_b: Pipe::new(cut[0]),
            compared_exp_a: Pipe::new(cut[0]),
            compared_exp_b: Pipe::new(cut[0]),
            compared_shift_ab: Pipe::new(cut[0]),
            compared_shift_ba: Pipe::new(cut[0]),
            compared_exp_greater: Pipe::new(cut[0]),
            compared_exp_equal: Pipe::new(cut[0]),
            compared_frac_not_less: Pipe::new(cut[0]),
            compared_sign_a: Pipe::new(cut[0]),
            compared_sign_b: Pipe::new(cut[0]),
            compared_nan: Pipe::new(cut[0]),
            compared_inf: Pipe::new(cut[0]),
            compared_cancel: Pipe::new(cut[0]),
            reversed_a: Default::default(),
            reversed_b: Default::default(),
            trailing_a: Default::default(),
            trailing_b: Default::default(),
            compared_zeros_a: Pipe::new(cut[0]),
            compared_zeros_b: Pipe::new(cut[0]),
            a_larger: Default::default(),
            subtract_now: Default::default(),
            x_sig: Default::default(),
            y_sig: Default::default(),
            shift: Default::default(),
            category: Default::default(),
            y_wide: Default::default(),
            y_shifted: Default::default(),
            y_sticky: Default::default(),
            y_aligned: Default::default(),
            aligned_x: Pipe::new(cut[1]),
            aligned_y: Pipe::new(cut[1]),
            aligned_exp: Pipe::new(cut[1]),
            aligned_subtract: Pipe::new(cut[1]),
            aligned_category: Pipe::new(cut[1]),
            lza_t: Default::default(),
            lza_g: Default::default(),
            lza_z: Default::default(),
            indicator: Default::default(),
            anticipated: Default::default(),
            summed: Pipe::new(cut[2]),
            summed_zeros: Pipe::new(cut[2]),
            summed_exp: Pipe::new(cut[2]),
            summed_exp_below: Pipe::new(cut[2]),
            summed_category: Pipe::new(cut[2]),
            shifted: Default::default(),
            normalized: Default::default(),
            exp_select: Default::default(),
            normal_sig: Pipe::new(cut[3]),
            normal_round: Pipe::new(cut[3]),
            normal_sticky: Pipe::new(cut[3]),
            normal_exp: Pipe::new(cut[3]),
            normal_category: Pipe::new(cut[3]),
            rounder: Default::default(),
            result: Pipe::new(cut[4]),
            subtract: Constant::new(SUB),
            frac_mask: Constant::new((Bits::<W>::from(1) << M as u64) - 1),
            extra_bits: Constant::new(3.into()),
            align_limit: Constant::new((A as u64).into()),
            all_zeros: Constant::new(Bits::<5>::mask()),
            // Significand bit i is bit i+3 of the aligned frame, reversed: bit 28-i.
            reversed_bits: (0..S)
                .map(|i| Constant::new(Bits::<32>::from(1) << (28 - i) as u64))
                .collect(),
            carry_in: Constant::new(1.into()),
            lza_top: Constant::new(Bits::<A>::from(1) << (A - 1) as u64),
            // The indicator's top bit goes to bit 30: the A1-bit frame's count.
            left_align: Constant::new(((31 - A) as u64).into()),
            exp_one: Constant::new(1.into()),
            exp_all_ones: Constant::new(Bits::<X>::mask()),
            sig_shift: Constant::new(((A1 - S) as u64).into()),
            top_bit: Constant::new(Bits::<A1>::from(1) << A as u64),
            round_bit: Constant::new(Bits::<A1>::from(1) << (A1 - S - 1) as u64),
            sticky_bits: Constant::new((Bits::<A1>::from(1) << (A1 - S - 1) as u64) - 1),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const A: usize,
        const A1: usize,
        const SUB: bool,
    > Logic for FloatAdd<E, M, W, S, X, A, A1, SUB>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack_a.x.next = self.a.val();
        self.unpack_b.x.next = self.b.val();
        self.sign_b.next = self.unpack_b.sign.val() ^ self.subtract.val();
        // Cut 0. |a| ≥ |b| ⇔ exp_a > exp_b, or equal exponents and frac_a ≥ frac_b.
        clock!(
            self,
            clock,
            compared_sig_a,
            compared_sig_b,
            compared_exp_a,
            compared_exp_b,
            compared_shift_ab,
            compared_shift_ba,
            compared_exp_greater,
            compared_exp_equal,
            compared_frac_not_less,
            compared_sign_a,
            compared_sign_b,
            compared_nan,
            compared_inf,
            compared_cancel
        );
        self.compared_sig_a.d.next = self.unpack_a.sig.val();
        self.compared_sig_b.d.next = self.unpack_b.sig.val();
        self.compared_exp_a.d.next = self.unpack_a.exp.val();
        self.compared_exp_b.d.next = self.unpack_b.exp.val();
        // The alignment shift for either order; only the one of the larger operand is used.
        self.diff_ab.next = self.unpack_a.exp.val() - self.unpack_b.exp.val();
        self.diff_ba.next = self.unpack_b.exp.val() - self.unpack_a.exp.val();
        // A zero (or flushed subnormal) y is shifted out entirely, its trailing zeros count as
        // all (no sticky bit): y aligns to 0 without a mask on its significand.
        self.compared_shift_ab.d.next = bit_cast::<5, E>(self.diff_ab.val());
        if (self.diff_ab.val() > self.align_limit.val()) | self.unpack_b.zero.val() {
            self.compared_shift_ab.d.next = bit_cast::<5, E>(self.align_limit.val());
        }
        self.compared_shift_ba.d.next = bit_cast::<5, E>(self.diff_ba.val());
        if (self.diff_ba.val() > self.align_limit.val()) | self.unpack_a.zero.val() {
            self.compared_shift_ba.d.next = bit_cast::<5, E>(self.align_limit.val());
        }
        self.compared_exp_greater.d.next = self.unpack_a.exp.val() > self.unpack_b.exp.val();
        self.compared_exp_equal.d.next = self.unpack_a.exp.val() == self.unpack_b.exp.val();
        self.compared_frac_not_less.d.next =
            (self.a.val() & self.frac_mask.val()) >= (self.b.val() & self.frac_mask.val());
        self.compared_sign_a.d.next = self.unpack_a.sign.val();
        self.compared_sign_b.d.next = self.sign_b.val();
        self.compared_nan.d.next = self.unpack_a.nan.val()
            | self.unpack_b.nan.val()
            | (self.unpack_a.inf.val()
                & self.unpack_b.inf.val()
                & (self.unpack_a.sign.val() ^ self.sign_b.val()));
        self.compared_inf.d.next = self.unpack_a.inf.val() | self.unpack_b.inf.val();
        // Trailing zeros of each significand in the aligned frame (3 extra low bits), as the
        // leading zeros of the bit-reversed frame (an all-zero significand counts 31).
        self.reversed_a.next = 0.into();
        self.reversed_b.next = 0.into();
        for i in 0..S {
            if self.unpack_a.sig.val().get_bit(i) {
                self.reversed_a.next = self.reversed_a.val() | self.reversed_bits[i].val();
            }
            if self.unpack_b.sig.val().get_bit(i) {
                self.reversed_b.next = self.reversed_b.val() | self.reversed_bits[i].val();
            }
        }
        self.trailing_a.x.next = self.reversed_a.val();
        self.trailing_b.x.next = self.reversed_b.val();
        clock!(self, clock, compared_zeros_a, compared_zeros_b);
        self.compared_zeros_a.d.next = bit_cast::<5, 8>(self.trailing_a.count.val());
        if self.unpack_a.zero.val() {
            self.compared_zeros_a.d.next = self.all_zeros.val();
        }
        self.compared_zeros_b.d.next = bit_cast::<5, 8>(self.trailing_b.count.val());
        if self.unpack_b.zero.val() {
            self.compared_zeros_b.d.next = self.all_zeros.val();
        }
        // The sum is exactly 0 when both operands are zeros or equal magnitudes cancel.
        self.compared_cancel.d.next = (self.unpack_a.zero.val() & self.unpack_b.zero.val())
            | ((self.unpack_a.sign.val() ^ self.sign_b.val())
                & (self.unpack_a.exp.val() == self.unpack_b.exp.val())
                & ((self.a.val() & self.frac_mask.val()) == (self.b.val() & self.frac_mask.val())));
        // x is the operand of larger magnitude and gives the result's sign.
        self.a_larger.next = self.compared_exp_greater.q.val()
            | (self.compared_exp_equal.q.val() & self.compared_frac_not_less.q.val());
        self.subtract_now.next = self.compared_sign_a.q.val() ^ self.compared_sign_b.q.val();
        self.category.next.nan = self.compared_nan.q.val();
        self.category.next.inf = self.compared_inf.q.val();
        self.category.next.zero = self.compared_cancel.q.val();
        if self.a_larger.val() {
            self.x_sig.next = self.compared_sig_a.q.val();
            self.y_sig.next = self.compared_sig_b.q.val();
            self.shift.next = self.compared_shift_ab.q.val();
            self.aligned_exp.d.next = self.compared_exp_a.q.val();
            self.category.next.sign = self.compared_sign_a.q.val();
        } else {
            self.x_sig.next = self.compared_sig_b.q.val();
            self.y_sig.next = self.compared_sig_a.q.val();
            self.shift.next = self.compared_shift_ba.q.val();
            self.aligned_exp.d.next = self.compared_exp_b.q.val();
            self.category.next.sign = self.compared_sign_b.q.val();
        }
        // An exact zero is +0, except (−0) + (−0) = −0: same signs and both zero.
        if self.compared_cancel.q.val() & !self.compared_inf.q.val() {
            self.category.next.sign = self.compared_sign_a.q.val() & !self.subtract_now.val();
        }
        // Align y to x; the bits shifted out leave a sticky 1 in the lowest bit. Some are
        // shifted out when the shift exceeds y's trailing zeros: a comparison of registered
        // counts for either order, selected after, so it does not wait for the ordering.
        self.y_wide.next = bit_cast::<A, S>(self.y_sig.val()) << self.extra_bits.val();
        self.y_shifted.next = self.y_wide.val() >> self.shift.val();
        self.y_sticky.next = self.compared_shift_ba.q.val() > self.compared_zeros_a.q.val();
        if self.a_larger.val() {
            self.y_sticky.next = self.compared_shift_ab.q.val() > self.compared_zeros_b.q.val();
        }
        self.y_aligned.next = self.y_shifted.val();
        if self.y_sticky.val() {
            self.y_aligned.next = self.y_shifted.val() | self.carry_in.val();
        }
        // Cut 1. x − y = x + !y + 1, and x's lowest bit is 0: the +1 goes there.
        clock!(
            self,
            clock,
            aligned_x,
            aligned_y,
            aligned_exp,
            aligned_subtract,
            aligned_category
        );
        self.aligned_x.d.next = bit_cast::<A, S>(self.x_sig.val()) << self.extra_bits.val();
        self.aligned_y.d.next = self.y_aligned.val();
        if self.subtract_now.val() {
            self.aligned_x.d.next =
                (bit_cast::<A, S>(self.x_sig.val()) << self.extra_bits.val()) | self.carry_in.val();
            self.aligned_y.d.next = !self.y_aligned.val();
        }
        self.aligned_subtract.d.next = self.subtract_now.val();
        self.aligned_category.d.next = self.category.val();
        // Cut 2. The sum, and beside it the leading zeros of a difference anticipated from
        // its addends: indicator bit i (a function of addend bits i-1..i+1, one LUT) marks
        // where a string of equal-sum digits ends; its leading one sits at the difference's
        // leading one or one place above. Below bit 0 the addends count as zeros, above the
        // top as differing (the carry out is always 1). A sum has no zeros to anticipate: its
        // leading one is x's or one place above, which the correction finds.
        clock!(
            self,
            clock,
            summed,
            summed_zeros,
            summed_exp,
            summed_exp_below,
            summed_category
        );
        self.summed.d.next =
            bit_cast::<A1, A>(self.aligned_x.q.val()) + bit_cast::<A1, A>(self.aligned_y.q.val());
        self.lza_t.next =
            ((self.aligned_x.q.val() ^ self.aligned_y.q.val()) >> 1) | self.lza_top.val();
        self.lza_g.next = self.aligned_x.q.val() & self.aligned_y.q.val();
        self.lza_z.next = !(self.aligned_x.q.val() | self.aligned_y.q.val());
        self.indicator.next = (self.lza_t.val()
            & ((self.lza_g.val() & !((self.lza_z.val() << 1) | self.carry_in.val()))
                | (self.lza_z.val() & !(self.lza_g.val() << 1))))
            | (!self.lza_t.val()
                & ((self.lza_z.val() & !((self.lza_z.val() << 1) | self.carry_in.val()))
                    | (self.lza_g.val() & !(self.lza_g.val() << 1))));
        self.anticipated.x.next = bit_cast::<32, A>(self.indicator.val()) << self.left_align.val();
        // The count is of the sum's A1-bit frame (one more than the difference's), in which
        // the sum's top bit A1-1 is x's leading one's place plus one.
        self.summed_zeros.d.next = 0.into();
        if self.aligned_subtract.q.val() {
            self.summed_zeros.d.next = self.anticipated.count.val();
        }
        self.summed_exp.d.next = bit_cast::<X, E>(self.aligned_exp.q.val()) + self.exp_one.val();
        self.summed_exp_below.d.next = bit_cast::<X, E>(self.aligned_exp.q.val());
        self.summed_category.d.next = self.aligned_category.q.val();
        // Normalize by the anticipated count; when it was one short the top bit is still 0.
        // |x| ≥ |y|: a difference never borrows, and its carry out (always 1) is shifted out
        // (its count is at least 1).
        self.shifted.next = self.summed.q.val() << self.summed_zeros.q.val();
        // Both exponents are computed before the correction is known; they are selected by
        // AND/OR, not by a mux that yosys would fold into one subtractor behind a mux.
        self.normalized.next = self.shifted.val();
        self.exp_select.next = self.exp_all_ones.val();
        if !(self.shifted.val() & self.top_bit.val()).any() {
            self.normalized.next = self.shifted.val() << 1;
            self.exp_select.next = 0.into();
        }
        self.normal_exp.d.next = ((self.summed_exp.q.val()
            - bit_cast::<X, 8>(self.summed_zeros.q.val()))
            & self.exp_select.val())
            | ((self.summed_exp_below.q.val() - bit_cast::<X, 8>(self.summed_zeros.q.val()))
                & !self.exp_select.val());
        // Cut 3.
        clock!(
            self,
            clock,
            normal_sig,
            normal_round,
            normal_sticky,
            normal_exp,
            normal_category
        );
        self.normal_sig.d.next = bit_cast::<S, A1>(self.normalized.val() >> self.sig_shift.val());
        self.normal_round.d.next = (self.normalized.val() & self.round_bit.val()).any();
        self.normal_sticky.d.next = (self.normalized.val() & self.sticky_bits.val()).any();
        self.normal_category.d.next = self.summed_category.q.val();
        self.rounder.category.next = self.normal_category.q.val();
        self.rounder.exp.next = self.normal_exp.q.val();
        self.rounder.sig.next = self.normal_sig.q.val();
        self.rounder.round.next = self.normal_round.q.val();
        self.rounder.sticky.next = self.normal_sticky.q.val();
        // Cut 4.
        clock!(self, clock, result);
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FloatAdd<E, M, W, S, X, A, A1, SUB>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize,
     const A: usize, const A1: usize, const SUB: bool],
    W, W, out = bits);
