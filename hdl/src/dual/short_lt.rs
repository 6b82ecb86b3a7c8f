//! Step 5 of the bfp filter, its comparator: x < y between two short floats at any
//! exponents, bit for bit `hw_model::dual::bfp::Fx::lt`. Different signs (negative, zero,
//! positive) decide alone; equal signs compare the leading bits' exponents (exponent plus
//! the magnitude's bit count), and equal leading bits compare the magnitudes normalised to
//! the same leading position. Combinational: `Decide` holds the registers.

use rust_hdl::prelude::*;

use super::round::{SHORT_EXP_BITS, SHORT_M_BITS};

/// `lt` = x < y for x = `xm`·2^`xe`, y = `ym`·2^`ye` (M-bit two's-complement mantissas,
/// signed exponents).
#[derive(LogicBlock)]
pub struct ShortLt<const M: usize> {
    pub xm: Signal<In, Bits<M>>,
    pub xe: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub ym: Signal<In, Bits<M>>,
    pub ye: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub lt: Signal<Out, Bit>,
    sign: Constant<Bits<M>>,
    one: Constant<Bits<M>>,
    one_e: Constant<Bits<SHORT_EXP_BITS>>,
    width: Constant<Bits<SHORT_EXP_BITS>>,
    /// The exponents' sign bit: flipped, signed order is unsigned order.
    exp_sign: Constant<Bits<SHORT_EXP_BITS>>,
    x_neg: Signal<Local, Bit>,
    y_neg: Signal<Local, Bit>,
    x_zero: Signal<Local, Bit>,
    y_zero: Signal<Local, Bit>,
    /// |m| (unsigned: −2^(M−1) reads as 2^(M−1)), its bit count, the leading bit's exponent
    /// (offset binary) and the magnitude with its leading bit at M − 1.
    x_mag: Signal<Local, Bits<M>>,
    y_mag: Signal<Local, Bits<M>>,
    x_len: Signal<Local, Bits<SHORT_EXP_BITS>>,
    y_len: Signal<Local, Bits<SHORT_EXP_BITS>>,
    x_top: Signal<Local, Bits<SHORT_EXP_BITS>>,
    y_top: Signal<Local, Bits<SHORT_EXP_BITS>>,
    x_norm: Signal<Local, Bits<M>>,
    y_norm: Signal<Local, Bits<M>>,
}

impl<const M: usize> Default for ShortLt<M> {
    fn default() -> Self {
        let exp = |v: u64| Constant::new(v.to_bits());
        Self {
            xm: Default::default(),
            xe: Default::default(),
            ym: Default::default(),
            ye: Default::default(),
            lt: Default::default(),
            sign: Constant::new(Bits::<M>::from(1) << (M as u64 - 1)),
            one: Constant::new(1u64.to_bits()),
            one_e: exp(1),
            width: exp(M as u64),
            exp_sign: exp(1 << (SHORT_EXP_BITS - 1)),
            x_neg: Default::default(),
            y_neg: Default::default(),
            x_zero: Default::default(),
            y_zero: Default::default(),
            x_mag: Default::default(),
            y_mag: Default::default(),
            x_len: Default::default(),
            y_len: Default::default(),
            x_top: Default::default(),
            y_top: Default::default(),
            x_norm: Default::default(),
            y_norm: Default::default(),
        }
    }
}

/// The comparator at the short floats' width.
pub type Lt = ShortLt<SHORT_M_BITS>;

impl<const M: usize> Logic for ShortLt<M> {
    #[hdl_gen]
    fn update(&mut self) {
        self.x_neg.next = (self.xm.val() & self.sign.val()).any();
        self.y_neg.next = (self.ym.val() & self.sign.val()).any();
        self.x_zero.next = !self.xm.val().any();
        self.y_zero.next = !self.ym.val().any();
        self.x_mag.next = self.xm.val();
        if self.x_neg.val() {
            self.x_mag.next = !self.xm.val() + self.one.val();
        }
        self.y_mag.next = self.ym.val();
        if self.y_neg.val() {
            self.y_mag.next = !self.ym.val() + self.one.val();
        }
        self.x_len.next = 0.into();
        self.y_len.next = 0.into();
        for i in 0..M {
            if self.x_mag.val().get_bit(i) {
                self.x_len.next = i.to_bits() + self.one_e.val();
            }
            if self.y_mag.val().get_bit(i) {
                self.y_len.next = i.to_bits() + self.one_e.val();
            }
        }
        self.x_top.next = (self.xe.val() + self.x_len.val()) ^ self.exp_sign.val();
        self.y_top.next = (self.ye.val() + self.y_len.val()) ^ self.exp_sign.val();
        self.x_norm.next = self.x_mag.val() << (self.width.val() - self.x_len.val());
        self.y_norm.next = self.y_mag.val() << (self.width.val() - self.y_len.val());
        if self.x_neg.val() != self.y_neg.val() || self.x_zero.val() || self.y_zero.val() {
            // Negative < zero < positive.
            self.lt.next = (self.x_neg.val() && !self.y_neg.val())
                || (self.x_zero.val() && !self.y_zero.val() && !self.y_neg.val());
        } else if self.x_top.val() != self.y_top.val() {
            // The larger leading bit is the larger magnitude.
            self.lt.next = (self.x_top.val() < self.y_top.val()) != self.x_neg.val();
        } else {
            self.lt.next = (self.x_norm.val() < self.y_norm.val()) != self.x_neg.val();
            if self.x_norm.val() == self.y_norm.val() {
                self.lt.next = false;
            }
        }
    }
}
