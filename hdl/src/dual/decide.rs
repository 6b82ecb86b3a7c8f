//! Step 5 of the bfp filter: the decisions, bit for bit `hw_model::dual::bfp::decide`.
//! det and the numerators N_u, N_v, N_t arrive as integers at their last bits' exponents
//! with their margins in units of those bits; value ± margin are integer adders, each sum
//! normalised outward to a short float ([`Round`]: H = up(|det| + e_D), L = down(|det| −
//! e_D), per numerator hi = up(σN + e), lo = down(σN − e)); then the table's rows are short
//! comparisons ([`ShortLt`]), one short adder ([`AddDown`]) and one 25 × 10 product
//! (τ'·bound: the unsigned [`IntMul`] on magnitudes, the sign beside). One register stage:
//! the rows, `miss` and `forward` the cycle after their inputs.

use hw_model::dual::bfp::{
    det_epsilon, split, widths, Vector, FLUSH_SHIFT, QUOTIENT_MAX, QUOTIENT_RANGE, RECIPROCAL_MIN,
    SHORT_BITS,
};
use rust_hdl::prelude::*;

use super::add_down::AddDown;
use super::round::{Round, SHORT_EXP_BITS, SHORT_M_BITS};
use super::short_lt::{Lt, ShortLt};
use super::translate::SIGNIFICAND_BITS;
use super::WIDTH;
use crate::intmul::IntMul;

const W: [u32; 6] = widths(WIDTH);

/// Cycles from the inputs to the rows, `miss` and `forward`.
pub const LATENCY: usize = 1;

/// det = e1·p̂: two mantissas' product and two bits for the sum of three.
pub const DET_BITS: usize = (W[Vector::E1 as usize] + W[Vector::P as usize] + 2) as usize;
/// N_u = s·p̂, N_v = dir·q̂, N_t = e2·q̂: the same, at the wider pair (all three equal).
pub const NUM_BITS: usize = (W[Vector::S as usize] + W[Vector::P as usize] + 2) as usize;
const _: () = assert!(
    W[Vector::S as usize] + W[Vector::P as usize]
        == W[Vector::Dir as usize] + W[Vector::Q as usize]
        && W[Vector::E2 as usize] == W[Vector::Dir as usize]
);

/// The bits of QUOTIENT_RANGE (|value| + margin ≤ QUOTIENT_RANGE·2^ΣE).
const RANGE_BITS: u32 = u32::BITS - (QUOTIENT_RANGE as u32).leading_zeros();

/// A margin in units of its value's last bit 2^(ΣE − K), K = W_a + W_x − 3: below
/// QUOTIENT_RANGE·2^K.
pub const DET_MARGIN_BITS: usize =
    (W[Vector::E1 as usize] + W[Vector::P as usize] - 3 + RANGE_BITS) as usize;
pub const NUM_MARGIN_BITS: usize =
    (W[Vector::S as usize] + W[Vector::P as usize] - 3 + RANGE_BITS) as usize;

/// value ± margin: one bit more than the value (exact for any inputs of these widths).
pub const DET_SUM_BITS: usize = DET_BITS + 1;
pub const NUM_SUM_BITS: usize = NUM_BITS + 1;

/// τ' = ±significand − 2^k (k = 0, or up to 24 below 2^-102): a sign and a magnitude of one
/// bit more than the significand.
pub const TAU_BITS: usize = SIGNIFICAND_BITS + 2;
const TAU_MAG_BITS: usize = TAU_BITS - 1;
/// |bound| ≤ 2^(SHORT_BITS − 1): SHORT_BITS unsigned bits.
const BOUND_MAG_BITS: usize = SHORT_BITS as usize;
const PRODUCT_MAG_BITS: usize = TAU_MAG_BITS + BOUND_MAG_BITS;
/// The signed product.
pub const PRODUCT_BITS: usize = PRODUCT_MAG_BITS + 1;
/// DET_EPSILON's mantissa: an fp32 significand and a sign.
const EPS_M_BITS: usize = SIGNIFICAND_BITS + 1;

