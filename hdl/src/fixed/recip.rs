//! Fixed-point reciprocal `y = 1 / a` = 2^(2F) / X in units of 2^-F (X the raw signed
//! operand), quantised with the format's mode, then the overflow mode; recip(0) = max.
//!
//! |X| divides 2^(2F) by restoring division (`DivisionRow`), one
//! quotient bit a row. The numerator has a single 1, at bit 2F: its quotient bit is 1 only
//! for |X| = 1, so it is decided before the rows (remainder 0 or 1), and 2F rows give the
//! other bits. The remainder then tells where the fraction rem/|X| lies: ≥ 1/2 when
//! 2·rem ≥ |X|, and is exactly 0 or 1/2 otherwise; `SignedRound` applies the mode to the sign.
//!
//! Cut points (max_stages() = 2F + 3): 0. after taking |X|; i+1. after division row i
//! (i < 2F); 2F+1. after comparing 2·rem with |X|; 2F+2. after quantisation, before
//! saturation. At max_stages every register-to-register path holds about one row's logic
//! (a W-bit subtract and a mux).

use rust_hdl::prelude::*;

use super::division_row::DivisionRow;
use super::fit::Fit;
use super::round::SignedRound;
use crate::macros::clock;
use crate::pipe::{chain, placement, Pipe};

/// W: the format's width, F its fraction bits; Q = 2F+1 (quotient bits);
/// K = max(2F+2, W) (the signed quotient); RND: round to nearest; SAT: saturate.
#[derive(LogicBlock)]
pub struct FixedRecip<
    const W: usize,
    const F: usize,
    const Q: usize,
    const K: usize,
    const RND: bool,
    const SAT: bool,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    negative: Signal<Local, Bit>,
    unit: Signal<Local, Bit>,
    operand_divisor: Pipe<Bits<W>>,
    operand_remainder: Pipe<Bits<W>>,
    operand_quotient: Pipe<Bits<Q>>,
    operand_negative: Pipe<Bit>,
    operand_zero: Pipe<Bit>,
    rows: Vec<DivisionRow<W, Q>>,
    row_remainder: Vec<Pipe<Bits<W>>>,
    row_quotient: Vec<Pipe<Bits<Q>>>,
    row_divisor: Vec<Pipe<Bits<W>>>,
    row_negative: Vec<Pipe<Bit>>,
    row_zero: Vec<Pipe<Bit>>,
    remainder: Signal<Local, Bits<W>>,
    quotient: Signal<Local, Bits<Q>>,
    divisor: Signal<Local, Bits<W>>,
    quotient_negative: Signal<Local, Bit>,
    quotient_zero: Signal<Local, Bit>,
    doubled: Signal<Local, Bits<W>>,
    decided_magnitude: Pipe<Bits<K>>,
    decided_round: Pipe<Bit>,
    decided_sticky: Pipe<Bit>,
    decided_negative: Pipe<Bit>,
    decided_zero: Pipe<Bit>,
    rounder: SignedRound<K, RND>,
    rounded: Pipe<Bits<K>>,
    rounded_zero: Pipe<Bit>,
    fit: Fit<K, W, SAT>,
    sign_shift: Constant<Bits<8>>,
    zero: Constant<Bits<W>>,
    one: Constant<Bits<W>>,
    minus_one: Constant<Bits<W>>,
    quotient_one: Constant<Bits<Q>>,
    quotient_zero_bits: Constant<Bits<Q>>,
    max: Constant<Bits<W>>,
}

impl<
        const W: usize,
        const F: usize,
        const Q: usize,
        const K: usize,
        const RND: bool,
        const SAT: bool,
    > FixedRecip<W, F, Q, K, RND, SAT>
{
    pub const CUTS: usize = 2 * F + 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            F >= 1 && F < W && Q == 2 * F + 1 && K == W.max(2 * F + 2),
            "FixedRecip: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        let rows = &cut[1..=2 * F];
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            negative: Default::default(),
            unit: Default::default(),
            operand_divisor: Pipe::new(cut[0]),
            operand_remainder: Pipe::new(cut[0]),
            operand_quotient: Pipe::new(cut[0]),
            operand_negative: Pipe::new(cut[0]),
            operand_zero: Pipe::new(cut[0]),
            rows: (0..2 * F).map(|_| Default::default()).collect(),
            row_remainder: chain(rows),
            row_quotient: chain(rows),
            row_divisor: chain(rows),
            row_negative: chain(rows),
            row_zero: chain(rows),
            remainder: Default::default(),
            quotient: Default::default(),
            divisor: Default::default(),
            quotient_negative: Default::default(),
            quotient_zero: Default::default(),
            doubled: Default::default(),
            decided_magnitude: Pipe::new(cut[2 * F + 1]),
            decided_round: Pipe::new(cut[2 * F + 1]),
            decided_sticky: Pipe::new(cut[2 * F + 1]),
            decided_negative: Pipe::new(cut[2 * F + 1]),
            decided_zero: Pipe::new(cut[2 * F + 1]),
            rounder: Default::default(),
            rounded: Pipe::new(cut[2 * F + 2]),
            rounded_zero: Pipe::new(cut[2 * F + 2]),
            fit: Default::default(),
            sign_shift: Constant::new((W - 1).to_bits()),
            zero: Constant::new(Bits::<W>::default()),
            one: Constant::new(1.into()),
            minus_one: Constant::new(Bits::<W>::mask()),
            quotient_one: Constant::new(1.into()),
            quotient_zero_bits: Constant::new(Bits::<Q>::default()),
            max: Constant::new(Bits::<W>::mask() >> 1),
        }
    }
}

