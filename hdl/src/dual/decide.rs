//! Step 5 of the bfp filter: the decisions, bit for bit `hw_model::dual::bfp::decide`.
//! det and the numerators N_u, N_v, N_t arrive as integers at their last bits' exponents
//! with their margins in units of those bits; value ± margin are integer adders, each sum
//! normalised outward to a short float ([`Round`]: H = up(|det| + e_D), L = down(|det| −
//! e_D), per numerator hi = up(σN + e), lo = down(σN − e)); then the table's rows are short
//! comparisons ([`ShortLt`], and [`Pow2Lt`] against the powers of two 2^-126 and 2^125), one short adder ([`AddDown`]) and one 25 × 10 product
//! (τ'·bound: the unsigned [`IntMul`] on magnitudes, the sign beside).
//!
//! Pipelined, one decision a cycle, so that no stage holds more than one carry chain or
//! one normaliser half: |det| and σN; the sums; the two halves of each `Round` (H, L, hi,
//! lo at cycle [`SHORT`]); then the comparisons and the product's magnitude; the product's
//! sign; its `Round`; the last comparison and `miss`. The short adder runs beside the
//! product, and shorter branches wait in [`Delay`] lines.

use hw_model::dual::bfp::{
    det_epsilon, split, value_bits, widths, Vector, DET, FLUSH_SHIFT, N_T, N_U, N_V, QUOTIENT_MAX,
    RECIPROCAL_MIN, SHORT_BITS,
};
use rust_hdl::prelude::*;

use super::add_down::{self, AddDown};
use super::dot::dot_bits;
use super::margin::margin_bits;
use super::pow2_lt::Pow2Lt;
use super::round::{self, Round, SHORT_EXP_BITS, SHORT_M_BITS};
use super::short_lt::{Lt, ShortLt};
use super::translate::SIGNIFICAND_BITS;
use super::WIDTH;
use crate::intmul::IntMul;
use crate::macros::clock;
use crate::mt::delay::Delay;

const W: [u32; 6] = widths(WIDTH);

/// A vector's mantissa width at [`WIDTH`].
const fn width(v: Vector) -> usize {
    W[v as usize] as usize
}

/// det = e1·p̂ at its dot's exact width (`bfp::value_bits`, the widths the Plücker filter
/// fits its values to; [`dot_bits`] of the `Dot` that computes it).
pub const DET_BITS: usize = value_bits(WIDTH, DET) as usize;
/// N_u = s·p̂, N_v = dir·q̂, N_t = e2·q̂: the same, at the wider pair (all three equal).
pub const NUM_BITS: usize = value_bits(WIDTH, N_U) as usize;
const _: () = assert!(
    DET_BITS == dot_bits(width(Vector::E1), width(Vector::P))
        && NUM_BITS == dot_bits(width(Vector::S), width(Vector::P))
        && NUM_BITS == value_bits(WIDTH, N_V) as usize
        && NUM_BITS == value_bits(WIDTH, N_T) as usize
);

/// The margins in units of their value's last bit, at step 4's widths ([`margin_bits`]).
pub const DET_MARGIN_BITS: usize = margin_bits(DET);
pub const NUM_MARGIN_BITS: usize = margin_bits(N_U);
const _: () = assert!(
    NUM_MARGIN_BITS == margin_bits(N_V)
        && NUM_MARGIN_BITS == margin_bits(N_T)
        // Narrower than its value: value ± margin fits one bit more.
        && DET_MARGIN_BITS < DET_BITS
        && NUM_MARGIN_BITS < NUM_BITS
);

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

/// The pipeline, as the cycle at which each value is registered: the sums (the `Round`s'
/// inputs); H, L, hi, lo; τ'; the product's magnitude; its signed form (its `Round`'s
/// input); the rounded product; the short sum down(lo_u + lo_v).
const SUMS: usize = 2;
/// H, L, hi and lo: their `Round`s' outputs.
pub const SHORT: usize = SUMS + round::LATENCY;
const TAU: usize = 2;
const PRODUCT: usize = SHORT + 1;
const SIGNED: usize = PRODUCT + 1;
const ROUNDED: usize = SIGNED + round::LATENCY;
const SUMMED: usize = SHORT + add_down::LATENCY;
const _: () = assert!(TAU < SHORT && SUMMED <= ROUNDED);

