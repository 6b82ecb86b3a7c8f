//! Step 3 of the bfp filter, its dots: the exact dot product of two mantissa vectors (three
//! signed products and their sum), bit for bit the model's `hw_model::dual::bfp::dot`:
//! det = e1·p̂, N_u = s·p̂, N_v = dir·q̂, N_t = e2·q̂. The value's last bit is the sum of
//! the two blocks' (its exponent is the margin's and the decisions' business, step 4 and 5).
//!
//! Two register stages, where DSP48E1s have them: the three products (M registers), then
//! the sum (P register).

use hw_model::dual::bfp::{widths, Vector};
use rust_hdl::prelude::*;

use super::WIDTH;
use crate::intmul::SignedMul;
use crate::macros::clock;

/// Clock edges from the inputs to the value.
pub const LATENCY: usize = 2;

/// The smallest two's-complement width that holds every dot of an `a`-bit and a `b`-bit
/// vector: each product lies in [−2^(a+b−2) + 2^(min(a,b)−1), 2^(a+b−2)] (2^(a+b−2) only
/// for the two most negative operands), so the sum of three lies within ±3·2^(a+b−2):
/// beyond a + b bits (±2^(a+b−1)), within a + b + 1.
pub const fn dot_bits(a: usize, b: usize) -> usize {
    a + b + 1
}

/// A vector's mantissa width at W = [`WIDTH`].
const fn width(v: Vector) -> usize {
    widths(WIDTH)[v as usize] as usize
}

/// The `Dot` of vectors `a` and `b`'s mantissas, its widths from the model's.
macro_rules! dot {
    ($a:expr, $b:expr) => {
        Dot<
            { width($a) },
            { width($b) },
            { width($a) + width($b) },
            { dot_bits(width($a), width($b)) },
        >
    };
}

/// det = e1·p̂ (18 × 18 → 37 bits at W = 18).
pub type DetDot = dot!(Vector::E1, Vector::P);
/// N_u = s·p̂ (25 × 18 → 44 bits).
pub type NuDot = dot!(Vector::S, Vector::P);
/// N_v = dir·q̂ (18 × 25 → 44 bits).
pub type NvDot = dot!(Vector::Dir, Vector::Q);
/// N_t = e2·q̂ (18 × 25 → 44 bits).
pub type NtDot = dot!(Vector::E2, Vector::Q);

/// `v` = a·b of AW- and BW-bit two's-complement mantissas, OW = [`dot_bits`] wide; PW =
/// AW + BW is the products' width.
#[derive(LogicBlock)]
pub struct Dot<const AW: usize, const BW: usize, const PW: usize, const OW: usize> {
    pub clock: Signal<In, Clock>,
    pub a: [Signal<In, Bits<AW>>; 3],
    pub b: [Signal<In, Bits<BW>>; 3],
    pub v: Signal<Out, Bits<OW>>,
    mul: [SignedMul<AW, BW, PW>; 3],
    /// Stage 1: the products.
    product_reg: [DFF<Bits<PW>>; 3],
    /// Stage 2: the value.
    v_reg: DFF<Bits<OW>>,
    /// The products' sign bit, and the bits above them a negative one extends into.
    sign: Constant<Bits<PW>>,
    extension: Constant<Bits<OW>>,
    /// The products sign-extended to OW bits.
    term: [Signal<Local, Bits<OW>>; 3],
}

impl<const AW: usize, const BW: usize, const PW: usize, const OW: usize> Default
    for Dot<AW, BW, PW, OW>
{
    fn default() -> Self {
        assert_eq!(PW, AW + BW, "Dot: the products need AW + BW bits");
        assert_eq!(
            OW,
            dot_bits(AW, BW),
            "Dot: the value needs dot_bits(AW, BW)"
        );
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            v: Default::default(),
            mul: Default::default(),
            product_reg: Default::default(),
            v_reg: Default::default(),
            sign: Constant::new(Bits::<PW>::from(1) << (PW as u64 - 1)),
            extension: Constant::new(!Bits::<OW>::default() << PW as u64),
            term: Default::default(),
        }
    }
}

impl<const AW: usize, const BW: usize, const PW: usize, const OW: usize> Logic
    for Dot<AW, BW, PW, OW>
{
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            clock!(self, clock, product_reg[k]);
        }
        clock!(self, clock, v_reg);
        // Stage 1: the three products (signed multipliers, one DSP48E1 each at W = 18).
        for k in 0..3 {
            self.mul[k].a.next = self.a[k].val();
            self.mul[k].b.next = self.b[k].val();
            self.product_reg[k].d.next = self.mul[k].p.val();
        }
        // Stage 2: the sum, exact in OW bits. (bit_cast in a loop loses the loop variable:
        // one per product.)
        self.term[0].next = bit_cast::<OW, PW>(self.product_reg[0].q.val());
        self.term[1].next = bit_cast::<OW, PW>(self.product_reg[1].q.val());
        self.term[2].next = bit_cast::<OW, PW>(self.product_reg[2].q.val());
        for k in 0..3 {
            if (self.product_reg[k].q.val() & self.sign.val()).any() {
                self.term[k].next = self.term[k].val() | self.extension.val();
            }
        }
        self.v_reg.d.next = self.term[0].val() + self.term[1].val() + self.term[2].val();
        self.v.next = self.v_reg.q.val();
    }
}
