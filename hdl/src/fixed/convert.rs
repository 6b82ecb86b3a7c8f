//! Conversions between fp32 and a fixed-point format (the SPEC in `hw_model::format`).
//!
//! `FromF32`: NaN → 0, ±Inf → max/min in either overflow mode, zeros and subnormals → 0;
//! a finite value sig·2^(e−150) is sig·2^k in units of 2^-F (k = e − 150 + F). One left
//! shift by k + 25 puts it over 25 guard bits: above them the magnitude, then the round bit,
//! then the sticky bits. k is clamped to [−25, W]: below, the magnitude is 0 and only the
//! sticky bit is set; above, the low W bits are 0 and the value is out of range, as it is
//! for any larger k. A magnitude ≥ 2^W is out of range whatever its sign, and only its low
//! W bits matter to Wrap, so it is kept as those bits plus bit W = "≥ 2^W": the rounding
//! and the overflow logic stay W+3 bits wide. `SignedRound` quantises, `Fit` applies the
//! overflow mode.
//! Cut points (max_stages() = 2): 0. after the alignment shift; 1. after quantisation.
//!
//! `ToF32`: |x| is normalized (leading one to the top) and rounded once, RNE, by the float
//! operators' `Round` for fp32; every catalogue value is an fp32 normal number.
//! Cut points (max_stages() = 2): 0. after taking |x|; 1. after normalization.

use rust_hdl::prelude::*;

use super::fit::Fit;
use super::round::SignedRound;
use crate::float::round::{ResultClass, Round};
use crate::float::unpack::Unpack;
use crate::pipe::{placement, Pipe};

/// Guard bits below the units of 2^-F in `FromF32`'s alignment: fp32's 24-bit significand
/// shifted right by 25 leaves no bit at or above the round position.
const GUARD: usize = 25;

/// fp32 → fixed. W: the format's width, F its fraction bits; L = W + 49 (the aligned
/// significand); K = W + 3 (the signed magnitude); RND: round to nearest; SAT: saturate.
#[derive(LogicBlock)]
pub struct FixedFromF32<
    const W: usize,
    const F: usize,
    const L: usize,
    const K: usize,
    const RND: bool,
    const SAT: bool,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<32>>,
    pub y: Signal<Out, Bits<W>>,
    unpack: Unpack<8, 23, 32, 24>,
    exponent: Signal<Local, Bits<10>>,
    amount: Signal<Local, Bits<10>>,
    flushed_sig: Signal<Local, Bits<24>>,
    aligned: Signal<Local, Bits<L>>,
    magnitude: Pipe<Bits<K>>,
    round: Pipe<Bit>,
    sticky: Pipe<Bit>,
    negative: Pipe<Bit>,
    nan: Pipe<Bit>,
    inf: Pipe<Bit>,
    rounder: SignedRound<K, RND>,
    rounded: Pipe<Bits<K>>,
    rounded_negative: Pipe<Bit>,
    rounded_nan: Pipe<Bit>,
    rounded_inf: Pipe<Bit>,
    fit: Fit<K, W, SAT>,
    exponent_offset: Constant<Bits<10>>,
    exponent_negative: Constant<Bits<10>>,
    amount_limit: Constant<Bits<10>>,
    guard: Constant<Bits<8>>,
    round_bit: Constant<Bits<L>>,
    sticky_bits: Constant<Bits<L>>,
    overflow_shift: Constant<Bits<8>>,
    low_bits: Constant<Bits<K>>,
    overflow_bit: Constant<Bits<K>>,
    no_amount: Constant<Bits<10>>,
    zero: Constant<Bits<W>>,
    max: Constant<Bits<W>>,
    min: Constant<Bits<W>>,
}

