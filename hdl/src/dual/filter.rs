//! The whole bfp filter, one lane: steps 1–5 composed, bit for bit the model's
//! `hw_model::dual::bfp::values` followed by `decide` (`Filter::certain_miss(q, 1.0)` for the
//! pair bfp18/fp32, `FilterKind::Bfp`). One query per cycle, fully pipelined.
//!
//! Step 1 ([`Translate`] × 9) moves v1, v2 and orig to v0 = 0; step 2 ([`ToBlock`] × 4) gives
//! dir, e1, e2 and s their blocks; step 3 cuts p = dir × e2 and q = s × e1 ([`CrossBlock`](super::cross_block::CrossBlock))
//! and takes the four dots ([`Dot`](super::dot::Dot)); step 4 the four margins ([`Margin`](super::margin::Margin)); step 5 the
//! decisions ([`Decide`]). Beside them, this block refuses what the model's `values` refuses
//! (a non-finite input, a zero vector, a block exponent outside [`EXP_MIN`, `EXP_MAX`], a
//! triple's exponent sum below `SUM_MIN`): such a query is forwarded whatever `Decide` says.
//! (`values` also refuses a margin term that overflows i128; at W = 18 none can, and
//! `Margin::new` asserts that every wired term fits its width.)
//!
//! Every side signal (dir's inputs, t_min, the block exponents, the dropped distances, the
//! refusal and `valid`) is delay-matched with [`Delay`] lines whose lengths come from the
//! blocks' `LATENCY` constants, so the lane stays right when a block is pipelined deeper.

use hw_model::dual::bfp::{widths, Vector, DET, EXP_MAX, EXP_MIN, N_T, N_U, N_V, SUM_MIN};
use rust_hdl::prelude::*;

use super::cross_block::{self, PCross, QCross, DIR_BIAS, EDGE_BIAS, P_BIAS, Q_BIAS};
use super::decide::{self, Decide};
use super::dot::{self, DetDot, NtDot, NuDot, NvDot};
use super::margin::{self, DetMargin, TMargin, UMargin, VMargin};
use super::round::SHORT_EXP_BITS;
use super::to_block::{self, DirToBlock, EdgeToBlock, SToBlock, ToBlock, BELOW_BITS, EXP_BITS};
use super::translate::{self, Translate, FIELD_BITS, SIGNIFICAND_BITS};
use super::WIDTH;
use crate::macros::clock;
use crate::mt::delay::Delay;

/// Clock edges from the inputs to the blocks of dir, e1, e2 and s (steps 1 and 2).
const BLOCKS: usize = translate::LATENCY + to_block::LATENCY;
/// … to the cut cross products p and q (step 3's first half).
const CROSSED: usize = BLOCKS + cross_block::LATENCY;
/// … to the values det, N_u, N_v, N_t and their margins at `Decide`'s inputs.
const VALUES: usize = CROSSED + dot::LATENCY;

/// Clock edges from a query to its `miss` and `forward`.
pub const LATENCY: usize = VALUES + decide::LATENCY;

// The margins start from the cut's dropped distance and must be ready with the dots.
const _: () = assert!(
    dot::LATENCY >= margin::LATENCY,
    "BfpFilter: a margin must not take longer than a dot"
);

/// A vector's mantissa width at W = [`WIDTH`].
const fn width(v: Vector) -> usize {
    widths(WIDTH)[v as usize] as usize
}

/// The bias of a vector's block exponent field (`ToBlock::e`, `CrossBlock::e`).
const fn bias(v: Vector) -> usize {
    match v {
        Vector::Dir => DIR_BIAS,
        Vector::E1 | Vector::E2 | Vector::S => EDGE_BIAS,
        Vector::P => P_BIAS,
        Vector::Q => Q_BIAS,
    }
}

/// The value a·x's last bit is 2^(a.lsb + x.lsb) (the model's `values`), a vector's lsb
/// being its field − bias − (width − 1): the value's exponent is field_a + field_x less this.
const fn lsb_offset(value: [Vector; 4]) -> usize {
    let [a, _, _, x] = value;
    bias(a) + width(a) - 1 + bias(x) + width(x) - 1
}

/// The model's E_a + E_b + E_c ≥ SUM_MIN, on biased fields: field_a + field_b + field_c ≥
/// this.
const fn sum_floor(value: [Vector; 4]) -> usize {
    let [a, b, c, _] = value;
    let floor = SUM_MIN + (bias(a) + bias(b) + bias(c)) as i32;
    assert!(floor >= 0, "the SUM_MIN check needs a non-negative floor");
    floor as usize
}