/// The decision of one query: the table's rows (each its condition), `miss` (a certain
/// miss: the fallback would answer no hit) and `forward` (to the fallback).
#[derive(LogicBlock)]
pub struct Decide {
    pub clock: Signal<In, Clock>,
    /// det·2^`det_e` (two's complement, signed exponent) and its margin.
    pub det: Signal<In, Bits<DET_BITS>>,
    pub det_e: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub det_margin: Signal<In, Bits<DET_MARGIN_BITS>>,
    /// N_u, N_v, N_t likewise.
    pub num: [Signal<In, Bits<NUM_BITS>>; 3],
    pub num_e: [Signal<In, Bits<SHORT_EXP_BITS>>; 3],
    pub num_margin: [Signal<In, Bits<NUM_MARGIN_BITS>>; 3],
    /// The query's t_min, fp32 bits.
    pub t_min: Signal<In, Bits<32>>,
    pub parallel: Signal<Out, Bit>,
    pub in_range: Signal<Out, Bit>,
    pub u_below: Signal<Out, Bit>,
    pub u_above: Signal<Out, Bit>,
    pub v_below: Signal<Out, Bit>,
    pub uv_above: Signal<Out, Bit>,
    pub t_below: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    parallel_reg: DFF<Bit>,
    in_range_reg: DFF<Bit>,
    u_below_reg: DFF<Bit>,
    u_above_reg: DFF<Bit>,
    v_below_reg: DFF<Bit>,
    uv_above_reg: DFF<Bit>,
    t_below_reg: DFF<Bit>,
    miss_reg: DFF<Bit>,
    /// H and L; per numerator hi and lo; down(τ'·bound).
    high: Round<DET_SUM_BITS, true>,
    low: Round<DET_SUM_BITS, false>,
    hi: [Round<NUM_SUM_BITS, true>; 3],
    lo: [Round<NUM_SUM_BITS, false>; 3],
    product: Round<PRODUCT_BITS, false>,
    mul: IntMul<TAU_MAG_BITS, BOUND_MAG_BITS, PRODUCT_MAG_BITS>,
    sum: AddDown,
    /// H < eps.
    eps_lt: ShortLt<EPS_M_BITS>,
    /// L < 2^-126, H < 2^125, hi < L·2^125, −lo < L·2^125.
    tiny_lt: Lt,
    huge_lt: Lt,
    hi_room: [Lt; 3],
    lo_room: [Lt; 3],
    /// −hi_u < H·2^-124, −hi_v < H·2^-124.
    u_flush: Lt,
    v_flush: Lt,
    /// H < lo_u, H < down(lo_u + lo_v), hi_t < down(τ'·bound).
    u_lt: Lt,
    uv_lt: Lt,
    t_lt: Lt,
    eps_m: Constant<Bits<EPS_M_BITS>>,
    eps_e: Constant<Bits<SHORT_EXP_BITS>>,
    /// Sign extension of a short mantissa to EPS_M_BITS.
    eps_extension: Constant<Bits<EPS_M_BITS>>,
    one_m: Constant<Bits<SHORT_M_BITS>>,
    short_sign: Constant<Bits<SHORT_M_BITS>>,
    reciprocal_min: Constant<Bits<SHORT_EXP_BITS>>,
    quotient_max: Constant<Bits<SHORT_EXP_BITS>>,
    flush_shift: Constant<Bits<SHORT_EXP_BITS>>,
    exp_sign: Constant<Bits<SHORT_EXP_BITS>>,
    /// det's and N's sign bits (in the wider sums).
    det_sign: Constant<Bits<DET_SUM_BITS>>,
    det_one: Constant<Bits<DET_SUM_BITS>>,
    num_sign: Constant<Bits<NUM_SUM_BITS>>,
    num_one: Constant<Bits<NUM_SUM_BITS>>,
    /// The high bits of a sign extension of det or N by one bit.
    det_top: Constant<Bits<DET_SUM_BITS>>,
    num_top: Constant<Bits<NUM_SUM_BITS>>,
    /// fp32: the hidden bit, the field of ±Inf/NaN, the field's bias to t_min's last bit.
    hidden: Constant<Bits<TAU_BITS>>,
    tau_one: Constant<Bits<TAU_BITS>>,
    tau_sign: Constant<Bits<TAU_BITS>>,
    field_max: Constant<Bits<8>>,
    fp32_bias: Constant<Bits<SHORT_EXP_BITS>>,
    product_one: Constant<Bits<PRODUCT_BITS>>,
    det_wide: Signal<Local, Bits<DET_SUM_BITS>>,
    det_abs: Signal<Local, Bits<DET_SUM_BITS>>,
    det_neg: Signal<Local, Bit>,
    /// N and its margin one bit wider, σN per numerator.
    num_wide: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    margin_wide: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    n: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    in_range_now: Signal<Local, Bit>,
    u_below_now: Signal<Local, Bit>,
    v_below_now: Signal<Local, Bit>,
    certain: Signal<Local, Bit>,
    /// τ' = ±significand − 2^k at t_min's exponent, its magnitude and the bound.
    field: Signal<Local, Bits<8>>,
    t_e: Signal<Local, Bits<SHORT_EXP_BITS>>,
    significand: Signal<Local, Bits<TAU_BITS>>,
    unit_shift: Signal<Local, Bits<SHORT_EXP_BITS>>,
    tau: Signal<Local, Bits<TAU_BITS>>,
    tau_neg: Signal<Local, Bit>,
    tau_abs: Signal<Local, Bits<TAU_BITS>>,
    bound_m: Signal<Local, Bits<SHORT_M_BITS>>,
    bound_e: Signal<Local, Bits<SHORT_EXP_BITS>>,
    bound_neg: Signal<Local, Bit>,
    bound_abs: Signal<Local, Bits<SHORT_M_BITS>>,
    signed_product: Signal<Local, Bits<PRODUCT_BITS>>,
}

