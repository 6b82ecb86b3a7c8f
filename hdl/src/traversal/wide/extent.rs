//! One axis's bound on the node's extent in t, from exponents alone (docs/wide-nodes.md,
//! step 2): `max(α_b, e + inv_b + 8, pad_b) − 124` in biased exponents, absent (all ones)
//! when the reciprocal is flushed or not finite or `α` or `pad_t` is not finite.
//! Combinational; [`super::grid::NodeGrid`] registers it.

use rust_hdl::prelude::*;

use super::Word;

/// An 11-bit two's complement value with its sign bit flipped: unsigned order is signed order.
pub type Ordered = Bits<11>;

#[derive(LogicBlock)]
pub struct AxisExtent {
    pub alpha: Signal<In, Word>,
    pub inv_dir: Signal<In, Word>,
    pub pad_t: Signal<In, Word>,
    /// The node's grid exponent (i8).
    pub exp: Signal<In, Bits<8>>,
    pub bound: Signal<Out, Ordered>,
    alpha_exp: Signal<Local, Bits<8>>,
    inv_exp: Signal<Local, Bits<8>>,
    pad_exp: Signal<Local, Bits<8>>,
    exp_wide: Signal<Local, Ordered>,
    slope_term: Signal<Local, Ordered>,
    alpha_term: Signal<Local, Ordered>,
    pad_term: Signal<Local, Ordered>,
    flip: Constant<Ordered>,
    exp_sign: Constant<Ordered>,
    slope_bias: Constant<Ordered>,
    bound_bias: Constant<Ordered>,
    absent: Constant<Ordered>,
}

impl Default for AxisExtent {
    fn default() -> Self {
        Self {
            alpha: Default::default(),
            inv_dir: Default::default(),
            pad_t: Default::default(),
            exp: Default::default(),
            bound: Default::default(),
            alpha_exp: Default::default(),
            inv_exp: Default::default(),
            pad_exp: Default::default(),
            exp_wide: Default::default(),
            slope_term: Default::default(),
            alpha_term: Default::default(),
            pad_term: Default::default(),
            flip: Constant::new(0x400.into()),
            exp_sign: Constant::new(0x700.into()),
            // e + inv_b + 8 − 124, flipped (+ 0x400), e sign-extended.
            slope_bias: Constant::new((0x400 - 116).into()),
            // b − 124 of a non-negative b, flipped: (b | 0x400) − 124.
            bound_bias: Constant::new((0x800 - 124).into()),
            absent: Constant::new(0x7FF.into()),
        }
    }
}

impl Logic for AxisExtent {
    #[hdl_gen]
    fn update(&mut self) {
        self.alpha_exp.next = self.alpha.val().get_bits::<8>(23);
        self.inv_exp.next = self.inv_dir.val().get_bits::<8>(23);
        self.pad_exp.next = self.pad_t.val().get_bits::<8>(23);
        self.exp_wide.next = bit_cast::<11, 8>(self.exp.val());
        if self.exp.val().get_bit(7) {
            self.exp_wide.next = self.exp_wide.val() | self.exp_sign.val();
        }
        self.slope_term.next =
            self.exp_wide.val() + bit_cast::<11, 8>(self.inv_exp.val()) + self.slope_bias.val();
        self.alpha_term.next =
            (bit_cast::<11, 8>(self.alpha_exp.val()) | self.flip.val()) + self.bound_bias.val();
        self.pad_term.next =
            (bit_cast::<11, 8>(self.pad_exp.val()) | self.flip.val()) + self.bound_bias.val();
        self.bound.next = self.alpha_term.val();
        if (self.slope_term.val() > self.alpha_term.val())
            & (self.slope_term.val() >= self.pad_term.val())
        {
            self.bound.next = self.slope_term.val();
        } else if self.pad_term.val() > self.alpha_term.val() {
            self.bound.next = self.pad_term.val();
        }
        if !self.inv_exp.val().any()
            | self.inv_exp.val().all()
            | self.alpha_exp.val().all()
            | self.pad_exp.val().all()
        {
            self.bound.next = self.absent.val();
        }
    }
}
