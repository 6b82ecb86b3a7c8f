//! The Plücker lane's decisions, bit for bit `hw_model::dual::signs::decide`: bfp's rows
//! made stronger so that nothing is normalised, aligned or multiplied. Integer adders form
//! |det| ± e_D, σN + e and |N| + e at each value's last bit; bit lengths ([`BitLength`])
//! and exponent adders compare them; u + v > 1 is the sign of σN_w + M_w, M_w N_w's own
//! margin plus one power of two per other margin (at its length, moved to N_w's grid: a
//! decoder, not a shifter). One decision a cycle, one carry chain or one length a stage:
//! σN, |N| and the margins' lengths; the sums and M_w's shifts; the lengths and M_w; the
//! exponent sums and σN_w + M_w; the rows; `miss`.

use hw_model::dual::bfp::{FLUSH_SHIFT, QUOTIENT_MAX, RECIPROCAL_MIN};
use hw_model::dual::signs::{eps_exp, uv_shift_max, T_NORMAL_MIN};
use rust_hdl::prelude::*;

use super::bit_length::{BitLength, LENGTH_BITS};
use super::decide::{DET_BITS, DET_MARGIN_BITS, NUM_BITS, NUM_MARGIN_BITS};
use super::plucker::EDGE_VALUE_BITS;
use super::round::SHORT_EXP_BITS;
use super::WIDTH;
use crate::macros::clock;
use crate::mt::delay::Delay;

/// |det| ± e_D: one bit more than det (H < 2^DET_BITS, L signed).
const DET_SUM_BITS: usize = DET_BITS + 1;
/// σN, σN + e and |N| + e: one bit more than N.
const NUM_SUM_BITS: usize = NUM_BITS + 1;
/// σN_w.
const W_BITS: usize = EDGE_VALUE_BITS + 1;
/// σN_w + M_w (M_w below 2^NUM_MARGIN_BITS).
const HW_BITS: usize = max(W_BITS, NUM_MARGIN_BITS + 1) + 1;
/// Exponent arithmetic: grids (short exponents), lengths, t_min's exponent and the rows'
/// constants, signed, with room for their sums and differences.
pub const X_BITS: usize = SHORT_EXP_BITS + 3;

const fn max(a: usize, b: usize) -> usize {
    if a > b {
        a
    } else {
        b
    }
}

/// Clock edges from the inputs to the rows, `miss` and `forward`.
pub const LATENCY: usize = 6;

type X = Bits<X_BITS>;
type Len = Bits<LENGTH_BITS>;

