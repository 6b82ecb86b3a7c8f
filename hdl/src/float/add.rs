//! Float addition and subtraction `y = a ± b` (RNE, FTZ, see the SPEC in `hw_model::format`).
//!
//! The operand of larger magnitude is x, the other y; y's significand (with 3 extra low
//! bits: guard, round and a sticky bit that collects everything shifted out) is aligned to
//! x, added or subtracted, normalized by the position of the leading one and rounded.
//!
//! Cut points (registers are spread over them by `pipe::placement`; max_stages() = 4):
//!   0. after unpacking and ordering the operands
//!   1. after aligning y
//!   2. after the add/subtract
//!   3. after normalization, before rounding and packing
//! stages = 1 registers cut 2, stages = 2 cuts 1 and 3, stages = 3 cuts 0, 2 and 3.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// E, M: the format; W = 1+E+M; S = M+1; S1 = S+1; X = exponent width (≥ E+2);
/// A = S+3 (aligned significand); A1 = A+1 (sum); SUB: subtract instead of add.
#[derive(LogicBlock)]
pub struct FloatAdd<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const S1: usize,
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
    a_larger: Signal<Local, Bit>,
    category: Signal<Local, ResultClass>,
    ordered_x: Pipe<Bits<S>>,
    ordered_y: Pipe<Bits<S>>,
    ordered_exp: Pipe<Bits<E>>,
    ordered_diff: Pipe<Bits<E>>,
    ordered_subtract: Pipe<Bit>,
    ordered_category: Pipe<ResultClass>,
    shift: Signal<Local, Bits<E>>,
    y_wide: Signal<Local, Bits<A>>,
    y_shifted: Signal<Local, Bits<A>>,
    aligned_x: Pipe<Bits<A>>,
    aligned_y: Pipe<Bits<A>>,
    aligned_exp: Pipe<Bits<E>>,
    aligned_subtract: Pipe<Bit>,
    aligned_category: Pipe<ResultClass>,
    sum: Signal<Local, Bits<A1>>,
    sum_category: Signal<Local, ResultClass>,
    summed: Pipe<Bits<A1>>,
    summed_exp: Pipe<Bits<E>>,
    summed_category: Pipe<ResultClass>,
    leading_one: Signal<Local, Bits<8>>,
    normalized: Signal<Local, Bits<A1>>,
    normal_sig: Pipe<Bits<S>>,
    normal_round: Pipe<Bit>,
    normal_sticky: Pipe<Bit>,
    normal_exp: Pipe<Bits<X>>,
    normal_category: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, S1, X>,
    subtract: Constant<Bit>,
    magnitude: Constant<Bits<W>>,
    extra_bits: Constant<Bits<8>>,
    align_limit: Constant<Bits<E>>,
    one: Constant<Bits<A>>,
    sum_top: Constant<Bits<8>>,
    exp_offset: Constant<Bits<X>>,
    round_bit: Constant<Bits<A1>>,
    sticky_bits: Constant<Bits<A1>>,
    sig_shift: Constant<Bits<8>>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const S1: usize,
        const X: usize,
        const A: usize,
        const A1: usize,
        const SUB: bool,
    > FloatAdd<E, M, W, S, S1, X, A, A1, SUB>
{
    pub const CUTS: usize = 4;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(A == S + 3 && A1 == A + 1 && X >= E + 2, "FloatAdd: inconsistent widths");
        assert!((A as u64) < (1 << E) && A1 < 256, "FloatAdd: the format is too narrow or too wide");
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            unpack_a: Default::default(),
            unpack_b: Default::default(),
            sign_b: Default::default(),
            a_larger: Default::default(),
            category: Default::default(),
            ordered_x: Pipe::new(cut[0]),
            ordered_y: Pipe::new(cut[0]),
            ordered_exp: Pipe::new(cut[0]),
            ordered_diff: Pipe::new(cut[0]),
            ordered_subtract: Pipe::new(cut[0]),
            ordered_category: Pipe::new(cut[0]),
            shift: Default::default(),
            y_wide: Default::default(),
            y_shifted: Default::default(),
            aligned_x: Pipe::new(cut[1]),
            aligned_y: Pipe::new(cut[1]),
            aligned_exp: Pipe::new(cut[1]),
            aligned_subtract: Pipe::new(cut[1]),
            aligned_category: Pipe::new(cut[1]),
            sum: Default::default(),
            sum_category: Default::default(),
            summed: Pipe::new(cut[2]),
            summed_exp: Pipe::new(cut[2]),
            summed_category: Pipe::new(cut[2]),
            leading_one: Default::default(),
            normalized: Default::default(),
            normal_sig: Pipe::new(cut[3]),
            normal_round: Pipe::new(cut[3]),
            normal_sticky: Pipe::new(cut[3]),
            normal_exp: Pipe::new(cut[3]),
            normal_category: Pipe::new(cut[3]),
            rounder: Default::default(),
            subtract: Constant::new(SUB),
            magnitude: Constant::new(Bits::<W>::mask() >> 1),
            extra_bits: Constant::new(3.into()),
            align_limit: Constant::new((A as u64).into()),
            one: Constant::new(1.into()),
            sum_top: Constant::new((A as u64).into()),
            // x's leading 1 sits at bit A-1 of the sum: exponent = exp_x + leading_one - (A-1).
            exp_offset: Constant::new(((A - 1) as u64).into()),
            round_bit: Constant::new(Bits::<A1>::from(1) << (A1 - S - 1) as u64),
            sticky_bits: Constant::new((Bits::<A1>::from(1) << (A1 - S - 1) as u64) - 1),
            sig_shift: Constant::new(((A1 - S) as u64).into()),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const S1: usize,
        const X: usize,
        const A: usize,
        const A1: usize,
        const SUB: bool,
    > Logic for FloatAdd<E, M, W, S, S1, X, A, A1, SUB>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack_a.x.next = self.a.val();
        self.unpack_b.x.next = self.b.val();
        self.sign_b.next = self.unpack_b.sign.val() ^ self.subtract.val();
        self.a_larger.next = (self.a.val() & self.magnitude.val()) >= (self.b.val() & self.magnitude.val());
        self.category.next.nan = self.unpack_a.nan.val()
            | self.unpack_b.nan.val()
            | (self.unpack_a.inf.val() & self.unpack_b.inf.val() & (self.unpack_a.sign.val() ^ self.sign_b.val()));
        self.category.next.inf = self.unpack_a.inf.val() | self.unpack_b.inf.val();
        self.category.next.zero = false;
        // Cut 0: x is the operand of larger magnitude and gives the result's sign.
        self.ordered_x.clock.next = self.clock.val();
        self.ordered_y.clock.next = self.clock.val();
        self.ordered_exp.clock.next = self.clock.val();
        self.ordered_diff.clock.next = self.clock.val();
        self.ordered_subtract.clock.next = self.clock.val();
        self.ordered_category.clock.next = self.clock.val();
        if self.a_larger.val() {
            self.ordered_x.d.next = self.unpack_a.sig.val();
            self.ordered_y.d.next = self.unpack_b.sig.val();
            self.ordered_exp.d.next = self.unpack_a.exp.val();
            self.ordered_diff.d.next = self.unpack_a.exp.val() - self.unpack_b.exp.val();
            self.category.next.sign = self.unpack_a.sign.val();
        } else {
            self.ordered_x.d.next = self.unpack_b.sig.val();
            self.ordered_y.d.next = self.unpack_a.sig.val();
            self.ordered_exp.d.next = self.unpack_b.exp.val();
            self.ordered_diff.d.next = self.unpack_b.exp.val() - self.unpack_a.exp.val();
            self.category.next.sign = self.sign_b.val();
        }
        self.ordered_subtract.d.next = self.unpack_a.sign.val() ^ self.sign_b.val();
        self.ordered_category.d.next = self.category.val();
        // Align y to x; the bits shifted out leave a sticky 1 in the lowest bit.
        if self.ordered_diff.q.val() > self.align_limit.val() {
            self.shift.next = self.align_limit.val();
        } else {
            self.shift.next = self.ordered_diff.q.val();
        }
        self.y_wide.next = bit_cast::<A, S>(self.ordered_y.q.val()) << self.extra_bits.val();
        self.y_shifted.next = self.y_wide.val() >> self.shift.val();
        // Cut 1.
        self.aligned_x.clock.next = self.clock.val();
        self.aligned_y.clock.next = self.clock.val();
        self.aligned_exp.clock.next = self.clock.val();
        self.aligned_subtract.clock.next = self.clock.val();
        self.aligned_category.clock.next = self.clock.val();
        self.aligned_x.d.next = bit_cast::<A, S>(self.ordered_x.q.val()) << self.extra_bits.val();
        if (self.y_shifted.val() << self.shift.val()) != self.y_wide.val() {
            self.aligned_y.d.next = self.y_shifted.val() | self.one.val();
        } else {
            self.aligned_y.d.next = self.y_shifted.val();
        }
        self.aligned_exp.d.next = self.ordered_exp.q.val();
        self.aligned_subtract.d.next = self.ordered_subtract.q.val();
        self.aligned_category.d.next = self.ordered_category.q.val();
        // |x| >= |y|, so the difference is never negative.
        if self.aligned_subtract.q.val() {
            self.sum.next = bit_cast::<A1, A>(self.aligned_x.q.val()) - bit_cast::<A1, A>(self.aligned_y.q.val());
        } else {
            self.sum.next = bit_cast::<A1, A>(self.aligned_x.q.val()) + bit_cast::<A1, A>(self.aligned_y.q.val());
        }
        // An exact zero is +0, except (−0) + (−0) = −0: same signs and both zero.
        self.sum_category.next = self.aligned_category.q.val();
        self.sum_category.next.zero = !self.sum.val().any();
        if !self.sum.val().any() & !self.aligned_category.q.val().inf {
            self.sum_category.next.sign = self.aligned_category.q.val().sign & !self.aligned_subtract.q.val();
        }
        // Cut 2.
        self.summed.clock.next = self.clock.val();
        self.summed_exp.clock.next = self.clock.val();
        self.summed_category.clock.next = self.clock.val();
        self.summed.d.next = self.sum.val();
        self.summed_exp.d.next = self.aligned_exp.q.val();
        self.summed_category.d.next = self.sum_category.val();
        // Normalize: the leading one goes to the top bit of the sum.
        self.leading_one.next = 0.into();
        for i in 0..A1 {
            if self.summed.q.val().get_bit(i) {
                self.leading_one.next = i.to_bits();
            }
        }
        self.normalized.next = self.summed.q.val() << (self.sum_top.val() - self.leading_one.val());
        // Cut 3.
        self.normal_sig.clock.next = self.clock.val();
        self.normal_round.clock.next = self.clock.val();
        self.normal_sticky.clock.next = self.clock.val();
        self.normal_exp.clock.next = self.clock.val();
        self.normal_category.clock.next = self.clock.val();
        self.normal_sig.d.next = bit_cast::<S, A1>(self.normalized.val() >> self.sig_shift.val());
        self.normal_round.d.next = (self.normalized.val() & self.round_bit.val()).any();
        self.normal_sticky.d.next = (self.normalized.val() & self.sticky_bits.val()).any();
        self.normal_exp.d.next = bit_cast::<X, E>(self.summed_exp.q.val()) + bit_cast::<X, 8>(self.leading_one.val())
            - self.exp_offset.val();
        self.normal_category.d.next = self.summed_category.q.val();
        self.rounder.category.next = self.normal_category.q.val();
        self.rounder.exp.next = self.normal_exp.q.val();
        self.rounder.sig.next = self.normal_sig.q.val();
        self.rounder.round.next = self.normal_round.q.val();
        self.rounder.sticky.next = self.normal_sticky.q.val();
        self.y.next = self.rounder.y.val();
    }
}

crate::impl_operator!(binary FloatAdd<E, M, W, S, S1, X, A, A1, SUB>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const S1: usize, const X: usize,
     const A: usize, const A1: usize, const SUB: bool],
    W, W, out = bits);
