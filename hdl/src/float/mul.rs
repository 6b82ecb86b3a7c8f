//! Float multiplication `y = a × b` (RNE, FTZ, see the SPEC in `hw_model::format`).
//!
//! Cut points (registers are spread over them by `pipe::placement`; max_stages() = 3):
//!   0. after the significand multiplier (the DSP output register), exponent sum, category
//!   1. after normalization, before rounding and packing
//!   2. the result, after rounding and packing
//!
//! stages = 1 registers the normalized product, 2 the multiplier output and the result.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::intmul::IntMul;
use crate::pipe::{placement, Pipe};

/// E, M: the format; W = 1+E+M; S = M+1; S2 = 2S; X = exponent width (≥ E+2)
/// ([`crate::widths::FloatWidths`]).
#[derive(LogicBlock)]
pub struct FloatMul<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const S2: usize,
    const X: usize,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    unpack_a: Unpack<E, M, W, S>,
    unpack_b: Unpack<E, M, W, S>,
    exp_sum: Signal<Local, Bits<X>>,
    category: Signal<Local, ResultClass>,
    multiplier: IntMul<S, S, S2>,
    product: Pipe<Bits<S2>>,
    product_exp: Pipe<Bits<X>>,
    product_class: Pipe<ResultClass>,
    product_top: Signal<Local, Bit>,
    product_normalized: Signal<Local, Bits<S2>>,
    normal_sig: Pipe<Bits<S>>,
    normal_round: Pipe<Bit>,
    normal_sticky: Pipe<Bit>,
    normal_exp: Pipe<Bits<X>>,
    normal_class: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, X>,
    result: Pipe<Bits<W>>,
    exp_offset: Signal<Local, Bits<X>>,
    minus_bias: Constant<Bits<X>>,
    one_minus_bias: Constant<Bits<X>>,
    top_bit: Constant<Bits<S2>>,
    sig_width: Constant<Bits<8>>,
    round_bit: Constant<Bits<S2>>,
    sticky_bits: Constant<Bits<S2>>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const S2: usize,
        const X: usize,
    > FloatMul<E, M, W, S, S2, X>
{
    pub const CUTS: usize = 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(S2 == 2 * S && X >= E + 2, "FloatMul: inconsistent widths");
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            unpack_a: Default::default(),
            unpack_b: Default::default(),
            exp_sum: Default::default(),
            category: Default::default(),
            multiplier: Default::default(),
            product: Pipe::new(cut[0]),
            product_exp: Pipe::new(cut[0]),
            product_class: Pipe::new(cut[0]),
            product_top: Default::default(),
            product_normalized: Default::default(),
            normal_sig: Pipe::new(cut[1]),
            normal_round: Pipe::new(cut[1]),
            normal_sticky: Pipe::new(cut[1]),
            normal_exp: Pipe::new(cut[1]),
            normal_class: Pipe::new(cut[1]),
            rounder: Default::default(),
            result: Pipe::new(cut[2]),
            exp_offset: Default::default(),
            // −bias in X-bit two's complement.
            minus_bias: Constant::new(((1u64 << X) - ((1u64 << (E - 1)) - 1)).into()),
            one_minus_bias: Constant::new(((1u64 << X) - ((1u64 << (E - 1)) - 2)).into()),
            top_bit: Constant::new(Bits::<S2>::from(1) << (S2 - 1) as u64),
            sig_width: Constant::new(S.to_bits()),
            round_bit: Constant::new(Bits::<S2>::from(1) << (S - 1) as u64),
            sticky_bits: Constant::new((Bits::<S2>::from(1) << (S - 1) as u64) - 1),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const S2: usize,
        const X: usize,
    > Logic for FloatMul<E, M, W, S, S2, X>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack_a.x.next = self.a.val();
        self.unpack_b.x.next = self.b.val();
        // The sum of the biased exponents; the bias is taken off with normalization's +1, in
        // one adder (a three-operand sum would be two carry chains).
        self.exp_sum.next =
            bit_cast::<X, E>(self.unpack_a.exp.val()) + bit_cast::<X, E>(self.unpack_b.exp.val());
        self.category.next.sign = self.unpack_a.sign.val() ^ self.unpack_b.sign.val();
        self.category.next.nan = self.unpack_a.nan.val()
            | self.unpack_b.nan.val()
            | (self.unpack_a.zero.val() & self.unpack_b.inf.val())
            | (self.unpack_a.inf.val() & self.unpack_b.zero.val());
        self.category.next.inf = self.unpack_a.inf.val() | self.unpack_b.inf.val();
        self.category.next.zero = self.unpack_a.zero.val() | self.unpack_b.zero.val();
        self.multiplier.a.next = self.unpack_a.sig.val();
        self.multiplier.b.next = self.unpack_b.sig.val();
        // Cut 0: synthesis packs these registers into the DSP slices.
        clock!(self, clock, product, product_exp, product_class);
        self.product.d.next = self.multiplier.p.val();
        self.product_exp.d.next = self.exp_sum.val();
        self.product_class.d.next = self.category.val();
        // The product of two significands in [1, 2) is in [1, 4): bring its leading 1 to the top.
        self.product_top.next = (self.product.q.val() & self.top_bit.val()).any();
        if self.product_top.val() {
            self.product_normalized.next = self.product.q.val();
        } else {
            self.product_normalized.next = self.product.q.val() << 1;
        }
        // Cut 1.
        clock!(
            self,
            clock,
            normal_sig,
            normal_round,
            normal_sticky,
            normal_exp,
            normal_class
        );
        self.normal_sig.d.next =
            bit_cast::<S, S2>(self.product_normalized.val() >> self.sig_width.val());
        self.normal_round.d.next = (self.product_normalized.val() & self.round_bit.val()).any();
        self.normal_sticky.d.next = (self.product_normalized.val() & self.sticky_bits.val()).any();
        self.exp_offset.next = self.minus_bias.val();
        if self.product_top.val() {
            self.exp_offset.next = self.one_minus_bias.val();
        }
        self.normal_exp.d.next = self.product_exp.q.val() + self.exp_offset.val();
        self.normal_class.d.next = self.product_class.q.val();
        self.rounder.category.next = self.normal_class.q.val();
        self.rounder.exp.next = self.normal_exp.q.val();
        self.rounder.sig.next = self.normal_sig.q.val();
        self.rounder.round.next = self.normal_round.q.val();
        self.rounder.sticky.next = self.normal_sticky.q.val();
        // Cut 2.
        clock!(self, clock, result);
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(binary FloatMul<E, M, W, S, S2, X>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const S2: usize, const X: usize],
    W, W, out = bits);