/// The decision of one query, [`LATENCY`] cycles after its inputs; a new query every cycle.
/// Values are two's complement at their last bit's exponent (signed short exponents, as
/// `Decide` takes them), margins in units of that bit.
#[derive(LogicBlock)]
pub struct SignDecide {
    pub clock: Signal<In, Clock>,
    pub det: Signal<In, Bits<DET_BITS>>,
    pub det_e: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub det_margin: Signal<In, Bits<DET_MARGIN_BITS>>,
    /// N_u, N_v, N_t.
    pub num: [Signal<In, Bits<NUM_BITS>>; 3],
    pub num_e: [Signal<In, Bits<SHORT_EXP_BITS>>; 3],
    pub num_margin: [Signal<In, Bits<NUM_MARGIN_BITS>>; 3],
    /// N_w and its own margin.
    pub w: Signal<In, Bits<EDGE_VALUE_BITS>>,
    pub w_e: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub w_margin: Signal<In, Bits<NUM_MARGIN_BITS>>,
    /// The query's t_min, fp32 bits.
    pub t_min: Signal<In, Bits<32>>,
    pub parallel: Signal<Out, Bit>,
    pub in_range: Signal<Out, Bit>,
    pub u_below: Signal<Out, Bit>,
    pub v_below: Signal<Out, Bit>,
    pub uv_above: Signal<Out, Bit>,
    pub t_below: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    /// Cycle 1: |det|, σN, |N|, σN_w, the margins, the lengths of e_D, e_u, e_v, the
    /// grids, t_min's class and p.
    d_reg: DFF<Bits<DET_SUM_BITS>>,
    n_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    a_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    nw_reg: DFF<Bits<W_BITS>>,
    dm_reg: DFF<Bits<DET_MARGIN_BITS>>,
    nm_reg: [DFF<Bits<NUM_MARGIN_BITS>>; 3],
    wm_reg: DFF<Bits<NUM_MARGIN_BITS>>,
    e_len_reg: [DFF<Len>; 3],
    l_reg: [DFF<X>; 5],
    unknown_reg: DFF<Bit>,
    small_reg: DFF<Bit>,
    p_reg: DFF<X>,
    /// Cycle 2: H, L, hi, reach; M_w's shifts.
    high_reg: DFF<Bits<DET_SUM_BITS>>,
    low_reg: DFF<Bits<DET_SUM_BITS>>,
    hi_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    reach_reg: [DFF<Bits<NUM_SUM_BITS>>; 3],
    s_reg: [DFF<X>; 3],
    nw_delay: Delay<Bits<W_BITS>>,
    wm_reg2: DFF<Bits<NUM_MARGIN_BITS>>,
    /// Cycle 3: the lengths, the signs, M_w and whether its shifts fit.
    len_h_reg: DFF<Len>,
    len_l_reg: DFF<Len>,
    len_hi_reg: [DFF<Len>; 3],
    len_reach_reg: [DFF<Len>; 3],
    low_pos_reg: DFF<Bit>,
    hi_neg_reg: [DFF<Bit>; 3],
    hi_t_pos_reg: DFF<Bit>,
    mw_reg: DFF<Bits<NUM_MARGIN_BITS>>,
    fits_reg: DFF<Bit>,
    /// Cycle 4: the exponent sums; σN_w + M_w < 0.
    lh_reg: DFF<X>,
    ll_reg: DFF<X>,
    reach_x_reg: [DFF<X>; 3],
    below_x_reg: [DFF<X>; 3],
    t_x_reg: DFF<X>,
    w_neg_reg: DFF<Bit>,
    /// Waiting lines (to cycle 4 or 5).
    l_delay: [Delay<X>; 4],
    unknown_delay: Delay<Bit>,
    small_delay: Delay<Bit>,
    p_delay: Delay<X>,
    low_pos_delay: DFF<Bit>,
    hi_neg_delay: [DFF<Bit>; 3],
    hi_t_pos_delay: DFF<Bit>,
    fits_delay: DFF<Bit>,
    /// Cycle 5: the rows; cycle 6: miss, the rows beside it.
    parallel_reg: DFF<Bit>,
    in_range_reg: DFF<Bit>,
    u_below_reg: DFF<Bit>,
    v_below_reg: DFF<Bit>,
    uv_above_reg: DFF<Bit>,
    t_below_reg: DFF<Bit>,
    parallel_out: DFF<Bit>,
    in_range_out: DFF<Bit>,
    u_below_out: DFF<Bit>,
    v_below_out: DFF<Bit>,
    uv_above_out: DFF<Bit>,
    t_below_out: DFF<Bit>,
    miss_reg: DFF<Bit>,
    /// Lengths.
    det_margin_len: BitLength<DET_MARGIN_BITS>,
    num_margin_len: [BitLength<NUM_MARGIN_BITS>; 2],
    high_len: BitLength<DET_SUM_BITS>,
    low_len: BitLength<DET_SUM_BITS>,
    hi_len: [BitLength<NUM_SUM_BITS>; 3],
    reach_len: [BitLength<NUM_SUM_BITS>; 3],
    /// Constants: sign bits and sign extensions, ones; the rows' exponents (offset binary
    /// in comparisons: `x_sign` flips the sign bit); fp32's fields.
    det_sign: Constant<Bits<DET_BITS>>,
    det_ext: Constant<Bits<DET_SUM_BITS>>,
    det_one: Constant<Bits<DET_SUM_BITS>>,
    det_sum_sign: Constant<Bits<DET_SUM_BITS>>,
    num_sign: Constant<Bits<NUM_BITS>>,
    num_ext: Constant<Bits<NUM_SUM_BITS>>,
    num_one: Constant<Bits<NUM_SUM_BITS>>,
    num_sum_sign: Constant<Bits<NUM_SUM_BITS>>,
    w_sign: Constant<Bits<EDGE_VALUE_BITS>>,
    w_ext: Constant<Bits<W_BITS>>,
    w_one: Constant<Bits<W_BITS>>,
    nw_sign: Constant<Bits<W_BITS>>,
    hw_sign: Constant<Bits<HW_BITS>>,
    hw_ext: Constant<Bits<HW_BITS>>,
    short_sign: Constant<Bits<SHORT_EXP_BITS>>,
    short_ext: Constant<X>,
    x_sign: Constant<X>,
    x_one: Constant<X>,
    mw_one: Constant<Bits<NUM_MARGIN_BITS>>,
    eps_exp: Constant<X>,
    reciprocal_min: Constant<X>,
    quotient_max: Constant<X>,
    flush_shift: Constant<X>,
    shift_max: Constant<X>,
    field_max: Constant<Bits<8>>,
    field_normal: Constant<Bits<8>>,
    field_bias: Constant<X>,
    /// Combinational.
    det_wide: Signal<Local, Bits<DET_SUM_BITS>>,
    det_neg: Signal<Local, Bit>,
    det_zero: Signal<Local, Bit>,
    num_wide: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    w_wide: Signal<Local, Bits<W_BITS>>,
    exps: [Signal<Local, Bits<SHORT_EXP_BITS>>; 5],
    lx: [Signal<Local, X>; 5],
    field: Signal<Local, Bits<8>>,
    terms: [Signal<Local, Bits<NUM_MARGIN_BITS>>; 3],
    fits: [Signal<Local, Bit>; 3],
    hw: Signal<Local, Bits<HW_BITS>>,
    low_mag: Signal<Local, Bits<DET_SUM_BITS>>,
    hi_mag: [Signal<Local, Bits<NUM_SUM_BITS>>; 3],
    len_x: [Signal<Local, X>; 8],
    small_row: Signal<Local, Bit>,
    at_least_row: Signal<Local, Bit>,
}