/// Width of the sum of three block exponent fields.
const SUM_BITS: usize = EXP_BITS + 2;

/// dir's `ToBlock` input: an fp32 significand with its sign (the type check below keeps it
/// `DirToBlock`'s).
const DIR_IW: usize = SIGNIFICAND_BITS + 1;
const _: fn(DirToBlock) -> ToBlock<DIR_IW, { width(Vector::Dir) }> = |b| b;

type DirM = Bits<{ width(Vector::Dir) }>;
type EdgeM = Bits<{ width(Vector::E1) }>;
type SM = Bits<{ width(Vector::S) }>;
const _: () = assert!(width(Vector::E1) == width(Vector::E2));

/// One lane of the bfp filter: a query (fp32 bits) in when `valid`, its decision out
/// [`LATENCY`] clocks later with `valid_out`: `miss` (a certain miss: the fp32 fallback
/// would answer no hit) or `forward` (everything else, including every query the model's
/// `values` refuses). Exactly one of them is set on every clock.
#[derive(LogicBlock)]
pub struct BfpFilter {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    pub v0: [Signal<In, Bits<32>>; 3],
    pub v1: [Signal<In, Bits<32>>; 3],
    pub v2: [Signal<In, Bits<32>>; 3],
    pub orig: [Signal<In, Bits<32>>; 3],
    pub dir: [Signal<In, Bits<32>>; 3],
    pub t_min: Signal<In, Bits<32>>,
    pub valid_out: Signal<Out, Bit>,
    pub miss: Signal<Out, Bit>,
    pub forward: Signal<Out, Bit>,
    /// Step 1: e1 = v1 − v0, e2 = v2 − v0, s = orig − v0 per component.
    e1_sub: [Translate; 3],
    e2_sub: [Translate; 3],
    s_sub: [Translate; 3],
    /// dir has no translation: its components wait for the others'.
    dir_line: [Delay<Bits<32>>; 3],
    /// Step 2.
    dir_block: DirToBlock,
    e1_block: EdgeToBlock,
    e2_block: EdgeToBlock,
    s_block: SToBlock,
    /// Step 3: p = dir × e2, q = s × e1, then the dots det = e1·p̂, N_u = s·p̂, N_v = dir·q̂,
    /// N_t = e2·q̂; the mantissas of dir, e1, e2 and s wait for the cut.
    p_cross: PCross,
    q_cross: QCross,
    dir_m: [Delay<DirM>; 3],
    e1_m: [Delay<EdgeM>; 3],
    e2_m: [Delay<EdgeM>; 3],
    s_m: [Delay<SM>; 3],
    det_dot: DetDot,
    nu_dot: NuDot,
    nv_dot: NvDot,
    nt_dot: NtDot,
    /// Step 4: the dropped distances wait so that each margin is ready with its dot.
    dir_below: Delay<Bits<BELOW_BITS>>,
    e1_below: Delay<Bits<BELOW_BITS>>,
    e2_below: Delay<Bits<BELOW_BITS>>,
    s_below: Delay<Bits<BELOW_BITS>>,
    p_below: Delay<Bits<BELOW_BITS>>,
    q_below: Delay<Bits<BELOW_BITS>>,
    det_margin: DetMargin,
    u_margin: UMargin,
    v_margin: VMargin,
    t_margin: TMargin,
    /// The values' exponents: the base blocks' fields wait for the cut's, and the sums for
    /// the dots.
    dir_e: Delay<Bits<EXP_BITS>>,
    e1_e: Delay<Bits<EXP_BITS>>,
    e2_e: Delay<Bits<EXP_BITS>>,
    s_e: Delay<Bits<EXP_BITS>>,
    det_e: Delay<Bits<SHORT_EXP_BITS>>,
    nu_e: Delay<Bits<SHORT_EXP_BITS>>,
    nv_e: Delay<Bits<SHORT_EXP_BITS>>,
    nt_e: Delay<Bits<SHORT_EXP_BITS>>,
    /// Step 5, and t_min waiting for it.
    decide: Decide,
    t_min_line: Delay<Bits<32>>,
    /// A non-finite input (seen on entry) waits for the blocks; the refusal then waits for
    /// the decision; `valid` for all of it.
    bad_line: Delay<Bit>,
    refuse_line: Delay<Bit>,
    valid_line: Delay<Bit>,
    /// fp32: the field of ±Inf and NaN, the hidden bit, one.
    field_max: Constant<Bits<FIELD_BITS>>,
    hidden: Constant<Bits<DIR_IW>>,
    dir_one: Constant<Bits<DIR_IW>>,
    /// [EXP_MIN, EXP_MAX] on dir's and on e1's, e2's and s's biased fields.
    dir_min: Constant<Bits<EXP_BITS>>,
    dir_max: Constant<Bits<EXP_BITS>>,
    edge_min: Constant<Bits<EXP_BITS>>,
    edge_max: Constant<Bits<EXP_BITS>>,
    /// SUM_MIN per value, on the sums of biased fields.
    det_floor: Constant<Bits<SUM_BITS>>,
    nu_floor: Constant<Bits<SUM_BITS>>,
    nv_floor: Constant<Bits<SUM_BITS>>,
    nt_floor: Constant<Bits<SUM_BITS>>,
    /// Per value, field_a + field_x less its exponent.
    det_offset: Constant<Bits<SHORT_EXP_BITS>>,
    nu_offset: Constant<Bits<SHORT_EXP_BITS>>,
    nv_offset: Constant<Bits<SHORT_EXP_BITS>>,
    nt_offset: Constant<Bits<SHORT_EXP_BITS>>,
    /// dir's components as signed significands (0 for a zero or a flushed subnormal).
    dir_bits: [Signal<Local, Bits<32>>; 3],
    dir_x: [Signal<Local, Bits<DIR_IW>>; 3],
    /// Any of the fifteen coordinates is ±Inf or NaN.
    non_finite: Signal<Local, Bit>,
    /// The refusals the blocks show: a zero vector, an exponent out of range, a small sum.
    zero: Signal<Local, Bit>,
    out_of_range: Signal<Local, Bit>,
    det_sum: Signal<Local, Bits<SUM_BITS>>,
    nu_sum: Signal<Local, Bits<SUM_BITS>>,
    nv_sum: Signal<Local, Bits<SUM_BITS>>,
    nt_sum: Signal<Local, Bits<SUM_BITS>>,
    sum_low: Signal<Local, Bit>,
}

