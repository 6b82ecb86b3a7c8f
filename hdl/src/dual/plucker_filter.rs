//! The whole Plücker filter, one lane: bit for bit the model's
//! `hw_model::dual::plucker::sign_inputs` followed by `signs::decide`
//! (`Filter::certain_miss(q, 1.0)` for bfp18/fp32 with `--dual-filter plucker-signs`). One
//! test per cycle, fully pipelined.
//!
//! The ray's and the triangle's stored vectors come in (`plucker::Operands`, formed once
//! per ray and per scene). [`PluckerDatapath`] computes −det, −N_u, −N_v, −N_w, −N_t; beside
//! it, [`SBound`] gives E_s, an exponent stage the values' grids (hence each dot's distance
//! below its value's last bit) and ΣE of each value, a second the fallback's shift y = its
//! constant's shift + ΣE − L; five [`PluckerMargin`]s the margins, ready with the values
//! (N_w's without a fallback term). The values are fitted to the bfp filter's step-5 widths
//! (det floored by 7 bits, N_t by 8, N_u and N_v sign-extended; N_w as it is) and
//! [`SignDecide`] decides. A query the model forwards is forwarded whatever the decisions
//! say: no stored vectors (`stored` low), a fallback exponent outside the range its
//! constant covers, a value's grid outside what step 5 receives from the bfp filter, or a
//! fallback term of 2^(MB − 1) or more.

use hw_model::dual::bfp::{lsb_range, DET, EXP_MAX, EXP_MIN, N_U, SUM_MIN};
use hw_model::dual::plucker::{fallback_term, margin_constants};
use rust_hdl::prelude::*;

use super::align_add::{EXP_BIAS, EXP_BITS};
use super::decide::{self, DET_MARGIN_BITS, NUM_BITS, NUM_MARGIN_BITS};
use super::plucker::{
    self, PluckerDatapath, DET_BITS, EDGE_VALUE_BITS, NT_BITS, OFFSET_BITS, W, WT,
};
use super::plucker_margin::{self, PluckerMargin, BELOW_BITS, Y_BIAS, Y_BITS};
use super::round::SHORT_EXP_BITS;
use super::s_bound::{self, SBound, CUT_BITS};
use super::sign_decide::{self, SignDecide};
use crate::macros::clock;
use crate::mt::delay::Delay;

/// The values' floors onto step 5's widths.
const K_DET: usize = DET_BITS - decide::DET_BITS;
const K_T: usize = NT_BITS - NUM_BITS;
const _: () = assert!(EDGE_VALUE_BITS <= NUM_BITS);

/// A value's grid, biased by 2·[`EXP_BIAS`] (two fields added).
const L_BITS: usize = EXP_BITS + 1;
const L_BIAS: i64 = 2 * EXP_BIAS as i64;
/// Step 5's exponents are L's low bits: L_BIAS is 0 modulo 2^SHORT_EXP_BITS.
const _: () = assert!(L_BIAS % (1 << SHORT_EXP_BITS) == 0);
/// ΣE, biased by 3·[`EXP_BIAS`] (three block exponent fields added).
const SUM_BITS: usize = EXP_BITS + 2;
const SUM_BIAS: i64 = 3 * EXP_BIAS as i64;

/// Cycles of the exponent stages before the margins: [`SBound`], then ΣE and y.
const EXPS: usize = s_bound::LATENCY + 1;
const _: () = assert!(
    EXPS + plucker_margin::LATENCY == plucker::LATENCY,
    "PluckerFilter: the margins must be ready with the values"
);

/// Clock edges from a query to its `miss` and `forward`.
pub const LATENCY: usize = plucker::LATENCY + sign_decide::LATENCY;

type Exp = Bits<EXP_BITS>;

