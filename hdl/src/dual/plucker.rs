//! The Plücker filter's datapath (docs/precision.md, "The Plücker filter"), bit for bit
//! `hw_model::dual::plucker::datapath` at W = [`super::WIDTH`]: the five values −det,
//! −N_u, −N_v, −N_w and −N_t from the ray's stored vectors (dir, its moment m = orig × dir,
//! −orig) and the triangle's (n, the edge vectors e1, −e2, e3, their moments v0 × e1,
//! −(v0 × e2), v1 × e3, ṽ0·ñ), each an exact integer on its grid. No translation and
//! no conversion: 27 products, 12 adders and 4 alignments. Every value leaves
//! [`LATENCY`] cycles after its operands.

use hw_model::dual::plucker::{offset_bits, wide};
use rust_hdl::prelude::*;

use super::align_add::{self, AlignAdd, EXP_BIAS, EXP_BITS};
use super::dot::{self, dot_bits, Dot};
use super::edge_value::EdgeValue;
use super::WIDTH;
use crate::mt::delay::Delay;

/// The mantissa width of dir, m, the edges and their moments.
pub const W: usize = WIDTH as usize;
/// The mantissa width of orig and n (the t test's vectors).
pub const WT: usize = wide(WIDTH) as usize;
/// The stored ṽ0·ñ: the exact dot of two wide blocks, as wide as orig·n.
pub const OFFSET_BITS: usize = offset_bits(WIDTH) as usize;
/// An edge's dots and their sum.
pub const EDGE_DOT_BITS: usize = dot_bits(W, W);
pub const EDGE_VALUE_BITS: usize = EDGE_DOT_BITS + 1;
/// dir·n.
pub const DET_BITS: usize = dot_bits(W, WT);
/// orig·n and its sum with ṽ0·ñ.
pub const NT_DOT_BITS: usize = dot_bits(WT, WT);
pub const NT_BITS: usize = NT_DOT_BITS + 1;
const _: () = assert!(OFFSET_BITS == NT_DOT_BITS);

/// Cycles from the operands to the values.
pub const LATENCY: usize = dot::LATENCY + align_add::LATENCY;

/// The datapath: each value two's complement, each grid exponent a biased field
/// ([`EXP_BIAS`]) computed from its blocks'.
#[derive(LogicBlock)]
pub struct PluckerDatapath {
    pub clock: Signal<In, Clock>,
    pub dir: [Signal<In, Bits<W>>; 3],
    pub dir_e: Signal<In, Bits<EXP_BITS>>,
    pub moment: [Signal<In, Bits<W>>; 3],
    pub moment_e: Signal<In, Bits<EXP_BITS>>,
    pub orig: [Signal<In, Bits<WT>>; 3],
    pub orig_e: Signal<In, Bits<EXP_BITS>>,
    pub n: [Signal<In, Bits<WT>>; 3],
    pub n_e: Signal<In, Bits<EXP_BITS>>,
    pub e1: [Signal<In, Bits<W>>; 3],
    pub e1_e: Signal<In, Bits<EXP_BITS>>,
    pub e2: [Signal<In, Bits<W>>; 3],
    pub e2_e: Signal<In, Bits<EXP_BITS>>,
    pub e3: [Signal<In, Bits<W>>; 3],
    pub e3_e: Signal<In, Bits<EXP_BITS>>,
    /// v0 × e1, −(v0 × e2), v1 × e3 (e2 is stored as −e2).
    pub m1: [Signal<In, Bits<W>>; 3],
    pub m1_e: Signal<In, Bits<EXP_BITS>>,
    pub m2: [Signal<In, Bits<W>>; 3],
    pub m2_e: Signal<In, Bits<EXP_BITS>>,
    pub m3: [Signal<In, Bits<W>>; 3],
    pub m3_e: Signal<In, Bits<EXP_BITS>>,
    /// ṽ0·ñ.
    pub offset: Signal<In, Bits<OFFSET_BITS>>,
    pub offset_e: Signal<In, Bits<EXP_BITS>>,
    /// dir·n = −det.
    pub det: Signal<Out, Bits<DET_BITS>>,
    pub det_e: Signal<Out, Bits<EXP_BITS>>,
    /// −N_u = (−e2)·m + dir·(−(v0 × e2)), −N_v = e1·m + dir·(v0 × e1),
    /// −N_w = e3·m + dir·(v1 × e3).
    pub nu: Signal<Out, Bits<EDGE_VALUE_BITS>>,
    pub nu_e: Signal<Out, Bits<EXP_BITS>>,
    pub nv: Signal<Out, Bits<EDGE_VALUE_BITS>>,
    pub nv_e: Signal<Out, Bits<EXP_BITS>>,
    pub nw: Signal<Out, Bits<EDGE_VALUE_BITS>>,
    pub nw_e: Signal<Out, Bits<EXP_BITS>>,
    /// −N_t = (−orig)·n + ṽ0·ñ.
    pub nt: Signal<Out, Bits<NT_BITS>>,
    pub nt_e: Signal<Out, Bits<EXP_BITS>>,
    det_dot: Dot<W, WT, { W + WT }, DET_BITS>,
    /// dir·n waits for the sums of the others.
    det_delay: Delay<Bits<DET_BITS>>,
    det_e_delay: Delay<Bits<EXP_BITS>>,
    /// The edge values: N_u, −N_v, −N_w (separate fields: rust-hdl's Verilog cannot index
    /// a submodule array's signal array in a loop).
    edge_u: EdgeValue,
    edge_v: EdgeValue,
    edge_w: EdgeValue,
    on_dot: Dot<WT, WT, { 2 * WT }, NT_DOT_BITS>,
    on_e: Delay<Bits<EXP_BITS>>,
    /// ṽ0·ñ, waiting for orig·n.
    offset_delay: Delay<Bits<OFFSET_BITS>>,
    offset_e_delay: Delay<Bits<EXP_BITS>>,
    nt_sum: AlignAdd<NT_DOT_BITS, NT_BITS>,
    bias: Constant<Bits<EXP_BITS>>,
}

