//! Fixed-point multiplication `y = a × b`: the exact 2W-bit product (units 2^-2F), shifted
//! right by F with the quantisation mode, then the overflow mode.
//!
//! The DSP multiplier is unsigned: a two's-complement operand a = a_u − 2^W·a_sign, so the
//! signed product is a_u·b_u − 2^W·(a_sign·b_u + b_sign·a_u) modulo 2^2W; the correction
//! (a W-bit sum) is formed next to the multiplier and subtracted from its upper half.
//!
//! Cut points (max_stages() = 4):
//! - 0: the operands and the correction (DSP input registers);
//! - 1: the unsigned product (DSP output register);
//! - 2: the signed product;
//! - 3: the quantised product, before saturation.
//!
//! The correction and the rounding are two 2W-bit carry chains, so they are kept apart.

use rust_hdl::prelude::*;

use super::fit::Fit;
use crate::intmul::IntMul;
use crate::pipe::{placement, Pipe};

/// W: the format's width, F its fraction bits, P = 2W; RND: round to nearest; SAT: saturate.
#[derive(LogicBlock)]
pub struct FixedMul<
    const W: usize,
    const F: usize,
    const P: usize,
    const RND: bool,
    const SAT: bool,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub b: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    correction: Signal<Local, Bits<W>>,
    operand_a: Pipe<Bits<W>>,
    operand_b: Pipe<Bits<W>>,
    operand_correction: Pipe<Bits<W>>,
    multiplier: IntMul<W, W, P>,
    product: Pipe<Bits<P>>,
    product_correction: Pipe<Bits<W>>,
    /// The signed product (`signed` would be a Verilog keyword).
    exact: Pipe<Bits<P>>,
    floor: Signal<Local, Bits<P>>,
    quantised: Pipe<Bits<P>>,
    fit: Fit<P, W, SAT>,
    nearest: Constant<Bit>,
    sign_shift: Constant<Bits<8>>,
    width: Constant<Bits<8>>,
    frac: Constant<Bits<8>>,
    product_sign_shift: Constant<Bits<8>>,
    extension: Constant<Bits<P>>,
    round_bit: Constant<Bits<P>>,
    zero: Constant<Bits<W>>,
}

impl<const W: usize, const F: usize, const P: usize, const RND: bool, const SAT: bool>
    FixedMul<W, F, P, RND, SAT>
{
    pub const CUTS: usize = 4;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            P == 2 * W && F >= 1 && F < W,
            "FixedMul: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            correction: Default::default(),
            operand_a: Pipe::new(cut[0]),
            operand_b: Pipe::new(cut[0]),
            operand_correction: Pipe::new(cut[0]),
            multiplier: Default::default(),
            product: Pipe::new(cut[1]),
            product_correction: Pipe::new(cut[1]),
            exact: Pipe::new(cut[2]),
            floor: Default::default(),
            quantised: Pipe::new(cut[3]),
            fit: Default::default(),
            nearest: Constant::new(RND),
            sign_shift: Constant::new((W - 1).to_bits()),
            width: Constant::new(W.to_bits()),
            frac: Constant::new(F.to_bits()),
            product_sign_shift: Constant::new((P - 1).to_bits()),
            // The bits an arithmetic right shift by F fills with the sign.
            extension: Constant::new(!(Bits::<P>::mask() >> F as u64)),
            round_bit: Constant::new(Bits::<P>::from(1) << (F - 1) as u64),
            zero: Constant::new(Bits::<W>::default()),
        }
    }
}

impl<const W: usize, const F: usize, const P: usize, const RND: bool, const SAT: bool> Logic
    for FixedMul<W, F, P, RND, SAT>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.correction.next = self.zero.val();
        if (self.a.val() >> self.sign_shift.val()).any() {
            self.correction.next = self.correction.val() + self.b.val();
        }
        if (self.b.val() >> self.sign_shift.val()).any() {
            self.correction.next = self.correction.val() + self.a.val();
        }
        // Cut 0.
        clock!(self, clock, operand_a, operand_b, operand_correction);
        self.operand_a.d.next = self.a.val();
        self.operand_b.d.next = self.b.val();
        self.operand_correction.d.next = self.correction.val();
        self.multiplier.a.next = self.operand_a.q.val();
        self.multiplier.b.next = self.operand_b.q.val();
        // Cut 1.
        clock!(self, clock, product, product_correction);
        self.product.d.next = self.multiplier.p.val();
        self.product_correction.d.next = self.operand_correction.q.val();
        // Cut 2.
        clock!(self, clock, exact);
        self.exact.d.next = self.product.q.val()
            - (bit_cast::<P, W>(self.product_correction.q.val()) << self.width.val());
        // Arithmetic shift right by F (floor), plus the first dropped bit when rounding.
        self.floor.next = self.exact.q.val() >> self.frac.val();
        if (self.exact.q.val() >> self.product_sign_shift.val()).any() {
            self.floor.next = (self.exact.q.val() >> self.frac.val()) | self.extension.val();
        }
        // Cut 3.
        clock!(self, clock, quantised);
        self.quantised.d.next = self.floor.val()
            + (self.nearest.val() & (self.exact.q.val() & self.round_bit.val()).any());
        self.fit.v.next = self.quantised.q.val();
        self.y.next = self.fit.y.val();
    }
}

crate::impl_operator!(binary FixedMul<W, F, P, RND, SAT>,
    [const W: usize, const F: usize, const P: usize, const RND: bool, const SAT: bool],
    W, W, out = bits);
