//! The Plücker filter's bound on |s| = |orig − v0| for the fallback's margin, bit for bit
//! `hw_model::dual::plucker::s_exponent`: −orig's block and v0's cut floored onto the grid
//! G = max(E_orig, E_v0) − [`CUT_BITS`] + 1, added per component to c_k,
//! B = max_k |c_k + 2| + 2, and E_s = G + ⌈log₂B⌉ (the bit length of B − 1). orig is cut to its top
//! [`CUT_BITS`] first (wires: floors compose), so of the two floors only the operand with
//! the smaller exponent moves: one CUT_BITS-bit arithmetic shifter a component. One register
//! stage.

use hw_model::dual::plucker::S_BOUND_BITS;
use rust_hdl::prelude::*;

use super::align_add::EXP_BITS;
use super::plucker::WT;

/// Bits of v0's cut.
pub const CUT_BITS: usize = S_BOUND_BITS as usize;
/// c_k + 2 and B: each floored operand fits CUT_BITS signed bits, their sum one more, and
/// one more again for the + 2 and the magnitude.
const C_BITS: usize = CUT_BITS + 2;
/// The bit length of B − 1.
const LEN_BITS: usize = 4;
const _: () = assert!(1 << LEN_BITS > C_BITS);

/// Cycles from the inputs to `e`.
pub const LATENCY: usize = 1;

/// E_s (a biased field, as the block exponents' fields) of −orig (`orig`, WT-bit
/// mantissas on the grid `orig_e`) and v0's cut (`cut`, on the grid `cut_e`).
#[derive(LogicBlock)]
pub struct SBound {
    pub clock: Signal<In, Clock>,
    pub orig: [Signal<In, Bits<WT>>; 3],
    pub orig_e: Signal<In, Bits<EXP_BITS>>,
    pub cut: [Signal<In, Bits<CUT_BITS>>; 3],
    pub cut_e: Signal<In, Bits<EXP_BITS>>,
    pub e: Signal<Out, Bits<EXP_BITS>>,
    e_reg: DFF<Bits<EXP_BITS>>,
    /// WT − 1 and CUT_BITS − 1: a field's last bit to its block exponent (the latter also
    /// the largest shift that still matters); WT − CUT_BITS, orig's fixed cut.
    orig_top: Constant<Bits<EXP_BITS>>,
    cut_top: Constant<Bits<EXP_BITS>>,
    orig_cut: Constant<Bits<EXP_BITS>>,
    cut_sign: Constant<Bits<CUT_BITS>>,
    c_sign: Constant<Bits<C_BITS>>,
    extension: Constant<Bits<C_BITS>>,
    two: Constant<Bits<C_BITS>>,
    one: Constant<Bits<C_BITS>>,
    len_one: Constant<Bits<LEN_BITS>>,
    /// The block exponent fields, G's field and the smaller operand's shift onto G.
    orig_exp: Signal<Local, Bits<EXP_BITS>>,
    cut_exp: Signal<Local, Bits<EXP_BITS>>,
    grid: Signal<Local, Bits<EXP_BITS>>,
    shift: Signal<Local, Bits<EXP_BITS>>,
    /// orig's top CUT_BITS; the larger operand (on G already) and the smaller, floored onto
    /// G, both sign-extended.
    orig_cut_m: [Signal<Local, Bits<CUT_BITS>>; 3],
    large: [Signal<Local, Bits<CUT_BITS>>; 3],
    small: [Signal<Local, Bits<CUT_BITS>>; 3],
    small_floor: [Signal<Local, Bits<CUT_BITS>>; 3],
    large_wide: [Signal<Local, Bits<C_BITS>>; 3],
    small_wide: [Signal<Local, Bits<C_BITS>>; 3],
    /// c_k + 2, then |c_k + 2| + 2.
    c: [Signal<Local, Bits<C_BITS>>; 3],
    mag: [Signal<Local, Bits<C_BITS>>; 3],
    b: Signal<Local, Bits<C_BITS>>,
    b_less: Signal<Local, Bits<C_BITS>>,
    len: Signal<Local, Bits<LEN_BITS>>,
}