impl Default for BfpFilter {
    fn default() -> Self {
        let bits = |v: usize| -> u64 { v as u64 };
        let field = |v: i32| -> Constant<Bits<EXP_BITS>> {
            assert!((0..1 << EXP_BITS).contains(&v), "{v} is no biased field");
            Constant::new((v as u64).to_bits())
        };
        let floor =
            |value| -> Constant<Bits<SUM_BITS>> { Constant::new(bits(sum_floor(value)).to_bits()) };
        let offset = |value| -> Constant<Bits<SHORT_EXP_BITS>> {
            Constant::new((bits(lsb_offset(value)) & ((1 << SHORT_EXP_BITS) - 1)).to_bits())
        };
        let range = |v: Vector| {
            (
                field(EXP_MIN + bias(v) as i32),
                field(EXP_MAX + bias(v) as i32),
            )
        };
        let (dir_min, dir_max) = range(Vector::Dir);
        let (edge_min, edge_max) = range(Vector::E1);
        let base_below = cross_block::LATENCY + dot::LATENCY - margin::LATENCY;
        Self {
            clock: Default::default(),
            valid: Default::default(),
            v0: Default::default(),
            v1: Default::default(),
            v2: Default::default(),
            orig: Default::default(),
            dir: Default::default(),
            t_min: Default::default(),
            valid_out: Default::default(),
            miss: Default::default(),
            forward: Default::default(),
            e1_sub: Default::default(),
            e2_sub: Default::default(),
            s_sub: Default::default(),
            dir_line: Delay::lines(translate::LATENCY),
            dir_block: Default::default(),
            e1_block: Default::default(),
            e2_block: Default::default(),
            s_block: Default::default(),
            p_cross: Default::default(),
            q_cross: Default::default(),
            dir_m: Delay::lines(cross_block::LATENCY),
            e1_m: Delay::lines(cross_block::LATENCY),
            e2_m: Delay::lines(cross_block::LATENCY),
            s_m: Delay::lines(cross_block::LATENCY),
            det_dot: Default::default(),
            nu_dot: Default::default(),
            nv_dot: Default::default(),
            nt_dot: Default::default(),
            dir_below: Delay::new(base_below),
            e1_below: Delay::new(base_below),
            e2_below: Delay::new(base_below),
            s_below: Delay::new(base_below),
            p_below: Delay::new(dot::LATENCY - margin::LATENCY),
            q_below: Delay::new(dot::LATENCY - margin::LATENCY),
            det_margin: DetMargin::det(),
            u_margin: UMargin::n_u(),
            v_margin: VMargin::n_v(),
            t_margin: TMargin::n_t(),
            dir_e: Delay::new(cross_block::LATENCY),
            e1_e: Delay::new(cross_block::LATENCY),
            e2_e: Delay::new(cross_block::LATENCY),
            s_e: Delay::new(cross_block::LATENCY),
            det_e: Delay::new(dot::LATENCY),
            nu_e: Delay::new(dot::LATENCY),
            nv_e: Delay::new(dot::LATENCY),
            nt_e: Delay::new(dot::LATENCY),
            decide: Default::default(),
            t_min_line: Delay::new(VALUES),
            bad_line: Delay::new(BLOCKS),
            refuse_line: Delay::new(LATENCY - BLOCKS),
            valid_line: Delay::new(LATENCY),
            field_max: Constant::new(bits((1 << FIELD_BITS) - 1).to_bits()),
            hidden: Constant::new(bits(1 << (SIGNIFICAND_BITS - 1)).to_bits()),
            dir_one: Constant::new(1u64.to_bits()),
            dir_min,
            dir_max,
            edge_min,
            edge_max,
            det_floor: floor(DET),
            nu_floor: floor(N_U),
            nv_floor: floor(N_V),
            nt_floor: floor(N_T),
            det_offset: offset(DET),
            nu_offset: offset(N_U),
            nv_offset: offset(N_V),
            nt_offset: offset(N_T),
            dir_bits: Default::default(),
            dir_x: Default::default(),
            non_finite: Default::default(),
            zero: Default::default(),
            out_of_range: Default::default(),
            det_sum: Default::default(),
            nu_sum: Default::default(),
            nv_sum: Default::default(),
            nt_sum: Default::default(),
            sum_low: Default::default(),
        }
    }
}

