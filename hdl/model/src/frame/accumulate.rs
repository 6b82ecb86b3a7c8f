//! Per-pixel accumulation in fixed point: what makes the frame's image independent of the
//! order in which the traversal unit answers rays.
//!
//! Every contribution c (an fp32 RGB computed per ray, deterministic) becomes, per channel,
//! the integer `floor(fl(255·c) · 2^16)` saturated to 28 bits ([`CONTRIBUTION`]: units of
//! 2^-16 of an 8-bit step, range ±2048 steps). A pixel sums its contributions in integers,
//! which is associative and, with [`SUM_BITS`] bits, cannot overflow ([`max_sum`]), so the
//! sum is the same in any order. The 8-bit channel is `clamp(sum >> 16, 0, 255)`.
//!
//! Why this format (docs/frame.md, "Accumulation"): the reference writes
//! `trunc(fl(255·clamp(x, 0, 1)))` of its fp32 sum x. For a pixel with one contribution the
//! channel above equals it bit for bit: v = fl(255·c) is the reference's product, and
//! `floor(floor(v·2^16)/2^16) = floor(v)` for any v (truncation, not rounding, in the
//! conversion is what makes this hold: a rounded v just below an integer could step up to
//! it). For several contributions it is the exact `floor(Σ fl(255·c_k))` up to the 2^-16 per
//! contribution the truncation drops, where the reference rounded its running sum in fp32.
//! The multiply by 255 is per contribution, before the sum, so that a sum needs no fp32
//! rounding at all.

use crate::fixed::FixedFormat;
use crate::format::{Arith, Overflow, Quant};
use crate::fp32::{Fp32, Vec3};
use crate::Format;

use super::FrameLimits;

/// The conversion's format as the fixed-point operators take it.
const FIXED: FixedFormat = FixedFormat {
    int: 12,
    frac: 16,
    quant: Quant::Trn,
    overflow: Overflow::Sat,
};

/// A contribution's fixed-point format: 12 integer bits (sign included) and 16 fraction bits
/// of an 8-bit step, truncated, saturated (NaN converts to 0: see docs/frame.md).
pub const CONTRIBUTION: Format = Format::Fixed {
    int: FIXED.int,
    frac: FIXED.frac,
    quant: FIXED.quant,
    overflow: FIXED.overflow,
};

/// Fraction bits of [`CONTRIBUTION`] (and of a pixel's sum).
pub const FRACTION_BITS: u32 = FIXED.frac;

/// Bits of a pixel's signed sum per channel (a DSP48E1's accumulator is 48 bits).
pub const SUM_BITS: u32 = 48;

/// One contribution to a pixel: per channel a [`CONTRIBUTION`] value (in units of 2^-16).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Contribution(pub [i32; 3]);

impl Contribution {
    /// `c` in fixed point: per channel `fl(255·c)`, then converted to [`CONTRIBUTION`].
    pub fn of(c: Vec3) -> Contribution {
        let steps = Fp32::new(255.0);
        Contribution(c.components().map(|x| {
            let bits = FIXED.convert_in_f32((steps * x).f32());
            FIXED.value(bits) as i32
        }))
    }

    pub fn is_zero(&self) -> bool {
        self.0 == [0; 3]
    }
}

/// The largest |sum| a pixel reaches under `limits`: contributions of the largest magnitude
/// (2^27 units), as many as a pixel can have. A pixel's ray tree has at most 2^(D+1) − 1
/// traced castRay nodes (D the largest max depth: each hit spawns at most a reflection and a
/// refraction); each adds at most max(lights, 2) contributions (a diffuse or Phong hit one
/// per light; a glass hit whose two children are past the depth two backgrounds; a miss one).
pub fn max_sum(limits: &FrameLimits) -> u128 {
    let nodes = (1u128 << (limits.max_depth + 1)) - 1;
    let per_node = limits.lights.max(2) as u128;
    nodes * per_node * (1u128 << (CONTRIBUTION.width() - 1))
}

