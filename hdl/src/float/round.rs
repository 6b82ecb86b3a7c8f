//! Rounds a normalized result to the format and packs it: round to nearest even, overflow to
//! ±Inf, flush to ±0 when the rounded result is below the smallest normal (tininess after
//! rounding), and the special results (canonical NaN, ±Inf, ±0) the operator decided on.
//!
//! Short paths: the fraction is incremented while the rounding decision is made, whether rounding carries into the exponent (the significand is all ones and
//! rounds up) is an AND tree beside the fraction increment, and the overflow/underflow tests
//! are made on the unrounded exponent for both outcomes (as is the exponent increment) and then
//! selected, so no carry chain waits for the rounding decision.

use rust_hdl::prelude::*;

/// What an operator knows about its result besides the significand: the sign, and whether
/// the result is NaN, ±Inf or ±0 regardless of rounding and of `exp` (priority in that order).
#[derive(Clone, Copy, Debug, Default, PartialEq, LogicStruct)]
pub struct ResultClass {
    pub sign: Bit,
    pub nan: Bit,
    pub inf: Bit,
    pub zero: Bit,
}

/// E, M: the format; W = 1 + E + M; S = M + 1; X: width of the signed exponent.
#[derive(LogicBlock)]
pub struct Round<const E: usize, const M: usize, const W: usize, const S: usize, const X: usize> {
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
    round_up: Signal<Local, Bit>,
    frac_up: Signal<Local, Bits<M>>,
    frac: Signal<Local, Bits<M>>,
    carry: Signal<Local, Bit>,
    negative: Signal<Local, Bit>,
    exp_field: Signal<Local, Bits<E>>,
    tiny: Signal<Local, Bit>,
    huge: Signal<Local, Bit>,
    sign_bit: Signal<Local, Bits<W>>,
    overflow: Signal<Local, Bit>,
    underflow: Signal<Local, Bit>,
    keep: Signal<Local, Bits<W>>,
    special: Signal<Local, Bits<W>>,
    frac_one: Constant<Bits<M>>,
    frac_half: Constant<Bits<8>>,
    exp_one: Constant<Bits<E>>,
    frac_low: Constant<Bits<M>>,
    frac_width: Constant<Bits<8>>,
    exp_negative: Constant<Bits<X>>,
    exp_inf: Constant<Bits<X>>,
    exp_below_inf: Constant<Bits<X>>,
    exp_zero: Constant<Bits<X>>,
    sign_mask: Constant<Bits<W>>,
    inf_pattern: Constant<Bits<W>>,
    nan_pattern: Constant<Bits<W>>,
    zero_pattern: Constant<Bits<W>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const X: usize> Default
    for Round<E, M, W, S, X>
{
    fn default() -> Self {
        assert!(
            W == 1 + E + M && S == M + 1 && X > E + 1,
            "Round: inconsistent widths"
        );
        let exp_ones = (1u64 << E) - 1;
        Self {
            category: Default::default(),
            exp: Default::default(),
            sig: Default::default(),
            round: Default::default(),
            sticky: Default::default(),
            y: Default::default(),
            round_up: Default::default(),
            frac_up: Default::default(),
            frac: Default::default(),
            carry: Default::default(),
            negative: Default::default(),
            exp_field: Default::default(),
            tiny: Default::default(),
            huge: Default::default(),
            sign_bit: Default::default(),
            overflow: Default::default(),
            underflow: Default::default(),
            keep: Default::default(),
            special: Default::default(),
            frac_one: Constant::new(1.into()),
            frac_half: Constant::new((M / 2).to_bits()),
            exp_one: Constant::new(1.into()),
            frac_low: Constant::new((Bits::<M>::from(1) << (M / 2) as u64) - 1),
            frac_width: Constant::new(M.to_bits()),
            exp_negative: Constant::new(Bits::<X>::from(1) << (X - 1) as u64),
            exp_inf: Constant::new(exp_ones.into()),
            exp_below_inf: Constant::new((exp_ones - 1).into()),
            exp_zero: Constant::new(Bits::<X>::default()),
            sign_mask: Constant::new(Bits::<W>::from(1) << (W - 1) as u64),
            inf_pattern: Constant::new((exp_ones << M).into()),
            nan_pattern: Constant::new(((exp_ones << M) | (1 << (M - 1))).into()),
            zero_pattern: Constant::new(Bits::<W>::default()),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize, const X: usize> Logic
    for Round<E, M, W, S, X>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.round_up.next = self.round.val() & (self.sticky.val() | self.sig.val().get_bit(0));
        // The carry of a rounding overflow leaves the fraction bits 0: 1.11..1 + ulp = 10.00..0.
        // The increment does not wait for the rounding decision, which only selects it.
        // It is a carry-select incrementer: two half-width chains side by side, the high half
        // taking its +1 when the low half is all ones.
        self.frac.next = bit_cast::<M, S>(self.sig.val());
        if (self.frac.val() & self.frac_low.val()) == self.frac_low.val() {
            self.frac_up.next = ((self.frac.val() >> self.frac_half.val()) + self.frac_one.val())
                << self.frac_half.val();
        } else {
            self.frac_up.next = (self.frac.val() & !self.frac_low.val())
                | (((self.frac.val() & self.frac_low.val()) + self.frac_one.val())
                    & self.frac_low.val());
        }
        if self.round_up.val() {
            self.frac.next = self.frac_up.val();
        }
        self.carry.next = self.round_up.val() & self.sig.val().all();
        self.negative.next = self.exp.val() >= self.exp_negative.val();
        // Underflow: the rounded exponent is ≤ 0; overflow: it is ≥ all ones.
        self.exp_field.next = bit_cast::<E, X>(self.exp.val());
        if self.carry.val() {
            self.exp_field.next = bit_cast::<E, X>(self.exp.val()) + self.exp_one.val();
            self.tiny.next = self.negative.val();
            self.huge.next = !self.negative.val() & (self.exp.val() >= self.exp_below_inf.val());
        } else {
            self.tiny.next = self.negative.val() | (self.exp.val() == self.exp_zero.val());
            self.huge.next = !self.negative.val() & (self.exp.val() >= self.exp_inf.val());
        }
        // The result's fields by AND/OR (a priority mux over the whole word maps onto mux trees):
        // NaN > Inf or overflow > zero or underflow > the rounded number.
        self.overflow.next = !self.category.val().nan
            & (self.category.val().inf | (self.huge.val() & !self.category.val().zero));
        self.underflow.next = !self.category.val().nan
            & !self.overflow.val()
            & (self.category.val().zero | self.tiny.val());
        self.keep.next = self.zero_pattern.val();
        if !(self.category.val().nan | self.overflow.val() | self.underflow.val()) {
            self.keep.next = !self.zero_pattern.val();
        }
        self.sign_bit.next = self.zero_pattern.val();
        if self.category.val().sign & !self.category.val().nan {
            self.sign_bit.next = self.sign_mask.val();
        }
        self.special.next = self.zero_pattern.val();
        if self.category.val().nan {
            self.special.next = self.nan_pattern.val();
        }
        if self.overflow.val() {
            self.special.next = self.inf_pattern.val();
        }
        self.y.next = self.sign_bit.val()
            | self.special.val()
            | (((bit_cast::<W, E>(self.exp_field.val()) << self.frac_width.val())
                | bit_cast::<W, M>(self.frac.val()))
                & self.keep.val());
    }
}
