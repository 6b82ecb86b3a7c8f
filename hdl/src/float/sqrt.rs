//! Correctly rounded float square root `y = √a` (RNE, FTZ; √±0 = ±0, √+Inf = +Inf, a NaN or
//! a value below zero gives the canonical NaN), bit for bit `hw_model`'s `FloatFormat::sqrt`,
//! by restoring square root, one root bit a row ([`SqrtRow`]).
//!
//! With a = sig·2^(E−M) (E the unbiased exponent, sig = 1.f with M fraction bits), the
//! result's biased exponent is ⌊E/2⌋ + bias = (e_field + bias) >> 1 (bias is odd), never out
//! of range, and its significand is √(sig·2^(M+6+p)) = √(1.f·2^p)·2^(M+3) with p = E mod 2:
//! a root of Q = M + 4 bits whose top bit is always set, the significand (M + 1 bits), a
//! round bit and two more. The remainder is the sticky flag: √ of a float is never halfway
//! between two floats, so one rounding of root and sticky is the correct one (the model
//! forms the same root at another scale, `man + 3` or more bits). The radicand's nonzero
//! bits are sig·2^p: only its top RW = 2·⌈(M + 2)/2⌉ bits enter the rows (the first RW/2
//! rows bring down its pairs, the others zeros). Before row i the root has i bits and the
//! remainder is at most twice it, so 4·remainder + 3 < 2^(M+6) = 2^R.
//!
//! Cut points (max_stages() = M + 6): 0. after unpacking; i + 1. after row i (i < Q);
//! Q + 1. the result, after rounding and packing. At max_stages every register-to-register
//! path holds one row (an R-bit compare and subtract and a mux).

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::sqrt_row::SqrtRow;
use super::unpack::Unpack;
use crate::macros::clock;
use crate::pipe::{chain, placement, Pipe};

/// Bits of the root: the significand, a round bit and two more.
pub const fn root_bits(m: usize) -> usize {
    m + 4
}
/// Bits of the partial remainder.
pub const fn remainder_bits(m: usize) -> usize {
    m + 6
}
/// Bits of the radicand the rows bring down: sig·2^p aligned to whole pairs.
pub const fn radicand_bits(m: usize) -> usize {
    (m + 3) / 2 * 2
}