impl<
        const W: usize,
        const F: usize,
        const Q: usize,
        const K: usize,
        const RND: bool,
        const SAT: bool,
    > Logic for FixedRecip<W, F, Q, K, RND, SAT>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.negative.next = (self.a.val() >> self.sign_shift.val()).any();
        self.unit.next = (self.a.val() == self.one.val()) | (self.a.val() == self.minus_one.val());
        // Cut 0: |X| (min's magnitude 2^(W-1) is right as an unsigned number) and the
        // numerator's first quotient bit.
        clock!(
            self,
            clock,
            operand_divisor,
            operand_remainder,
            operand_quotient,
            operand_negative,
            operand_zero
        );
        if self.negative.val() {
            self.operand_divisor.d.next = self.zero.val() - self.a.val();
        } else {
            self.operand_divisor.d.next = self.a.val();
        }
        if self.unit.val() {
            self.operand_remainder.d.next = self.zero.val();
            self.operand_quotient.d.next = self.quotient_one.val();
        } else {
            self.operand_remainder.d.next = self.one.val();
            self.operand_quotient.d.next = self.quotient_zero_bits.val();
        }
        self.operand_negative.d.next = self.negative.val();
        self.operand_zero.d.next = !self.a.val().any();
        // Row i reads cut i and feeds cut i + 1.
        self.rows[0].remainder_in.next = self.operand_remainder.q.val();
        self.rows[0].quotient_in.next = self.operand_quotient.q.val();
        self.rows[0].divisor.next = self.operand_divisor.q.val();
        self.row_negative[0].d.next = self.operand_negative.q.val();
        self.row_zero[0].d.next = self.operand_zero.q.val();
        for i in 1..self.rows.len() {
            self.rows[i].remainder_in.next = self.row_remainder[i - 1].q.val();
            self.rows[i].quotient_in.next = self.row_quotient[i - 1].q.val();
            self.rows[i].divisor.next = self.row_divisor[i - 1].q.val();
            self.row_negative[i].d.next = self.row_negative[i - 1].q.val();
            self.row_zero[i].d.next = self.row_zero[i - 1].q.val();
        }
        for i in 0..self.rows.len() {
            clock!(
                self,
                clock,
                row_remainder[i],
                row_quotient[i],
                row_divisor[i],
                row_negative[i],
                row_zero[i]
            );
            self.row_remainder[i].d.next = self.rows[i].remainder_out.val();
            self.row_quotient[i].d.next = self.rows[i].quotient_out.val();
            self.row_divisor[i].d.next = self.rows[i].divisor.val();
            // The last row's pipes are the divider's result (the last assignment wins).
            self.remainder.next = self.row_remainder[i].q.val();
            self.quotient.next = self.row_quotient[i].q.val();
            self.divisor.next = self.row_divisor[i].q.val();
            self.quotient_negative.next = self.row_negative[i].q.val();
            self.quotient_zero.next = self.row_zero[i].q.val();
        }
        // rem < |X| ≤ 2^(W-1), so 2·rem fits in W bits.
        self.doubled.next = self.remainder.val() << 1;
        // Cut 2F+1.
        clock!(
            self,
            clock,
            decided_magnitude,
            decided_round,
            decided_sticky,
            decided_negative,
            decided_zero
        );
        self.decided_magnitude.d.next = bit_cast::<K, Q>(self.quotient.val());
        self.decided_round.d.next = self.doubled.val() >= self.divisor.val();
        self.decided_sticky.d.next =
            self.remainder.val().any() & (self.doubled.val() != self.divisor.val());
        self.decided_negative.d.next = self.quotient_negative.val();
        self.decided_zero.d.next = self.quotient_zero.val();
        self.rounder.negative.next = self.decided_negative.q.val();
        self.rounder.magnitude.next = self.decided_magnitude.q.val();
        self.rounder.round.next = self.decided_round.q.val();
        self.rounder.sticky.next = self.decided_sticky.q.val();
        // Cut 2F+2.
        clock!(self, clock, rounded, rounded_zero);
        self.rounded.d.next = self.rounder.value.val();
        self.rounded_zero.d.next = self.decided_zero.q.val();
        self.fit.v.next = self.rounded.q.val();
        if self.rounded_zero.q.val() {
            self.y.next = self.max.val();
        } else {
            self.y.next = self.fit.y.val();
        }
    }
}

crate::impl_operator!(unary FixedRecip<W, F, Q, K, RND, SAT>,
    [const W: usize, const F: usize, const Q: usize, const K: usize, const RND: bool, const SAT: bool],
    W, W, out = bits);