impl<
        const W: usize,
        const F: usize,
        const L: usize,
        const K: usize,
        const RND: bool,
        const SAT: bool,
    > FixedFromF32<W, F, L, K, RND, SAT>
{
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            L == W + 24 + GUARD && K == W + 3 && F < W && W <= 64,
            "FixedFromF32: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            exponent: Default::default(),
            amount: Default::default(),
            flushed_sig: Default::default(),
            aligned: Default::default(),
            magnitude: Pipe::new(cut[0]),
            round: Pipe::new(cut[0]),
            sticky: Pipe::new(cut[0]),
            negative: Pipe::new(cut[0]),
            nan: Pipe::new(cut[0]),
            inf: Pipe::new(cut[0]),
            rounder: Default::default(),
            rounded: Pipe::new(cut[1]),
            rounded_negative: Pipe::new(cut[1]),
            rounded_nan: Pipe::new(cut[1]),
            rounded_inf: Pipe::new(cut[1]),
            fit: Default::default(),
            // k + GUARD = e − 150 + F + GUARD, in 10-bit two's complement.
            exponent_offset: Constant::new(((1024 + F + GUARD - 150) as u64 % 1024).into()),
            exponent_negative: Constant::new((1u64 << 9).into()),
            amount_limit: Constant::new(((W + GUARD) as u64).into()),
            guard: Constant::new(GUARD.to_bits()),
            round_bit: Constant::new(Bits::<L>::from(1) << (GUARD - 1) as u64),
            sticky_bits: Constant::new((Bits::<L>::from(1) << (GUARD - 1) as u64) - 1),
            overflow_shift: Constant::new((W + GUARD).to_bits()),
            low_bits: Constant::new(Bits::<K>::mask() >> (K - W) as u64),
            overflow_bit: Constant::new(Bits::<K>::from(1) << W as u64),
            no_amount: Constant::new(0.into()),
            zero: Constant::new(Bits::<W>::default()),
            max: Constant::new(Bits::<W>::mask() >> 1),
            min: Constant::new(Bits::<W>::from(1) << (W - 1) as u64),
        }
    }
}

impl<
        const W: usize,
        const F: usize,
        const L: usize,
        const K: usize,
        const RND: bool,
        const SAT: bool,
    > Logic for FixedFromF32<W, F, L, K, RND, SAT>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        self.exponent.next = bit_cast::<10, 8>(self.unpack.exp.val()) + self.exponent_offset.val();
        if (self.exponent.val() & self.exponent_negative.val()).any() {
            self.amount.next = self.no_amount.val();
        } else if self.exponent.val() > self.amount_limit.val() {
            self.amount.next = self.amount_limit.val();
        } else {
            self.amount.next = self.exponent.val();
        }
        // Unpack leaves a subnormal's fraction in `sig`; here it would set the sticky bit.
        self.flushed_sig.next = 0.into();
        if !self.unpack.zero.val() {
            self.flushed_sig.next = self.unpack.sig.val();
        }
        self.aligned.next = bit_cast::<L, 24>(self.flushed_sig.val()) << self.amount.val();
        // Cut 0.
        clock!(self, clock, magnitude, round, sticky, negative, nan, inf);
        self.magnitude.d.next =
            bit_cast::<K, L>(self.aligned.val() >> self.guard.val()) & self.low_bits.val();
        if (self.aligned.val() >> self.overflow_shift.val()).any() {
            self.magnitude.d.next = (bit_cast::<K, L>(self.aligned.val() >> self.guard.val())
                & self.low_bits.val())
                | self.overflow_bit.val();
        }
        self.round.d.next = (self.aligned.val() & self.round_bit.val()).any();
        self.sticky.d.next = (self.aligned.val() & self.sticky_bits.val()).any();
        self.negative.d.next = self.unpack.sign.val();
        self.nan.d.next = self.unpack.nan.val();
        self.inf.d.next = self.unpack.inf.val();
        self.rounder.negative.next = self.negative.q.val();
        self.rounder.magnitude.next = self.magnitude.q.val();
        self.rounder.round.next = self.round.q.val();
        self.rounder.sticky.next = self.sticky.q.val();
        // Cut 1.
        clock!(
            self,
            clock,
            rounded,
            rounded_negative,
            rounded_nan,
            rounded_inf
        );
        self.rounded.d.next = self.rounder.value.val();
        self.rounded_negative.d.next = self.negative.q.val();
        self.rounded_nan.d.next = self.nan.q.val();
        self.rounded_inf.d.next = self.inf.q.val();
        self.fit.v.next = self.rounded.q.val();
        if self.rounded_nan.q.val() {
            self.y.next = self.zero.val();
        } else if self.rounded_inf.q.val() {
            if self.rounded_negative.q.val() {
                self.y.next = self.min.val();
            } else {
                self.y.next = self.max.val();
            }
        } else {
            self.y.next = self.fit.y.val();
        }
    }
}

crate::impl_operator!(unary FixedFromF32<W, F, L, K, RND, SAT>,
    [const W: usize, const F: usize, const L: usize, const K: usize, const RND: bool, const SAT: bool],
    32, W, out = bits);

