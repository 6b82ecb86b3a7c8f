//! Correctly rounded float reciprocal `y = 1 / a` (RNE, FTZ; 1/±0 = ±Inf, 1/±Inf = ±0).
//!
//! The significand quotient 2^(2M+2) / sig is computed by restoring division, one quotient
//! bit per row: Q = M+3 bits (the top one is set only for sig = 1.0, then the result is an
//! exact power of two), so the M+1 result bits, a round bit and the remainder as sticky bit
//! give the correctly rounded result.
//!
//! Cut points (max_stages() = Q + 3 = M + 6): 0. after unpacking; i+1. after division row i;
//! Q+1. after picking the significand, round and sticky bits; Q+2. the result, after rounding
//! and packing. With max_stages every register-to-register path holds one row (a carry-select
//! compare and subtract of M+2 bits and a mux) or the rounding; fewer stages are spread evenly.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::pipe::{chain, placement, Pipe};

/// One row of the restoring divider: doubles the partial remainder and subtracts the
/// divisor if it fits, shifting the quotient bit into `q`.
#[derive(LogicBlock)]
pub struct DivisionRow<const R: usize, const Q: usize> {
    pub remainder_in: Signal<In, Bits<R>>,
    pub quotient_in: Signal<In, Bits<Q>>,
    pub divisor: Signal<In, Bits<R>>,
    pub remainder_out: Signal<Out, Bits<R>>,
    pub quotient_out: Signal<Out, Bits<Q>>,
    doubled: Signal<Local, Bits<R>>,
    low_doubled: Signal<Local, Bits<R>>,
    low_divisor: Signal<Local, Bits<R>>,
    high_doubled: Signal<Local, Bits<R>>,
    high_divisor: Signal<Local, Bits<R>>,
    low_difference: Signal<Local, Bits<R>>,
    high_difference: Signal<Local, Bits<R>>,
    fits: Signal<Local, Bit>,
    one: Constant<Bits<Q>>,
    half: Constant<Bits<8>>,
    low_mask: Constant<Bits<R>>,
    borrow: Constant<Bits<R>>,
}

impl<const R: usize, const Q: usize> Default for DivisionRow<R, Q> {
    fn default() -> Self {
        Self {
            remainder_in: Default::default(),
            quotient_in: Default::default(),
            divisor: Default::default(),
            remainder_out: Default::default(),
            quotient_out: Default::default(),
            doubled: Default::default(),
            low_doubled: Default::default(),
            low_divisor: Default::default(),
            high_doubled: Default::default(),
            high_divisor: Default::default(),
            low_difference: Default::default(),
            high_difference: Default::default(),
            fits: Default::default(),
            one: Constant::new(1.into()),
            half: Constant::new((R / 2).to_bits()),
            low_mask: Constant::new((Bits::<R>::from(1) << (R / 2) as u64) - 1),
            borrow: Constant::new(1.into()),
        }
    }
}

impl<const R: usize, const Q: usize> Logic for DivisionRow<R, Q> {
    #[hdl_gen]
    fn update(&mut self) {
        // The remainder is below the divisor (< 2^(R-1)), so doubling it never overflows.
        self.doubled.next = self.remainder_in.val() << 1;
        // Compare and subtract in two halves side by side (carry select): the high half's
        // difference is taken with and without the low half's borrow.
        self.low_doubled.next = self.doubled.val() & self.low_mask.val();
        self.low_divisor.next = self.divisor.val() & self.low_mask.val();
        self.high_doubled.next = self.doubled.val() >> self.half.val();
        self.high_divisor.next = self.divisor.val() >> self.half.val();
        // doubled ≥ divisor: by the high halves, ≥ or > as the low half borrows or not.
        if self.low_doubled.val() >= self.low_divisor.val() {
            self.fits.next = self.high_doubled.val() >= self.high_divisor.val();
        } else {
            self.fits.next = self.high_doubled.val() > self.high_divisor.val();
        }
        self.low_difference.next = (self.low_doubled.val() - self.low_divisor.val()) & self.low_mask.val();
        if self.low_doubled.val() >= self.low_divisor.val() {
            self.high_difference.next = self.high_doubled.val() - self.high_divisor.val();
        } else {
            self.high_difference.next = self.high_doubled.val() - self.high_divisor.val() - self.borrow.val();
        }
        if self.fits.val() {
            self.remainder_out.next = (self.high_difference.val() << self.half.val()) | self.low_difference.val();
            self.quotient_out.next = (self.quotient_in.val() << 1) | self.one.val();
        } else {
            self.remainder_out.next = self.doubled.val();
            self.quotient_out.next = self.quotient_in.val() << 1;
        }
    }
}