/// One lane of the Plücker filter: a test's stored vectors in when `valid`, its decision
/// out [`LATENCY`] clocks later with `valid_out`: `miss` (a certain miss: the fp32 fallback
/// would answer no hit) or `forward` (everything else). Exactly one of them is set on every
/// clock. Grid exponents are the datapath's biased fields.
#[derive(LogicBlock)]
pub struct PluckerFilter {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    /// The ray and the triangle have stored vectors (else the test is forwarded).
    pub stored: Signal<In, Bit>,
    pub dir: [Signal<In, Bits<W>>; 3],
    pub dir_e: Signal<In, Exp>,
    pub moment: [Signal<In, Bits<W>>; 3],
    pub moment_e: Signal<In, Exp>,
    /// −orig.
    pub orig: [Signal<In, Bits<WT>>; 3],
    pub orig_e: Signal<In, Exp>,
    pub n: [Signal<In, Bits<WT>>; 3],
    pub n_e: Signal<In, Exp>,
    /// e1, −e2, e3.
    pub e1: [Signal<In, Bits<W>>; 3],
    pub e1_e: Signal<In, Exp>,
    pub e2: [Signal<In, Bits<W>>; 3],
    pub e2_e: Signal<In, Exp>,
    pub e3: [Signal<In, Bits<W>>; 3],
    pub e3_e: Signal<In, Exp>,
    /// v0 × e1, −(v0 × e2), v1 × e3.
    pub m1: [Signal<In, Bits<W>>; 3],
    pub m1_e: Signal<In, Exp>,
    pub m2: [Signal<In, Bits<W>>; 3],
    pub m2_e: Signal<In, Exp>,
    pub m3: [Signal<In, Bits<W>>; 3],
    pub m3_e: Signal<In, Exp>,
    /// ṽ0·ñ.
    pub offset: Signal<In, Bits<OFFSET_BITS>>,
    pub offset_e: Signal<In, Exp>,
    /// v0's cut.
    pub cut: [Signal<In, Bits<CUT_BITS>>; 3],
    pub cut_e: Signal<In, Exp>,
    /// The test's t_min, fp32 bits.
    pub t_min: Signal<In, Bits<32>>,
    pub valid_out: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    datapath: PluckerDatapath,
    s_bound: SBound,
    det_margin: PluckerMargin<DET_MARGIN_BITS>,
    u_margin: PluckerMargin<NUM_MARGIN_BITS>,
    v_margin: PluckerMargin<NUM_MARGIN_BITS>,
    t_margin: PluckerMargin<NUM_MARGIN_BITS>,
    w_margin: PluckerMargin<NUM_MARGIN_BITS>,
    decide: SignDecide,
    /// Stage 1: each value's grid L (det, N_u, N_v, N_t, N_w; fitted: + k), the finer dot's
    /// distance below it (N_u, N_v, N_t, N_w), the block exponents of dir, e1, −e2, and
    /// whether a grid is out of step 5's reach or nothing is stored.
    l1u: Signal<Local, Bits<L_BITS>>,
    l2u: Signal<Local, Bits<L_BITS>>,
    l1v: Signal<Local, Bits<L_BITS>>,
    l2v: Signal<Local, Bits<L_BITS>>,
    l1t: Signal<Local, Bits<L_BITS>>,
    l2t: Signal<Local, Bits<L_BITS>>,
    l1w: Signal<Local, Bits<L_BITS>>,
    l2w: Signal<Local, Bits<L_BITS>>,
    l: [Signal<Local, Bits<L_BITS>>; 5],
    fine: [Signal<Local, Bits<L_BITS>>; 4],
    l_reg: [DFF<Bits<L_BITS>>; 5],
    below_reg: [DFF<Bits<BELOW_BITS>>; 4],
    e_reg: [DFF<Exp>; 3],
    refuse1: DFF<Bit>,
    /// Stage 2: ΣE of each value, y, and whether an exponent is outside the fallback
    /// constant's range.
    sum: [Signal<Local, Bits<SUM_BITS>>; 4],
    sum_y: [Signal<Local, Bits<Y_BITS>>; 4],
    l_y: [Signal<Local, Bits<Y_BITS>>; 4],
    y_reg: [DFF<Bits<Y_BITS>>; 4],
    below2_reg: [DFF<Bits<BELOW_BITS>>; 4],
    l2_reg: [DFF<Bits<L_BITS>>; 5],
    refuse2: DFF<Bit>,
    /// Stage 3 (the decisions' inputs): the exponents, and every refusal.
    l3_reg: [DFF<Bits<L_BITS>>; 5],
    refuse3: DFF<Bit>,
    refuse_line: Delay<Bit>,
    valid_line: Delay<Bit>,
    t_min_line: Delay<Bits<32>>,
    /// The values fitted.
    nu_wide: Signal<Local, Bits<NUM_BITS>>,
    nv_wide: Signal<Local, Bits<NUM_BITS>>,
    edge_sign: Constant<Bits<EDGE_VALUE_BITS>>,
    edge_extension: Constant<Bits<NUM_BITS>>,
    k_det: Constant<Bits<L_BITS>>,
    k_t: Constant<Bits<L_BITS>>,
    /// det has no finer dot: its margin's shifter idles.
    zero_below: Constant<Bits<BELOW_BITS>>,
    offset_bias: Constant<Bits<L_BITS>>,
    /// Block exponent field = last bit's field + W − 1.
    last_to_top: Constant<Exp>,
    /// The ranges: L's (det's, the numerators'), E's, ΣE's floor; y's offset.
    det_low: Constant<Bits<L_BITS>>,
    det_high: Constant<Bits<L_BITS>>,
    num_low: Constant<Bits<L_BITS>>,
    num_high: Constant<Bits<L_BITS>>,
    e_low: Constant<Exp>,
    e_high: Constant<Exp>,
    sum_low: Constant<Bits<SUM_BITS>>,
    y_offset: Constant<Bits<Y_BITS>>,
}

