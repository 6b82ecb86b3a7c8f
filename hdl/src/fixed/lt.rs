//! Fixed-point comparison `y = a < b` (signed).
//!
//! Cut points (max_stages() = 1): 0. the output.

use rust_hdl::prelude::*;

use crate::pipe::{placement, Pipe};

/// W: the format's width.
#[derive(LogicBlock)]
pub struct FixedLt<const W: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bit>,
    result: Pipe<Bit>,
    sign_bit: Constant<Bits<W>>,
}

impl<const W: usize> FixedLt<W> {
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
            result: Pipe::new(cut[0]),
            sign_bit: Constant::new(Bits::<W>::from(1) << (W - 1) as u64),
        }
    }
}

impl<const W: usize> Logic for FixedLt<W> {
    #[hdl_gen]
    fn update(&mut self) {
        // Flipping the sign bit maps two's complement order onto unsigned order.
        clock!(self, clock, result);
        self.result.d.next =
            (self.a.val() ^ self.sign_bit.val()) < (self.b.val() ^ self.sign_bit.val());
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FixedLt<W>, [const W: usize], W, 1, out = bit);