impl Logic for BfpFilter {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            clock!(
                self,
                clock,
                e1_sub[k],
                e2_sub[k],
                s_sub[k],
                dir_line[k],
                dir_m[k],
                e1_m[k],
                e2_m[k],
                s_m[k]
            );
        }
        clock!(
            self,
            clock,
            dir_block,
            e1_block,
            e2_block,
            s_block,
            p_cross,
            q_cross,
            det_dot,
            nu_dot,
            nv_dot,
            nt_dot,
            dir_below,
            e1_below,
            e2_below,
            s_below,
            p_below,
            q_below,
            det_margin,
            u_margin,
            v_margin,
            t_margin,
            dir_e,
            e1_e,
            e2_e,
            s_e,
            det_e,
            nu_e,
            nv_e,
            nt_e,
            decide,
            t_min_line,
            bad_line,
            refuse_line,
            valid_line
        );

        // On entry: the translations, dir's wait, and the non-finite inputs.
        self.non_finite.next = false;
        for k in 0..3 {
            self.e1_sub[k].a.next = self.v1[k].val();
            self.e1_sub[k].b.next = self.v0[k].val();
            self.e2_sub[k].a.next = self.v2[k].val();
            self.e2_sub[k].b.next = self.v0[k].val();
            self.s_sub[k].a.next = self.orig[k].val();
            self.s_sub[k].b.next = self.v0[k].val();
            self.dir_line[k].d.next = self.dir[k].val();
            if self.v0[k].val().get_bits::<8>(23) == self.field_max.val()
                || self.v1[k].val().get_bits::<8>(23) == self.field_max.val()
                || self.v2[k].val().get_bits::<8>(23) == self.field_max.val()
                || self.orig[k].val().get_bits::<8>(23) == self.field_max.val()
                || self.dir[k].val().get_bits::<8>(23) == self.field_max.val()
            {
                self.non_finite.next = true;
            }
        }
        self.bad_line.d.next = self.non_finite.val();
        self.valid_line.d.next = self.valid.val();
        self.t_min_line.d.next = self.t_min.val();

        // Step 2: dir's significands with their signs (as `split`), the translations'
        // differences at their fields.
        for k in 0..3 {
            self.dir_bits[k].next = self.dir_line[k].q.val();
        }
        // (bit_cast in a loop loses the loop variable: one per component.)
        self.dir_x[0].next =
            bit_cast::<DIR_IW, 23>(self.dir_bits[0].val().get_bits::<23>(0)) | self.hidden.val();
        self.dir_x[1].next =
            bit_cast::<DIR_IW, 23>(self.dir_bits[1].val().get_bits::<23>(0)) | self.hidden.val();
        self.dir_x[2].next =
            bit_cast::<DIR_IW, 23>(self.dir_bits[2].val().get_bits::<23>(0)) | self.hidden.val();
        for k in 0..3 {
            if !self.dir_bits[k].val().get_bits::<8>(23).any() {
                self.dir_x[k].next = 0.into();
            }
            if self.dir_bits[k].val().get_bit(31) {
                self.dir_x[k].next = !self.dir_x[k].val() + self.dir_one.val();
            }
            self.dir_block.x[k].next = self.dir_x[k].val();
            self.dir_block.f[k].next = self.dir_bits[k].val().get_bits::<8>(23);
            self.e1_block.x[k].next = self.e1_sub[k].d.val();
            self.e1_block.f[k].next = self.e1_sub[k].e.val();
            self.e2_block.x[k].next = self.e2_sub[k].d.val();
            self.e2_block.f[k].next = self.e2_sub[k].e.val();
            self.s_block.x[k].next = self.s_sub[k].d.val();
            self.s_block.f[k].next = self.s_sub[k].e.val();
        }

        // The blocks are out: what the model's `values` refuses.
        self.zero.next = self.dir_block.zero.val()
            || self.e1_block.zero.val()
            || self.e2_block.zero.val()
            || self.s_block.zero.val();
        self.out_of_range.next = self.dir_block.e.val() < self.dir_min.val()
            || self.dir_block.e.val() > self.dir_max.val()
            || self.e1_block.e.val() < self.edge_min.val()
            || self.e1_block.e.val() > self.edge_max.val()
            || self.e2_block.e.val() < self.edge_min.val()
            || self.e2_block.e.val() > self.edge_max.val()
            || self.s_block.e.val() < self.edge_min.val()
            || self.s_block.e.val() > self.edge_max.val();
        // E_a + E_b + E_c of det = e1·(dir × e2), N_u = s·(dir × e2), N_v = dir·(s × e1),
        // N_t = e2·(s × e1).
        self.det_sum.next = bit_cast::<SUM_BITS, EXP_BITS>(self.e1_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.dir_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e2_block.e.val());
        self.nu_sum.next = bit_cast::<SUM_BITS, EXP_BITS>(self.s_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.dir_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e2_block.e.val());
        self.nv_sum.next = bit_cast::<SUM_BITS, EXP_BITS>(self.dir_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.s_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e1_block.e.val());
        self.nt_sum.next = bit_cast::<SUM_BITS, EXP_BITS>(self.e2_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.s_block.e.val())
            + bit_cast::<SUM_BITS, EXP_BITS>(self.e1_block.e.val());
        self.sum_low.next = self.det_sum.val() < self.det_floor.val()
            || self.nu_sum.val() < self.nu_floor.val()
            || self.nv_sum.val() < self.nv_floor.val()
            || self.nt_sum.val() < self.nt_floor.val();
        self.refuse_line.d.next = self.bad_line.q.val()
            || self.zero.val()
            || self.out_of_range.val()
            || self.sum_low.val();

        // Step 3: the cuts.
        for k in 0..3 {
            self.p_cross.x[k].next = self.dir_block.m[k].val();
            self.p_cross.y[k].next = self.e2_block.m[k].val();
            self.q_cross.x[k].next = self.s_block.m[k].val();
            self.q_cross.y[k].next = self.e1_block.m[k].val();
            self.dir_m[k].d.next = self.dir_block.m[k].val();
            self.e1_m[k].d.next = self.e1_block.m[k].val();
            self.e2_m[k].d.next = self.e2_block.m[k].val();
            self.s_m[k].d.next = self.s_block.m[k].val();
        }
        self.p_cross.ex.next = self.dir_block.e.val();
        self.p_cross.ey.next = self.e2_block.e.val();
        self.q_cross.ex.next = self.s_block.e.val();
        self.q_cross.ey.next = self.e1_block.e.val();
        self.dir_e.d.next = self.dir_block.e.val();
        self.e1_e.d.next = self.e1_block.e.val();
        self.e2_e.d.next = self.e2_block.e.val();
        self.s_e.d.next = self.s_block.e.val();
        self.dir_below.d.next = self.dir_block.below.val();
        self.e1_below.d.next = self.e1_block.below.val();
        self.e2_below.d.next = self.e2_block.below.val();
        self.s_below.d.next = self.s_block.below.val();

        // The cuts are out: the dots, the values' exponents (a.lsb + x.lsb, modulo
        // 2^SHORT_EXP_BITS: exact for every query not refused) and the margins' inputs.
        for k in 0..3 {
            self.det_dot.a[k].next = self.e1_m[k].q.val();
            self.det_dot.b[k].next = self.p_cross.m[k].val();
            self.nu_dot.a[k].next = self.s_m[k].q.val();
            self.nu_dot.b[k].next = self.p_cross.m[k].val();
            self.nv_dot.a[k].next = self.dir_m[k].q.val();
            self.nv_dot.b[k].next = self.q_cross.m[k].val();
            self.nt_dot.a[k].next = self.e2_m[k].q.val();
            self.nt_dot.b[k].next = self.q_cross.m[k].val();
        }
        self.det_e.d.next = bit_cast::<SHORT_EXP_BITS, EXP_BITS>(self.e1_e.q.val())
            + bit_cast::<SHORT_EXP_BITS, { cross_block::CROSS_EXP_BITS }>(self.p_cross.e.val())
            - self.det_offset.val();
        self.nu_e.d.next = bit_cast::<SHORT_EXP_BITS, EXP_BITS>(self.s_e.q.val())
            + bit_cast::<SHORT_EXP_BITS, { cross_block::CROSS_EXP_BITS }>(self.p_cross.e.val())
            - self.nu_offset.val();
        self.nv_e.d.next = bit_cast::<SHORT_EXP_BITS, EXP_BITS>(self.dir_e.q.val())
            + bit_cast::<SHORT_EXP_BITS, { cross_block::CROSS_EXP_BITS }>(self.q_cross.e.val())
            - self.nv_offset.val();
        self.nt_e.d.next = bit_cast::<SHORT_EXP_BITS, EXP_BITS>(self.e2_e.q.val())
            + bit_cast::<SHORT_EXP_BITS, { cross_block::CROSS_EXP_BITS }>(self.q_cross.e.val())
            - self.nt_offset.val();
        self.p_below.d.next = self.p_cross.below.val();
        self.q_below.d.next = self.q_cross.below.val();

        // Step 4: each margin from a, b, c and the cut x of its value.
        self.det_margin.below[0].next = self.e1_below.q.val();
        self.det_margin.below[1].next = self.dir_below.q.val();
        self.det_margin.below[2].next = self.e2_below.q.val();
        self.det_margin.below[3].next = self.p_below.q.val();
        self.u_margin.below[0].next = self.s_below.q.val();
        self.u_margin.below[1].next = self.dir_below.q.val();
        self.u_margin.below[2].next = self.e2_below.q.val();
        self.u_margin.below[3].next = self.p_below.q.val();
        self.v_margin.below[0].next = self.dir_below.q.val();
        self.v_margin.below[1].next = self.s_below.q.val();
        self.v_margin.below[2].next = self.e1_below.q.val();
        self.v_margin.below[3].next = self.q_below.q.val();
        self.t_margin.below[0].next = self.e2_below.q.val();
        self.t_margin.below[1].next = self.s_below.q.val();
        self.t_margin.below[2].next = self.e1_below.q.val();
        self.t_margin.below[3].next = self.q_below.q.val();

        // Step 5: the dots' widths are `Decide`'s (both `dot_bits`).
        self.decide.det.next = self.det_dot.v.val();
        self.decide.det_e.next = self.det_e.q.val();
        self.decide.det_margin.next = self.det_margin.margin.val();
        self.decide.num[0].next = self.nu_dot.v.val();
        self.decide.num[1].next = self.nv_dot.v.val();
        self.decide.num[2].next = self.nt_dot.v.val();
        self.decide.num_e[0].next = self.nu_e.q.val();
        self.decide.num_e[1].next = self.nv_e.q.val();
        self.decide.num_e[2].next = self.nt_e.q.val();
        self.decide.num_margin[0].next = self.u_margin.margin.val();
        self.decide.num_margin[1].next = self.v_margin.margin.val();
        self.decide.num_margin[2].next = self.t_margin.margin.val();
        self.decide.t_min.next = self.t_min_line.q.val();

        // A refused query is forwarded whatever the decision.
        self.valid_out.next = self.valid_line.q.val();
        self.miss.next = self.decide.miss.val() && !self.refuse_line.q.val();
        self.forward.next = self.decide.forward.val() || self.refuse_line.q.val();
    }
}
