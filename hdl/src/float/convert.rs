//! Conversions between fp32 and a float format with E ≤ 8, M ≤ 23: `FromF32` rounds (RNE,
//! FTZ, overflow to Inf), `ToF32` is exact (subnormal inputs flush to ±0, NaN → canonical).
//!
//! Cut points: FromF32 (max_stages() = 2): 0. before rounding, 1. the result; ToF32
//! (max_stages() = 1): 0. the result. One FromF32 register goes to the result.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// fp32 → (E, M). W = 1+E+M; S = M+1; X = 10 (fp32's exponent range, signed).
#[derive(LogicBlock)]
pub struct FloatFromF32<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const X: usize,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<32>>,
    pub y: Signal<Out, Bits<W>>,
    unpack: Unpack<8, 23, 32, 24>,
    category: Signal<Local, ResultClass>,
    narrow_sig: Pipe<Bits<S>>,
    narrow_round: Pipe<Bit>,
    narrow_sticky: Pipe<Bit>,
    narrow_exp: Pipe<Bits<X>>,
    narrow_category: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, X>,
    result: Pipe<Bits<W>>,
    dropped_bits: Constant<Bits<8>>,
    round_bit: Constant<Bits<24>>,
    sticky_bits: Constant<Bits<24>>,
    rebias: Constant<Bits<X>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const X: usize>
    FloatFromF32<E, M, W, S, X>
{
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            E <= 8 && M <= 23 && X >= 10,
            "FloatFromF32: formats up to fp32 only"
        );
        let cut = placement(stages, Self::CUTS);
        let dropped = 23 - M;
        let round_bit = if dropped > 0 {
            1u64 << (dropped - 1)
        } else {
            0
        };
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            category: Default::default(),
            narrow_sig: Pipe::new(cut[0]),
            narrow_round: Pipe::new(cut[0]),
            narrow_sticky: Pipe::new(cut[0]),
            narrow_exp: Pipe::new(cut[0]),
            narrow_category: Pipe::new(cut[0]),
            rounder: Default::default(),
            result: Pipe::new(cut[1]),
            dropped_bits: Constant::new((dropped as u64).into()),
            round_bit: Constant::new(round_bit.into()),
            sticky_bits: Constant::new(round_bit.saturating_sub(1).into()),
            rebias: Constant::new((127 - ((1u64 << (E - 1)) - 1)).into()),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const X: usize> Logic
    for FloatFromF32<E, M, W, S, X>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        self.category.next.sign = self.unpack.sign.val();
        self.category.next.nan = self.unpack.nan.val();
        self.category.next.inf = self.unpack.inf.val();
        self.category.next.zero = self.unpack.zero.val();
        clock!(
            self,
            clock,
            narrow_sig,
            narrow_round,
            narrow_sticky,
            narrow_exp,
            narrow_category
        );
        self.narrow_sig.d.next =
            bit_cast::<S, 24>(self.unpack.sig.val() >> self.dropped_bits.val());
        self.narrow_round.d.next = (self.unpack.sig.val() & self.round_bit.val()).any();
        self.narrow_sticky.d.next = (self.unpack.sig.val() & self.sticky_bits.val()).any();
        self.narrow_exp.d.next = bit_cast::<X, 8>(self.unpack.exp.val()) - self.rebias.val();
        self.narrow_category.d.next = self.category.val();
        self.rounder.category.next = self.narrow_category.q.val();
        self.rounder.exp.next = self.narrow_exp.q.val();
        self.rounder.sig.next = self.narrow_sig.q.val();
        self.rounder.round.next = self.narrow_round.q.val();
        self.rounder.sticky.next = self.narrow_sticky.q.val();
        clock!(self, clock, result);
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary FloatFromF32<E, M, W, S, X>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize],
    32, W, out = bits);

/// (E, M) → fp32. W = 1+E+M; S = M+1.
#[derive(LogicBlock)]
pub struct FloatToF32<const E: usize, const M: usize, const W: usize, const S: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<32>>,
    unpack: Unpack<E, M, W, S>,
    sign_bit: Signal<Local, Bits<32>>,
    exp32: Signal<Local, Bits<8>>,
    result: Pipe<Bits<32>>,
    rebias: Constant<Bits<8>>,
    frac_shift: Constant<Bits<8>>,
    frac_mask: Constant<Bits<32>>,
    exp_shift: Constant<Bits<8>>,
    sign_mask: Constant<Bits<32>>,
    inf: Constant<Bits<32>>,
    nan: Constant<Bits<32>>,
    zero: Constant<Bits<32>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> FloatToF32<E, M, W, S> {
    pub const CUTS: usize = 1;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(E <= 8 && M <= 23, "FloatToF32: formats up to fp32 only");
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            sign_bit: Default::default(),
            exp32: Default::default(),
            result: Pipe::new(cut[0]),
            rebias: Constant::new((127 - ((1u64 << (E - 1)) - 1)).into()),
            frac_shift: Constant::new(((23 - M) as u64).into()),
            frac_mask: Constant::new(0x7f_ffff.into()),
            exp_shift: Constant::new(23.into()),
            sign_mask: Constant::new(0x8000_0000u64.into()),
            inf: Constant::new(0x7f80_0000.into()),
            nan: Constant::new(0x7fc0_0000.into()),
            zero: Constant::new(0.into()),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> Logic
    for FloatToF32<E, M, W, S>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        self.sign_bit.next = self.zero.val();
        if self.unpack.sign.val() {
            self.sign_bit.next = self.sign_mask.val();
        }
        self.exp32.next = bit_cast::<8, E>(self.unpack.exp.val()) + self.rebias.val();
        clock!(self, clock, result);
        if self.unpack.nan.val() {
            self.result.d.next = self.nan.val();
        } else if self.unpack.inf.val() {
            self.result.d.next = self.sign_bit.val() | self.inf.val();
        } else if self.unpack.zero.val() {
            self.result.d.next = self.sign_bit.val();
        } else {
            self.result.d.next = self.sign_bit.val()
                | (bit_cast::<32, 8>(self.exp32.val()) << self.exp_shift.val())
                | ((bit_cast::<32, S>(self.unpack.sig.val()) << self.frac_shift.val())
                    & self.frac_mask.val());
        }
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary FloatToF32<E, M, W, S>,
    [const E: usize, const M: usize, const W: usize, const S: usize],
    W, 32, out = bits);
