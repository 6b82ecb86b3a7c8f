//! Quantises a sign-magnitude result to a signed integer: the division and the fp32
//! conversion produce |x| = magnitude + fraction, and the SPEC's modes act on the signed x.
//!
//! With `round` = (fraction ≥ 1/2) and `sticky` = (fraction ∉ {0, 1/2}):
//!   Trn (toward −∞): x ≥ 0 keeps the magnitude, x < 0 adds 1 to it when the fraction ≠ 0;
//!   Rnd (ties toward +∞): x ≥ 0 adds `round`, x < 0 adds 1 only above one half.
//! The negation shares the incrementer: −(m + inc) = !m + (1 − inc).

use rust_hdl::prelude::*;

/// K: width of the magnitude and of the signed result (the magnitude + 1 must be < 2^(K-1)).
#[derive(LogicBlock)]
pub struct SignedRound<const K: usize, const RND: bool> {
    pub negative: Signal<In, Bit>,
    pub magnitude: Signal<In, Bits<K>>,
    pub round: Signal<In, Bit>,
    pub sticky: Signal<In, Bit>,
    /// The quantised value, two's complement.
    pub value: Signal<Out, Bits<K>>,
    increment: Signal<Local, Bit>,
    /// 1 − increment, as its own 1-bit signal: written inline as `!increment` inside the
    /// K-bit sum, Verilog widens the operand to K bits before inverting it (−1, not 1).
    keep: Signal<Local, Bit>,
    nearest: Constant<Bit>,
}

impl<const K: usize, const RND: bool> Default for SignedRound<K, RND> {
    fn default() -> Self {
        Self {
            negative: Default::default(),
            magnitude: Default::default(),
            round: Default::default(),
            sticky: Default::default(),
            value: Default::default(),
            increment: Default::default(),
            keep: Default::default(),
            nearest: Constant::new(RND),
        }
    }
}

impl<const K: usize, const RND: bool> Logic for SignedRound<K, RND> {
    #[hdl_gen]
    fn update(&mut self) {
        if self.nearest.val() {
            if self.negative.val() {
                self.increment.next = self.round.val() & self.sticky.val();
            } else {
                self.increment.next = self.round.val();
            }
        } else {
            self.increment.next = self.negative.val() & (self.round.val() | self.sticky.val());
        }
        self.keep.next = !self.increment.val();
        if self.negative.val() {
            self.value.next = !self.magnitude.val() + self.keep.val();
        } else {
            self.value.next = self.magnitude.val() + self.increment.val();
        }
    }
}
