//! Rounds a normalized result to the format and packs it: round to nearest even, overflow to
//! ±Inf, flush to ±0 when the rounded result is below the smallest normal (tininess after
//! rounding), and the special results (canonical NaN, ±Inf, ±0) the operator decided on.

use rust_hdl::prelude::*;

/// What an operator knows about its result besides the significand: the sign, and whether
/// the result is NaN, ±Inf or ±0 regardless of rounding (priority in that order).
#[derive(Clone, Copy, Debug, Default, PartialEq, LogicStruct)]
pub struct ResultClass {
    pub sign: Bit,
    pub nan: Bit,
    pub inf: Bit,
    pub zero: Bit,
}

/// E, M: the format; W = 1 + E + M; S = M + 1; S1 = S + 1; X: width of the signed exponent.
#[derive(LogicBlock)]
pub struct Round<const E: usize, const M: usize, const W: usize, const S: usize, const S1: usize, const X: usize> {
    pub category: Signal<In, ResultClass>,
    /// Biased exponent of `sig`'s leading bit, two's complement (may be out of range).
    pub exp: Signal<In, Bits<X>>,
    /// Significand with its leading 1 at the top bit.
    pub sig: Signal<In, Bits<S>>,
    /// The first bit below `sig`.
    pub round: Signal<In, Bit>,
    /// Whether any bit below `round` is set.
    pub sticky: Signal<In, Bit>,
    pub y: Signal<Out, Bits<W>>,
    rounded: Signal<Local, Bits<S1>>,
    carry: Signal<Local, Bit>,
    exp_rounded: Signal<Local, Bits<X>>,
    exp_field: Signal<Local, Bits<E>>,
    frac: Signal<Local, Bits<M>>,
    tiny: Signal<Local, Bit>,
    huge: Signal<Local, Bit>,
    sign_bit: Signal<Local, Bits<W>>,
    frac_width: Constant<Bits<8>>,
    carry_bit: Constant<Bits<S1>>,
    exp_negative: Constant<Bits<X>>,
    exp_inf: Constant<Bits<X>>,
    sign_mask: Constant<Bits<W>>,
    inf_pattern: Constant<Bits<W>>,
    nan_pattern: Constant<Bits<W>>,
    zero_pattern: Constant<Bits<W>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const S1: usize, const X: usize> Default
    for Round<E, M, W, S, S1, X>
{
    fn default() -> Self {
        assert!(W == 1 + E + M && S == M + 1 && S1 == S + 1 && X > E + 1, "Round: inconsistent widths");
        let exp_ones = (1u64 << E) - 1;
        Self {
            category: Default::default(),
            exp: Default::default(),
            sig: Default::default(),
            round: Default::default(),
            sticky: Default::default(),
            y: Default::default(),
            rounded: Default::default(),
            carry: Default::default(),
            exp_rounded: Default::default(),
            exp_field: Default::default(),
            frac: Default::default(),
            tiny: Default::default(),
            huge: Default::default(),
            sign_bit: Default::default(),
            frac_width: Constant::new(M.to_bits()),
            carry_bit: Constant::new(Bits::<S1>::from(1) << S as u64),
            exp_negative: Constant::new(Bits::<X>::from(1) << (X - 1) as u64),
            exp_inf: Constant::new(exp_ones.into()),
            sign_mask: Constant::new(Bits::<W>::from(1) << (W - 1) as u64),
            inf_pattern: Constant::new((exp_ones << M).into()),
            nan_pattern: Constant::new(((exp_ones << M) | (1 << (M - 1))).into()),
            zero_pattern: Constant::new(Bits::<W>::default()),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const S1: usize, const X: usize> Logic
    for Round<E, M, W, S, S1, X>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.rounded.next = bit_cast::<S1, S>(self.sig.val())
            + (self.round.val() & (self.sticky.val() | self.sig.val().get_bit(0)));
        self.carry.next = (self.rounded.val() & self.carry_bit.val()).any();
        self.exp_rounded.next = self.exp.val() + self.carry.val();
        self.exp_field.next = bit_cast::<E, X>(self.exp_rounded.val());
        self.frac.next = bit_cast::<M, S1>(self.rounded.val());
        self.tiny.next = (self.exp_rounded.val() >= self.exp_negative.val()) | !self.exp_rounded.val().any();
        self.huge.next = (self.exp_rounded.val() < self.exp_negative.val()) & (self.exp_rounded.val() >= self.exp_inf.val());
        self.sign_bit.next = self.zero_pattern.val();
        if self.category.val().sign {
            self.sign_bit.next = self.sign_mask.val();
        }
        if self.category.val().nan {
            self.y.next = self.nan_pattern.val();
        } else if self.category.val().inf | self.huge.val() {
            self.y.next = self.sign_bit.val() | self.inf_pattern.val();
        } else if self.category.val().zero | self.tiny.val() {
            self.y.next = self.sign_bit.val();
        } else {
            // The carry of a rounding overflow leaves the fraction bits 0: 1.11..1 + ulp = 10.00..0.
            self.y.next = self.sign_bit.val()
                | (bit_cast::<W, E>(self.exp_field.val()) << self.frac_width.val())
                | bit_cast::<W, M>(self.frac.val());
        }
    }
}