/// E, M: the format; W = 1+E+M; S = M+1; X = exponent width (≥ E+2);
/// R = M+2 (remainder); Q = M+3 (quotient bits = rows).
#[derive(LogicBlock)]
pub struct FloatRecip<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const X: usize,
    const R: usize,
    const Q: usize,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    unpack: Unpack<E, M, W, S>,
    category: Signal<Local, ResultClass>,
    operand_divisor: Pipe<Bits<R>>,
    operand_exp: Pipe<Bits<X>>,
    operand_category: Pipe<ResultClass>,
    rows: Vec<DivisionRow<R, Q>>,
    row_remainder: Vec<Pipe<Bits<R>>>,
    row_quotient: Vec<Pipe<Bits<Q>>>,
    row_divisor: Vec<Pipe<Bits<R>>>,
    row_exp: Vec<Pipe<Bits<X>>>,
    row_category: Vec<Pipe<ResultClass>>,
    remainder: Signal<Local, Bits<R>>,
    quotient: Signal<Local, Bits<Q>>,
    quotient_exp: Signal<Local, Bits<X>>,
    quotient_category: Signal<Local, ResultClass>,
    exact_power: Signal<Local, Bit>,
    rounding_sig: Pipe<Bits<S>>,
    rounding_round: Pipe<Bit>,
    rounding_sticky: Pipe<Bit>,
    rounding_exp: Pipe<Bits<X>>,
    rounding_category: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, X>,
    result: Pipe<Bits<W>>,
    exp_base: Constant<Bits<X>>,
    first_remainder: Constant<Bits<R>>,
    no_quotient: Constant<Bits<Q>>,
    quotient_top: Constant<Bits<Q>>,
    one: Constant<Bits<Q>>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const R: usize,
        const Q: usize,
    > FloatRecip<E, M, W, S, X, R, Q>
{
    pub const CUTS: usize = Q + 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(R == M + 2 && Q == M + 3 && X >= E + 2, "FloatRecip: inconsistent widths");
        let cut = placement(stages, Self::CUTS);
        let rows = &cut[1..=Q];
        let bias = (1u64 << (E - 1)) - 1;
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            category: Default::default(),
            operand_divisor: Pipe::new(cut[0]),
            operand_exp: Pipe::new(cut[0]),
            operand_category: Pipe::new(cut[0]),
            rows: (0..Q).map(|_| Default::default()).collect(),
            row_remainder: chain(rows),
            row_quotient: chain(rows),
            row_divisor: chain(rows),
            row_exp: chain(rows),
            row_category: chain(rows),
            remainder: Default::default(),
            quotient: Default::default(),
            quotient_exp: Default::default(),
            quotient_category: Default::default(),
            exact_power: Default::default(),
            rounding_sig: Pipe::new(cut[Q + 1]),
            rounding_round: Pipe::new(cut[Q + 1]),
            rounding_sticky: Pipe::new(cut[Q + 1]),
            rounding_exp: Pipe::new(cut[Q + 1]),
            rounding_category: Pipe::new(cut[Q + 1]),
            rounder: Default::default(),
            result: Pipe::new(cut[Q + 2]),
            // 1/(sig·2^(e−bias)) = (2/sig)·2^(bias−e−1): biased exponent 2·bias − 1 − e.
            exp_base: Constant::new((2 * bias - 1).into()),
            // The part of 2^(2M+2) above the first quotient bit, 2^(M+2).
            first_remainder: Constant::new((1u64 << (M - 1)).into()),
            no_quotient: Constant::new(0.into()),
            quotient_top: Constant::new(Bits::<Q>::from(1) << (Q - 1) as u64),
            one: Constant::new(1.into()),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const R: usize,
        const Q: usize,
    > Logic for FloatRecip<E, M, W, S, X, R, Q>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        self.category.next.sign = self.unpack.sign.val();
        self.category.next.nan = self.unpack.nan.val();
        self.category.next.inf = self.unpack.zero.val();
        self.category.next.zero = self.unpack.inf.val();
        // Cut 0.
        self.operand_divisor.clock.next = self.clock.val();
        self.operand_exp.clock.next = self.clock.val();
        self.operand_category.clock.next = self.clock.val();
        self.operand_divisor.d.next = bit_cast::<R, S>(self.unpack.sig.val());
        self.operand_exp.d.next = self.exp_base.val() - bit_cast::<X, E>(self.unpack.exp.val());
        self.operand_category.d.next = self.category.val();
        // Row i reads cut i and feeds cut i + 1.
        self.rows[0].remainder_in.next = self.first_remainder.val();
        self.rows[0].quotient_in.next = self.no_quotient.val();
        self.rows[0].divisor.next = self.operand_divisor.q.val();
        self.row_exp[0].d.next = self.operand_exp.q.val();
        self.row_category[0].d.next = self.operand_category.q.val();
        for i in 1..Q {
            self.rows[i].remainder_in.next = self.row_remainder[i - 1].q.val();
            self.rows[i].quotient_in.next = self.row_quotient[i - 1].q.val();
            self.rows[i].divisor.next = self.row_divisor[i - 1].q.val();
            self.row_exp[i].d.next = self.row_exp[i - 1].q.val();
            self.row_category[i].d.next = self.row_category[i - 1].q.val();
        }
        for i in 0..Q {
            self.row_remainder[i].clock.next = self.clock.val();
            self.row_quotient[i].clock.next = self.clock.val();
            self.row_divisor[i].clock.next = self.clock.val();
            self.row_exp[i].clock.next = self.clock.val();
            self.row_category[i].clock.next = self.clock.val();
            self.row_remainder[i].d.next = self.rows[i].remainder_out.val();
            self.row_quotient[i].d.next = self.rows[i].quotient_out.val();
            self.row_divisor[i].d.next = self.rows[i].divisor.val();
            // The last row's pipes are the divider's result (the last assignment wins).
            self.remainder.next = self.row_remainder[i].q.val();
            self.quotient.next = self.row_quotient[i].q.val();
            self.quotient_exp.next = self.row_exp[i].q.val();
            self.quotient_category.next = self.row_category[i].q.val();
        }
        // The quotient is in (2^(M+1), 2^(M+2)) except for sig = 1.0 (exactly 2^(M+2)).
        self.exact_power.next = (self.quotient.val() & self.quotient_top.val()).any();
        // Cut Q + 1.
        self.rounding_sig.clock.next = self.clock.val();
        self.rounding_round.clock.next = self.clock.val();
        self.rounding_sticky.clock.next = self.clock.val();
        self.rounding_exp.clock.next = self.clock.val();
        self.rounding_category.clock.next = self.clock.val();
        if self.exact_power.val() {
            self.rounding_sig.d.next = bit_cast::<S, Q>(self.quotient.val() >> 2);
        } else {
            self.rounding_sig.d.next = bit_cast::<S, Q>(self.quotient.val() >> 1);
        }
        self.rounding_round.d.next = (self.quotient.val() & self.one.val()).any();
        self.rounding_sticky.d.next = self.remainder.val().any();
        self.rounding_exp.d.next = self.quotient_exp.val() + self.exact_power.val();
        self.rounding_category.d.next = self.quotient_category.val();
        self.rounder.sig.next = self.rounding_sig.q.val();
        self.rounder.round.next = self.rounding_round.q.val();
        self.rounder.sticky.next = self.rounding_sticky.q.val();
        self.rounder.exp.next = self.rounding_exp.q.val();
        self.rounder.category.next = self.rounding_category.q.val();
        // Cut Q + 2.
        self.result.clock.next = self.clock.val();
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary FloatRecip<E, M, W, S, X, R, Q>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize,
     const R: usize, const Q: usize],
    W, W, out = bits);
