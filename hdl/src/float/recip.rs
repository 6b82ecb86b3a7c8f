//! Correctly rounded float reciprocal `y = 1 / a` (RNE, FTZ; 1/±0 = ±Inf, 1/±Inf = ±0) by a
//! table-driven quadratic approximation and an exact rounding test.
//!
//! With sig = 1.f (M fraction bits) ≠ 1, the result significand is RN(T), T = 2^(2M+1)/sig
//! in (2^M, 2^(M+1)) (exponent 2·bias − 1 − e). The top K fraction bits index a table of
//! (A, B, C) per segment, the low D = M − K bits are d, and
//!
//! ```text
//! Y = A − (B·d >> (D+2)) + (C·(d² >> r) >> (D2H+2))       (mod 2^(M+5))
//! ```
//!
//! approximates T·2^5 (2 guard and 3 working bits) with an error below a quarter of T's last
//! unit, so the candidate c = ⌊Y / 2^5⌋ is RN(T) or RN(T) − 1: RN(T) = c + 1 exactly when
//! T > c + 1/2, i.e. when sig·(2c + 1) < 2^(2M+2). That product is 2^(2M+2) + Δ with
//! |Δ| < 2^(M+3) (c is within 1.25 of T), so bit M+3 of it mod 2^(M+4) is the sign of Δ;
//! mod 2^(M+4) it is sig·(2·frac + 1) + (sig mod 8)·2^(M+1) for c = 2^M + frac, an
//! (M+1)×(M+1) product (the size of a multiplier's) and a 3-bit add. T·2^5 lies in
//! (2^(M+5), 2^(M+6)), so Y is kept without its top bit, which is always set.
//! sig = 1 gives the exact result 1.0·2^(bias − e).
//!
//! The coefficients are fitted when the operator is built (interpolation at the Chebyshev
//! nodes of each segment, f64). With K = (M + 3) / 3 the worst error over all fractions is
//! 0.29 of that bound for fp32, 0.20 fp24, 0.18 fp16, 0.16 bf16 (measured with a throwaway
//! integer model of this datapath while choosing K); the operator tests check every fraction
//! of fp16, bf16 (rust-hdl) and fp32, fp24 (Verilator) against the model.
//!
//! Cut points (max_stages() = 5): 0. after the table, B·d and d²; 1. after A − B·d and
//! C·d²; 2. after the sum; 3. after the rounding test (sig·(2c+1)) and c + 1; 4. the result,
//! after choosing c or c + 1 and packing. A DSP48E1 multiplier and a carry chain of at most
//! M + 5 bits lie between two cuts.

use rust_hdl::prelude::*;

use super::round::{ResultClass, Round};
use super::unpack::Unpack;
use crate::intmul::IntMul;
use crate::pipe::{placement, Pipe};

/// Guard plus working bits of Y below the result's last bit.
const EXTRA_BITS: usize = 5;
/// Widest operand of a DSP48E1's unsigned multiplier input B (18-bit signed).
const DSP_B_BITS: usize = 17;

/// Table index bits of an M-bit fraction.
pub const fn index_bits(m: usize) -> usize {
    (m + 3) / 3
}
/// Bits of d, the fraction below the table index.
pub const fn d_bits(m: usize) -> usize {
    m - index_bits(m)
}
/// Bits of Y (without its top bit, always set).
pub const fn y_bits(m: usize) -> usize {
    m + EXTRA_BITS
}
/// Bits of the linear coefficient B (< 2^(D+8)).
pub const fn b_bits(m: usize) -> usize {
    d_bits(m) + 8
}
/// Bits of the quadratic coefficient C (< 2^(8+D−K)).
pub const fn c_bits(m: usize) -> usize {
    8 + d_bits(m) - index_bits(m)
}
/// Bits of d² kept for the quadratic term (at most one DSP input).
pub const fn square_bits(m: usize) -> usize {
    let full = 2 * d_bits(m);
    if full < DSP_B_BITS {
        full
    } else {
        DSP_B_BITS
    }
}