impl Default for Decide {
    fn default() -> Self {
        let exp = |v: i32| Constant::new(((v as u64) & ((1 << SHORT_EXP_BITS) - 1)).to_bits());
        let eps = det_epsilon();
        // fp32's exponent field of 1.0 less its last bit's exponent.
        let bias =
            (1.0f32.to_bits() >> (SIGNIFICAND_BITS - 1)) as i32 - split(1.0).expect("finite").e;
        let high_ones = |from: usize, width: usize| ((1u64 << width) - 1) & !((1u64 << from) - 1);
        Self {
            clock: Default::default(),
            det: Default::default(),
            det_e: Default::default(),
            det_margin: Default::default(),
            num: Default::default(),
            num_e: Default::default(),
            num_margin: Default::default(),
            t_min: Default::default(),
            parallel: Default::default(),
            in_range: Default::default(),
            u_below: Default::default(),
            u_above: Default::default(),
            v_below: Default::default(),
            uv_above: Default::default(),
            t_below: Default::default(),
            miss: Default::default(),
            forward: Default::default(),
            parallel_reg: Default::default(),
            in_range_reg: Default::default(),
            u_below_reg: Default::default(),
            u_above_reg: Default::default(),
            v_below_reg: Default::default(),
            uv_above_reg: Default::default(),
            t_below_reg: Default::default(),
            miss_reg: Default::default(),
            high: Default::default(),
            low: Default::default(),
            hi: Default::default(),
            lo: Default::default(),
            product: Default::default(),
            mul: Default::default(),
            sum: Default::default(),
            eps_lt: Default::default(),
            tiny_lt: Default::default(),
            huge_lt: Default::default(),
            hi_room: Default::default(),
            lo_room: Default::default(),
            u_flush: Default::default(),
            v_flush: Default::default(),
            u_lt: Default::default(),
            uv_lt: Default::default(),
            t_lt: Default::default(),
            eps_m: Constant::new((eps.m as u64).to_bits()),
            eps_e: exp(eps.e),
            eps_extension: Constant::new(high_ones(SHORT_M_BITS, EPS_M_BITS).to_bits()),
            one_m: Constant::new(1u64.to_bits()),
            short_sign: Constant::new((1u64 << (SHORT_M_BITS - 1)).to_bits()),
            reciprocal_min: exp(RECIPROCAL_MIN),
            quotient_max: exp(QUOTIENT_MAX),
            flush_shift: exp(FLUSH_SHIFT),
            exp_sign: exp(1 << (SHORT_EXP_BITS - 1)),
            det_sign: Constant::new((1u64 << (DET_BITS - 1)).to_bits()),
            det_one: Constant::new(1u64.to_bits()),
            num_sign: Constant::new((1u64 << (NUM_BITS - 1)).to_bits()),
            num_one: Constant::new(1u64.to_bits()),
            det_top: Constant::new((1u64 << DET_BITS).to_bits()),
            num_top: Constant::new((1u64 << NUM_BITS).to_bits()),
            hidden: Constant::new((1u64 << (SIGNIFICAND_BITS - 1)).to_bits()),
            tau_one: Constant::new(1u64.to_bits()),
            tau_sign: Constant::new((1u64 << (TAU_BITS - 1)).to_bits()),
            field_max: Constant::new(0xffu64.to_bits()),
            fp32_bias: exp(bias),
            product_one: Constant::new(1u64.to_bits()),
            det_wide: Default::default(),
            det_abs: Default::default(),
            det_neg: Default::default(),
            num_wide: Default::default(),
            margin_wide: Default::default(),
            n: Default::default(),
            in_range_now: Default::default(),
            u_below_now: Default::default(),
            v_below_now: Default::default(),
            certain: Default::default(),
            field: Default::default(),
            t_e: Default::default(),
            significand: Default::default(),
            unit_shift: Default::default(),
            tau: Default::default(),
            tau_neg: Default::default(),
            tau_abs: Default::default(),
            bound_m: Default::default(),
            bound_e: Default::default(),
            bound_neg: Default::default(),
            bound_abs: Default::default(),
            signed_product: Default::default(),
        }
    }
}

