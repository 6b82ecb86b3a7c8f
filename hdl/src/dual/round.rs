//! Step 5 of the bfp filter, its normaliser: an integer at a given exponent to a short float
//! rounded outward, bit for bit `hw_model::dual::bfp::round`. The mantissa's bit count (of
//! x XOR its sign) decides the shift that leaves `SHORT_BITS` signed bits; the arithmetic
//! shift rounds down, and rounding up adds one if a shifted-out bit was set. A value that
//! already fits keeps its exponent. Two register stages, so that neither the leading-bit
//! search nor the shift and increment lengthen a pipeline stage of `Decide`: the bit count,
//! then the short float.

use hw_model::dual::bfp::{widths, Vector, EXP_MAX, EXP_MIN, SHORT_BITS};
use rust_hdl::prelude::*;

use super::WIDTH;

/// Clock edges from `x`, `e` to `m`, `f`.
pub const LATENCY: usize = 2;

/// A short float's mantissa: `SHORT_BITS` signed bits and one more for the carry of a
/// rounding up (2^(SHORT_BITS − 1) itself).
pub const SHORT_M_BITS: usize = SHORT_BITS as usize + 1;

/// How far any exponent of step 5 reaches (in magnitude, loosely): a triple of block
/// exponents, the two widest mantissas below it (a value's last bit), fp32's last bit
/// (2^-150, t_min's) and the range row's 2^±126.
const EXP_REACH: u32 = 3 * max(EXP_MAX.unsigned_abs(), EXP_MIN.unsigned_abs())
    + 2 * widths(WIDTH)[Vector::S as usize]
    + 150
    + 126;

const fn max(a: u32, b: u32) -> u32 {
    if a > b {
        a
    } else {
        b
    }
}

/// Two's-complement width of step 5's exponents: every exponent of [`EXP_REACH`] fits.
pub const SHORT_EXP_BITS: usize = (u32::BITS - EXP_REACH.leading_zeros()) as usize + 1;

/// `x`·2^`e` (IW-bit two's complement, `e` signed) as `m`·2^`f` with `m` at most
/// `SHORT_BITS` signed bits (one more when rounding up carries), rounded down (UP = false:
/// the shift alone) or up (UP = true: plus one if a dropped bit was set).
#[derive(LogicBlock)]
pub struct Round<const IW: usize, const UP: bool> {
    pub clock: Signal<In, Clock>,
    pub x: Signal<In, Bits<IW>>,
    pub e: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub m: Signal<Out, Bits<SHORT_M_BITS>>,
    pub f: Signal<Out, Bits<SHORT_EXP_BITS>>,
    /// UP as a bit (a const generic used as a value would reach the Verilog as a bare name).
    up: Constant<Bit>,
    sign: Constant<Bits<IW>>,
    ones: Constant<Bits<IW>>,
    one: Constant<Bits<SHORT_EXP_BITS>>,
    one_m: Constant<Bits<SHORT_M_BITS>>,
    /// SHORT_BITS − 1: the magnitude bits a short mantissa holds.
    keep: Constant<Bits<SHORT_EXP_BITS>>,
    /// Stage 1: x, e and the bit count of x XOR its sign.
    x_reg: DFF<Bits<IW>>,
    e_reg: DFF<Bits<SHORT_EXP_BITS>>,
    length_reg: DFF<Bits<SHORT_EXP_BITS>>,
    /// Stage 2: the short float.
    m_reg: DFF<Bits<SHORT_M_BITS>>,
    f_reg: DFF<Bits<SHORT_EXP_BITS>>,
    negative: Signal<Local, Bit>,
    magnitude: Signal<Local, Bits<IW>>,
    length: Signal<Local, Bits<SHORT_EXP_BITS>>,
    held_negative: Signal<Local, Bit>,
    shift: Signal<Local, Bits<SHORT_EXP_BITS>>,
    shifted: Signal<Local, Bits<IW>>,
    /// A shifted-out bit was set.
    sticky: Signal<Local, Bit>,
}

/// The two directions of the filter's bounds, per input width.
pub type RoundUp<const IW: usize> = Round<IW, true>;
pub type RoundDown<const IW: usize> = Round<IW, false>;

impl<const IW: usize, const UP: bool> Default for Round<IW, UP> {
    fn default() -> Self {
        let exp = |v: u64| Constant::new(v.to_bits());
        Self {
            clock: Default::default(),
            x: Default::default(),
            e: Default::default(),
            m: Default::default(),
            f: Default::default(),
            up: Constant::new(UP),
            sign: Constant::new(Bits::<IW>::from(1) << (IW as u64 - 1)),
            ones: Constant::new(!Bits::<IW>::default()),
            one: exp(1),
            one_m: Constant::new(1u64.to_bits()),
            keep: exp(u64::from(SHORT_BITS) - 1),
            x_reg: Default::default(),
            e_reg: Default::default(),
            length_reg: Default::default(),
            m_reg: Default::default(),
            f_reg: Default::default(),
            negative: Default::default(),
            held_negative: Default::default(),
            magnitude: Default::default(),
            length: Default::default(),
            shift: Default::default(),
            shifted: Default::default(),
            sticky: Default::default(),
        }
    }
}

impl<const IW: usize, const UP: bool> Logic for Round<IW, UP> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, x_reg, e_reg, length_reg, m_reg, f_reg);
        // Stage 1: the bit count of x XOR its sign.
        self.negative.next = (self.x.val() & self.sign.val()).any();
        self.magnitude.next = self.x.val();
        if self.negative.val() {
            self.magnitude.next = !self.x.val();
        }
        self.length.next = 0.into();
        for i in 0..IW {
            if self.magnitude.val().get_bit(i) {
                self.length.next = i.to_bits() + self.one.val();
            }
        }
        self.x_reg.d.next = self.x.val();
        self.e_reg.d.next = self.e.val();
        self.length_reg.d.next = self.length.val();
        // Stage 2: fits already (at most SHORT_BITS signed bits): kept, at its own exponent.
        self.held_negative.next = (self.x_reg.q.val() & self.sign.val()).any();
        self.m_reg.d.next = bit_cast::<SHORT_M_BITS, IW>(self.x_reg.q.val());
        self.f_reg.d.next = self.e_reg.q.val();
        self.shift.next = 0.into();
        self.shifted.next = self.x_reg.q.val();
        self.sticky.next = false;
        if self.length_reg.q.val() > self.keep.val() {
            self.shift.next = self.length_reg.q.val() - self.keep.val();
            // Arithmetic shift right (down, towards −∞): a negative value's complement
            // shifts in zeros.
            self.shifted.next = self.x_reg.q.val() >> self.shift.val();
            if self.held_negative.val() {
                self.shifted.next = !(!self.x_reg.q.val() >> self.shift.val());
            }
            self.sticky.next = (self.x_reg.q.val() & !(self.ones.val() << self.shift.val())).any();
            self.m_reg.d.next = bit_cast::<SHORT_M_BITS, IW>(self.shifted.val());
            if self.up.val() && self.sticky.val() {
                self.m_reg.d.next =
                    bit_cast::<SHORT_M_BITS, IW>(self.shifted.val()) + self.one_m.val();
            }
            self.f_reg.d.next = self.e_reg.q.val() + self.shift.val();
        }
        self.m.next = self.m_reg.q.val();
        self.f.next = self.f_reg.q.val();
    }
}