/// The (A, B, C) table of an M-bit fraction: entry i approximates 2^(2M+6)/sig over the
/// segment sig ∈ [2^M + i·2^D, 2^M + (i+1)·2^D) as A − B·d/2^(D+2) + C·(d²/2^r)/2^(D2H+2),
/// with A reduced mod 2^(M+5).
fn table(m: usize) -> Vec<(u64, u64, u64)> {
    let (k, d) = (index_bits(m), d_bits(m));
    let r = 2 * d - square_bits(m);
    let (b_shift, c_shift) = (d + 2, square_bits(m) + 2);
    let scale = 2f64.powi((m + 1 + EXTRA_BITS) as i32);
    let span = ((1u64 << d) - 1) as f64;
    (0..1u64 << k)
        .map(|i| {
            let x0 = 1.0 + i as f64 / (1u64 << k) as f64;
            let f = |d: f64| scale / (x0 + d / 2f64.powi(m as i32));
            // The quadratic through f at the three Chebyshev nodes of [0, span]
            // (Newton's divided differences).
            let n: Vec<f64> = (0..3)
                .map(|j| {
                    span * (1.0 - ((2 * j + 1) as f64 * std::f64::consts::PI / 6.0).cos()) / 2.0
                })
                .collect();
            let y: Vec<f64> = n.iter().map(|&x| f(x)).collect();
            let f01 = (y[1] - y[0]) / (n[1] - n[0]);
            let f12 = (y[2] - y[1]) / (n[2] - n[1]);
            let f012 = (f12 - f01) / (n[2] - n[0]);
            let a = y[0] - f01 * n[0] + f012 * n[0] * n[1];
            let b = -(f01 - f012 * (n[0] + n[1]));
            let c = f012;
            assert!(b > 0.0 && c > 0.0, "1/x is decreasing and convex");
            let a_q = (a.round() as u64) & ((1u64 << y_bits(m)) - 1);
            let b_q = (b * 2f64.powi(b_shift as i32)).round() as u64;
            let c_q = (c * 2f64.powi((r + c_shift) as i32)).round() as u64;
            assert!(
                b_q < 1 << b_bits(m) && c_q < 1 << c_bits(m),
                "recip table entry {i} of M = {m} exceeds its width"
            );
            (a_q, b_q, c_q)
        })
        .collect()
}

/// E, M: the format; W, S, X: a word, a significand, a signed exponent (≥ E+2); then the
/// table and product widths K, D, YW, BW, CW, D2, D2H, P1, P2, PC, each named and computed
/// by [`crate::widths::RecipWidths`] (which says why they are parameters).
#[derive(LogicBlock)]
pub struct FloatRecip<
    const E: usize,
    const M: usize,
    const W: usize,
    const S: usize,
    const X: usize,
    const K: usize,
    const D: usize,
    const YW: usize,
    const BW: usize,
    const CW: usize,
    const D2: usize,
    const D2H: usize,
    const P1: usize,
    const P2: usize,
    const PC: usize,
> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<W>>,
    pub y: Signal<Out, Bits<W>>,
    unpack: Unpack<E, M, W, S>,
    category: Signal<Local, ResultClass>,
    index: Signal<Local, Bits<K>>,
    d: Signal<Local, Bits<D>>,
    table_a: ROM<Bits<YW>, K>,
    table_b: ROM<Bits<BW>, K>,
    table_c: ROM<Bits<CW>, K>,
    linear: IntMul<BW, D, P1>,
    square: IntMul<D, D, D2>,
    // Cut 0.
    lookup_a: Pipe<Bits<YW>>,
    lookup_c: Pipe<Bits<CW>>,
    lookup_linear: Pipe<Bits<P1>>,
    lookup_square: Pipe<Bits<D2H>>,
    lookup_sig: Pipe<Bits<S>>,
    lookup_exp: Pipe<Bits<X>>,
    lookup_exact: Pipe<Bit>,
    lookup_category: Pipe<ResultClass>,
    quadratic: IntMul<CW, D2H, P2>,
    // Cut 1.
    partial_sum: Pipe<Bits<YW>>,
    partial_quadratic: Pipe<Bits<P2>>,
    partial_sig: Pipe<Bits<S>>,
    partial_exp: Pipe<Bits<X>>,
    partial_exact: Pipe<Bit>,
    partial_category: Pipe<ResultClass>,
    sum: Signal<Local, Bits<YW>>,
    // Cut 2.
    candidate_frac: Pipe<Bits<M>>,
    candidate_sig: Pipe<Bits<S>>,
    candidate_exp: Pipe<Bits<X>>,
    candidate_exact: Pipe<Bit>,
    candidate_category: Pipe<ResultClass>,
    check: IntMul<S, S, PC>,
    check_top: Signal<Local, Bits<3>>,
    // Cut 3.
    decided_up: Pipe<Bit>,
    decided_frac: Pipe<Bits<M>>,
    decided_frac_up: Pipe<Bits<M>>,
    decided_exp: Pipe<Bits<X>>,
    decided_exact: Pipe<Bit>,
    decided_category: Pipe<ResultClass>,
    rounder: Round<E, M, W, S, X>,
    // Cut 4.
    result: Pipe<Bits<W>>,
    exp_base: Constant<Bits<X>>,
    d_shift: Constant<Bits<8>>,
    b_shift: Constant<Bits<8>>,
    r_shift: Constant<Bits<8>>,
    c_shift: Constant<Bits<8>>,
    extra_shift: Constant<Bits<8>>,
    check_shift: Constant<Bits<8>>,
    hidden_bit: Constant<Bits<S>>,
    low_three: Constant<Bits<S>>,
    one: Constant<Bits<M>>,
    exp_one: Constant<Bits<X>>,
    no_bit: Constant<Bit>,
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const K: usize,
        const D: usize,
        const YW: usize,
        const BW: usize,
        const CW: usize,
        const D2: usize,
        const D2H: usize,
        const P1: usize,
        const P2: usize,
        const PC: usize,
    > FloatRecip<E, M, W, S, X, K, D, YW, BW, CW, D2, D2H, P1, P2, PC>
{
    pub const CUTS: usize = 5;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        assert!(
            W == 1 + E + M
                && S == M + 1
                && X >= E + 2
                && (K, D, YW, BW, CW, D2H)
                    == (
                        index_bits(M),
                        d_bits(M),
                        y_bits(M),
                        b_bits(M),
                        c_bits(M),
                        square_bits(M)
                    )
                && (D2, P1, P2, PC) == (2 * D, BW + D, CW + D2H, 2 * S),
            "FloatRecip: inconsistent widths"
        );
        let cut = placement(stages, Self::CUTS);
        let bias = (1u64 << (E - 1)) - 1;
        let entries = table(M);
        let rom = |field: fn(&(u64, u64, u64)) -> u64| entries.iter().map(field);
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            unpack: Default::default(),
            category: Default::default(),
            index: Default::default(),
            d: Default::default(),
            table_a: rom(|e| e.0).map(Bits::<YW>::from).into(),
            table_b: rom(|e| e.1).map(Bits::<BW>::from).into(),
            table_c: rom(|e| e.2).map(Bits::<CW>::from).into(),
            linear: Default::default(),
            square: Default::default(),
            lookup_a: Pipe::new(cut[0]),
            lookup_c: Pipe::new(cut[0]),
            lookup_linear: Pipe::new(cut[0]),
            lookup_square: Pipe::new(cut[0]),
            lookup_sig: Pipe::new(cut[0]),
            lookup_exp: Pipe::new(cut[0]),
            lookup_exact: Pipe::new(cut[0]),
            lookup_category: Pipe::new(cut[0]),
            quadratic: Default::default(),
            partial_sum: Pipe::new(cut[1]),
            partial_quadratic: Pipe::new(cut[1]),
            partial_sig: Pipe::new(cut[1]),
            partial_exp: Pipe::new(cut[1]),
            partial_exact: Pipe::new(cut[1]),
            partial_category: Pipe::new(cut[1]),
            sum: Default::default(),
            candidate_frac: Pipe::new(cut[2]),
            candidate_sig: Pipe::new(cut[2]),
            candidate_exp: Pipe::new(cut[2]),
            candidate_exact: Pipe::new(cut[2]),
            candidate_category: Pipe::new(cut[2]),
            check: Default::default(),
            check_top: Default::default(),
            decided_up: Pipe::new(cut[3]),
            decided_frac: Pipe::new(cut[3]),
            decided_frac_up: Pipe::new(cut[3]),
            decided_exp: Pipe::new(cut[3]),
            decided_exact: Pipe::new(cut[3]),
            decided_category: Pipe::new(cut[3]),
            rounder: Default::default(),
            result: Pipe::new(cut[4]),
            // 1/(sig·2^(e−bias)) = (2/sig)·2^(bias−e−1): biased exponent 2·bias − 1 − e.
            exp_base: Constant::new((2 * bias - 1).into()),
            d_shift: Constant::new(D.to_bits()),
            b_shift: Constant::new((D + 2).to_bits()),
            r_shift: Constant::new((2 * D - D2H).to_bits()),
            c_shift: Constant::new((D2H + 2).to_bits()),
            extra_shift: Constant::new(EXTRA_BITS.to_bits()),
            check_shift: Constant::new((M + 1).to_bits()),
            hidden_bit: Constant::new(Bits::<S>::from(1) << M as u64),
            low_three: Constant::new(7.into()),
            one: Constant::new(1.into()),
            exp_one: Constant::new(1.into()),
            no_bit: Constant::new(false),
        }
    }
}

