//! Step 1 of the bfp filter: a − b of two fp32 numbers as an integer, bit for bit
//! `hw_model::dual::bfp::translate`. Both significands are signed and moved up by the
//! guard bits; the one with the smaller exponent is shifted right arithmetically by the
//! exponent difference (floor: its lost bits are dropped); then one 29-bit subtraction. No
//! rounding and no normalisation. One register stage: the result the cycle after its inputs.

use hw_model::dual::bfp::GUARD_BITS;
use rust_hdl::prelude::*;

/// fp32's significand with its hidden bit, and its exponent field.
pub const SIGNIFICAND_BITS: usize = 24;
pub const FIELD_BITS: usize = 8;

/// Width of the difference: a significand, the guard bits, a sign and a carry.
pub const DIFF_BITS: usize = SIGNIFICAND_BITS + GUARD_BITS as usize + 2;

/// Cycles from the inputs to `d` and `e`.
pub const LATENCY: usize = 1;

/// `d`·2^(`e` − 150 − GUARD_BITS) = a − b (subnormals read as 0); `d` is two's complement,
/// `e` the larger exponent field.
#[derive(LogicBlock)]
pub struct Translate {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<32>>,
    pub b: Signal<In, Bits<32>>,
    pub d: Signal<Out, Bits<DIFF_BITS>>,
    pub e: Signal<Out, Bits<FIELD_BITS>>,
    d_reg: DFF<Bits<DIFF_BITS>>,
    e_reg: DFF<Bits<FIELD_BITS>>,
    hidden: Constant<Bits<DIFF_BITS>>,
    one: Constant<Bits<DIFF_BITS>>,
    /// The difference's sign bit (a Rust constant as a bit index would reach the Verilog as
    /// an undefined name).
    sign: Constant<Bits<DIFF_BITS>>,
    guard: Constant<Bits<FIELD_BITS>>,
    /// The largest shift that still matters: beyond it only the sign is left.
    max_shift: Constant<Bits<FIELD_BITS>>,
    ea: Signal<Local, Bits<FIELD_BITS>>,
    eb: Signal<Local, Bits<FIELD_BITS>>,
    /// The signed significands, moved up by the guard bits.
    sa: Signal<Local, Bits<DIFF_BITS>>,
    sb: Signal<Local, Bits<DIFF_BITS>>,
    shift: Signal<Local, Bits<FIELD_BITS>>,
    /// The operand with the smaller exponent, before and after its arithmetic shift.
    lesser: Signal<Local, Bits<DIFF_BITS>>,
    shifted: Signal<Local, Bits<DIFF_BITS>>,
}

impl Default for Translate {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            d: Default::default(),
            e: Default::default(),
            d_reg: Default::default(),
            e_reg: Default::default(),
            hidden: Constant::new((1u64 << 23).to_bits()),
            one: Constant::new(1u64.to_bits()),
            sign: Constant::new((1u64 << (DIFF_BITS - 1)).to_bits()),
            guard: Constant::new((GUARD_BITS as u64).to_bits()),
            max_shift: Constant::new(((DIFF_BITS - 1) as u64).to_bits()),
            ea: Default::default(),
            eb: Default::default(),
            sa: Default::default(),
            sb: Default::default(),
            shift: Default::default(),
            lesser: Default::default(),
            shifted: Default::default(),
        }
    }
}

impl Logic for Translate {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, d_reg, e_reg);
        self.ea.next = self.a.val().get_bits::<8>(23);
        self.eb.next = self.b.val().get_bits::<8>(23);
        // Significand with its hidden bit (0 for a zero or a flushed subnormal), signed.
        self.sa.next = 0.into();
        if self.ea.val().any() {
            self.sa.next = (self.hidden.val()
                | bit_cast::<DIFF_BITS, 23>(self.a.val().get_bits::<23>(0)))
                << self.guard.val();
        }
        if self.a.val().get_bit(31) {
            self.sa.next = !self.sa.val() + self.one.val();
        }
        self.sb.next = 0.into();
        if self.eb.val().any() {
            self.sb.next = (self.hidden.val()
                | bit_cast::<DIFF_BITS, 23>(self.b.val().get_bits::<23>(0)))
                << self.guard.val();
        }
        if self.b.val().get_bit(31) {
            self.sb.next = !self.sb.val() + self.one.val();
        }
        if self.ea.val() >= self.eb.val() {
            self.shift.next = self.ea.val() - self.eb.val();
            self.lesser.next = self.sb.val();
            self.e_reg.d.next = self.ea.val();
        } else {
            self.shift.next = self.eb.val() - self.ea.val();
            self.lesser.next = self.sa.val();
            self.e_reg.d.next = self.eb.val();
        }
        if self.shift.val() > self.max_shift.val() {
            self.shift.next = self.max_shift.val();
        }
        // Arithmetic shift right: a negative value's complement shifts in zeros.
        self.shifted.next = self.lesser.val() >> self.shift.val();
        if (self.lesser.val() & self.sign.val()).any() {
            self.shifted.next = !(!self.lesser.val() >> self.shift.val());
        }
        if self.ea.val() >= self.eb.val() {
            self.d_reg.d.next = self.sa.val() - self.shifted.val();
        } else {
            self.d_reg.d.next = self.shifted.val() - self.sb.val();
        }
        self.d.next = self.d_reg.q.val();
        self.e.next = self.e_reg.q.val();
    }
}