/// Cycles from the inputs to the rows, `miss` and `forward`: the last comparison
/// (hi_t < down(τ'·bound)) and `miss` after the rounded product.
pub const LATENCY: usize = ROUNDED + 1;

/// The decision of one query: the table's rows (each its condition), `miss` (a certain
/// miss: the fallback would answer no hit) and `forward` (to the fallback), [`LATENCY`]
/// cycles after the inputs; a new query every cycle.
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
    /// Cycle 1: |det|, σN and the margins; t_min's exponent and signed significand.
    abs_reg: DFF<Bits<DET_SUM_BITS>>,
    n_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    det_margin_reg: DFF<Bits<DET_MARGIN_BITS>>,
    num_margin_reg: [DFF<Bits<NUM_MARGIN_BITS>>; 3],
    t_e_reg: DFF<Bits<SHORT_EXP_BITS>>,
    significand_reg: DFF<Bits<TAU_BITS>>,
    /// Cycle [`SUMS`]: value ± margin.
    high_x_reg: DFF<Bits<DET_SUM_BITS>>,
    low_x_reg: DFF<Bits<DET_SUM_BITS>>,
    hi_x_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    lo_x_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    /// The exponents beside them.
    det_e_delay: Delay<Bits<SHORT_EXP_BITS>>,
    num_e_delay: [Delay<Bits<SHORT_EXP_BITS>>; 3],
    /// Cycle [`TAU`]: τ'; |τ'| and its sign wait for the bound at [`SHORT`], t_min's
    /// exponent for the product's, its finiteness for the last row.
    tau_reg: DFF<Bits<TAU_BITS>>,
    tau_abs_delay: Delay<Bits<TAU_BITS>>,
    tau_neg_delay: Delay<Bit>,
    t_e_delay: Delay<Bits<SHORT_EXP_BITS>>,
    finite_delay: Delay<Bit>,
    /// H and L; per numerator hi and lo (cycle [`SHORT`]).
    high: Round<DET_SUM_BITS, true>,
    low: Round<DET_SUM_BITS, false>,
    hi: [Round<NUM_SUM_BITS, true>; 3],
    lo: [Round<NUM_SUM_BITS, false>; 3],
    /// H < eps.
    eps_lt: ShortLt<EPS_M_BITS>,
    /// L < 2^-126, H < 2^125: against powers of two, exponent comparisons.
    tiny_lt: Pow2Lt,
    huge_lt: Pow2Lt,
    /// hi < L·2^125, −lo < L·2^125.
    hi_room: [Lt; 3],
    lo_room: [Lt; 3],
    /// −hi_u < H·2^-124, −hi_v < H·2^-124.
    u_flush: Lt,
    v_flush: Lt,
    /// H < lo_u.
    u_lt: Lt,
    /// The rows decided at [`SHORT`], waiting for the last one.
    parallel_delay: Delay<Bit>,
    in_range_delay: Delay<Bit>,
    u_below_delay: Delay<Bit>,
    u_above_delay: Delay<Bit>,
    v_below_delay: Delay<Bit>,
    /// Cycle [`PRODUCT`]: |τ'|·|bound|, its sign and exponent.
    mul: IntMul<TAU_MAG_BITS, BOUND_MAG_BITS, PRODUCT_MAG_BITS>,
    product_reg: DFF<Bits<PRODUCT_MAG_BITS>>,
    product_neg_reg: DFF<Bit>,
    product_e_reg: DFF<Bits<SHORT_EXP_BITS>>,
    /// Cycle [`SIGNED`]: the signed product, into down(τ'·bound) at [`ROUNDED`].
    signed_reg: DFF<Bits<PRODUCT_BITS>>,
    signed_e_reg: DFF<Bits<SHORT_EXP_BITS>>,
    product: Round<PRODUCT_BITS, false>,
    /// down(lo_u + lo_v) at [`SUMMED`], H beside it; H < the sum, waiting for the last row.
    sum: AddDown,
    high_m_delay: Delay<Bits<SHORT_M_BITS>>,
    high_f_delay: Delay<Bits<SHORT_EXP_BITS>>,
    uv_lt: Lt,
    uv_delay: Delay<Bit>,
    /// hi_t beside down(τ'·bound), and hi_t < it.
    hi_t_m_delay: Delay<Bits<SHORT_M_BITS>>,
    hi_t_f_delay: Delay<Bits<SHORT_EXP_BITS>>,
    t_lt: Lt,
    /// Cycle [`LATENCY`]: the outputs.
    parallel_reg: DFF<Bit>,
    in_range_reg: DFF<Bit>,
    u_below_reg: DFF<Bit>,
    u_above_reg: DFF<Bit>,
    v_below_reg: DFF<Bit>,
    uv_above_reg: DFF<Bit>,
    t_below_reg: DFF<Bit>,
    miss_reg: DFF<Bit>,
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
    det_neg: Signal<Local, Bit>,
    /// N one bit wider, σN per numerator.
    num_wide: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    n: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    in_range_now: Signal<Local, Bit>,
    u_below_now: Signal<Local, Bit>,
    v_below_now: Signal<Local, Bit>,
    t_below_now: Signal<Local, Bit>,
    /// τ' = ±significand − 2^k at t_min's exponent, its magnitude and the bound.
    field: Signal<Local, Bits<8>>,
    significand: Signal<Local, Bits<TAU_BITS>>,
    unit_shift: Signal<Local, Bits<SHORT_EXP_BITS>>,
    tau_neg: Signal<Local, Bit>,
    tau_abs: Signal<Local, Bits<TAU_BITS>>,
    bound_m: Signal<Local, Bits<SHORT_M_BITS>>,
    bound_e: Signal<Local, Bits<SHORT_EXP_BITS>>,
    bound_neg: Signal<Local, Bit>,
    bound_abs: Signal<Local, Bits<SHORT_M_BITS>>,
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
            abs_reg: Default::default(),
            n_reg: Default::default(),
            det_margin_reg: Default::default(),
            num_margin_reg: Default::default(),
            t_e_reg: Default::default(),
            significand_reg: Default::default(),
            high_x_reg: Default::default(),
            low_x_reg: Default::default(),
            hi_x_reg: Default::default(),
            lo_x_reg: Default::default(),
            // The inputs' exponents reach the sums.
            det_e_delay: Delay::new(SUMS),
            num_e_delay: Delay::lines(SUMS),
            tau_reg: Default::default(),
            // From τ' (cycle TAU) and t_min's exponent (cycle 1) to the bound (SHORT).
            tau_abs_delay: Delay::new(SHORT - TAU),
            tau_neg_delay: Delay::new(SHORT - TAU),
            t_e_delay: Delay::new(SHORT - 1),
            // From t_min to the last row.
            finite_delay: Delay::new(ROUNDED),
            high: Default::default(),
            low: Default::default(),
            hi: Default::default(),
            lo: Default::default(),
            eps_lt: Default::default(),
            tiny_lt: Pow2Lt::new(RECIPROCAL_MIN),
            huge_lt: Pow2Lt::new(QUOTIENT_MAX),
            hi_room: Default::default(),
            lo_room: Default::default(),
            u_flush: Default::default(),
            v_flush: Default::default(),
            u_lt: Default::default(),
            parallel_delay: Delay::new(ROUNDED - SHORT),
            in_range_delay: Delay::new(ROUNDED - SHORT),
            u_below_delay: Delay::new(ROUNDED - SHORT),
            u_above_delay: Delay::new(ROUNDED - SHORT),
            v_below_delay: Delay::new(ROUNDED - SHORT),
            mul: Default::default(),
            product_reg: Default::default(),
            product_neg_reg: Default::default(),
            product_e_reg: Default::default(),
            signed_reg: Default::default(),
            signed_e_reg: Default::default(),
            product: Default::default(),
            sum: Default::default(),
            high_m_delay: Delay::new(SUMMED - SHORT),
            high_f_delay: Delay::new(SUMMED - SHORT),
            uv_lt: Default::default(),
            uv_delay: Delay::new(ROUNDED - SUMMED),
            hi_t_m_delay: Delay::new(ROUNDED - SHORT),
            hi_t_f_delay: Delay::new(ROUNDED - SHORT),
            t_lt: Default::default(),
            parallel_reg: Default::default(),
            in_range_reg: Default::default(),
            u_below_reg: Default::default(),
            u_above_reg: Default::default(),
            v_below_reg: Default::default(),
            uv_above_reg: Default::default(),
            t_below_reg: Default::default(),
            miss_reg: Default::default(),
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
            det_neg: Default::default(),
            num_wide: Default::default(),
            n: Default::default(),
            in_range_now: Default::default(),
            u_below_now: Default::default(),
            v_below_now: Default::default(),
            t_below_now: Default::default(),
            field: Default::default(),
            significand: Default::default(),
            unit_shift: Default::default(),
            tau_neg: Default::default(),
            tau_abs: Default::default(),
            bound_m: Default::default(),
            bound_e: Default::default(),
            bound_neg: Default::default(),
            bound_abs: Default::default(),
        }
    }
}