impl<
        const E: usize,
        const M: usize,
        const W: usize,
        const S: usize,
        const X: usize,
        const K: usize,
        const D: usize,
        const YW: usize,
        const BW: usize,
        const CW: usize,
        const D2: usize,
        const D2H: usize,
        const P1: usize,
        const P2: usize,
        const PC: usize,
    > Logic for FloatRecip<E, M, W, S, X, K, D, YW, BW, CW, D2, D2H, P1, P2, PC>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.unpack.x.next = self.a.val();
        self.category.next.sign = self.unpack.sign.val();
        self.category.next.nan = self.unpack.nan.val();
        self.category.next.inf = self.unpack.zero.val();
        self.category.next.zero = self.unpack.inf.val();
        // The table's segment and the offset d in it.
        self.index.next = bit_cast::<K, S>(self.unpack.sig.val() >> self.d_shift.val());
        self.d.next = bit_cast::<D, S>(self.unpack.sig.val());
        self.table_a.address.next = self.index.val();
        self.table_b.address.next = self.index.val();
        self.table_c.address.next = self.index.val();
        self.linear.a.next = self.table_b.data.val();
        self.linear.b.next = self.d.val();
        self.square.a.next = self.d.val();
        self.square.b.next = self.d.val();
        // Cut 0.
        clock!(
            self,
            clock,
            lookup_a,
            lookup_c,
            lookup_linear,
            lookup_square,
            lookup_sig,
            lookup_exp,
            lookup_exact,
            lookup_category
        );
        self.lookup_a.d.next = self.table_a.data.val();
        self.lookup_c.d.next = self.table_c.data.val();
        self.lookup_linear.d.next = self.linear.p.val();
        self.lookup_square.d.next = bit_cast::<D2H, D2>(self.square.p.val() >> self.r_shift.val());
        self.lookup_sig.d.next = self.unpack.sig.val();
        self.lookup_exp.d.next = self.exp_base.val() - bit_cast::<X, E>(self.unpack.exp.val());
        self.lookup_exact.d.next = self.unpack.sig.val() == self.hidden_bit.val();
        self.lookup_category.d.next = self.category.val();
        self.quadratic.a.next = self.lookup_c.q.val();
        self.quadratic.b.next = self.lookup_square.q.val();
        // Cut 1.
        clock!(
            self,
            clock,
            partial_sum,
            partial_quadratic,
            partial_sig,
            partial_exp,
            partial_exact,
            partial_category
        );
        self.partial_sum.d.next = self.lookup_a.q.val()
            - bit_cast::<YW, P1>(self.lookup_linear.q.val() >> self.b_shift.val());
        self.partial_quadratic.d.next = self.quadratic.p.val();
        self.partial_sig.d.next = self.lookup_sig.q.val();
        self.partial_exp.d.next = self.lookup_exp.q.val();
        self.partial_exact.d.next = self.lookup_exact.q.val();
        self.partial_category.d.next = self.lookup_category.q.val();
        self.sum.next = self.partial_sum.q.val()
            + bit_cast::<YW, P2>(self.partial_quadratic.q.val() >> self.c_shift.val());
        // Cut 2: the candidate c = 2^M + frac.
        clock!(
            self,
            clock,
            candidate_frac,
            candidate_sig,
            candidate_exp,
            candidate_exact,
            candidate_category
        );
        self.candidate_frac.d.next = bit_cast::<M, YW>(self.sum.val() >> self.extra_shift.val());
        self.candidate_sig.d.next = self.partial_sig.q.val();
        self.candidate_exp.d.next = self.partial_exp.q.val();
        self.candidate_exact.d.next = self.partial_exact.q.val();
        self.candidate_category.d.next = self.partial_category.q.val();
        // Bits M+1..M+3 of sig·(2c + 1) = sig·2^(M+1) + sig·(2·frac + 1): see the module docs.
        self.check.a.next = self.candidate_sig.q.val();
        self.check.b.next =
            (bit_cast::<S, M>(self.candidate_frac.q.val()) << 1) | bit_cast::<S, M>(self.one.val());
        self.check_top.next = bit_cast::<3, PC>(self.check.p.val() >> self.check_shift.val())
            + bit_cast::<3, S>(self.candidate_sig.q.val() & self.low_three.val());
        // Cut 3.
        clock!(
            self,
            clock,
            decided_up,
            decided_frac,
            decided_frac_up,
            decided_exp,
            decided_exact,
            decided_category
        );
        self.decided_up.d.next = self.check_top.val().get_bit(2);
        self.decided_frac.d.next = self.candidate_frac.q.val();
        self.decided_frac_up.d.next = self.candidate_frac.q.val() + self.one.val();
        self.decided_exp.d.next = self.candidate_exp.q.val();
        self.decided_exact.d.next = self.candidate_exact.q.val();
        self.decided_category.d.next = self.candidate_category.q.val();
        // The result is exact: nothing is left to round.
        self.rounder.round.next = self.no_bit.val();
        self.rounder.sticky.next = self.no_bit.val();
        self.rounder.category.next = self.decided_category.q.val();
        self.rounder.exp.next = self.decided_exp.q.val();
        if self.decided_exact.q.val() {
            self.rounder.sig.next = self.hidden_bit.val();
            self.rounder.exp.next = self.decided_exp.q.val() + self.exp_one.val();
        } else if self.decided_up.q.val() {
            self.rounder.sig.next =
                self.hidden_bit.val() | bit_cast::<S, M>(self.decided_frac_up.q.val());
        } else {
            self.rounder.sig.next =
                self.hidden_bit.val() | bit_cast::<S, M>(self.decided_frac.q.val());
        }
        // Cut 4.
        clock!(self, clock, result);
        self.result.d.next = self.rounder.y.val();
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary FloatRecip<E, M, W, S, X, K, D, YW, BW, CW, D2, D2H, P1, P2, PC>,
    [const E: usize, const M: usize, const W: usize, const S: usize, const X: usize,
     const K: usize, const D: usize, const YW: usize, const BW: usize, const CW: usize,
     const D2: usize, const D2H: usize, const P1: usize, const P2: usize, const PC: usize],
    W, W, out = bits);