impl Default for PluckerDatapath {
    fn default() -> Self {
        Self {
            clock: Default::default(),
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
            det: Default::default(),
            det_e: Default::default(),
            nu: Default::default(),
            nu_e: Default::default(),
            nv: Default::default(),
            nv_e: Default::default(),
            nw: Default::default(),
            nw_e: Default::default(),
            nt: Default::default(),
            nt_e: Default::default(),
            det_dot: Default::default(),
            det_delay: Delay::new(align_add::LATENCY),
            det_e_delay: Delay::new(LATENCY),
            edge_u: Default::default(),
            edge_v: Default::default(),
            edge_w: Default::default(),
            on_dot: Default::default(),
            on_e: Delay::new(dot::LATENCY),
            offset_delay: Delay::new(dot::LATENCY),
            offset_e_delay: Delay::new(dot::LATENCY),
            nt_sum: Default::default(),
            bias: Constant::new(EXP_BIAS.to_bits()),
        }
    }
}

impl Logic for PluckerDatapath {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            det_dot,
            det_delay,
            det_e_delay,
            on_dot,
            on_e,
            offset_delay,
            offset_e_delay,
            nt_sum,
            edge_u,
            edge_v,
            edge_w
        );
        self.edge_u.dir_e.next = self.dir_e.val();
        self.edge_v.dir_e.next = self.dir_e.val();
        self.edge_w.dir_e.next = self.dir_e.val();
        self.edge_u.moment_e.next = self.moment_e.val();
        self.edge_v.moment_e.next = self.moment_e.val();
        self.edge_w.moment_e.next = self.moment_e.val();
        for k in 0..3 {
            self.det_dot.a[k].next = self.dir[k].val();
            self.det_dot.b[k].next = self.n[k].val();
            self.on_dot.a[k].next = self.orig[k].val();
            self.on_dot.b[k].next = self.n[k].val();
            self.edge_u.dir[k].next = self.dir[k].val();
            self.edge_v.dir[k].next = self.dir[k].val();
            self.edge_w.dir[k].next = self.dir[k].val();
            self.edge_u.moment[k].next = self.moment[k].val();
            self.edge_v.moment[k].next = self.moment[k].val();
            self.edge_w.moment[k].next = self.moment[k].val();
            // u from e2, v from e1, w from e3, as the model orders them.
            self.edge_u.a[k].next = self.e2[k].val();
            self.edge_u.b[k].next = self.m2[k].val();
            self.edge_v.a[k].next = self.e1[k].val();
            self.edge_v.b[k].next = self.m1[k].val();
            self.edge_w.a[k].next = self.e3[k].val();
            self.edge_w.b[k].next = self.m3[k].val();
        }
        self.edge_u.a_e.next = self.e2_e.val();
        self.edge_u.b_e.next = self.m2_e.val();
        self.edge_v.a_e.next = self.e1_e.val();
        self.edge_v.b_e.next = self.m1_e.val();
        self.edge_w.a_e.next = self.e3_e.val();
        self.edge_w.b_e.next = self.m3_e.val();
        // dir·n: its exponent beside it, then one more stage to meet the sums.
        self.det_e_delay.d.next = self.dir_e.val() + self.n_e.val() - self.bias.val();
        self.det_delay.d.next = self.det_dot.v.val();
        // −N_t = (−orig)·n + ṽ0·ñ.
        self.on_e.d.next = self.orig_e.val() + self.n_e.val() - self.bias.val();
        self.offset_delay.d.next = self.offset.val();
        self.offset_e_delay.d.next = self.offset_e.val();
        self.nt_sum.a.next = self.on_dot.v.val();
        self.nt_sum.ea.next = self.on_e.q.val();
        self.nt_sum.b.next = self.offset_delay.q.val();
        self.nt_sum.eb.next = self.offset_e_delay.q.val();
        self.det.next = self.det_delay.q.val();
        self.det_e.next = self.det_e_delay.q.val();
        self.nu.next = self.edge_u.v.val();
        self.nu_e.next = self.edge_u.e.val();
        self.nv.next = self.edge_v.v.val();
        self.nv_e.next = self.edge_v.e.val();
        self.nw.next = self.edge_w.v.val();
        self.nw_e.next = self.edge_w.e.val();
        self.nt.next = self.nt_sum.s.val();
        self.nt_e.next = self.nt_sum.e.val();
    }
}