impl Logic for Decide {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            abs_reg,
            det_margin_reg,
            t_e_reg,
            significand_reg,
            high_x_reg,
            low_x_reg,
            det_e_delay,
            tau_reg,
            tau_abs_delay,
            tau_neg_delay,
            t_e_delay,
            finite_delay,
            high,
            low
        );
        for k in 0..3 {
            clock!(
                self,
                clock,
                n_reg[k],
                num_margin_reg[k],
                hi_x_reg[k],
                lo_x_reg[k],
                num_e_delay[k],
                hi[k],
                lo[k]
            );
        }
        clock!(
            self,
            clock,
            parallel_delay,
            in_range_delay,
            u_below_delay,
            u_above_delay,
            v_below_delay,
            product_reg,
            product_neg_reg,
            product_e_reg,
            signed_reg,
            signed_e_reg,
            product,
            sum,
            high_m_delay,
            high_f_delay,
            uv_delay,
            hi_t_m_delay,
            hi_t_f_delay,
            parallel_reg,
            in_range_reg,
            u_below_reg,
            u_above_reg,
            v_below_reg,
            uv_above_reg,
            t_below_reg,
            miss_reg
        );

        // Cycle 1: |det| one bit wider (det sign-extended by hand).
        self.det_wide.next = bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val());
        self.det_neg.next = (self.det_wide.val() & self.det_sign.val()).any();
        if self.det_neg.val() {
            self.det_wide.next =
                bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val()) | self.det_top.val();
        }
        self.abs_reg.d.next = self.det_wide.val();
        if self.det_neg.val() {
            self.abs_reg.d.next = !self.det_wide.val() + self.det_one.val();
        }
        self.det_margin_reg.d.next = self.det_margin.val();
        // σN per numerator (σ = sign(det); 0 for a zero det). (bit_cast in a loop loses the
        // loop variable: one per numerator.)
        self.num_wide[0].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[0].val());
        self.num_wide[1].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[1].val());
        self.num_wide[2].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[2].val());
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
            self.n_reg[k].d.next = self.n[k].val();
            self.num_margin_reg[k].d.next = self.num_margin[k].val();
        }
        // t_min's last bit's exponent and signed significand; subnormals read as 0.
        self.field.next = self.t_min.val().get_bits::<8>(23);
        self.t_e_reg.d.next =
            bit_cast::<SHORT_EXP_BITS, 8>(self.field.val()) - self.fp32_bias.val();
        self.significand.next = 0.into();
        if self.field.val().any() {
            self.significand.next =
                self.hidden.val() | bit_cast::<TAU_BITS, 23>(self.t_min.val().get_bits::<23>(0));
        }
        self.significand_reg.d.next = self.significand.val();
        if self.t_min.val().get_bit(31) {
            self.significand_reg.d.next = !self.significand.val() + self.tau_one.val();
        }
        // A non-finite t_min decides nothing.
        self.finite_delay.d.next = self.field.val() != self.field_max.val();

        // Cycle SUMS: value ± margin at the value's last bit, exponents beside.
        self.high_x_reg.d.next = self.abs_reg.q.val()
            + bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.det_margin_reg.q.val());
        self.low_x_reg.d.next = self.abs_reg.q.val()
            - bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.det_margin_reg.q.val());
        self.hi_x_reg[0].d.next = self.n_reg[0].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[0].q.val());
        self.hi_x_reg[1].d.next = self.n_reg[1].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[1].q.val());
        self.hi_x_reg[2].d.next = self.n_reg[2].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[2].q.val());
        self.lo_x_reg[0].d.next = self.n_reg[0].q.val()
            - bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[0].q.val());
        self.lo_x_reg[1].d.next = self.n_reg[1].q.val()
            - bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[1].q.val());
        self.lo_x_reg[2].d.next = self.n_reg[2].q.val()
            - bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.num_margin_reg[2].q.val());
        self.det_e_delay.d.next = self.det_e.val();
        for k in 0..3 {
            self.num_e_delay[k].d.next = self.num_e[k].val();
        }
        // Cycle TAU: τ' = ±significand − 2^k at t_min's last bit 2^e, k = max(0, −126 − e)
        // (λ below 2^-102; one unit above).
        self.unit_shift.next = 0.into();
        if (self.t_e_reg.q.val() ^ self.exp_sign.val())
            < (self.reciprocal_min.val() ^ self.exp_sign.val())
        {
            self.unit_shift.next = self.reciprocal_min.val() - self.t_e_reg.q.val();
        }
        self.tau_reg.d.next =
            self.significand_reg.q.val() - (self.tau_one.val() << self.unit_shift.val());
        self.t_e_delay.d.next = self.t_e_reg.q.val();
        // Its sign and magnitude, waiting for the bound.
        self.tau_neg.next = (self.tau_reg.q.val() & self.tau_sign.val()).any();
        self.tau_abs.next = self.tau_reg.q.val();
        if self.tau_neg.val() {
            self.tau_abs.next = !self.tau_reg.q.val() + self.tau_one.val();
        }
        self.tau_abs_delay.d.next = self.tau_abs.val();
        self.tau_neg_delay.d.next = self.tau_neg.val();

        // Cycles SUMS to SHORT: the short floats H, L, hi, lo.
        self.high.x.next = self.high_x_reg.q.val();
        self.high.e.next = self.det_e_delay.q.val();
        self.low.x.next = self.low_x_reg.q.val();
        self.low.e.next = self.det_e_delay.q.val();
        for k in 0..3 {
            self.hi[k].x.next = self.hi_x_reg[k].q.val();
            self.hi[k].e.next = self.num_e_delay[k].q.val();
            self.lo[k].x.next = self.lo_x_reg[k].q.val();
            self.lo[k].e.next = self.num_e_delay[k].q.val();
        }

        // After SHORT: H < eps (H sign-extended to eps's width).
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
        self.huge_lt.xm.next = self.high.m.val();
        self.huge_lt.xe.next = self.high.f.val();
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
        // u > 1: H < lo_u.
        self.u_lt.xm.next = self.high.m.val();
        self.u_lt.xe.next = self.high.f.val();
        self.u_lt.ym.next = self.lo[0].m.val();
        self.u_lt.ye.next = self.lo[0].f.val();
        self.parallel_delay.d.next = self.eps_lt.lt.val();
        self.in_range_delay.d.next = self.in_range_now.val();
        self.u_below_delay.d.next = self.u_below_now.val();
        self.u_above_delay.d.next = self.u_lt.lt.val();
        self.v_below_delay.d.next = self.v_below_now.val();
        // u + v > 1: H < down(lo_u + lo_v), H waiting for the sum.
        self.sum.xm.next = self.lo[0].m.val();
        self.sum.xe.next = self.lo[0].f.val();
        self.sum.ym.next = self.lo[1].m.val();
        self.sum.ye.next = self.lo[1].f.val();
        self.high_m_delay.d.next = self.high.m.val();
        self.high_f_delay.d.next = self.high.f.val();
        self.uv_lt.xm.next = self.high_m_delay.q.val();
        self.uv_lt.xe.next = self.high_f_delay.q.val();
        self.uv_lt.ym.next = self.sum.sm.val();
        self.uv_lt.ye.next = self.sum.se.val();
        self.uv_delay.d.next = self.uv_lt.lt.val();
        // t ≤ t_min, cycle PRODUCT: |τ'|·|bound|, bound = L if τ' ≥ 0 else H.
        self.bound_m.next = self.low.m.val();
        self.bound_e.next = self.low.f.val();
        if self.tau_neg_delay.q.val() {
            self.bound_m.next = self.high.m.val();
            self.bound_e.next = self.high.f.val();
        }
        self.bound_neg.next = (self.bound_m.val() & self.short_sign.val()).any();
        self.bound_abs.next = self.bound_m.val();
        if self.bound_neg.val() {
            self.bound_abs.next = !self.bound_m.val() + self.one_m.val();
        }
        self.mul.a.next = bit_cast::<TAU_MAG_BITS, TAU_BITS>(self.tau_abs_delay.q.val());
        self.mul.b.next = bit_cast::<BOUND_MAG_BITS, SHORT_M_BITS>(self.bound_abs.val());
        self.product_reg.d.next = self.mul.p.val();
        self.product_neg_reg.d.next = self.tau_neg_delay.q.val() != self.bound_neg.val();
        self.product_e_reg.d.next = self.t_e_delay.q.val() + self.bound_e.val();
        // Cycle SIGNED: the signed product, rounded down by ROUNDED.
        self.signed_reg.d.next =
            bit_cast::<PRODUCT_BITS, PRODUCT_MAG_BITS>(self.product_reg.q.val());
        if self.product_neg_reg.q.val() {
            self.signed_reg.d.next =
                !bit_cast::<PRODUCT_BITS, PRODUCT_MAG_BITS>(self.product_reg.q.val())
                    + self.product_one.val();
        }
        self.signed_e_reg.d.next = self.product_e_reg.q.val();
        self.product.x.next = self.signed_reg.q.val();
        self.product.e.next = self.signed_e_reg.q.val();
        // hi_t < down(τ'·bound), hi_t waiting for it.
        self.hi_t_m_delay.d.next = self.hi[2].m.val();
        self.hi_t_f_delay.d.next = self.hi[2].f.val();
        self.t_lt.xm.next = self.hi_t_m_delay.q.val();
        self.t_lt.xe.next = self.hi_t_f_delay.q.val();
        self.t_lt.ym.next = self.product.m.val();
        self.t_lt.ye.next = self.product.f.val();

        // Cycle LATENCY: the rows, miss and forward.
        self.t_below_now.next = self.t_lt.lt.val() && self.finite_delay.q.val();
        self.t_below_reg.d.next = self.t_below_now.val();
        self.parallel_reg.d.next = self.parallel_delay.q.val();
        self.in_range_reg.d.next = self.in_range_delay.q.val();
        self.u_below_reg.d.next = self.u_below_delay.q.val();
        self.u_above_reg.d.next = self.u_above_delay.q.val();
        self.v_below_reg.d.next = self.v_below_delay.q.val();
        self.uv_above_reg.d.next = self.uv_delay.q.val();
        self.miss_reg.d.next = self.parallel_delay.q.val()
            || (self.in_range_delay.q.val()
                && (self.u_below_delay.q.val()
                    || self.u_above_delay.q.val()
                    || self.v_below_delay.q.val()
                    || self.uv_delay.q.val()
                    || self.t_below_now.val()));
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
