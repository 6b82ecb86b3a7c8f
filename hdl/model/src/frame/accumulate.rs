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
        Contribution(c.components().map(|x| Contribution::of_steps(steps * x)))
    }

    /// One channel's value from v = fl(255·c), in steps: v in [`CONTRIBUTION`] (the
    /// conversion [`Contribution::of`] does after the multiply).
    pub fn of_steps(v: Fp32) -> i32 {
        FIXED.value(FIXED.convert_in_f32(v.f32())) as i32
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

/// The most contributions one shaded ray adds to its pixel, the bound a frame unit's *settle*
/// record (their sum, [`Settle`]) is sized for: max(lights, 2), the per-node bound of
/// [`max_sum`] (this model's shading adds at most 2 per ray: a glass hit whose two children
/// are past the depth; a miss, an unoccluded shadow ray or a mirror past the depth one).
pub const fn max_contributions_per_ray(limits: &FrameLimits) -> u64 {
    at_least_2(limits.lights) as u64
}

/// The most rays one shaded ray spawns: a shadow ray per light, or a reflection and a
/// refraction.
pub const fn max_spawned(limits: &FrameLimits) -> u32 {
    at_least_2(limits.lights) as u32
}

const fn at_least_2(lights: usize) -> usize {
    if lights > 2 {
        lights
    } else {
        2
    }
}

/// The most rays of one pixel out at once: 2^D · max(lights, 1) (D the largest max depth).
/// The rays out at once are never one another's ancestors (a ray's spawned rays go out when it
/// is shaded, and it retires with them), so they are at most the leaves of the pixel's ray
/// tree. A cast ray at depth D has at most max(lights, 1) leaves: its shadow rays, or itself
/// (its reflection and refraction are past the depth); one at depth d < D at most
/// max(lights, 2·L(d + 1)) = 2·L(d + 1) (shadow rays, or two cast children). Shadow rays make
/// this more than the 2^(D+1) − 1 cast rays of the tree: 2^18 against 2^16 − 1 at
/// [`FrameLimits::HW`].
pub const fn max_outstanding(limits: &FrameLimits) -> u64 {
    let leaves = if limits.lights > 1 { limits.lights } else { 1 };
    (1u64 << limits.max_depth) * leaves as u64
}

/// What one shaded ray does to its pixel, as one record: its contributions' sum per channel
/// and how many rays it spawned. [`Accumulator::settle`] applies it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Settle {
    pub sum: [i64; 3],
    pub spawned: u32,
}

impl Settle {
    pub fn of(contributions: &[Contribution], spawned: u32) -> Settle {
        let mut sum = [0i64; 3];
        for c in contributions {
            for (s, c) in sum.iter_mut().zip(c.0) {
                *s += i64::from(c);
            }
        }
        Settle { sum, spawned }
    }
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
}

impl Accumulator {
    pub fn new(pixels: usize) -> Accumulator {
        Accumulator {
            pixels: vec![PixelSum::default(); pixels],
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
    }

    /// A ray of pixel `p` has returned and been shaded (its spawned rays issued first): the
    /// pixel's 8-bit colour if that was its last ray.
    pub fn retire(&mut self, p: usize) -> Option<[u8; 3]> {
        let px = &mut self.pixels[p];
        px.outstanding -= 1;
        (px.outstanding == 0).then(|| px.sum.map(rgb8))
    }

    /// Pixel `p`'s primary ray goes out, its slot starting over (sums 0, one ray out): a
    /// slot's first pixel, or the next pixel in a slot whose pixel has finished. On a new
    /// accumulator this is [`Accumulator::issue`].
    pub fn open(&mut self, p: usize) {
        self.pixels[p] = PixelSum {
            sum: [0; 3],
            outstanding: 1,
        };
    }

    /// One shaded ray of pixel `p` as one record: its contributions' sum added, its spawned
    /// rays issued, itself retired; the pixel's 8-bit colour if that was its last ray. The
    /// same as [`Accumulator::add`] of each contribution, [`Accumulator::issue`] of each
    /// spawned ray and [`Accumulator::retire`].
    pub fn settle(&mut self, p: usize, s: &Settle) -> Option<[u8; 3]> {
        let px = &mut self.pixels[p];
        for (sum, add) in px.sum.iter_mut().zip(s.sum) {
            *sum += add;
        }
        px.outstanding += s.spawned;
        self.retire(p)
    }
}

/// A channel's sum as the 8-bit value: `clamp(sum >> 16, 0, 255)` (the shift is a floor).
pub fn rgb8(sum: i64) -> u8 {
    (sum >> FRACTION_BITS).clamp(0, 255) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{rngs::StdRng, Rng, SeedableRng};
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
    }

    /// A random contribution: mostly a colour's, some at the format's extremes or negative.
    fn random_contribution(rng: &mut StdRng) -> Contribution {
        let lo = -(1i32 << (CONTRIBUTION.width() - 1));
        let hi = (1i32 << (CONTRIBUTION.width() - 1)) - 1;
        Contribution(std::array::from_fn(|_| match rng.gen_range(0..8) {
            0 => lo,
            1 => hi,
            2 => rng.gen_range(lo..=hi),
            _ => rng.gen_range(0..=255 << FRACTION_BITS),
        }))
    }

