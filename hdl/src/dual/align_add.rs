//! The Plücker filter's sum of two values on different grids, bit for bit
//! `hw_model::dual::plucker::align_add`: the value with the smaller grid exponent is shifted
//! right arithmetically by the exponent difference (at most N − 1: beyond, only its sign is
//! left) and added to the other, so the sum is floor-truncated onto the coarser grid. One
//! register stage.

use rust_hdl::prelude::*;

/// Bits of a grid exponent, biased by [`EXP_BIAS`] so that unsigned comparisons order it.
pub const EXP_BITS: usize = 10;
/// The bias of a grid exponent field: the field is exponent + `EXP_BIAS`.
pub const EXP_BIAS: u64 = 1 << (EXP_BITS - 1);

/// Cycles from the inputs to `s` and `e`.
pub const LATENCY: usize = 1;

/// `s`·2^`e` = floor(a·2^`ea` + b·2^`eb`) on the grid 2^max(`ea`, `eb`); `a`, `b` are N-bit
/// two's complement, `s` O = N + 1 bits, the exponents biased fields.
#[derive(LogicBlock)]
pub struct AlignAdd<const N: usize, const O: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<N>>,
    pub ea: Signal<In, Bits<EXP_BITS>>,
    pub b: Signal<In, Bits<N>>,
    pub eb: Signal<In, Bits<EXP_BITS>>,
    pub s: Signal<Out, Bits<O>>,
    pub e: Signal<Out, Bits<EXP_BITS>>,
    s_reg: DFF<Bits<O>>,
    e_reg: DFF<Bits<EXP_BITS>>,
    /// The operands' sign bit, and the bits above them a negative one extends into.
    sign: Constant<Bits<N>>,
    extension: Constant<Bits<O>>,
    /// The largest shift that still matters.
    max_shift: Constant<Bits<EXP_BITS>>,
    shift: Signal<Local, Bits<EXP_BITS>>,
    coarse: Signal<Local, Bits<N>>,
    fine: Signal<Local, Bits<N>>,
    shifted: Signal<Local, Bits<N>>,
    /// Both terms sign-extended to O bits.
    coarse_wide: Signal<Local, Bits<O>>,
    shifted_wide: Signal<Local, Bits<O>>,
}

impl<const N: usize, const O: usize> Default for AlignAdd<N, O> {
    fn default() -> Self {
        assert_eq!(O, N + 1, "AlignAdd: the sum needs N + 1 bits");
        Self {
            clock: Default::default(),
            a: Default::default(),
            ea: Default::default(),
            b: Default::default(),
            eb: Default::default(),
            s: Default::default(),
            e: Default::default(),
            s_reg: Default::default(),
            e_reg: Default::default(),
            sign: Constant::new(Bits::<N>::from(1) << (N as u64 - 1)),
            extension: Constant::new(!Bits::<O>::default() << N as u64),
            max_shift: Constant::new(((N - 1) as u64).to_bits()),
            shift: Default::default(),
            coarse: Default::default(),
            fine: Default::default(),
            shifted: Default::default(),
            coarse_wide: Default::default(),
            shifted_wide: Default::default(),
        }
    }
}

impl<const N: usize, const O: usize> Logic for AlignAdd<N, O> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, s_reg, e_reg);
        if self.ea.val() >= self.eb.val() {
            self.shift.next = self.ea.val() - self.eb.val();
            self.coarse.next = self.a.val();
            self.fine.next = self.b.val();
            self.e_reg.d.next = self.ea.val();
        } else {
            self.shift.next = self.eb.val() - self.ea.val();
            self.coarse.next = self.b.val();
            self.fine.next = self.a.val();
            self.e_reg.d.next = self.eb.val();
        }
        if self.shift.val() > self.max_shift.val() {
            self.shift.next = self.max_shift.val();
        }
        // Arithmetic shift right: a negative value's complement shifts in zeros.
        self.shifted.next = self.fine.val() >> self.shift.val();
        if (self.fine.val() & self.sign.val()).any() {
            self.shifted.next = !(!self.fine.val() >> self.shift.val());
        }
        self.coarse_wide.next = bit_cast::<O, N>(self.coarse.val());
        if (self.coarse.val() & self.sign.val()).any() {
            self.coarse_wide.next = self.coarse_wide.val() | self.extension.val();
        }
        self.shifted_wide.next = bit_cast::<O, N>(self.shifted.val());
        if (self.shifted.val() & self.sign.val()).any() {
            self.shifted_wide.next = self.shifted_wide.val() | self.extension.val();
        }
        self.s_reg.d.next = self.coarse_wide.val() + self.shifted_wide.val();
        self.s.next = self.s_reg.q.val();
        self.e.next = self.e_reg.q.val();
    }
}
