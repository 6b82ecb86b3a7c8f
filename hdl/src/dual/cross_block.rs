//! Step 3 of the bfp filter, its cross products: two blocks' mantissas to the exact cross
//! product (six signed products, three subtractions), cut to a block at the fixed exponent
//! E_x + E_y + 1, bit for bit `hw_model::dual::bfp::cross_block`. Every component of the
//! exact product lies in (−2^(E_x+E_y+1), 2^(E_x+E_y+1)), so it fits XW + YW bits and the
//! cut is a fixed arithmetic shift by XW + YW − W: the top W bits, wires, no leading-bit
//! search and no shifter. The dropped part's bound is the leading one of the dropped low
//! bits, a 3-way max; the components share their last bit, so the max of their leading ones
//! is the leading one of their OR: one search instead of three.
//!
//! The block exponent is in this block: the model's `cross_block` returns it, and the
//! output is then a whole block (`m`, `e`, `below`) like `ToBlock`'s, registered with its
//! mantissas. Its field is the sum of the inputs' biased fields plus one, so its bias is
//! the sum of theirs: [`P_BIAS`] for p = dir × e2, [`Q_BIAS`] for q = s × e1. Its last bit is
//! implicit, 2^(e − bias − W + 1), as `ToBlock`'s.
//!
//! Two register stages, where a DSP48E1 has them: the six products (its M register), then
//! the block (its P register, after the subtraction).

use hw_model::dual::bfp::{widths, Vector, DROP_WINDOW, GUARD_BITS};
use rust_hdl::prelude::*;

use super::to_block::{BELOW_BITS, EXP_BITS};
use super::translate::{FIELD_BITS, SIGNIFICAND_BITS};
use super::WIDTH;
use crate::intmul::SignedMul;
use crate::macros::clock;

/// Clock edges from the inputs to the block.
pub const LATENCY: usize = 2;

/// Width of the cut's block exponent field: the sum of two `ToBlock::e` fields plus one.
pub const CROSS_EXP_BITS: usize = EXP_BITS + 1;

/// The bias of dir's block exponent field (`DirToBlock::e`): an fp32 significand's last
/// bit is at its exponent field − 150 (fp32's bias 127 plus 23 fraction bits).
pub const DIR_BIAS: usize = (1 << (FIELD_BITS - 1)) - 1 + SIGNIFICAND_BITS - 1;
/// The bias of e1's, e2's and s's fields (`EdgeToBlock::e`, `SToBlock::e`): `Translate`'s
/// differences sit `GUARD_BITS` below the larger operand's last bit.
pub const EDGE_BIAS: usize = DIR_BIAS + GUARD_BITS as usize;
/// The bias of p's field (dir × e2) and of q's (s × e1).
pub const P_BIAS: usize = DIR_BIAS + EDGE_BIAS;
pub const Q_BIAS: usize = EDGE_BIAS + EDGE_BIAS;

/// A vector's mantissa width at W = [`WIDTH`].
const fn width(v: Vector) -> usize {
    widths(WIDTH)[v as usize] as usize
}

/// p = dir × e2, cut to W bits.
pub type PCross = CrossBlock<
    { width(Vector::Dir) },
    { width(Vector::E2) },
    { width(Vector::Dir) + width(Vector::E2) },
    { width(Vector::P) },
>;
/// q = s × e1, cut to W + `S_EXTRA_BITS` bits.
pub type QCross = CrossBlock<
    { width(Vector::S) },
    { width(Vector::E1) },
    { width(Vector::S) + width(Vector::E1) },
    { width(Vector::Q) },
>;

/// x × y (XW- and YW-bit two's-complement mantissas, block exponent fields `ex`, `ey`) to
/// `m[k]`·2^(`e` − bias − W + 1) with `e` = `ex` + `ey` + 1; PW = XW + YW is the exact
/// products' width. `below` is e minus the exponent of the largest dropped part (in
/// W − 1..=`DROP_WINDOW`), 0 when nothing was dropped, as `ToBlock::below`.
#[derive(LogicBlock)]
pub struct CrossBlock<const XW: usize, const YW: usize, const PW: usize, const W: usize> {
    pub clock: Signal<In, Clock>,
    pub x: [Signal<In, Bits<XW>>; 3],
    pub y: [Signal<In, Bits<YW>>; 3],
    pub ex: Signal<In, Bits<EXP_BITS>>,
    pub ey: Signal<In, Bits<EXP_BITS>>,
    pub m: [Signal<Out, Bits<W>>; 3],
    pub e: Signal<Out, Bits<CROSS_EXP_BITS>>,
    pub below: Signal<Out, Bits<BELOW_BITS>>,
    /// Component k is `mul[2k]` − `mul[2k + 1]`: x1·y2 − x2·y1, x2·y0 − x0·y2, x0·y1 − x1·y0.
    mul: [SignedMul<XW, YW, PW>; 6],
    /// Stage 1: the products and the block exponent.
    product_reg: [DFF<Bits<PW>>; 6],
    sum_reg: DFF<Bits<CROSS_EXP_BITS>>,
    /// Stage 2: the block.
    m_reg: [DFF<Bits<W>>; 3],
    e_reg: DFF<Bits<CROSS_EXP_BITS>>,
    below_reg: DFF<Bits<BELOW_BITS>>,
    one: Constant<Bits<CROSS_EXP_BITS>>,
    /// PW − W: the cut, the exact component's bits below the block's last bit.
    cut: Constant<Bits<EXP_BITS>>,
    /// Those bits' mask.
    low: Constant<Bits<PW>>,
    unit: Constant<Bits<EXP_BITS>>,
    /// PW − 1: the block exponent less the exact products' last bit.
    last: Constant<Bits<EXP_BITS>>,
    window: Constant<Bits<EXP_BITS>>,
    /// The exact cross product.
    c: [Signal<Local, Bits<PW>>; 3],
    /// The dropped bits of the three components ORed, and their bit count.
    rest: Signal<Local, Bits<PW>>,
    length: Signal<Local, Bits<EXP_BITS>>,
    distance: Signal<Local, Bits<EXP_BITS>>,
}

