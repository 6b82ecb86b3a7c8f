//! Where the walk enters a child (docs/wide-nodes.md, step 6): `t0' = τ + near·2^8` in units
//! of `2^(U−8)`, as fp32 rounded toward zero (0 below the smallest normal, the largest finite
//! value above it), and its width exponent
//! `w' = max(U + bitlen(far − near), exp(t0') − 23) + 2` clamped to `WIDTH_MIN..WIDTH_UNBOUNDED`;
//! for a node whose grid is unknown, the node's own `t0` and [`WIDTH_UNBOUNDED`].
//!
//! With `n = τ + near·2^8` (46 bits) and `E = U + 14` (the grid's extent), `t0'` has the
//! biased exponent `E + 150 − lz(n)` and the 23 bits below `n`'s leading one.
//!
//! Cut points ([`ChildEntry::CUTS`]): 0. after `n` and `far − near`; 1. after the leading
//! zeros; 2. after the normalization (`t0'`); 3. the results (the width).

use rust_hdl::prelude::*;

use super::{EntryCode, ExitCode, Magnitude, Shift, WidthExp, Word};
use crate::float::leading_zeros::LeadingZeros;
use crate::pipe::{placement, Pipe};
use hw_model::traversal::wide::box_test::{FRAC_BITS, WIDTH_MIN, WIDTH_UNBOUNDED};

/// Bits of `n`: `τ < 2^45` plus a code below 2^15 at `2^8`.
const N_BITS: usize = 46;
type Scaled = Bits<N_BITS>;
/// Exponents, two's complement.
type Exponent = Bits<12>;

#[derive(LogicBlock)]
pub struct ChildEntry {
    pub clock: Signal<In, Clock>,
    pub near: Signal<In, EntryCode>,
    pub far: Signal<In, ExitCode>,
    pub tau: Signal<In, Magnitude>,
    /// The grid's extent `E` (two's complement).
    pub extent: Signal<In, Shift>,
    pub unknown: Signal<In, Bit>,
    /// The node's own `t0`.
    pub t0: Signal<In, Word>,
    pub entry_t0: Signal<Out, Word>,
    pub entry_width: Signal<Out, WidthExp>,
    /// Cut 0.
    sum: Pipe<Scaled>,
    span: Pipe<ExitCode>,
    extent_0: Pipe<Shift>,
    unknown_0: Pipe<Bit>,
    t0_0: Pipe<Word>,
    sum_zeros_hi: LeadingZeros,
    sum_zeros_lo: LeadingZeros,
    span_zeros: LeadingZeros,
    zeros: Signal<Local, Bits<8>>,
    /// Cut 1.
    sum_1: Pipe<Scaled>,
    zeros_1: Pipe<Bits<8>>,
    sum_zero_1: Pipe<Bit>,
    span_bits_1: Pipe<Bits<8>>,
    extent_1: Pipe<Shift>,
    unknown_1: Pipe<Bit>,
    t0_1: Pipe<Word>,
    extent_wide: Signal<Local, Exponent>,
    normalized: Signal<Local, Scaled>,
    biased: Signal<Local, Exponent>,
    /// Cut 2.
    entry_t0_2: Pipe<Word>,
    entry_exp_2: Pipe<Bits<8>>,
    span_exp_2: Pipe<Exponent>,
    unknown_2: Pipe<Bit>,
    t0_2: Pipe<Word>,
    ulp_exp: Signal<Local, Exponent>,
    width: Signal<Local, Exponent>,
    /// Cut 3.
    entry_t0_out: Pipe<Word>,
    entry_width_out: Pipe<WidthExp>,
    extent_sign: Constant<Exponent>,
    exp_base: Constant<Exponent>,
    span_base: Constant<Exponent>,
    ulp_base: Constant<Exponent>,
    flip: Constant<Exponent>,
    width_min: Constant<Exponent>,
    width_max: Constant<Exponent>,
    exp_inf: Constant<Exponent>,
    largest: Constant<Word>,
    code_lsb: Constant<Bits<8>>,
    half_bits: Constant<Bits<8>>,
    short_bits: Constant<Bits<8>>,
    unbounded: Constant<WidthExp>,
}