/// fixed → fp32. W: the format's width, F its fraction bits; G = W + 25 (the normalized
/// magnitude over fp32's significand and round bit).
#[derive(LogicBlock)]
pub struct FixedToF32<const W: usize, const F: usize, const G: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<32>>,
    sign: Signal<Local, Bit>,
    magnitude: Pipe<Bits<W>>,
    magnitude_sign: Pipe<Bit>,
    leading_one: Signal<Local, Bits<8>>,
    normalized: Signal<Local, Bits<W>>,
    extended: Signal<Local, Bits<G>>,
    category: Signal<Local, ResultClass>,
    normal_sig: Pipe<Bits<24>>,
    normal_round: Pipe<Bit>,
    normal_sticky: Pipe<Bit>,
    normal_exp: Pipe<Bits<10>>,
    normal_category: Pipe<ResultClass>,
    rounder: Round<8, 23, 32, 24, 10>,
    /// W-1: the sign bit's position, and where normalization puts the leading one.
    msb: Constant<Bits<8>>,
    guard: Constant<Bits<8>>,
    sig_shift: Constant<Bits<8>>,
    round_bit: Constant<Bits<G>>,
    sticky_bits: Constant<Bits<G>>,
    exp_base: Constant<Bits<10>>,
    zero: Constant<Bits<W>>,
}

impl<const W: usize, const F: usize, const G: usize> FixedToF32<W, F, G> {
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            G == W + GUARD && F < W && W <= 64,
            "FixedToF32: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            sign: Default::default(),
            magnitude: Pipe::new(cut[0]),
            magnitude_sign: Pipe::new(cut[0]),
            leading_one: Default::default(),
            normalized: Default::default(),
            extended: Default::default(),
            category: Default::default(),
            normal_sig: Pipe::new(cut[1]),
            normal_round: Pipe::new(cut[1]),
            normal_sticky: Pipe::new(cut[1]),
            normal_exp: Pipe::new(cut[1]),
            normal_category: Pipe::new(cut[1]),
            rounder: Default::default(),
            msb: Constant::new((W - 1).to_bits()),
            guard: Constant::new(GUARD.to_bits()),
            sig_shift: Constant::new((G - 24).to_bits()),
            round_bit: Constant::new(Bits::<G>::from(1) << (G - 25) as u64),
            sticky_bits: Constant::new((Bits::<G>::from(1) << (G - 25) as u64) - 1),
            // The leading one at bit p is worth 2^(p−F): biased exponent p + 127 − F.
            exp_base: Constant::new(((127 - F) as u64).into()),
            zero: Constant::new(Bits::<W>::default()),
        }
    }
}

impl<const W: usize, const F: usize, const G: usize> Logic for FixedToF32<W, F, G> {
    #[hdl_gen]
    fn update(&mut self) {
        self.sign.next = (self.a.val() >> self.msb.val()).any();
        // Cut 0: |x| (min's magnitude 2^(W-1) is right as an unsigned number).
        clock!(self, clock, magnitude, magnitude_sign);
        if self.sign.val() {
            self.magnitude.d.next = self.zero.val() - self.a.val();
        } else {
            self.magnitude.d.next = self.a.val();
        }
        self.magnitude_sign.d.next = self.sign.val();
        self.leading_one.next = 0.into();
        for i in 0..W {
            if self.magnitude.q.val().get_bit(i) {
                self.leading_one.next = i.to_bits();
            }
        }
        self.normalized.next = self.magnitude.q.val() << (self.msb.val() - self.leading_one.val());
        // The leading one at bit G-1: fp32's 24 significand bits, the round bit, then sticky bits.
        self.extended.next = bit_cast::<G, W>(self.normalized.val()) << self.guard.val();
        self.category.next.sign = self.magnitude_sign.q.val();
        self.category.next.nan = false;
        self.category.next.inf = false;
        self.category.next.zero = !self.magnitude.q.val().any();
        // Cut 1.
        clock!(
            self,
            clock,
            normal_sig,
            normal_round,
            normal_sticky,
            normal_exp,
            normal_category
        );
        self.normal_sig.d.next = bit_cast::<24, G>(self.extended.val() >> self.sig_shift.val());
        self.normal_round.d.next = (self.extended.val() & self.round_bit.val()).any();
        self.normal_sticky.d.next = (self.extended.val() & self.sticky_bits.val()).any();
        self.normal_exp.d.next = bit_cast::<10, 8>(self.leading_one.val()) + self.exp_base.val();
        self.normal_category.d.next = self.category.val();
        self.rounder.category.next = self.normal_category.q.val();
        self.rounder.exp.next = self.normal_exp.q.val();
        self.rounder.sig.next = self.normal_sig.q.val();
        self.rounder.round.next = self.normal_round.q.val();
        self.rounder.sticky.next = self.normal_sticky.q.val();
        self.y.next = self.rounder.y.val();
    }
}

crate::impl_operator!(unary FixedToF32<W, F, G>, [const W: usize, const F: usize, const G: usize], W, 32, out = bits);