impl Default for SignDecide {
    fn default() -> Self {
        let x = |v: i64| Constant::new(((v as u64) & ((1u64 << X_BITS) - 1)).to_bits());
        let ones_above = |from: usize, width: usize| ((1u64 << width) - 1) & !((1u64 << from) - 1);
        let shift_max = uv_shift_max(WIDTH);
        assert!(
            shift_max < NUM_MARGIN_BITS as i32,
            "M_w's terms fit its width"
        );
        // The t row's normal class: fp32 fields from T_NORMAL_MIN's up.
        let field_normal = T_NORMAL_MIN + 127;
        assert!((1..255).contains(&field_normal));
        Self {
            clock: Default::default(),
            det: Default::default(),
            det_e: Default::default(),
            det_margin: Default::default(),
            num: Default::default(),
            num_e: Default::default(),
            num_margin: Default::default(),
            w: Default::default(),
            w_e: Default::default(),
            w_margin: Default::default(),
            t_min: Default::default(),
            parallel: Default::default(),
            in_range: Default::default(),
            u_below: Default::default(),
            v_below: Default::default(),
            uv_above: Default::default(),
            t_below: Default::default(),
            miss: Default::default(),
            forward: Default::default(),
            d_reg: Default::default(),
            n_reg: Default::default(),
            a_reg: Default::default(),
            nw_reg: Default::default(),
            dm_reg: Default::default(),
            nm_reg: Default::default(),
            wm_reg: Default::default(),
            e_len_reg: Default::default(),
            l_reg: Default::default(),
            unknown_reg: Default::default(),
            small_reg: Default::default(),
            p_reg: Default::default(),
            high_reg: Default::default(),
            low_reg: Default::default(),
            hi_reg: Default::default(),
            reach_reg: Default::default(),
            s_reg: Default::default(),
            nw_delay: Delay::new(2),
            wm_reg2: Default::default(),
            len_h_reg: Default::default(),
            len_l_reg: Default::default(),
            len_hi_reg: Default::default(),
            len_reach_reg: Default::default(),
            low_pos_reg: Default::default(),
            hi_neg_reg: Default::default(),
            hi_t_pos_reg: Default::default(),
            mw_reg: Default::default(),
            fits_reg: Default::default(),
            lh_reg: Default::default(),
            ll_reg: Default::default(),
            reach_x_reg: Default::default(),
            below_x_reg: Default::default(),
            t_x_reg: Default::default(),
            w_neg_reg: Default::default(),
            // The grids of det, N_u, N_v, N_t from cycle 1 to the sums at 4.
            l_delay: Delay::lines(2),
            // t_min's class and p from cycle 1 to the rows at 5.
            unknown_delay: Delay::new(3),
            small_delay: Delay::new(3),
            p_delay: Delay::new(3),
            low_pos_delay: Default::default(),
            hi_neg_delay: Default::default(),
            hi_t_pos_delay: Default::default(),
            fits_delay: Default::default(),
            parallel_reg: Default::default(),
            in_range_reg: Default::default(),
            u_below_reg: Default::default(),
            v_below_reg: Default::default(),
            uv_above_reg: Default::default(),
            t_below_reg: Default::default(),
            parallel_out: Default::default(),
            in_range_out: Default::default(),
            u_below_out: Default::default(),
            v_below_out: Default::default(),
            uv_above_out: Default::default(),
            t_below_out: Default::default(),
            miss_reg: Default::default(),
            det_margin_len: Default::default(),
            num_margin_len: Default::default(),
            high_len: Default::default(),
            low_len: Default::default(),
            hi_len: Default::default(),
            reach_len: Default::default(),
            det_sign: Constant::new((1u64 << (DET_BITS - 1)).to_bits()),
            det_ext: Constant::new(ones_above(DET_BITS, DET_SUM_BITS).to_bits()),
            det_one: Constant::new(1u64.to_bits()),
            det_sum_sign: Constant::new((1u64 << (DET_SUM_BITS - 1)).to_bits()),
            num_sign: Constant::new((1u64 << (NUM_BITS - 1)).to_bits()),
            num_ext: Constant::new(ones_above(NUM_BITS, NUM_SUM_BITS).to_bits()),
            num_one: Constant::new(1u64.to_bits()),
            num_sum_sign: Constant::new((1u64 << (NUM_SUM_BITS - 1)).to_bits()),
            w_sign: Constant::new((1u64 << (EDGE_VALUE_BITS - 1)).to_bits()),
            w_ext: Constant::new(ones_above(EDGE_VALUE_BITS, W_BITS).to_bits()),
            w_one: Constant::new(1u64.to_bits()),
            nw_sign: Constant::new((1u64 << (W_BITS - 1)).to_bits()),
            hw_sign: Constant::new((1u64 << (HW_BITS - 1)).to_bits()),
            hw_ext: Constant::new(ones_above(W_BITS, HW_BITS).to_bits()),
            short_sign: Constant::new((1u64 << (SHORT_EXP_BITS - 1)).to_bits()),
            short_ext: Constant::new(ones_above(SHORT_EXP_BITS, X_BITS).to_bits()),
            x_sign: x(1 << (X_BITS - 1)),
            x_one: x(1),
            mw_one: Constant::new(1u64.to_bits()),
            eps_exp: x(eps_exp().into()),
            reciprocal_min: x(RECIPROCAL_MIN.into()),
            quotient_max: x(QUOTIENT_MAX.into()),
            flush_shift: x(FLUSH_SHIFT.into()),
            shift_max: x(shift_max.into()),
            field_max: Constant::new(0xffu64.to_bits()),
            field_normal: Constant::new((field_normal as u64).to_bits()),
            field_bias: x(127),
            det_wide: Default::default(),
            det_neg: Default::default(),
            det_zero: Default::default(),
            num_wide: Default::default(),
            w_wide: Default::default(),
            exps: Default::default(),
            lx: Default::default(),
            field: Default::default(),
            terms: Default::default(),
            fits: Default::default(),
            hw: Default::default(),
            low_mag: Default::default(),
            hi_mag: Default::default(),
            len_x: Default::default(),
            small_row: Default::default(),
            at_least_row: Default::default(),
        }
    }
}

