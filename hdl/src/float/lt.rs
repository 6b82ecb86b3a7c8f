//! Float comparison `y = a < b` (false if either is NaN, −0 == +0, subnormals are zeros).
//!
//! The magnitudes are compared in three parts side by side (the exponent and the two halves
//! of the fraction) rather than as one (W−1)-bit compare, so the path is two short carry
//! chains and a few LUTs instead of one long chain.
//!
//! Cut points (max_stages() = 1): 0. the output.

use rust_hdl::prelude::*;

use super::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// E, M: the format; W = 1+E+M; S = M+1.
#[derive(LogicBlock)]
pub struct FloatLt<const E: usize, const M: usize, const W: usize, const S: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bit>,
    unpack_a: Unpack<E, M, W, S>,
    unpack_b: Unpack<E, M, W, S>,
    frac_high_a: Signal<Local, Bits<W>>,
    frac_high_b: Signal<Local, Bits<W>>,
    frac_low_a: Signal<Local, Bits<W>>,
    frac_low_b: Signal<Local, Bits<W>>,
    frac_less: Signal<Local, Bit>,
    frac_greater: Signal<Local, Bit>,
    /// Equal, nonzero exponents: the fractions decide.
    same_binade: Signal<Local, Bit>,
    a_smaller: Signal<Local, Bit>,
    b_smaller: Signal<Local, Bit>,
    result: Pipe<Bit>,
    frac_high: Constant<Bits<W>>,
    frac_low: Constant<Bits<W>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> FloatLt<E, M, W, S> {
    pub const CUTS: usize = 1;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            unpack_a: Default::default(),
            unpack_b: Default::default(),
            frac_high_a: Default::default(),
            frac_high_b: Default::default(),
            frac_low_a: Default::default(),
            frac_low_b: Default::default(),
            frac_less: Default::default(),
            frac_greater: Default::default(),
            same_binade: Default::default(),
            a_smaller: Default::default(),
            b_smaller: Default::default(),
            result: Pipe::new(cut[0]),
            frac_high: Constant::new(
                ((Bits::<W>::from(1) << M as u64) - 1)
                    & !((Bits::<W>::from(1) << (M / 2) as u64) - 1),
            ),
            frac_low: Constant::new((Bits::<W>::from(1) << (M / 2) as u64) - 1),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> Logic for FloatLt<E, M, W, S> {
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack_a.x.next = self.a.val();
        self.unpack_b.x.next = self.b.val();
        // Magnitudes order like the bit patterns without the sign; subnormals count as 0, so
        // with equal exponents the fractions only decide when the exponent is not 0.
        self.frac_high_a.next = self.a.val() & self.frac_high.val();
        self.frac_high_b.next = self.b.val() & self.frac_high.val();
        self.frac_low_a.next = self.a.val() & self.frac_low.val();
        self.frac_low_b.next = self.b.val() & self.frac_low.val();
        self.frac_less.next = (self.frac_high_a.val() < self.frac_high_b.val())
            | ((self.frac_high_a.val() == self.frac_high_b.val())
                & (self.frac_low_a.val() < self.frac_low_b.val()));
        self.frac_greater.next = (self.frac_high_a.val() > self.frac_high_b.val())
            | ((self.frac_high_a.val() == self.frac_high_b.val())
                & (self.frac_low_a.val() > self.frac_low_b.val()));
        self.same_binade.next =
            (self.unpack_a.exp.val() == self.unpack_b.exp.val()) & !self.unpack_a.zero.val();
        self.a_smaller.next = (self.unpack_a.exp.val() < self.unpack_b.exp.val())
            | (self.same_binade.val() & self.frac_less.val());
        self.b_smaller.next = (self.unpack_a.exp.val() > self.unpack_b.exp.val())
            | (self.same_binade.val() & self.frac_greater.val());
        clock!(self, clock, result);
        self.result.d.next = !(self.unpack_a.nan.val() | self.unpack_b.nan.val())
            & ((!self.unpack_a.sign.val() & !self.unpack_b.sign.val() & self.a_smaller.val())
                | (self.unpack_a.sign.val() & self.unpack_b.sign.val() & self.b_smaller.val())
                | (self.unpack_a.sign.val()
                    & !self.unpack_b.sign.val()
                    & !(self.unpack_a.zero.val() & self.unpack_b.zero.val())));
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FloatLt<E, M, W, S>,
    [const E: usize, const M: usize, const W: usize, const S: usize],
    W, 1, out = bit);