    /// Random ray trees in many slots, their shaded rays in random order: settling each ray as
    /// one record (and opening each slot) leaves every pixel as issuing, adding and retiring
    /// one by one does, and finishes the same pixels with the same colours.
    #[test]
    fn a_settle_record_is_its_issues_adds_and_retire() {
        let limits = FrameLimits::HW;
        let mut rng = StdRng::seed_from_u64(40);
        let slots = 16;
        let (mut one_by_one, mut records) = (Accumulator::new(slots), Accumulator::new(slots));
        // Per slot: rays out and rays the tree may still spawn (open when none is out).
        let mut out = vec![0u32; slots];
        let mut budget = vec![0u32; slots];
        let mut finished = 0;
        for _ in 0..20_000 {
            let p = rng.gen_range(0..slots);
            if out[p] == 0 {
                // A reused slot is a new accumulator's in `one_by_one`.
                one_by_one.pixels[p] = PixelSum::default();
                one_by_one.issue(p);
                records.open(p);
                out[p] = 1;
                budget[p] = rng.gen_range(0..40);
                continue;
            }
            let n = rng.gen_range(0..=max_contributions_per_ray(&limits));
            let contributions: Vec<Contribution> =
                (0..n).map(|_| random_contribution(&mut rng)).collect();
            let spawned = rng.gen_range(0..=max_spawned(&limits).min(budget[p]));
            budget[p] -= spawned;
            for &c in &contributions {
                one_by_one.add(p, c);
            }
            for _ in 0..spawned {
                one_by_one.issue(p);
            }
            let want = one_by_one.retire(p);
            let got = records.settle(p, &Settle::of(&contributions, spawned));
            assert_eq!(got, want, "slot {p}");
            assert_eq!(records.pixels[p], one_by_one.pixels[p], "slot {p}");
            out[p] = out[p] + spawned - 1;
            finished += usize::from(got.is_some());
        }
        assert!(finished > 1000, "{finished} pixels finished");
    }

    /// The worst ray tree, shaded breadth first: glass (two cast children) down to depth D,
    /// a diffuse hit under every light there; the rays out peak at exactly
    /// [`max_outstanding`], more than the tree's 2^(D+1) − 1 cast rays.
    #[test]
    fn the_widest_ray_tree_has_max_outstanding_rays_out() {
        for limits in [
            FrameLimits::HW,
            FrameLimits {
                lights: 1,
                max_depth: 4,
                ..FrameLimits::HW
            },
        ] {
            let mut acc = Accumulator::new(1);
            acc.open(0);
            let mut peak = 1;
            let mut level = 1u64;
            for depth in 0..=limits.max_depth {
                let children = if depth < limits.max_depth {
                    2
                } else {
                    limits.lights as u32
                };
                for _ in 0..level {
                    acc.settle(0, &Settle::of(&[], children));
                    peak = peak.max(u64::from(acc.pixels[0].outstanding));
                }
                level *= u64::from(children);
            }
            assert_eq!(peak, max_outstanding(&limits), "{limits:?}");
            for _ in 1..level {
                assert_eq!(acc.settle(0, &Settle::default()), None);
            }
            assert_eq!(acc.settle(0, &Settle::default()), Some([0; 3]));
        }
        let cast_rays = (1u64 << (FrameLimits::HW.max_depth + 1)) - 1;
        assert!(max_outstanding(&FrameLimits::HW) > cast_rays);
    }

    /// Random ray trees as the shading makes them (a cast ray spawns a shadow ray per light
    /// or up to two cast rays, none past the depth; a shadow ray nothing), shaded in random
    /// order: the rays out never exceed [`max_outstanding`].
    #[test]
    fn rays_out_never_exceed_max_outstanding() {
        let mut rng = StdRng::seed_from_u64(41);
        for (lights, max_depth) in [(0, 3), (1, 4), (3, 2), (5, 0), (8, 3)] {
            let limits = FrameLimits {
                lights,
                max_depth,
                ..FrameLimits::HW
            };
            let bound = max_outstanding(&limits);
            let mut widest = 0;
            for _ in 0..200 {
                // The rays out: Some(depth) for a cast ray, None for a shadow ray.
                let mut rays = vec![Some(0u32)];
                let mut acc = Accumulator::new(1);
                acc.open(0);
                while !rays.is_empty() {
                    let ray = rays.swap_remove(rng.gen_range(0..rays.len()));
                    let spawned: Vec<Option<u32>> = match ray {
                        None => vec![],
                        Some(d) => match rng.gen_range(0..3) {
                            0 => vec![None; lights],
                            _ if d == max_depth => vec![],
                            k => vec![Some(d + 1); k],
                        },
                    };
                    acc.settle(0, &Settle::of(&[], spawned.len() as u32));
                    rays.extend(spawned);
                    let out = u64::from(acc.pixels[0].outstanding);
                    assert_eq!(out, rays.len() as u64);
                    assert!(out <= bound, "{out} rays out, bound {bound}: {limits:?}");
                    widest = widest.max(out);
                }
            }
            assert!(widest > 1, "{limits:?}: trees too narrow to test");
        }
    }
}
