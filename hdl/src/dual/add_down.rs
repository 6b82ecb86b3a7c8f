//! Step 5 of the bfp filter, its short adder: x + y of two short floats rounded down, bit
//! for bit `hw_model::dual::bfp::add_down`. Both operands are placed on a grid
//! `ADD_GUARD_BITS` below the larger one's short mantissa (up exactly, or down by an
//! arithmetic shift: floor), added, and normalised down by a [`Round`]; a zero operand
//! passes the other to the normaliser. The grid's sum is registered before the normaliser
//! (itself two stages), so that the alignment and the leading-bit search of the sum are not
//! one path.

use hw_model::dual::bfp::{ADD_GUARD_BITS, SHORT_BITS};
use rust_hdl::prelude::*;

use super::round::{Round, SHORT_EXP_BITS, SHORT_M_BITS};

/// Clock edges from the operands to the sum: the grid's sum, then the normaliser.
pub const LATENCY: usize = 1 + super::round::LATENCY;

/// The grid's sum: each operand below 2^(SHORT_BITS − 1 + ADD_GUARD_BITS) in magnitude, a
/// sign and a carry.
pub const ADD_BITS: usize = SHORT_BITS as usize + ADD_GUARD_BITS as usize + 1;

/// (`sm`, `se`) = down(x + y) for x = `xm`·2^`xe`, y = `ym`·2^`ye`.
#[derive(LogicBlock)]
pub struct AddDown {
    pub clock: Signal<In, Clock>,
    pub xm: Signal<In, Bits<SHORT_M_BITS>>,
    pub xe: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub ym: Signal<In, Bits<SHORT_M_BITS>>,
    pub ye: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub sm: Signal<Out, Bits<SHORT_M_BITS>>,
    pub se: Signal<Out, Bits<SHORT_EXP_BITS>>,
    /// The sum on the grid (or the non-zero operand) and its exponent.
    sum_reg: DFF<Bits<ADD_BITS>>,
    grid_reg: DFF<Bits<SHORT_EXP_BITS>>,
    round: Round<ADD_BITS, false>,
    sign: Constant<Bits<SHORT_M_BITS>>,
    /// The sign extension of a mantissa to the grid's width.
    extension: Constant<Bits<ADD_BITS>>,
    one_e: Constant<Bits<SHORT_EXP_BITS>>,
    /// SHORT_BITS − 1 + ADD_GUARD_BITS: the grid below the larger leading bit.
    below: Constant<Bits<SHORT_EXP_BITS>>,
    /// The largest right shift that still matters.
    max_shift: Constant<Bits<SHORT_EXP_BITS>>,
    exp_sign: Constant<Bits<SHORT_EXP_BITS>>,
    x_wide: Signal<Local, Bits<ADD_BITS>>,
    y_wide: Signal<Local, Bits<ADD_BITS>>,
    /// Each operand's leading bit (of m XOR its sign) plus one, as an exponent.
    x_len: Signal<Local, Bits<SHORT_EXP_BITS>>,
    y_len: Signal<Local, Bits<SHORT_EXP_BITS>>,
    x_top: Signal<Local, Bits<SHORT_EXP_BITS>>,
    y_top: Signal<Local, Bits<SHORT_EXP_BITS>>,
    grid: Signal<Local, Bits<SHORT_EXP_BITS>>,
    x_shift: Signal<Local, Bits<SHORT_EXP_BITS>>,
    y_shift: Signal<Local, Bits<SHORT_EXP_BITS>>,
    x_at: Signal<Local, Bits<ADD_BITS>>,
    y_at: Signal<Local, Bits<ADD_BITS>>,
}

impl Default for AddDown {
    fn default() -> Self {
        let exp = |v: u64| Constant::new(v.to_bits());
        Self {
            clock: Default::default(),
            xm: Default::default(),
            xe: Default::default(),
            ym: Default::default(),
            ye: Default::default(),
            sm: Default::default(),
            se: Default::default(),
            sum_reg: Default::default(),
            grid_reg: Default::default(),
            round: Default::default(),
            sign: Constant::new((1u64 << (SHORT_M_BITS - 1)).to_bits()),
            extension: Constant::new(
                (((1u64 << ADD_BITS) - 1) & !((1u64 << SHORT_M_BITS) - 1)).to_bits(),
            ),
            one_e: exp(1),
            below: exp(u64::from(SHORT_BITS) - 1 + ADD_GUARD_BITS as u64),
            max_shift: exp(ADD_BITS as u64 - 1),
            exp_sign: exp(1 << (SHORT_EXP_BITS - 1)),
            x_wide: Default::default(),
            y_wide: Default::default(),
            x_len: Default::default(),
            y_len: Default::default(),
            x_top: Default::default(),
            y_top: Default::default(),
            grid: Default::default(),
            x_shift: Default::default(),
            y_shift: Default::default(),
            x_at: Default::default(),
            y_at: Default::default(),
        }
    }
}