/// E, M: the format; W, S, X: a word, a significand, a signed exponent (≥ E+2); Q, R, RW:
/// the root's, remainder's and radicand's bits ([`crate::widths::SqrtWidths`]).
#[derive(LogicBlock)]
pub struct FloatSqrt<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const X: usize,
    const Q: usize,
    const R: usize,
    const RW: usize,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    unpack: Unpack<E, M, W, S>,
    category: Signal<Local, ResultClass>,
    // Cut 0.
    operand_radicand: Pipe<Bits<RW>>,
    operand_exp: Pipe<Bits<X>>,
    operand_category: Pipe<ResultClass>,
    rows: Vec<SqrtRow<R, Q, RW>>,
    // Cuts 1 to Q.
    row_remainder: Vec<Pipe<Bits<R>>>,
    row_root: Vec<Pipe<Bits<Q>>>,
    row_radicand: Vec<Pipe<Bits<RW>>>,
    row_exp: Vec<Pipe<Bits<X>>>,
    row_category: Vec<Pipe<ResultClass>>,
    remainder: Signal<Local, Bits<R>>,
    root: Signal<Local, Bits<Q>>,
    rounder: Round<E, M, W, S, X>,
    // Cut Q + 1.
    result: Pipe<Bits<W>>,
    lead_shift: Constant<Bits<8>>,
    odd_shift: Constant<Bits<8>>,
    bias: Constant<Bits<X>>,
    low_two: Constant<Bits<Q>>,
    three: Constant<Bits<8>>,
    zero_remainder: Constant<Bits<R>>,
    zero_root: Constant<Bits<Q>>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const Q: usize,
        const R: usize,
        const RW: usize,
    > FloatSqrt<E, M, W, S, X, Q, R, RW>
{
    pub const CUTS: usize = M + 6;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            W == 1 + E + M
                && S == M + 1
                && X >= E + 2
                && (Q, R, RW) == (root_bits(M), remainder_bits(M), radicand_bits(M)),
            "FloatSqrt: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        let rows = &cut[1..=Q];
        let bias = (1u64 << (E - 1)) - 1;
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            category: Default::default(),
            operand_radicand: Pipe::new(cut[0]),
            operand_exp: Pipe::new(cut[0]),
            operand_category: Pipe::new(cut[0]),
            rows: (0..Q).map(|_| Default::default()).collect(),
            row_remainder: chain(rows),
            row_root: chain(rows),
            row_radicand: chain(rows),
            row_exp: chain(rows),
            row_category: chain(rows),
            remainder: Default::default(),
            root: Default::default(),
            rounder: Default::default(),
            result: Pipe::new(cut[Q + 1]),
            // sig·2^p sits at the top of the radicand: shifted by RW − (M + 2) + p.
            lead_shift: Constant::new((RW - M - 2).to_bits()),
            odd_shift: Constant::new((RW - M - 1).to_bits()),
            bias: Constant::new(bias.into()),
            low_two: Constant::new(3.into()),
            three: Constant::new(3usize.to_bits()),
            zero_remainder: Constant::new(Bits::<R>::default()),
            zero_root: Constant::new(Bits::<Q>::default()),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const Q: usize,
        const R: usize,
        const RW: usize,
    > Logic for FloatSqrt<E, M, W, S, X, Q, R, RW>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        // √−0 = −0; any other value below zero (−Inf included) is NaN.
        self.category.next.sign = self.unpack.sign.val() & self.unpack.zero.val();
        self.category.next.nan =
            self.unpack.nan.val() | (self.unpack.sign.val() & !self.unpack.zero.val());
        self.category.next.inf = self.unpack.inf.val();
        self.category.next.zero = self.unpack.zero.val();
        // Cut 0: the radicand sig·2^p, p = E mod 2 = 1 when the exponent field is even.
        clock!(self, clock, operand_radicand, operand_exp, operand_category);
        if self.unpack.exp.val().get_bit(0) {
            self.operand_radicand.d.next =
                bit_cast::<RW, S>(self.unpack.sig.val()) << self.lead_shift.val();
        } else {
            self.operand_radicand.d.next =
                bit_cast::<RW, S>(self.unpack.sig.val()) << self.odd_shift.val();
        }
        self.operand_exp.d.next = (bit_cast::<X, E>(self.unpack.exp.val()) + self.bias.val()) >> 1;
        self.operand_category.d.next = self.category.val();
        // Row i reads cut i and feeds cut i + 1.
        self.rows[0].remainder_in.next = self.zero_remainder.val();
        self.rows[0].root_in.next = self.zero_root.val();
        self.rows[0].radicand_in.next = self.operand_radicand.q.val();
        self.row_exp[0].d.next = self.operand_exp.q.val();
        self.row_category[0].d.next = self.operand_category.q.val();
        for i in 1..self.rows.len() {
            self.rows[i].remainder_in.next = self.row_remainder[i - 1].q.val();
            self.rows[i].root_in.next = self.row_root[i - 1].q.val();
            self.rows[i].radicand_in.next = self.row_radicand[i - 1].q.val();
            self.row_exp[i].d.next = self.row_exp[i - 1].q.val();
            self.row_category[i].d.next = self.row_category[i - 1].q.val();
        }
        for i in 0..self.rows.len() {
            clock!(
                self,
                clock,
                row_remainder[i],
                row_root[i],
                row_radicand[i],
                row_exp[i],
                row_category[i]
            );
            self.row_remainder[i].d.next = self.rows[i].remainder_out.val();
            self.row_root[i].d.next = self.rows[i].root_out.val();
            self.row_radicand[i].d.next = self.rows[i].radicand_out.val();
            // The last row's pipes are the root's (the last assignment wins).
            self.remainder.next = self.row_remainder[i].q.val();
            self.root.next = self.row_root[i].q.val();
            self.rounder.exp.next = self.row_exp[i].q.val();
            self.rounder.category.next = self.row_category[i].q.val();
        }
        // The root's top M + 1 bits are the significand, the next the round bit.
        self.rounder.sig.next = bit_cast::<S, Q>(self.root.val() >> self.three.val());
        self.rounder.round.next = self.root.val().get_bit(2);
        self.rounder.sticky.next =
            (self.root.val() & self.low_two.val()).any() | self.remainder.val().any();
        // Cut Q + 1.
        clock!(self, clock, result);
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary FloatSqrt<E, M, W, S, X, Q, R, RW>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize,
     const Q: usize, const R: usize, const RW: usize],
    W, W, out = bits);