impl Default for PluckerFilter {
    fn default() -> Self {
        let l_field = |v: i64| Constant::new(((v + L_BIAS) as u64).to_bits());
        let e_field = |v: i32| Constant::new(((v as i64 + EXP_BIAS as i64) as u64).to_bits());
        let det_range = lsb_range(super::WIDTH, DET);
        let num_range = lsb_range(super::WIDTH, N_U);
        // y + Y_BIAS = ΣE field − L field + (Y_BIAS + f.shift − SUM_BIAS + L_BIAS).
        let y_offset = Y_BIAS + fallback_term().shift as i64 - SUM_BIAS + L_BIAS;
        assert!((0..1 << Y_BITS).contains(&y_offset));
        let [det_c, u_c, v_c, t_c] = margin_constants(super::WIDTH);
        Self {
            clock: Default::default(),
            valid: Default::default(),
            stored: Default::default(),
            dir: Default::default(),
            dir_e: Default::default(),
            moment: Default::default(),
            moment_e: Default::default(),
            orig: Default::default(),
            orig_e: Default::default(),
            n: Default::default(),
            n_e: Default::default(),
            e1: Default::default(),
            e1_e: Default::default(),
            e2: Default::default(),
            e2_e: Default::default(),
            e3: Default::default(),
            e3_e: Default::default(),
            m1: Default::default(),
            m1_e: Default::default(),
            m2: Default::default(),
            m2_e: Default::default(),
            m3: Default::default(),
            m3_e: Default::default(),
            offset: Default::default(),
            offset_e: Default::default(),
            cut: Default::default(),
            cut_e: Default::default(),
            t_min: Default::default(),
            valid_out: Default::default(),
            miss: Default::default(),
            forward: Default::default(),
            datapath: Default::default(),
            s_bound: Default::default(),
            det_margin: PluckerMargin::new(det_c),
            u_margin: PluckerMargin::new(u_c),
            v_margin: PluckerMargin::new(v_c),
            t_margin: PluckerMargin::new(t_c),
            // The third edge has the others' constants.
            w_margin: PluckerMargin::dots_only(u_c),
            decide: Default::default(),
            l1u: Default::default(),
            l2u: Default::default(),
            l1v: Default::default(),
            l2v: Default::default(),
            l1t: Default::default(),
            l2t: Default::default(),
            l1w: Default::default(),
            l2w: Default::default(),
            l: Default::default(),
            fine: Default::default(),
            l_reg: Default::default(),
            below_reg: Default::default(),
            e_reg: Default::default(),
            refuse1: Default::default(),
            sum: Default::default(),
            sum_y: Default::default(),
            l_y: Default::default(),
            y_reg: Default::default(),
            below2_reg: Default::default(),
            l2_reg: Default::default(),
            refuse2: Default::default(),
            l3_reg: Default::default(),
            refuse3: Default::default(),
            refuse_line: Delay::new(sign_decide::LATENCY),
            valid_line: Delay::new(LATENCY),
            t_min_line: Delay::new(plucker::LATENCY),
            nu_wide: Default::default(),
            nv_wide: Default::default(),
            edge_sign: Constant::new(
                Bits::<EDGE_VALUE_BITS>::from(1) << (EDGE_VALUE_BITS as u64 - 1),
            ),
            edge_extension: Constant::new(!Bits::<NUM_BITS>::default() << EDGE_VALUE_BITS as u64),
            k_det: Constant::new((K_DET as u64).to_bits()),
            k_t: Constant::new((K_T as u64).to_bits()),
            zero_below: Constant::new(0u64.to_bits()),
            offset_bias: Constant::new(EXP_BIAS.to_bits()),
            last_to_top: Constant::new(((W - 1) as u64).to_bits()),
            det_low: l_field(*det_range.start() as i64),
            det_high: l_field(*det_range.end() as i64),
            num_low: l_field(*num_range.start() as i64),
            num_high: l_field(*num_range.end() as i64),
            e_low: e_field(EXP_MIN),
            e_high: e_field(EXP_MAX),
            sum_low: Constant::new(((SUM_MIN as i64 + SUM_BIAS) as u64).to_bits()),
            y_offset: Constant::new((y_offset as u64).to_bits()),
        }
    }
}