impl Logic for Decide {
    #[hdl_gen]
    fn update(&mut self) {
        self.parallel_reg.clock.next = self.clock.val();
        self.in_range_reg.clock.next = self.clock.val();
        self.u_below_reg.clock.next = self.clock.val();
        self.u_above_reg.clock.next = self.clock.val();
        self.v_below_reg.clock.next = self.clock.val();
        self.uv_above_reg.clock.next = self.clock.val();
        self.t_below_reg.clock.next = self.clock.val();
        self.miss_reg.clock.next = self.clock.val();
        // |det| ± e_D at det's last bit, one bit wider (det sign-extended by hand).
        self.det_wide.next = bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val());
        self.det_neg.next = (self.det_wide.val() & self.det_sign.val()).any();
        if self.det_neg.val() {
            self.det_wide.next =
                bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val()) | self.det_top.val();
        }
        self.det_abs.next = self.det_wide.val();
        if self.det_neg.val() {
            self.det_abs.next = !self.det_wide.val() + self.det_one.val();
        }
        self.high.x.next =
            self.det_abs.val() + bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.det_margin.val());
        self.high.e.next = self.det_e.val();
        self.low.x.next =
            self.det_abs.val() - bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.det_margin.val());
        self.low.e.next = self.det_e.val();
        // σN ± e per numerator (σ = sign(det); 0 for a zero det). (bit_cast in a loop
        // loses the loop variable: one per numerator.)
        self.num_wide[0].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[0].val());
        self.num_wide[1].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[1].val());
        self.num_wide[2].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[2].val());
        self.margin_wide[0].next =
            bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin[0].val());
        self.margin_wide[1].next =
            bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin[1].val());
        self.margin_wide[2].next =
            bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin[2].val());
        for k in 0..3 {
            self.n[k].next = self.num_wide[k].val();
            if (self.num_wide[k].val() & self.num_sign.val()).any() {
                self.n[k].next = self.num_wide[k].val() | self.num_top.val();
            }
            if self.det_neg.val() {
                self.n[k].next = !self.n[k].val() + self.num_one.val();
            }
            if !self.det.val().any() {
                self.n[k].next = 0.into();
            }
            self.hi[k].x.next = self.n[k].val() + self.margin_wide[k].val();
            self.hi[k].e.next = self.num_e[k].val();
            self.lo[k].x.next = self.n[k].val() - self.margin_wide[k].val();
            self.lo[k].e.next = self.num_e[k].val();
        }
        // H < eps (H sign-extended to eps's width).
        self.eps_lt.xm.next = bit_cast::<EPS_M_BITS, SHORT_M_BITS>(self.high.m.val());
        if (self.high.m.val() & self.short_sign.val()).any() {
            self.eps_lt.xm.next =
                bit_cast::<EPS_M_BITS, SHORT_M_BITS>(self.high.m.val()) | self.eps_extension.val();
        }
        self.eps_lt.xe.next = self.high.f.val();
        self.eps_lt.ym.next = self.eps_m.val();
        self.eps_lt.ye.next = self.eps_e.val();
        // The range row: L ≥ 2^-126, H < 2^125, max(hi, −lo) < L·2^125.
        self.tiny_lt.xm.next = self.low.m.val();
        self.tiny_lt.xe.next = self.low.f.val();
        self.tiny_lt.ym.next = self.one_m.val();
        self.tiny_lt.ye.next = self.reciprocal_min.val();
        self.huge_lt.xm.next = self.high.m.val();
        self.huge_lt.xe.next = self.high.f.val();
        self.huge_lt.ym.next = self.one_m.val();
        self.huge_lt.ye.next = self.quotient_max.val();
        for k in 0..3 {
            self.hi_room[k].xm.next = self.hi[k].m.val();
            self.hi_room[k].xe.next = self.hi[k].f.val();
            self.hi_room[k].ym.next = self.low.m.val();
            self.hi_room[k].ye.next = self.low.f.val() + self.quotient_max.val();
            self.lo_room[k].xm.next = !self.lo[k].m.val() + self.one_m.val();
            self.lo_room[k].xe.next = self.lo[k].f.val();
            self.lo_room[k].ym.next = self.low.m.val();
            self.lo_room[k].ye.next = self.low.f.val() + self.quotient_max.val();
        }
        self.in_range_now.next = !(self.low.m.val() & self.short_sign.val()).any()
            && self.low.m.val().any()
            && !self.tiny_lt.lt.val()
            && self.huge_lt.lt.val()
            && self.hi_room[0].lt.val()
            && self.hi_room[1].lt.val()
            && self.hi_room[2].lt.val()
            && self.lo_room[0].lt.val()
            && self.lo_room[1].lt.val()
            && self.lo_room[2].lt.val();
        // u < 0, v < 0: hi < 0 and not −hi < H·2^-124.
        self.u_flush.xm.next = !self.hi[0].m.val() + self.one_m.val();
        self.u_flush.xe.next = self.hi[0].f.val();
        self.u_flush.ym.next = self.high.m.val();
        self.u_flush.ye.next = self.high.f.val() + self.flush_shift.val();
        self.v_flush.xm.next = !self.hi[1].m.val() + self.one_m.val();
        self.v_flush.xe.next = self.hi[1].f.val();
        self.v_flush.ym.next = self.high.m.val();
        self.v_flush.ye.next = self.high.f.val() + self.flush_shift.val();
        self.u_below_now.next =
            (self.hi[0].m.val() & self.short_sign.val()).any() && !self.u_flush.lt.val();
        self.v_below_now.next =
            (self.hi[1].m.val() & self.short_sign.val()).any() && !self.v_flush.lt.val();
        // u > 1: H < lo_u; u + v > 1: H < down(lo_u + lo_v).
        self.u_lt.xm.next = self.high.m.val();
        self.u_lt.xe.next = self.high.f.val();
        self.u_lt.ym.next = self.lo[0].m.val();
        self.u_lt.ye.next = self.lo[0].f.val();
        self.sum.xm.next = self.lo[0].m.val();
        self.sum.xe.next = self.lo[0].f.val();
        self.sum.ym.next = self.lo[1].m.val();
        self.sum.ye.next = self.lo[1].f.val();
        self.uv_lt.xm.next = self.high.m.val();
        self.uv_lt.xe.next = self.high.f.val();
        self.uv_lt.ym.next = self.sum.sm.val();
        self.uv_lt.ye.next = self.sum.se.val();
        // t ≤ t_min: τ' = ±significand − 2^k at t_min's last bit 2^e, k = max(0, −126 − e)
        // (λ below 2^-102; one unit above); subnormals read as 0.
        self.field.next = self.t_min.val().get_bits::<8>(23);
        self.t_e.next = bit_cast::<SHORT_EXP_BITS, 8>(self.field.val()) - self.fp32_bias.val();
        self.significand.next = 0.into();
        if self.field.val().any() {
            self.significand.next =
                self.hidden.val() | bit_cast::<TAU_BITS, 23>(self.t_min.val().get_bits::<23>(0));
        }
        if self.t_min.val().get_bit(31) {
            self.significand.next = !self.significand.val() + self.tau_one.val();
        }
        self.unit_shift.next = 0.into();
        if (self.t_e.val() ^ self.exp_sign.val())
            < (self.reciprocal_min.val() ^ self.exp_sign.val())
        {
            self.unit_shift.next = self.reciprocal_min.val() - self.t_e.val();
        }
        self.tau.next = self.significand.val() - (self.tau_one.val() << self.unit_shift.val());
        self.tau_neg.next = (self.tau.val() & self.tau_sign.val()).any();
        self.tau_abs.next = self.tau.val();
        self.bound_m.next = self.low.m.val();
        self.bound_e.next = self.low.f.val();
        if self.tau_neg.val() {
            self.tau_abs.next = !self.tau.val() + self.tau_one.val();
            self.bound_m.next = self.high.m.val();
            self.bound_e.next = self.high.f.val();
        }
        self.bound_neg.next = (self.bound_m.val() & self.short_sign.val()).any();
        self.bound_abs.next = self.bound_m.val();
        if self.bound_neg.val() {
            self.bound_abs.next = !self.bound_m.val() + self.one_m.val();
        }
        self.mul.a.next = bit_cast::<TAU_MAG_BITS, TAU_BITS>(self.tau_abs.val());
        self.mul.b.next = bit_cast::<BOUND_MAG_BITS, SHORT_M_BITS>(self.bound_abs.val());
        self.signed_product.next = bit_cast::<PRODUCT_BITS, PRODUCT_MAG_BITS>(self.mul.p.val());
        if self.tau_neg.val() != self.bound_neg.val() {
            self.signed_product.next =
                !bit_cast::<PRODUCT_BITS, PRODUCT_MAG_BITS>(self.mul.p.val())
                    + self.product_one.val();
        }
        self.product.x.next = self.signed_product.val();
        self.product.e.next = self.t_e.val() + self.bound_e.val();
        self.t_lt.xm.next = self.hi[2].m.val();
        self.t_lt.xe.next = self.hi[2].f.val();
        self.t_lt.ym.next = self.product.m.val();
        self.t_lt.ye.next = self.product.f.val();
        // A non-finite t_min decides nothing.
        self.t_below_reg.d.next = self.t_lt.lt.val() && self.field.val() != self.field_max.val();
        self.parallel_reg.d.next = self.eps_lt.lt.val();
        self.in_range_reg.d.next = self.in_range_now.val();
        self.u_below_reg.d.next = self.u_below_now.val();
        self.u_above_reg.d.next = self.u_lt.lt.val();
        self.v_below_reg.d.next = self.v_below_now.val();
        self.uv_above_reg.d.next = self.uv_lt.lt.val();
        self.certain.next = self.u_below_now.val()
            || self.u_lt.lt.val()
            || self.v_below_now.val()
            || self.uv_lt.lt.val()
            || (self.t_lt.lt.val() && self.field.val() != self.field_max.val());
        self.miss_reg.d.next =
            self.eps_lt.lt.val() || (self.in_range_now.val() && self.certain.val());
        self.parallel.next = self.parallel_reg.q.val();
        self.in_range.next = self.in_range_reg.q.val();
        self.u_below.next = self.u_below_reg.q.val();
        self.u_above.next = self.u_above_reg.q.val();
        self.v_below.next = self.v_below_reg.q.val();
        self.uv_above.next = self.uv_above_reg.q.val();
        self.t_below.next = self.t_below_reg.q.val();
        self.miss.next = self.miss_reg.q.val();
        self.forward.next = !self.miss_reg.q.val();
    }
}