/// A pixel's sums and the rays of it still out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct PixelSum {
    sum: [i64; 3],
    outstanding: u32,
}

/// The sums of a set of pixels, indexed 0..n by the caller.
#[derive(Clone, Debug)]
pub struct Accumulator {
    pixels: Vec<PixelSum>,
    /// Contributions added (zero ones included).
    pub added: u64,
}

impl Accumulator {
    pub fn new(pixels: usize) -> Accumulator {
        Accumulator {
            pixels: vec![PixelSum::default(); pixels],
            added: 0,
        }
    }

    /// A ray of pixel `p` goes out.
    pub fn issue(&mut self, p: usize) {
        self.pixels[p].outstanding += 1;
    }

    pub fn add(&mut self, p: usize, c: Contribution) {
        let sum = &mut self.pixels[p].sum;
        for (s, c) in sum.iter_mut().zip(c.0) {
            *s += i64::from(c);
        }
        self.added += 1;
    }

    /// A ray of pixel `p` has returned and been shaded (its spawned rays issued first): the
    /// pixel's 8-bit colour if that was its last ray.
    pub fn retire(&mut self, p: usize) -> Option<[u8; 3]> {
        let px = &mut self.pixels[p];
        px.outstanding -= 1;
        (px.outstanding == 0).then(|| px.sum.map(rgb8))
    }
}

/// A channel's sum as the 8-bit value: `clamp(sum >> 16, 0, 255)` (the shift is a floor).
pub fn rgb8(sum: i64) -> u8 {
    (sum >> FRACTION_BITS).clamp(0, 255) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use sw_renderer::math::V3;
    use sw_renderer::shade::to_rgb8;

    #[test]
    fn the_sum_cannot_overflow_its_bits() {
        let bound = max_sum(&FrameLimits::HW);
        assert!(bound < 1u128 << (SUM_BITS - 1), "{bound:#x}");
        assert_eq!(
            CONTRIBUTION.width() - 1,
            27,
            "a contribution's magnitude is below 2^27 units"
        );
    }

    /// One contribution gives the reference's 8-bit value of that colour, bit for bit, for
    /// every fp32 value of 255·c in [0, 256) and around it (with c = v/255 rounded, the
    /// reference's own product is what both see).
    #[test]
    fn one_contribution_is_the_references_truncation() {
        let check = |c: f32| {
            let ours = rgb8(i64::from(Contribution::of(Vec3::of([c, 0.0, 0.0])).0[0]));
            let theirs = to_rgb8(V3::new(c, 0.0, 0.0))[0];
            assert_eq!(ours, theirs, "c = {c:e} ({:#x})", c.to_bits());
        };
        // Every float c in [2^-20, 1.05]: 255·c covers every truncation boundary.
        let (lo, hi) = (2f32.powi(-20).to_bits(), 1.05f32.to_bits());
        for bits in (lo..=hi).step_by(7) {
            check(f32::from_bits(bits));
        }
        for k in 0..=256u32 {
            let c = k as f32 / 255.0;
            for c in [c.next_down(), c, c.next_up()] {
                check(c);
            }
        }
        for c in [0.0, -0.0, -1.0, 2.0, 1e30, -1e30, f32::INFINITY, 1e-42] {
            check(c);
        }
    }

    #[test]
    fn a_pixel_is_final_when_its_last_ray_returns() {
        let mut acc = Accumulator::new(2);
        acc.issue(1);
        acc.add(1, Contribution::of(Vec3::of([0.5, 0.25, 2.0])));
        acc.issue(1); // a spawned ray, issued before its parent retires
        assert_eq!(acc.retire(1), None);
        acc.add(1, Contribution::of(Vec3::of([0.25, -1.0, 0.0])));
        assert_eq!(acc.retire(1), Some([191, 0, 255]));
        assert_eq!(acc.added, 2);
    }
}