impl ChildEntry {
    pub const CUTS: usize = 4;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        let exponent = |v: i64| Constant::new(((v as u64) & 0xFFF).into());
        Self {
            clock: Default::default(),
            near: Default::default(),
            far: Default::default(),
            tau: Default::default(),
            extent: Default::default(),
            unknown: Default::default(),
            t0: Default::default(),
            entry_t0: Default::default(),
            entry_width: Default::default(),
            sum: Pipe::new(cut[0]),
            span: Pipe::new(cut[0]),
            extent_0: Pipe::new(cut[0]),
            unknown_0: Pipe::new(cut[0]),
            t0_0: Pipe::new(cut[0]),
            sum_zeros_hi: Default::default(),
            sum_zeros_lo: Default::default(),
            span_zeros: Default::default(),
            zeros: Default::default(),
            sum_1: Pipe::new(cut[1]),
            zeros_1: Pipe::new(cut[1]),
            sum_zero_1: Pipe::new(cut[1]),
            span_bits_1: Pipe::new(cut[1]),
            extent_1: Pipe::new(cut[1]),
            unknown_1: Pipe::new(cut[1]),
            t0_1: Pipe::new(cut[1]),
            extent_wide: Default::default(),
            normalized: Default::default(),
            biased: Default::default(),
            entry_t0_2: Pipe::new(cut[2]),
            entry_exp_2: Pipe::new(cut[2]),
            span_exp_2: Pipe::new(cut[2]),
            unknown_2: Pipe::new(cut[2]),
            t0_2: Pipe::new(cut[2]),
            ulp_exp: Default::default(),
            width: Default::default(),
            entry_t0_out: Pipe::new(cut[3]),
            entry_width_out: Pipe::new(cut[3]),
            extent_sign: exponent(!0x3FF),
            // biased = (N_BITS − lz) − 1 + (E − 14 − FRAC_BITS) + 127.
            exp_base: exponent(N_BITS as i64 - 1 - 14 - i64::from(FRAC_BITS) + 127),
            // U + 2 = E − 12.
            span_base: exponent(-12),
            // exp(t0') − 23 + 2, exp the biased exponent less 127.
            ulp_base: exponent(-127 - 23 + 2),
            flip: exponent(0x800),
            width_min: exponent(i64::from(WIDTH_MIN) ^ 0x800),
            width_max: exponent((i64::from(WIDTH_UNBOUNDED) - 1) ^ 0x800),
            exp_inf: exponent(255),
            largest: Constant::new(u64::from(f32::MAX.to_bits()).into()),
            code_lsb: Constant::new(u64::from(FRAC_BITS).into()),
            half_bits: Constant::new(32.into()),
            short_bits: Constant::new(16.into()),
            unbounded: Constant::new((WIDTH_UNBOUNDED as u64 & 0x3FF).into()),
        }
    }
}

