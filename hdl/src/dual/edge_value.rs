//! One edge value of the Plücker filter, bit for bit the model's
//! (`hw_model::dual::plucker::datapath`): a·m + dir·b for the ray's dir and moment m and a
//! triangle's edge vector a and its moment b (N_u from e2, −N_v from e1, −N_w from e3). Two
//! dots and their sum on the coarser grid ([`AlignAdd`]); each dot's grid exponent is the
//! sum of its blocks', carried beside it.

use rust_hdl::prelude::*;

use super::align_add::{AlignAdd, EXP_BIAS, EXP_BITS};
use super::dot::{self, Dot};
use super::plucker::{EDGE_DOT_BITS, EDGE_VALUE_BITS, W};
use crate::mt::delay::Delay;

/// Cycles from the inputs to `v` and `e`.
pub const LATENCY: usize = dot::LATENCY + super::align_add::LATENCY;

/// `v`·2^`e` = a·m + dir·b, floored onto the coarser of the two dots' grids. Mantissas are
/// W-bit two's complement, exponents biased fields ([`EXP_BIAS`]).
#[derive(LogicBlock)]
pub struct EdgeValue {
    pub clock: Signal<In, Clock>,
    pub dir: [Signal<In, Bits<W>>; 3],
    pub dir_e: Signal<In, Bits<EXP_BITS>>,
    pub moment: [Signal<In, Bits<W>>; 3],
    pub moment_e: Signal<In, Bits<EXP_BITS>>,
    pub a: [Signal<In, Bits<W>>; 3],
    pub a_e: Signal<In, Bits<EXP_BITS>>,
    pub b: [Signal<In, Bits<W>>; 3],
    pub b_e: Signal<In, Bits<EXP_BITS>>,
    pub v: Signal<Out, Bits<EDGE_VALUE_BITS>>,
    pub e: Signal<Out, Bits<EXP_BITS>>,
    /// a·m and dir·b.
    am: Dot<W, W, { 2 * W }, EDGE_DOT_BITS>,
    db: Dot<W, W, { 2 * W }, EDGE_DOT_BITS>,
    /// Their grid exponents, waiting for the dots.
    am_e: Delay<Bits<EXP_BITS>>,
    db_e: Delay<Bits<EXP_BITS>>,
    sum: AlignAdd<EDGE_DOT_BITS, EDGE_VALUE_BITS>,
    bias: Constant<Bits<EXP_BITS>>,
}

impl Default for EdgeValue {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            dir: Default::default(),
            dir_e: Default::default(),
            moment: Default::default(),
            moment_e: Default::default(),
            a: Default::default(),
            a_e: Default::default(),
            b: Default::default(),
            b_e: Default::default(),
            v: Default::default(),
            e: Default::default(),
            am: Default::default(),
            db: Default::default(),
            am_e: Delay::new(dot::LATENCY),
            db_e: Delay::new(dot::LATENCY),
            sum: Default::default(),
            bias: Constant::new(EXP_BIAS.to_bits()),
        }
    }
}

impl Logic for EdgeValue {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, am, db, am_e, db_e, sum);
        for k in 0..3 {
            self.am.a[k].next = self.a[k].val();
            self.am.b[k].next = self.moment[k].val();
            self.db.a[k].next = self.dir[k].val();
            self.db.b[k].next = self.b[k].val();
        }
        // Biased fields: (x + B) + (y + B) − B.
        self.am_e.d.next = self.a_e.val() + self.moment_e.val() - self.bias.val();
        self.db_e.d.next = self.dir_e.val() + self.b_e.val() - self.bias.val();
        self.sum.a.next = self.am.v.val();
        self.sum.ea.next = self.am_e.q.val();
        self.sum.b.next = self.db.v.val();
        self.sum.eb.next = self.db_e.q.val();
        self.v.next = self.sum.s.val();
        self.e.next = self.sum.e.val();
    }
}
