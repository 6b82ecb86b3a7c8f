//! Fixed-point addition and subtraction `y = a ± b`: the exact (W+1)-bit sum, then the
//! overflow mode (no fraction bits are lost, so quantisation never acts).
//!
//! Cut points (max_stages() = 2): 0. after the adder; 1. the output (after saturation).

use rust_hdl::prelude::*;

use super::fit::Fit;
use crate::pipe::{placement, Pipe};

/// W: the format's width; W1 = W+1 (exact sum); SAT: saturate; SUB: subtract instead of add.
#[derive(LogicBlock)]
pub struct FixedAdd<const W: usize, const W1: usize, const SAT: bool, const SUB: bool> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    a_wide: Signal<Local, Bits<W1>>,
    b_wide: Signal<Local, Bits<W1>>,
    sum: Pipe<Bits<W1>>,
    fit: Fit<W1, W, SAT>,
    result: Pipe<Bits<W>>,
    subtract: Constant<Bit>,
    sign_shift: Constant<Bits<8>>,
    extension: Constant<Bits<W1>>,
}

impl<const W: usize, const W1: usize, const SAT: bool, const SUB: bool> FixedAdd<W, W1, SAT, SUB> {
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(W1 == W + 1, "FixedAdd: inconsistent widths");
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            a_wide: Default::default(),
            b_wide: Default::default(),
            sum: Pipe::new(cut[0]),
            fit: Default::default(),
            result: Pipe::new(cut[1]),
            subtract: Constant::new(SUB),
            sign_shift: Constant::new((W - 1).to_bits()),
            extension: Constant::new(Bits::<W1>::from(1) << W as u64),
        }
    }
}

impl<const W: usize, const W1: usize, const SAT: bool, const SUB: bool> Logic
    for FixedAdd<W, W1, SAT, SUB>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Sign-extend both operands by one bit: the exact sum or difference fits.
        self.a_wide.next = bit_cast::<W1, W>(self.a.val());
        if (self.a.val() >> self.sign_shift.val()).any() {
            self.a_wide.next = bit_cast::<W1, W>(self.a.val()) | self.extension.val();
        }
        self.b_wide.next = bit_cast::<W1, W>(self.b.val());
        if (self.b.val() >> self.sign_shift.val()).any() {
            self.b_wide.next = bit_cast::<W1, W>(self.b.val()) | self.extension.val();
        }
        clock!(self, clock, sum);
        if self.subtract.val() {
            self.sum.d.next = self.a_wide.val() - self.b_wide.val();
        } else {
            self.sum.d.next = self.a_wide.val() + self.b_wide.val();
        }
        self.fit.v.next = self.sum.q.val();
        clock!(self, clock, result);
        self.result.d.next = self.fit.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FixedAdd<W, W1, SAT, SUB>,
    [const W: usize, const W1: usize, const SAT: bool, const SUB: bool],
    W, W, out = bits);
