//! Float comparison `y = a < b` (false if either is NaN, −0 == +0, subnormals are zeros).
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
    magnitude_a: Signal<Local, Bits<W>>,
    magnitude_b: Signal<Local, Bits<W>>,
    result: Pipe<Bit>,
    magnitude: Constant<Bits<W>>,
    zero: Constant<Bits<W>>,
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
            magnitude_a: Default::default(),
            magnitude_b: Default::default(),
            result: Pipe::new(cut[0]),
            magnitude: Constant::new(Bits::<W>::mask() >> 1),
            zero: Constant::new(Bits::<W>::default()),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> Logic for FloatLt<E, M, W, S> {
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack_a.x.next = self.a.val();
        self.unpack_b.x.next = self.b.val();
        // Magnitudes order like the bit patterns without the sign; subnormals count as 0.
        self.magnitude_a.next = self.a.val() & self.magnitude.val();
        if self.unpack_a.zero.val() {
            self.magnitude_a.next = self.zero.val();
        }
        self.magnitude_b.next = self.b.val() & self.magnitude.val();
        if self.unpack_b.zero.val() {
            self.magnitude_b.next = self.zero.val();
        }
        self.result.clock.next = self.clock.val();
        self.result.d.next = !(self.unpack_a.nan.val() | self.unpack_b.nan.val())
            & ((!self.unpack_a.sign.val() & !self.unpack_b.sign.val() & (self.magnitude_a.val() < self.magnitude_b.val()))
                | (self.unpack_a.sign.val() & self.unpack_b.sign.val() & (self.magnitude_a.val() > self.magnitude_b.val()))
                | (self.unpack_a.sign.val()
                    & !self.unpack_b.sign.val()
                    & (self.magnitude_a.val().any() | self.magnitude_b.val().any())));
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FloatLt<E, M, W, S>,
    [const E: usize, const M: usize, const W: usize, const S: usize],
    W, 1, out = bit);