impl Default for SBound {
    fn default() -> Self {
        let field = |v: usize| Constant::new((v as u64).to_bits());
        Self {
            clock: Default::default(),
            orig: Default::default(),
            orig_e: Default::default(),
            cut: Default::default(),
            cut_e: Default::default(),
            e: Default::default(),
            e_reg: Default::default(),
            orig_top: field(WT - 1),
            cut_top: field(CUT_BITS - 1),
            orig_cut: field(WT - CUT_BITS),
            cut_sign: Constant::new(Bits::<CUT_BITS>::from(1) << (CUT_BITS as u64 - 1)),
            c_sign: Constant::new(Bits::<C_BITS>::from(1) << (C_BITS as u64 - 1)),
            extension: Constant::new(!Bits::<C_BITS>::default() << CUT_BITS as u64),
            two: Constant::new(2u64.to_bits()),
            one: Constant::new(1u64.to_bits()),
            len_one: Constant::new(1u64.to_bits()),
            orig_exp: Default::default(),
            cut_exp: Default::default(),
            grid: Default::default(),
            shift: Default::default(),
            orig_cut_m: Default::default(),
            large: Default::default(),
            small: Default::default(),
            small_floor: Default::default(),
            large_wide: Default::default(),
            small_wide: Default::default(),
            c: Default::default(),
            mag: Default::default(),
            b: Default::default(),
            b_less: Default::default(),
            len: Default::default(),
        }
    }
}

impl Logic for SBound {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, e_reg);
        // orig's top CUT_BITS (a constant shift: wires). (bit_cast of a loop-indexed signal
        // does not generate: written out.)
        self.orig_cut_m[0].next =
            bit_cast::<CUT_BITS, WT>(self.orig[0].val() >> self.orig_cut.val());
        self.orig_cut_m[1].next =
            bit_cast::<CUT_BITS, WT>(self.orig[1].val() >> self.orig_cut.val());
        self.orig_cut_m[2].next =
            bit_cast::<CUT_BITS, WT>(self.orig[2].val() >> self.orig_cut.val());
        // Block exponent fields: last bit + width − 1. G = max − (CUT_BITS − 1): the larger
        // operand is on G, the other shifts by the difference.
        self.orig_exp.next = self.orig_e.val() + self.orig_top.val();
        self.cut_exp.next = self.cut_e.val() + self.cut_top.val();
        if self.orig_exp.val() >= self.cut_exp.val() {
            self.grid.next = self.orig_exp.val() - self.cut_top.val();
            self.shift.next = self.orig_exp.val() - self.cut_exp.val();
            for k in 0..3 {
                self.large[k].next = self.orig_cut_m[k].val();
                self.small[k].next = self.cut[k].val();
            }
        } else {
            self.grid.next = self.cut_exp.val() - self.cut_top.val();
            self.shift.next = self.cut_exp.val() - self.orig_exp.val();
            for k in 0..3 {
                self.large[k].next = self.cut[k].val();
                self.small[k].next = self.orig_cut_m[k].val();
            }
        }
        if self.shift.val() > self.cut_top.val() {
            self.shift.next = self.cut_top.val();
        }
        for k in 0..3 {
            // The floor: an arithmetic shift (a negative value's complement shifts in zeros).
            self.small_floor[k].next = self.small[k].val() >> self.shift.val();
            if (self.small[k].val() & self.cut_sign.val()).any() {
                self.small_floor[k].next = !(!self.small[k].val() >> self.shift.val());
            }
        }
        self.large_wide[0].next = bit_cast::<C_BITS, CUT_BITS>(self.large[0].val());
        self.large_wide[1].next = bit_cast::<C_BITS, CUT_BITS>(self.large[1].val());
        self.large_wide[2].next = bit_cast::<C_BITS, CUT_BITS>(self.large[2].val());
        self.small_wide[0].next = bit_cast::<C_BITS, CUT_BITS>(self.small_floor[0].val());
        self.small_wide[1].next = bit_cast::<C_BITS, CUT_BITS>(self.small_floor[1].val());
        self.small_wide[2].next = bit_cast::<C_BITS, CUT_BITS>(self.small_floor[2].val());
        for k in 0..3 {
            if (self.large[k].val() & self.cut_sign.val()).any() {
                self.large_wide[k].next = self.large_wide[k].val() | self.extension.val();
            }
            if (self.small_floor[k].val() & self.cut_sign.val()).any() {
                self.small_wide[k].next = self.small_wide[k].val() | self.extension.val();
            }
            self.c[k].next = self.large_wide[k].val() + self.small_wide[k].val() + self.two.val();
            self.mag[k].next = self.c[k].val() + self.two.val();
            if (self.c[k].val() & self.c_sign.val()).any() {
                self.mag[k].next = self.two.val() - self.c[k].val();
            }
        }
        self.b.next = self.mag[0].val();
        if self.mag[1].val() > self.b.val() {
            self.b.next = self.mag[1].val();
        }
        if self.mag[2].val() > self.b.val() {
            self.b.next = self.mag[2].val();
        }
        self.b_less.next = self.b.val() - self.one.val();
        self.len.next = 0.into();
        for i in 0..C_BITS {
            if self.b_less.val().get_bit(i) {
                self.len.next = i.to_bits() + self.len_one.val();
            }
        }
        self.e_reg.d.next = self.grid.val() + bit_cast::<EXP_BITS, LEN_BITS>(self.len.val());
        self.e.next = self.e_reg.q.val();
    }
}