impl Logic for SignDecide {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            d_reg,
            nw_reg,
            dm_reg,
            wm_reg,
            unknown_reg,
            small_reg,
            p_reg,
            high_reg,
            low_reg,
            wm_reg2,
            len_h_reg,
            len_l_reg,
            low_pos_reg,
            hi_t_pos_reg,
            mw_reg,
            fits_reg,
            lh_reg,
            ll_reg,
            t_x_reg,
            w_neg_reg,
            low_pos_delay,
            hi_t_pos_delay,
            fits_delay,
            parallel_reg,
            in_range_reg,
            u_below_reg,
            v_below_reg,
            uv_above_reg,
            t_below_reg,
            parallel_out,
            in_range_out,
            u_below_out,
            v_below_out,
            uv_above_out,
            t_below_out,
            miss_reg
        );
        clock!(self, clock, nw_delay, unknown_delay, small_delay, p_delay);
        for k in 0..3 {
            clock!(
                self,
                clock,
                n_reg[k],
                a_reg[k],
                nm_reg[k],
                e_len_reg[k],
                hi_reg[k],
                reach_reg[k],
                s_reg[k],
                len_hi_reg[k],
                len_reach_reg[k],
                hi_neg_reg[k],
                reach_x_reg[k],
                below_x_reg[k],
                hi_neg_delay[k]
            );
        }
        for k in 0..5 {
            clock!(self, clock, l_reg[k]);
        }
        for k in 0..4 {
            clock!(self, clock, l_delay[k]);
        }

        // Cycle 1: |det| (one bit wider), σN and |N| per numerator, σN_w; σ = 0 for det = 0.
        self.det_neg.next = (self.det.val() & self.det_sign.val()).any();
        self.det_zero.next = !self.det.val().any();
        self.det_wide.next = bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val());
        if self.det_neg.val() {
            self.det_wide.next =
                bit_cast::<DET_SUM_BITS, DET_BITS>(self.det.val()) | self.det_ext.val();
        }
        self.d_reg.d.next = self.det_wide.val();
        if self.det_neg.val() {
            self.d_reg.d.next = !self.det_wide.val() + self.det_one.val();
        }
        // (bit_cast of a loop-indexed signal does not generate: written out.)
        self.num_wide[0].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[0].val());
        self.num_wide[1].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[1].val());
        self.num_wide[2].next = bit_cast::<NUM_SUM_BITS, NUM_BITS>(self.num[2].val());
        for k in 0..3 {
            if (self.num[k].val() & self.num_sign.val()).any() {
                self.num_wide[k].next = self.num_wide[k].val() | self.num_ext.val();
            }
            self.n_reg[k].d.next = self.num_wide[k].val();
            if self.det_neg.val() {
                self.n_reg[k].d.next = !self.num_wide[k].val() + self.num_one.val();
            }
            self.a_reg[k].d.next = self.num_wide[k].val();
            if (self.num[k].val() & self.num_sign.val()).any() {
                self.a_reg[k].d.next = !self.num_wide[k].val() + self.num_one.val();
            }
            if self.det_zero.val() {
                self.n_reg[k].d.next = 0.into();
                self.a_reg[k].d.next = 0.into();
            }
            self.nm_reg[k].d.next = self.num_margin[k].val();
        }
        self.w_wide.next = bit_cast::<W_BITS, EDGE_VALUE_BITS>(self.w.val());
        if (self.w.val() & self.w_sign.val()).any() {
            self.w_wide.next = bit_cast::<W_BITS, EDGE_VALUE_BITS>(self.w.val()) | self.w_ext.val();
        }
        self.nw_reg.d.next = self.w_wide.val();
        if self.det_neg.val() {
            self.nw_reg.d.next = !self.w_wide.val() + self.w_one.val();
        }
        if self.det_zero.val() {
            self.nw_reg.d.next = 0.into();
        }
        self.dm_reg.d.next = self.det_margin.val();
        self.wm_reg.d.next = self.w_margin.val();
        // The lengths of e_D, e_u, e_v (M_w's terms).
        self.det_margin_len.x.next = self.det_margin.val();
        self.num_margin_len[0].x.next = self.num_margin[0].val();
        self.num_margin_len[1].x.next = self.num_margin[1].val();
        self.e_len_reg[0].d.next = self.det_margin_len.len.val();
        self.e_len_reg[1].d.next = self.num_margin_len[0].len.val();
        self.e_len_reg[2].d.next = self.num_margin_len[1].len.val();
        // The grids (det, N_u, N_v, N_t, N_w), sign-extended.
        self.exps[0].next = self.det_e.val();
        self.exps[1].next = self.num_e[0].val();
        self.exps[2].next = self.num_e[1].val();
        self.exps[3].next = self.num_e[2].val();
        self.exps[4].next = self.w_e.val();
        self.lx[0].next = bit_cast::<X_BITS, SHORT_EXP_BITS>(self.exps[0].val());
        self.lx[1].next = bit_cast::<X_BITS, SHORT_EXP_BITS>(self.exps[1].val());
        self.lx[2].next = bit_cast::<X_BITS, SHORT_EXP_BITS>(self.exps[2].val());
        self.lx[3].next = bit_cast::<X_BITS, SHORT_EXP_BITS>(self.exps[3].val());
        self.lx[4].next = bit_cast::<X_BITS, SHORT_EXP_BITS>(self.exps[4].val());
        for k in 0..5 {
            if (self.exps[k].val() & self.short_sign.val()).any() {
                self.lx[k].next = self.lx[k].val() | self.short_ext.val();
            }
            self.l_reg[k].d.next = self.lx[k].val();
        }
        // t_min's class (`signs::Tau`) and p: NaN, Inf and negative normals decide nothing;
        // zeros, subnormals and fields below T_NORMAL_MIN's are small; else p = its
        // exponent, one less for a power of two.
        self.field.next = self.t_min.val().get_bits::<8>(23);
        self.unknown_reg.d.next = self.field.val() == self.field_max.val()
            || (self.field.val().any() && self.t_min.val().get_bit(31));
        self.small_reg.d.next = self.field.val() < self.field_normal.val();
        self.p_reg.d.next = bit_cast::<X_BITS, 8>(self.field.val()) - self.field_bias.val();
        if !self.t_min.val().get_bits::<23>(0).any() {
            self.p_reg.d.next =
                bit_cast::<X_BITS, 8>(self.field.val()) - self.field_bias.val() - self.x_one.val();
        }

        // Cycle 2: H = |det| + e_D, L = |det| − e_D, hi = σN + e, reach = |N| + e; M_w's
        // shifts len(e) + 1 + L_x − L_w.
        self.high_reg.d.next =
            self.d_reg.q.val() + bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.dm_reg.q.val());
        self.low_reg.d.next =
            self.d_reg.q.val() - bit_cast::<DET_SUM_BITS, DET_MARGIN_BITS>(self.dm_reg.q.val());
        self.hi_reg[0].d.next = self.n_reg[0].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[0].q.val());
        self.hi_reg[1].d.next = self.n_reg[1].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[1].q.val());
        self.hi_reg[2].d.next = self.n_reg[2].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[2].q.val());
        self.reach_reg[0].d.next = self.a_reg[0].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[0].q.val());
        self.reach_reg[1].d.next = self.a_reg[1].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[1].q.val());
        self.reach_reg[2].d.next = self.a_reg[2].q.val()
            + bit_cast::<NUM_SUM_BITS, NUM_MARGIN_BITS>(self.nm_reg[2].q.val());
        self.s_reg[0].d.next = bit_cast::<X_BITS, LENGTH_BITS>(self.e_len_reg[0].q.val())
            + self.x_one.val()
            + self.l_reg[0].q.val()
            - self.l_reg[4].q.val();
        self.s_reg[1].d.next = bit_cast::<X_BITS, LENGTH_BITS>(self.e_len_reg[1].q.val())
            + self.x_one.val()
            + self.l_reg[1].q.val()
            - self.l_reg[4].q.val();
        self.s_reg[2].d.next = bit_cast::<X_BITS, LENGTH_BITS>(self.e_len_reg[2].q.val())
            + self.x_one.val()
            + self.l_reg[2].q.val()
            - self.l_reg[4].q.val();
        self.nw_delay.d.next = self.nw_reg.q.val();
        self.wm_reg2.d.next = self.wm_reg.q.val();
        for k in 0..4 {
            self.l_delay[k].d.next = self.l_reg[k].q.val();
        }
        self.unknown_delay.d.next = self.unknown_reg.q.val();
        self.small_delay.d.next = self.small_reg.q.val();
        self.p_delay.d.next = self.p_reg.q.val();

        // Cycle 3: the lengths (of L and hi XOR their signs), the signs; M_w = N_w's margin
        // plus 2^s per term (1 for s < 0), if every s is at most the largest shift.
        self.high_len.x.next = self.high_reg.q.val();
        self.low_mag.next = self.low_reg.q.val();
        if (self.low_reg.q.val() & self.det_sum_sign.val()).any() {
            self.low_mag.next = !self.low_reg.q.val();
        }
        self.low_len.x.next = self.low_mag.val();
        for k in 0..3 {
            self.hi_mag[k].next = self.hi_reg[k].q.val();
            if (self.hi_reg[k].q.val() & self.num_sum_sign.val()).any() {
                self.hi_mag[k].next = !self.hi_reg[k].q.val();
            }
            self.hi_len[k].x.next = self.hi_mag[k].val();
            self.reach_len[k].x.next = self.reach_reg[k].q.val();
            self.len_hi_reg[k].d.next = self.hi_len[k].len.val();
            self.len_reach_reg[k].d.next = self.reach_len[k].len.val();
            self.hi_neg_reg[k].d.next = (self.hi_reg[k].q.val() & self.num_sum_sign.val()).any();
        }
        self.len_h_reg.d.next = self.high_len.len.val();
        self.len_l_reg.d.next = self.low_len.len.val();
        self.low_pos_reg.d.next =
            !(self.low_reg.q.val() & self.det_sum_sign.val()).any() && self.low_reg.q.val().any();
        self.hi_t_pos_reg.d.next = !(self.hi_reg[2].q.val() & self.num_sum_sign.val()).any()
            && self.hi_reg[2].q.val().any();
        for k in 0..3 {
            self.terms[k].next = self.mw_one.val();
            if !(self.s_reg[k].q.val() & self.x_sign.val()).any() {
                self.terms[k].next = self.mw_one.val() << self.s_reg[k].q.val();
            }
            self.fits[k].next = (self.s_reg[k].q.val() ^ self.x_sign.val())
                <= (self.shift_max.val() ^ self.x_sign.val());
        }
        self.mw_reg.d.next =
            self.wm_reg2.q.val() + self.terms[0].val() + self.terms[1].val() + self.terms[2].val();
        self.fits_reg.d.next = self.fits[0].val() && self.fits[1].val() && self.fits[2].val();

        // Cycle 4: lh = len(H) + L_D, ll = len(L) − 1 + L_D; per numerator len(reach) + L_x
        // and len(hi) − 1 + L_x; len(hi_t) + L_t; σN_w + M_w < 0.
        self.len_x[0].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_h_reg.q.val());
        self.len_x[1].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_l_reg.q.val());
        self.len_x[2].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_reach_reg[0].q.val());
        self.len_x[3].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_reach_reg[1].q.val());
        self.len_x[4].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_reach_reg[2].q.val());
        self.len_x[5].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_hi_reg[0].q.val());
        self.len_x[6].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_hi_reg[1].q.val());
        self.len_x[7].next = bit_cast::<X_BITS, LENGTH_BITS>(self.len_hi_reg[2].q.val());
        self.lh_reg.d.next = self.len_x[0].val() + self.l_delay[0].q.val();
        self.ll_reg.d.next = self.len_x[1].val() - self.x_one.val() + self.l_delay[0].q.val();
        for k in 0..3 {
            self.reach_x_reg[k].d.next = self.len_x[k + 2].val() + self.l_delay[k + 1].q.val();
            self.below_x_reg[k].d.next =
                self.len_x[k + 5].val() - self.x_one.val() + self.l_delay[k + 1].q.val();
            self.hi_neg_delay[k].d.next = self.hi_neg_reg[k].q.val();
        }
        self.t_x_reg.d.next = self.len_x[7].val() + self.l_delay[3].q.val();
        self.hw.next = bit_cast::<HW_BITS, W_BITS>(self.nw_delay.q.val())
            + bit_cast::<HW_BITS, NUM_MARGIN_BITS>(self.mw_reg.q.val());
        if (self.nw_delay.q.val() & self.nw_sign.val()).any() {
            self.hw.next = (bit_cast::<HW_BITS, W_BITS>(self.nw_delay.q.val()) | self.hw_ext.val())
                + bit_cast::<HW_BITS, NUM_MARGIN_BITS>(self.mw_reg.q.val());
        }
        self.w_neg_reg.d.next = (self.hw.val() & self.hw_sign.val()).any();
        self.low_pos_delay.d.next = self.low_pos_reg.q.val();
        self.hi_t_pos_delay.d.next = self.hi_t_pos_reg.q.val();
        self.fits_delay.d.next = self.fits_reg.q.val();

        // Cycle 5: the rows (signed comparisons in offset binary).
        self.parallel_reg.d.next =
            (self.lh_reg.q.val() ^ self.x_sign.val()) <= (self.eps_exp.val() ^ self.x_sign.val());
        self.in_range_reg.d.next = self.low_pos_delay.q.val()
            && (self.ll_reg.q.val() ^ self.x_sign.val())
                >= (self.reciprocal_min.val() ^ self.x_sign.val())
            && (self.lh_reg.q.val() ^ self.x_sign.val())
                <= (self.quotient_max.val() ^ self.x_sign.val())
            && (self.reach_x_reg[0].q.val() ^ self.x_sign.val())
                <= ((self.ll_reg.q.val() + self.quotient_max.val()) ^ self.x_sign.val())
            && (self.reach_x_reg[1].q.val() ^ self.x_sign.val())
                <= ((self.ll_reg.q.val() + self.quotient_max.val()) ^ self.x_sign.val())
            && (self.reach_x_reg[2].q.val() ^ self.x_sign.val())
                <= ((self.ll_reg.q.val() + self.quotient_max.val()) ^ self.x_sign.val());
        self.u_below_reg.d.next = self.hi_neg_delay[0].q.val()
            && ((self.lh_reg.q.val() + self.flush_shift.val()) ^ self.x_sign.val())
                <= (self.below_x_reg[0].q.val() ^ self.x_sign.val());
        self.v_below_reg.d.next = self.hi_neg_delay[1].q.val()
            && ((self.lh_reg.q.val() + self.flush_shift.val()) ^ self.x_sign.val())
                <= (self.below_x_reg[1].q.val() ^ self.x_sign.val());
        self.uv_above_reg.d.next = self.fits_delay.q.val() && self.w_neg_reg.q.val();
        self.small_row.next = self.hi_neg_delay[2].q.val()
            && ((self.lh_reg.q.val() + self.reciprocal_min.val()) ^ self.x_sign.val())
                <= (self.below_x_reg[2].q.val() ^ self.x_sign.val());
        self.at_least_row.next = !self.hi_t_pos_delay.q.val()
            || (self.t_x_reg.q.val() ^ self.x_sign.val())
                <= ((self.p_delay.q.val() + self.ll_reg.q.val()) ^ self.x_sign.val());
        self.t_below_reg.d.next = !self.unknown_delay.q.val() && self.at_least_row.val();
        if self.small_delay.q.val() {
            self.t_below_reg.d.next = !self.unknown_delay.q.val() && self.small_row.val();
        }

        // Cycle 6: miss, the rows beside it.
        self.miss_reg.d.next = self.parallel_reg.q.val()
            || (self.in_range_reg.q.val()
                && (self.u_below_reg.q.val()
                    || self.v_below_reg.q.val()
                    || self.uv_above_reg.q.val()
                    || self.t_below_reg.q.val()));
        self.parallel_out.d.next = self.parallel_reg.q.val();
        self.in_range_out.d.next = self.in_range_reg.q.val();
        self.u_below_out.d.next = self.u_below_reg.q.val();
        self.v_below_out.d.next = self.v_below_reg.q.val();
        self.uv_above_out.d.next = self.uv_above_reg.q.val();
        self.t_below_out.d.next = self.t_below_reg.q.val();
        self.parallel.next = self.parallel_out.q.val();
        self.in_range.next = self.in_range_out.q.val();
        self.u_below.next = self.u_below_out.q.val();
        self.v_below.next = self.v_below_out.q.val();
        self.uv_above.next = self.uv_above_out.q.val();
        self.t_below.next = self.t_below_out.q.val();
        self.miss.next = self.miss_reg.q.val();
        self.forward.next = !self.miss_reg.q.val();
    }
}