impl Logic for AddDown {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, sum_reg, grid_reg, round);
        // Sign-extended to the grid's width.
        self.x_wide.next = bit_cast::<ADD_BITS, SHORT_M_BITS>(self.xm.val());
        if (self.xm.val() & self.sign.val()).any() {
            self.x_wide.next =
                bit_cast::<ADD_BITS, SHORT_M_BITS>(self.xm.val()) | self.extension.val();
        }
        self.y_wide.next = bit_cast::<ADD_BITS, SHORT_M_BITS>(self.ym.val());
        if (self.ym.val() & self.sign.val()).any() {
            self.y_wide.next =
                bit_cast::<ADD_BITS, SHORT_M_BITS>(self.ym.val()) | self.extension.val();
        }
        self.x_len.next = 0.into();
        self.y_len.next = 0.into();
        for i in 0..SHORT_M_BITS {
            if self.xm.val().get_bit(i) != (self.xm.val() & self.sign.val()).any() {
                self.x_len.next = i.to_bits() + self.one_e.val();
            }
            if self.ym.val().get_bit(i) != (self.ym.val() & self.sign.val()).any() {
                self.y_len.next = i.to_bits() + self.one_e.val();
            }
        }
        self.x_top.next = self.xe.val() + self.x_len.val();
        self.y_top.next = self.ye.val() + self.y_len.val();
        // The grid below the larger top (signed order: the sign bits flipped).
        self.grid.next = self.x_top.val() - self.below.val();
        if (self.y_top.val() ^ self.exp_sign.val()) > (self.x_top.val() ^ self.exp_sign.val()) {
            self.grid.next = self.y_top.val() - self.below.val();
        }
        self.x_shift.next = 0.into();
        self.y_shift.next = 0.into();
        // Each operand on the grid: up exactly, or down by a floor (the shift, a positive
        // difference, clamped where only the sign is left).
        if (self.xe.val() ^ self.exp_sign.val()) >= (self.grid.val() ^ self.exp_sign.val()) {
            self.x_at.next = self.x_wide.val() << (self.xe.val() - self.grid.val());
        } else {
            self.x_shift.next = self.grid.val() - self.xe.val();
            if self.x_shift.val() > self.max_shift.val() {
                self.x_shift.next = self.max_shift.val();
            }
            self.x_at.next = !(!self.x_wide.val() >> self.x_shift.val());
            if !(self.xm.val() & self.sign.val()).any() {
                self.x_at.next = self.x_wide.val() >> self.x_shift.val();
            }
        }
        if (self.ye.val() ^ self.exp_sign.val()) >= (self.grid.val() ^ self.exp_sign.val()) {
            self.y_at.next = self.y_wide.val() << (self.ye.val() - self.grid.val());
        } else {
            self.y_shift.next = self.grid.val() - self.ye.val();
            if self.y_shift.val() > self.max_shift.val() {
                self.y_shift.next = self.max_shift.val();
            }
            self.y_at.next = !(!self.y_wide.val() >> self.y_shift.val());
            if !(self.ym.val() & self.sign.val()).any() {
                self.y_at.next = self.y_wide.val() >> self.y_shift.val();
            }
        }
        // A zero operand passes the other (its exponent never counts).
        self.sum_reg.d.next = self.x_at.val() + self.y_at.val();
        self.grid_reg.d.next = self.grid.val();
        if !self.xm.val().any() {
            self.sum_reg.d.next = self.y_wide.val();
            self.grid_reg.d.next = self.ye.val();
        } else if !self.ym.val().any() {
            self.sum_reg.d.next = self.x_wide.val();
            self.grid_reg.d.next = self.xe.val();
        }
        self.round.x.next = self.sum_reg.q.val();
        self.round.e.next = self.grid_reg.q.val();
        self.sm.next = self.round.m.val();
        self.se.next = self.round.f.val();
    }
}