impl Logic for ChildEntry {
    #[hdl_gen]
    fn update(&mut self) {
        self.sum.clock.next = self.clock.val();
        self.span.clock.next = self.clock.val();
        self.extent_0.clock.next = self.clock.val();
        self.unknown_0.clock.next = self.clock.val();
        self.t0_0.clock.next = self.clock.val();
        self.sum_1.clock.next = self.clock.val();
        self.zeros_1.clock.next = self.clock.val();
        self.sum_zero_1.clock.next = self.clock.val();
        self.span_bits_1.clock.next = self.clock.val();
        self.extent_1.clock.next = self.clock.val();
        self.unknown_1.clock.next = self.clock.val();
        self.t0_1.clock.next = self.clock.val();
        self.entry_t0_2.clock.next = self.clock.val();
        self.entry_exp_2.clock.next = self.clock.val();
        self.span_exp_2.clock.next = self.clock.val();
        self.unknown_2.clock.next = self.clock.val();
        self.t0_2.clock.next = self.clock.val();
        self.entry_t0_out.clock.next = self.clock.val();
        self.entry_width_out.clock.next = self.clock.val();
        // n = τ + near·2^8; far − near.
        self.sum.d.next = bit_cast::<N_BITS, 47>(self.tau.val())
            + (bit_cast::<N_BITS, 15>(self.near.val()) << self.code_lsb.val());
        self.span.d.next = self.far.val() - bit_cast::<16, 15>(self.near.val());
        self.extent_0.d.next = self.extent.val();
        self.unknown_0.d.next = self.unknown.val();
        self.t0_0.d.next = self.t0.val();
        // Leading zeros of n (its top 32 bits, then the 14 below, left-aligned) and of the
        // span (non-negative when the child is entered; 15 bits, left-aligned).
        self.sum_zeros_hi.x.next = bit_cast::<32, N_BITS>(self.sum.q.val() >> 14);
        self.sum_zeros_lo.x.next = bit_cast::<32, N_BITS>(self.sum.q.val()) << 18;
        self.zeros.next = self.sum_zeros_hi.count.val();
        if !self.sum.q.val().get_bits::<32>(14).any() {
            self.zeros.next = self.sum_zeros_lo.count.val() + self.half_bits.val();
        }
        self.span_zeros.x.next = bit_cast::<32, 16>(self.span.q.val()) << 16;
        self.span_bits_1.d.next = self.short_bits.val() - self.span_zeros.count.val();
        if !self.span.q.val().any() {
            self.span_bits_1.d.next = 0.into();
        }
        self.sum_1.d.next = self.sum.q.val();
        self.zeros_1.d.next = self.zeros.val();
        self.sum_zero_1.d.next = !self.sum.q.val().any();
        self.extent_1.d.next = self.extent_0.q.val();
        self.unknown_1.d.next = self.unknown_0.q.val();
        self.t0_1.d.next = self.t0_0.q.val();
        // t0': normalized, its exponent tested against the normal range.
        self.extent_wide.next = bit_cast::<12, 11>(self.extent_1.q.val());
        if self.extent_1.q.val().get_bit(10) {
            self.extent_wide.next = self.extent_wide.val() | self.extent_sign.val();
        }
        self.normalized.next = self.sum_1.q.val() << self.zeros_1.q.val();
        self.biased.next =
            self.extent_wide.val() + self.exp_base.val() - bit_cast::<12, 8>(self.zeros_1.q.val());
        self.entry_t0_2.d.next = (bit_cast::<32, 8>(bit_cast::<8, 12>(self.biased.val())) << 23)
            | bit_cast::<32, 23>(self.normalized.val().get_bits::<23>(22));
        self.entry_exp_2.d.next = bit_cast::<8, 12>(self.biased.val());
        if !self.biased.val().get_bit(11) & (self.biased.val() >= self.exp_inf.val()) {
            self.entry_t0_2.d.next = self.largest.val();
            self.entry_exp_2.d.next = 254.into();
        }
        if self.sum_zero_1.q.val() | self.biased.val().get_bit(11) | !self.biased.val().any() {
            self.entry_t0_2.d.next = 0.into();
            self.entry_exp_2.d.next = 0.into();
        }
        self.span_exp_2.d.next = self.extent_wide.val()
            + self.span_base.val()
            + bit_cast::<12, 8>(self.span_bits_1.q.val());
        self.unknown_2.d.next = self.unknown_1.q.val();
        self.t0_2.d.next = self.t0_1.q.val();
        // The width: the larger exponent, clamped (compared with the sign bit flipped).
        self.ulp_exp.next = bit_cast::<12, 8>(self.entry_exp_2.q.val()) + self.ulp_base.val();
        self.width.next = self.span_exp_2.q.val() ^ self.flip.val();
        if (self.ulp_exp.val() ^ self.flip.val()) > self.width.val() {
            self.width.next = self.ulp_exp.val() ^ self.flip.val();
        }
        if self.width.val() < self.width_min.val() {
            self.width.next = self.width_min.val();
        }
        if self.width.val() > self.width_max.val() {
            self.width.next = self.width_max.val();
        }
        self.entry_t0_out.d.next = self.entry_t0_2.q.val();
        self.entry_width_out.d.next = bit_cast::<10, 12>(self.width.val() ^ self.flip.val());
        if self.unknown_2.q.val() {
            self.entry_t0_out.d.next = self.t0_2.q.val();
            self.entry_width_out.d.next = self.unbounded.val();
        }
        self.entry_t0.next = self.entry_t0_out.q.val();
        self.entry_width.next = self.entry_width_out.q.val();
    }
}