impl Logic for PluckerFilter {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self, clock, datapath, s_bound, det_margin, u_margin, v_margin, t_margin, w_margin,
            decide
        );
        for k in 0..5 {
            clock!(self, clock, l_reg[k], l2_reg[k], l3_reg[k]);
        }
        for k in 0..4 {
            clock!(self, clock, y_reg[k], below_reg[k], below2_reg[k]);
        }
        for k in 0..3 {
            clock!(self, clock, e_reg[k]);
        }
        clock!(
            self,
            clock,
            refuse1,
            refuse2,
            refuse3,
            refuse_line,
            valid_line,
            t_min_line
        );

        // The datapath and the |s| bound take the operands as they come.
        for k in 0..3 {
            self.datapath.dir[k].next = self.dir[k].val();
            self.datapath.moment[k].next = self.moment[k].val();
            self.datapath.orig[k].next = self.orig[k].val();
            self.datapath.n[k].next = self.n[k].val();
            self.datapath.e1[k].next = self.e1[k].val();
            self.datapath.e2[k].next = self.e2[k].val();
            self.datapath.e3[k].next = self.e3[k].val();
            self.datapath.m1[k].next = self.m1[k].val();
            self.datapath.m2[k].next = self.m2[k].val();
            self.datapath.m3[k].next = self.m3[k].val();
            self.s_bound.orig[k].next = self.orig[k].val();
            self.s_bound.cut[k].next = self.cut[k].val();
        }
        self.datapath.dir_e.next = self.dir_e.val();
        self.datapath.moment_e.next = self.moment_e.val();
        self.datapath.orig_e.next = self.orig_e.val();
        self.datapath.n_e.next = self.n_e.val();
        self.datapath.e1_e.next = self.e1_e.val();
        self.datapath.e2_e.next = self.e2_e.val();
        self.datapath.e3_e.next = self.e3_e.val();
        self.datapath.m1_e.next = self.m1_e.val();
        self.datapath.m2_e.next = self.m2_e.val();
        self.datapath.m3_e.next = self.m3_e.val();
        self.datapath.offset.next = self.offset.val();
        self.datapath.offset_e.next = self.offset_e.val();
        self.s_bound.orig_e.next = self.orig_e.val();
        self.s_bound.cut_e.next = self.cut_e.val();

        // Stage 1: the grids. A dot's grid is the sum of its blocks' (det: dir·n; the edges:
        // a·m and dir·b, the value on the coarser; N_t: orig·n and ṽ0·ñ).
        self.l[0].next = bit_cast::<L_BITS, EXP_BITS>(self.dir_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.n_e.val())
            + self.k_det.val();
        self.l1u.next = bit_cast::<L_BITS, EXP_BITS>(self.e2_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.moment_e.val());
        self.l2u.next = bit_cast::<L_BITS, EXP_BITS>(self.dir_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.m2_e.val());
        self.l1v.next = bit_cast::<L_BITS, EXP_BITS>(self.e1_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.moment_e.val());
        self.l2v.next = bit_cast::<L_BITS, EXP_BITS>(self.dir_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.m1_e.val());
        self.l1t.next = bit_cast::<L_BITS, EXP_BITS>(self.orig_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.n_e.val());
        self.l2t.next = bit_cast::<L_BITS, EXP_BITS>(self.offset_e.val()) + self.offset_bias.val();
        self.l1w.next = bit_cast::<L_BITS, EXP_BITS>(self.e3_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.moment_e.val());
        self.l2w.next = bit_cast::<L_BITS, EXP_BITS>(self.dir_e.val())
            + bit_cast::<L_BITS, EXP_BITS>(self.m3_e.val());
        // Each value on its coarser dot's grid; the finer dot's distance below it.
        self.l[1].next = self.l1u.val();
        self.fine[0].next = self.l2u.val();
        if self.l2u.val() > self.l1u.val() {
            self.l[1].next = self.l2u.val();
            self.fine[0].next = self.l1u.val();
        }
        self.l[2].next = self.l1v.val();
        self.fine[1].next = self.l2v.val();
        if self.l2v.val() > self.l1v.val() {
            self.l[2].next = self.l2v.val();
            self.fine[1].next = self.l1v.val();
        }
        self.l[3].next = self.l1t.val() + self.k_t.val();
        self.fine[2].next = self.l2t.val();
        if self.l2t.val() > self.l1t.val() {
            self.l[3].next = self.l2t.val() + self.k_t.val();
            self.fine[2].next = self.l1t.val();
        }
        self.l[4].next = self.l1w.val();
        self.fine[3].next = self.l2w.val();
        if self.l2w.val() > self.l1w.val() {
            self.l[4].next = self.l2w.val();
            self.fine[3].next = self.l1w.val();
        }
        for k in 0..5 {
            self.l_reg[k].d.next = self.l[k].val();
        }
        self.below_reg[0].d.next =
            bit_cast::<BELOW_BITS, L_BITS>(self.l[1].val() - self.fine[0].val());
        self.below_reg[1].d.next =
            bit_cast::<BELOW_BITS, L_BITS>(self.l[2].val() - self.fine[1].val());
        self.below_reg[2].d.next =
            bit_cast::<BELOW_BITS, L_BITS>(self.l[3].val() - self.fine[2].val());
        self.below_reg[3].d.next =
            bit_cast::<BELOW_BITS, L_BITS>(self.l[4].val() - self.fine[3].val());
        self.e_reg[0].d.next = self.dir_e.val() + self.last_to_top.val();
        self.e_reg[1].d.next = self.e1_e.val() + self.last_to_top.val();
        self.e_reg[2].d.next = self.e2_e.val() + self.last_to_top.val();
        self.refuse1.d.next = !self.stored.val()
            || self.l[0].val() < self.det_low.val()
            || self.l[0].val() > self.det_high.val()
            || self.l[1].val() < self.num_low.val()
            || self.l[1].val() > self.num_high.val()
            || self.l[2].val() < self.num_low.val()
            || self.l[2].val() > self.num_high.val()
            || self.l[3].val() < self.num_low.val()
            || self.l[3].val() > self.num_high.val();

        // Stage 2: ΣE of det = e1·(dir × e2), N_u = s·(dir × e2), N_v = dir·(s × e1),
        // N_t = e2·(s × e1), and y = the fallback constant's shift + ΣE − L.
        self.sum[0].next = bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[1].q.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[0].q.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[2].q.val());
        self.sum[1].next = bit_cast::<SUM_BITS, EXP_BITS>(self.s_bound.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[0].q.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[2].q.val());
        self.sum[2].next = bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[0].q.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.s_bound.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[1].q.val());
        self.sum[3].next = bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[2].q.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.s_bound.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e_reg[1].q.val());
        // (bit_cast of a loop-indexed signal does not generate: written out.)
        self.sum_y[0].next = bit_cast::<Y_BITS, SUM_BITS>(self.sum[0].val());
        self.sum_y[1].next = bit_cast::<Y_BITS, SUM_BITS>(self.sum[1].val());
        self.sum_y[2].next = bit_cast::<Y_BITS, SUM_BITS>(self.sum[2].val());
        self.sum_y[3].next = bit_cast::<Y_BITS, SUM_BITS>(self.sum[3].val());
        self.l_y[0].next = bit_cast::<Y_BITS, L_BITS>(self.l_reg[0].q.val());
        self.l_y[1].next = bit_cast::<Y_BITS, L_BITS>(self.l_reg[1].q.val());
        self.l_y[2].next = bit_cast::<Y_BITS, L_BITS>(self.l_reg[2].q.val());
        self.l_y[3].next = bit_cast::<Y_BITS, L_BITS>(self.l_reg[3].q.val());
        for k in 0..4 {
            self.y_reg[k].d.next = self.sum_y[k].val() + self.y_offset.val() - self.l_y[k].val();
            self.below2_reg[k].d.next = self.below_reg[k].q.val();
        }
        for k in 0..5 {
            self.l2_reg[k].d.next = self.l_reg[k].q.val();
        }
        self.refuse2.d.next = self.refuse1.q.val()
            || self.e_reg[0].q.val() < self.e_low.val()
            || self.e_reg[0].q.val() > self.e_high.val()
            || self.e_reg[1].q.val() < self.e_low.val()
            || self.e_reg[1].q.val() > self.e_high.val()
            || self.e_reg[2].q.val() < self.e_low.val()
            || self.e_reg[2].q.val() > self.e_high.val()
            || self.s_bound.e.val() < self.e_low.val()
            || self.s_bound.e.val() > self.e_high.val()
            || self.sum[0].val() < self.sum_low.val()
            || self.sum[1].val() < self.sum_low.val()
            || self.sum[2].val() < self.sum_low.val()
            || self.sum[3].val() < self.sum_low.val();

        // The margins (ready at stage 3, with the values).
        self.det_margin.below.next = self.zero_below.val();
        self.det_margin.y.next = self.y_reg[0].q.val();
        self.u_margin.below.next = self.below2_reg[0].q.val();
        self.u_margin.y.next = self.y_reg[1].q.val();
        self.v_margin.below.next = self.below2_reg[1].q.val();
        self.v_margin.y.next = self.y_reg[2].q.val();
        self.t_margin.below.next = self.below2_reg[2].q.val();
        self.t_margin.y.next = self.y_reg[3].q.val();
        // N_w's margin has no fallback term: y is not read.
        self.w_margin.below.next = self.below2_reg[3].q.val();
        self.w_margin.y.next = self.y_reg[3].q.val();
        for k in 0..5 {
            self.l3_reg[k].d.next = self.l2_reg[k].q.val();
        }
        self.refuse3.d.next = self.refuse2.q.val();

        // Stage 3: the values fitted to step 5's widths (N_w as it is), their exponents
        // (L's low bits), the margins, t_min; and every refusal.
        self.nu_wide.next = bit_cast::<NUM_BITS, EDGE_VALUE_BITS>(self.datapath.nu.val());
        if (self.datapath.nu.val() & self.edge_sign.val()).any() {
            self.nu_wide.next = self.nu_wide.val() | self.edge_extension.val();
        }
        self.nv_wide.next = bit_cast::<NUM_BITS, EDGE_VALUE_BITS>(self.datapath.nv.val());
        if (self.datapath.nv.val() & self.edge_sign.val()).any() {
            self.nv_wide.next = self.nv_wide.val() | self.edge_extension.val();
        }
        self.decide.det.next =
            bit_cast::<{ decide::DET_BITS }, DET_BITS>(self.datapath.det.val() >> self.k_det.val());
        self.decide.num[0].next = self.nu_wide.val();
        self.decide.num[1].next = self.nv_wide.val();
        self.decide.num[2].next =
            bit_cast::<NUM_BITS, NT_BITS>(self.datapath.nt.val() >> self.k_t.val());
        self.decide.det_e.next = bit_cast::<SHORT_EXP_BITS, L_BITS>(self.l3_reg[0].q.val());
        self.decide.num_e[0].next = bit_cast::<SHORT_EXP_BITS, L_BITS>(self.l3_reg[1].q.val());
        self.decide.num_e[1].next = bit_cast::<SHORT_EXP_BITS, L_BITS>(self.l3_reg[2].q.val());
        self.decide.num_e[2].next = bit_cast::<SHORT_EXP_BITS, L_BITS>(self.l3_reg[3].q.val());
        self.decide.det_margin.next = self.det_margin.margin.val();
        self.decide.num_margin[0].next = self.u_margin.margin.val();
        self.decide.num_margin[1].next = self.v_margin.margin.val();
        self.decide.num_margin[2].next = self.t_margin.margin.val();
        self.decide.w.next = self.datapath.nw.val();
        self.decide.w_e.next = bit_cast::<SHORT_EXP_BITS, L_BITS>(self.l3_reg[4].q.val());
        self.decide.w_margin.next = self.w_margin.margin.val();
        self.t_min_line.d.next = self.t_min.val();
        self.decide.t_min.next = self.t_min_line.q.val();
        self.refuse_line.d.next = self.refuse3.q.val()
            || self.det_margin.over.val()
            || self.u_margin.over.val()
            || self.v_margin.over.val()
            || self.t_margin.over.val();
        self.valid_line.d.next = self.valid.val();

        self.valid_out.next = self.valid_line.q.val();
        self.miss.next = self.decide.miss.val() && !self.refuse_line.q.val();
        self.forward.next = self.decide.forward.val() || self.refuse_line.q.val();
    }
}