impl<const XW: usize, const YW: usize, const PW: usize, const W: usize> Default
    for CrossBlock<XW, YW, PW, W>
{
    fn default() -> Self {
        assert_eq!(
            PW,
            XW + YW,
            "CrossBlock: the exact products need XW + YW bits"
        );
        assert!(
            W <= PW,
            "CrossBlock: the cut keeps at most the exact product's bits"
        );
        assert!(
            PW < 1 << EXP_BITS,
            "CrossBlock: distances are EXP_BITS wide"
        );
        let exp = |v: usize| Constant::new((v as u64).to_bits());
        Self {
            clock: Default::default(),
            x: Default::default(),
            y: Default::default(),
            ex: Default::default(),
            ey: Default::default(),
            m: Default::default(),
            e: Default::default(),
            below: Default::default(),
            mul: Default::default(),
            product_reg: Default::default(),
            sum_reg: Default::default(),
            m_reg: Default::default(),
            e_reg: Default::default(),
            below_reg: Default::default(),
            one: Constant::new(1u64.to_bits()),
            cut: exp(PW - W),
            low: Constant::new(!(!Bits::<PW>::default() << (PW - W) as u64)),
            unit: exp(1),
            last: exp(PW - 1),
            window: exp(DROP_WINDOW as usize),
            c: Default::default(),
            rest: Default::default(),
            length: Default::default(),
            distance: Default::default(),
        }
    }
}

impl<const XW: usize, const YW: usize, const PW: usize, const W: usize> Logic
    for CrossBlock<XW, YW, PW, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..6 {
            clock!(self, clock, product_reg[k]);
        }
        for k in 0..3 {
            clock!(self, clock, m_reg[k]);
        }
        clock!(self, clock, sum_reg, e_reg, below_reg);
        // Stage 1: the six products (signed multipliers, one DSP48E1 each at W = 18).
        self.mul[0].a.next = self.x[1].val();
        self.mul[0].b.next = self.y[2].val();
        self.mul[1].a.next = self.x[2].val();
        self.mul[1].b.next = self.y[1].val();
        self.mul[2].a.next = self.x[2].val();
        self.mul[2].b.next = self.y[0].val();
        self.mul[3].a.next = self.x[0].val();
        self.mul[3].b.next = self.y[2].val();
        self.mul[4].a.next = self.x[0].val();
        self.mul[4].b.next = self.y[1].val();
        self.mul[5].a.next = self.x[1].val();
        self.mul[5].b.next = self.y[0].val();
        for k in 0..6 {
            self.product_reg[k].d.next = self.mul[k].p.val();
        }
        self.sum_reg.d.next = bit_cast::<CROSS_EXP_BITS, EXP_BITS>(self.ex.val())
            + bit_cast::<CROSS_EXP_BITS, EXP_BITS>(self.ey.val())
            + self.one.val();
        // Stage 2: each difference fits PW bits (the model's range), so PW-bit arithmetic
        // is exact.
        self.c[0].next = self.product_reg[0].q.val() - self.product_reg[1].q.val();
        self.c[1].next = self.product_reg[2].q.val() - self.product_reg[3].q.val();
        self.c[2].next = self.product_reg[4].q.val() - self.product_reg[5].q.val();
        // The cut: the top W bits (an arithmetic shift by a constant, so wires).
        self.m_reg[0].d.next = bit_cast::<W, PW>(self.c[0].val() >> self.cut.val());
        self.m_reg[1].d.next = bit_cast::<W, PW>(self.c[1].val() >> self.cut.val());
        self.m_reg[2].d.next = bit_cast::<W, PW>(self.c[2].val() >> self.cut.val());
        // The dropped part's leading bit, as a distance below the block exponent.
        self.rest.next = (self.c[0].val() | self.c[1].val() | self.c[2].val()) & self.low.val();
        self.length.next = 0.into();
        for i in 0..PW {
            if self.rest.val().get_bit(i) {
                self.length.next = i.to_bits() + self.unit.val();
            }
        }
        self.distance.next = self.last.val() - self.length.val();
        if self.distance.val() > self.window.val() {
            self.distance.next = self.window.val();
        }
        self.below_reg.d.next = 0.into();
        if self.rest.val().any() {
            self.below_reg.d.next = bit_cast::<BELOW_BITS, EXP_BITS>(self.distance.val());
        }
        self.e_reg.d.next = self.sum_reg.q.val();
        for k in 0..3 {
            self.m[k].next = self.m_reg[k].q.val();
        }
        self.e.next = self.e_reg.q.val();
        self.below.next = self.below_reg.q.val();
    }
}
