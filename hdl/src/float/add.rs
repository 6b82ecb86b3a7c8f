//! Float addition and subtraction `y = a ± b` (RNE, FTZ, see the SPEC in `hw_model::format`).
//!
//! The operand of larger magnitude is x, the other y; y's significand (with 3 extra low
//! bits: guard, round and a sticky bit that collects everything shifted out) is aligned to
//! x, added or subtracted, normalized by the position of the leading one and rounded.
//!
//! The stages are cut so that no register-to-register path holds two wide carry chains or a
//! carry chain and a wide shifter:
//!   0. after comparing: exponents (both differences, clamped to the alignment range) and
//!      fractions are compared separately, and an exact cancellation is detected there
//!   1. after ordering and aligning y (shifter and sticky mask side by side); y is already
//!      inverted for a subtraction and x carries the +1, so the next stage is one adder
//!   2. after the add
//!   3. after counting the sum's leading zeros
//!   4. after the normalizing shift and exponent adjust
//!   5. the result, after rounding and packing
//! Registers are spread over them by `pipe::placement`; max_stages() = 6.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// E, M: the format; W = 1+E+M; S = M+1; X = exponent width (≥ E+2);
/// A = S+3 (aligned significand); A1 = A+1 (sum); SUB: subtract instead of add.
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
    summed: Pipe<Bits<A1>>,
    summed_exp: Pipe<Bits<X>>,
    summed_subtract: Pipe<Bit>,
    summed_category: Pipe<ResultClass>,
    sum: Signal<Local, Bits<A1>>,
    smear: Signal<Local, Bits<A1>>,
    leading_one: Signal<Local, Bits<A1>>,
    leading_zeros: Signal<Local, Bits<8>>,
    counted: Pipe<Bits<A1>>,
    counted_zeros: Pipe<Bits<8>>,
    counted_exp: Pipe<Bits<X>>,
    counted_category: Pipe<ResultClass>,
    normalized: Signal<Local, Bits<A1>>,
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
    all_ones: Constant<Bits<A>>,
    carry_in: Constant<Bits<A>>,
    sum_carry: Constant<Bits<A1>>,
    smear_shifts: Vec<Constant<Bits<8>>>,
    count_masks: Vec<Constant<Bits<A1>>>,
    count_bits: Vec<Constant<Bits<8>>>,
    exp_one: Constant<Bits<X>>,
    sig_shift: Constant<Bits<8>>,
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
    pub const CUTS: usize = 6;

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
            summed: Pipe::new(cut[2]),
            summed_exp: Pipe::new(cut[2]),
            summed_subtract: Pipe::new(cut[2]),
            summed_category: Pipe::new(cut[2]),
            sum: Default::default(),
            smear: Default::default(),
            leading_one: Default::default(),
            leading_zeros: Default::default(),
            counted: Pipe::new(cut[3]),
            counted_zeros: Pipe::new(cut[3]),
            counted_exp: Pipe::new(cut[3]),
            counted_category: Pipe::new(cut[3]),
            normalized: Default::default(),
            normal_sig: Pipe::new(cut[4]),
            normal_round: Pipe::new(cut[4]),
            normal_sticky: Pipe::new(cut[4]),
            normal_exp: Pipe::new(cut[4]),
            normal_category: Pipe::new(cut[4]),
            rounder: Default::default(),
            result: Pipe::new(cut[5]),
            subtract: Constant::new(SUB),
            frac_mask: Constant::new((Bits::<W>::from(1) << M as u64) - 1),
            extra_bits: Constant::new(3.into()),
            align_limit: Constant::new((A as u64).into()),
            all_ones: Constant::new(Bits::<A>::mask()),
            carry_in: Constant::new(1.into()),
            sum_carry: Constant::new(Bits::<A1>::from(1) << A as u64),
            smear_shifts: (0..8)
                .map(|k| 1u64 << k)
                .take_while(|&k| k < A1 as u64)
                .map(|k| Constant::new(k.into()))
                .collect(),
            // Leading one at bit i: A1-1-i leading zeros; count bit k is set for the i in mask k.
            count_masks: (0..8)
                .map(|k| {
                    let mask = (0..A1)
                        .filter(|i| (A1 - 1 - i) >> k & 1 == 1)
                        .fold(Bits::<A1>::default(), |m, i| {
                            m | (Bits::<A1>::from(1) << i as u64)
                        });
                    Constant::new(mask)
                })
                .collect(),
            count_bits: (0..8).map(|k| Constant::new((1u64 << k).into())).collect(),
            exp_one: Constant::new(1.into()),
            sig_shift: Constant::new(((A1 - S) as u64).into()),
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
        self.compared_sig_a.clock.next = self.clock.val();
        self.compared_sig_b.clock.next = self.clock.val();
        self.compared_exp_a.clock.next = self.clock.val();
        self.compared_exp_b.clock.next = self.clock.val();
        self.compared_shift_ab.clock.next = self.clock.val();
        self.compared_shift_ba.clock.next = self.clock.val();
        self.compared_exp_greater.clock.next = self.clock.val();
        self.compared_exp_equal.clock.next = self.clock.val();
        self.compared_frac_not_less.clock.next = self.clock.val();
        self.compared_sign_a.clock.next = self.clock.val();
        self.compared_sign_b.clock.next = self.clock.val();
        self.compared_nan.clock.next = self.clock.val();
        self.compared_inf.clock.next = self.clock.val();
        self.compared_cancel.clock.next = self.clock.val();
        self.compared_sig_a.d.next = self.unpack_a.sig.val();
        self.compared_sig_b.d.next = self.unpack_b.sig.val();
        self.compared_exp_a.d.next = self.unpack_a.exp.val();
        self.compared_exp_b.d.next = self.unpack_b.exp.val();
        // The alignment shift for either order; only the one of the larger operand is used.
        self.diff_ab.next = self.unpack_a.exp.val() - self.unpack_b.exp.val();
        self.diff_ba.next = self.unpack_b.exp.val() - self.unpack_a.exp.val();
        self.compared_shift_ab.d.next = bit_cast::<5, E>(self.diff_ab.val());
        if self.diff_ab.val() > self.align_limit.val() {
            self.compared_shift_ab.d.next = bit_cast::<5, E>(self.align_limit.val());
        }
        self.compared_shift_ba.d.next = bit_cast::<5, E>(self.diff_ba.val());
        if self.diff_ba.val() > self.align_limit.val() {
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
        // Align y to x; the bits shifted out (selected by a mask, beside the shifter) leave
        // a sticky 1 in the lowest bit.
        self.y_wide.next = bit_cast::<A, S>(self.y_sig.val()) << self.extra_bits.val();
        self.y_shifted.next = self.y_wide.val() >> self.shift.val();
        self.y_sticky.next = (self.y_wide.val() & !(self.all_ones.val() << self.shift.val())).any();
        self.y_aligned.next = self.y_shifted.val();
        if self.y_sticky.val() {
            self.y_aligned.next = self.y_shifted.val() | self.carry_in.val();
        }
        // Cut 1. x − y = x + !y + 1, and x's lowest bit is 0: the +1 goes there.
        self.aligned_x.clock.next = self.clock.val();
        self.aligned_y.clock.next = self.clock.val();
        self.aligned_exp.clock.next = self.clock.val();
        self.aligned_subtract.clock.next = self.clock.val();
        self.aligned_category.clock.next = self.clock.val();
        self.aligned_x.d.next = bit_cast::<A, S>(self.x_sig.val()) << self.extra_bits.val();
        self.aligned_y.d.next = self.y_aligned.val();
        if self.subtract_now.val() {
            self.aligned_x.d.next =
                (bit_cast::<A, S>(self.x_sig.val()) << self.extra_bits.val()) | self.carry_in.val();
            self.aligned_y.d.next = !self.y_aligned.val();
        }
        self.aligned_subtract.d.next = self.subtract_now.val();
        self.aligned_category.d.next = self.category.val();
        // Cut 2. The sum's exponent is that of its bit A-1 (x's leading one) plus one.
        self.summed.clock.next = self.clock.val();
        self.summed_exp.clock.next = self.clock.val();
        self.summed_subtract.clock.next = self.clock.val();
        self.summed_category.clock.next = self.clock.val();
        self.summed.d.next =
            bit_cast::<A1, A>(self.aligned_x.q.val()) + bit_cast::<A1, A>(self.aligned_y.q.val());
        self.summed_exp.d.next = bit_cast::<X, E>(self.aligned_exp.q.val()) + self.exp_one.val();
        self.summed_subtract.d.next = self.aligned_subtract.q.val();
        self.summed_category.d.next = self.aligned_category.q.val();
        // |x| ≥ |y|: a difference never borrows, its carry out (always 1) is not part of it.
        self.sum.next = self.summed.q.val();
        if self.summed_subtract.q.val() {
            self.sum.next = self.summed.q.val() & !self.sum_carry.val();
        }
        // Normalize: the leading one goes to the top bit of the sum. Its position comes from
        // the sum smeared down from the leading one (log-depth ORs, not a priority chain).
        self.smear.next = self.sum.val();
        for k in 0..self.smear_shifts.len() {
            self.smear.next = self.smear.val() | (self.smear.val() >> self.smear_shifts[k].val());
        }
        self.leading_one.next = self.smear.val() & !(self.smear.val() >> 1);
        self.leading_zeros.next = 0.into();
        for k in 0..8 {
            if (self.leading_one.val() & self.count_masks[k].val()).any() {
                self.leading_zeros.next = self.leading_zeros.val() | self.count_bits[k].val();
            }
        }
        // Cut 3.
        self.counted.clock.next = self.clock.val();
        self.counted_zeros.clock.next = self.clock.val();
        self.counted_exp.clock.next = self.clock.val();
        self.counted_category.clock.next = self.clock.val();
        self.counted.d.next = self.sum.val();
        self.counted_zeros.d.next = self.leading_zeros.val();
        self.counted_exp.d.next = self.summed_exp.q.val();
        self.counted_category.d.next = self.summed_category.q.val();
        self.normalized.next = self.counted.q.val() << self.counted_zeros.q.val();
        // Cut 4.
        self.normal_sig.clock.next = self.clock.val();
        self.normal_round.clock.next = self.clock.val();
        self.normal_sticky.clock.next = self.clock.val();
        self.normal_exp.clock.next = self.clock.val();
        self.normal_category.clock.next = self.clock.val();
        self.normal_sig.d.next = bit_cast::<S, A1>(self.normalized.val() >> self.sig_shift.val());
        self.normal_round.d.next = (self.normalized.val() & self.round_bit.val()).any();
        self.normal_sticky.d.next = (self.normalized.val() & self.sticky_bits.val()).any();
        self.normal_exp.d.next =
            self.counted_exp.q.val() - bit_cast::<X, 8>(self.counted_zeros.q.val());
        self.normal_category.d.next = self.counted_category.q.val();
        self.rounder.category.next = self.normal_category.q.val();
        self.rounder.exp.next = self.normal_exp.q.val();
        self.rounder.sig.next = self.normal_sig.q.val();
        self.rounder.round.next = self.normal_round.q.val();
        self.rounder.sticky.next = self.normal_sticky.q.val();
        // Cut 5.
        self.result.clock.next = self.clock.val();
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FloatAdd<E, M, W, S, X, A, A1, SUB>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize,
     const A: usize, const A1: usize, const SUB: bool],
    W, W, out = bits);
