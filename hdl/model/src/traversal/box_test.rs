//! The traversal unit's box test, in the hardware's fp32 arithmetic (the SPEC of
//! `crate::format`: round to nearest even, subnormals flushed to zero).
//!
//! It is the software BVH's padded slab test (`sw_renderer::bvh::BoxRay`) operation for
//! operation, so on inputs without subnormals both give the same bits; where they differ
//! (a subnormal operand or result) this one is the hardware's definition. Conservative as the
//! BVH is: boxes are padded by the writer, the ray's origin is moved by `pad` towards and away
//! from every side, and the bound is loosened, so rounding never drops a box that holds a
//! triangle the Möller-Trumbore test hits.
//!
//! Comparisons are the hardware's `lt` (false on a NaN): a NaN slab distance is ignored, as
//! the software's selects ignore it, so a ray with NaN components enters boxes and its
//! Möller-Trumbore tests (all NaN) end it as a miss, as in software.

use crate::format::Format;

/// fp32 as the datapath computes it.
const F: Format = Format::FP32;

/// The two child boxes of an inner node, `[axis][child]`, as the scene image stores them.
pub use super::scene_image::ChildBoxes;
/// Relative padding of the ray origin and bound: the BVH's, which also padded the boxes.
pub use sw_renderer::bvh::PAD;

/// The slope used for a direction component whose reciprocal is not finite (0, a flushed
/// subnormal, NaN): huge instead of infinite, so that no 0·∞ NaN arises.
pub const HUGE_SLOPE: f32 = 1e30;

#[inline]
fn bits(x: f32) -> u64 {
    x.to_bits() as u64
}

#[inline]
fn word(b: u64) -> f32 {
    f32::from_bits(b as u32)
}

#[inline]
fn abs(b: u64) -> u64 {
    b & 0x7FFF_FFFF
}

/// `if lt(a, b) { b } else { a }`: the larger, keeping `a` on a tie or a NaN.
#[inline]
fn keep_larger(a: u64, b: u64) -> u64 {
    if F.lt(a, b) {
        b
    } else {
        a
    }
}

/// `if lt(b, a) { b } else { a }`: the smaller, keeping `a` on a tie or a NaN.
#[inline]
fn keep_smaller(a: u64, b: u64) -> u64 {
    if F.lt(b, a) {
        b
    } else {
        a
    }
}

/// A ray prepared for box tests once, when it enters the unit (fp32 words).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySetup {
    /// The origin moved by `pad` towards every box side's lower plane (+pad) …
    pub orig_lo: [f32; 3],
    /// … and towards the upper plane (−pad).
    pub orig_hi: [f32; 3],
    /// 1/dir, or ±[`HUGE_SLOPE`] where that is not finite.
    pub inv_dir: [f32; 3],
    /// `PAD · max |orig|`.
    pub pad: f32,
    /// The far end of the slab interval: [`t_hi`] of the ray's current bound.
    pub t_hi: f32,
}

/// `(bound + |bound|·PAD) + pad`: a bound loosened so that a hit rounded just beyond it
/// still has its box entered. Recomputed whenever a closest-hit ray's bound shrinks.
pub fn t_hi(bound: f32, pad: f32) -> f32 {
    let b = bits(bound);
    word(F.add(F.add(b, F.mul(abs(b), bits(PAD))), bits(pad)))
}

/// Prepares `(orig, dir)` with hit bound `bound` (the ray's t_max).
pub fn ray_setup(orig: [f32; 3], dir: [f32; 3], bound: f32) -> RaySetup {
    let o = orig.map(bits);
    let magnitude = o.iter().fold(0u64, |m, &x| keep_larger(m, abs(x)));
    let pad = F.mul(bits(PAD), magnitude);
    let inv_dir = dir.map(|d| {
        let inv = F.recip(bits(d));
        let finite = (inv >> 23) & 0xFF != 0xFF;
        if finite {
            word(inv)
        } else {
            HUGE_SLOPE.copysign(d)
        }
    });
    RaySetup {
        orig_lo: o.map(|x| word(F.add(x, pad))),
        orig_hi: o.map(|x| word(F.sub(x, pad))),
        inv_dir,
        pad: word(pad),
        t_hi: t_hi(bound, word(pad)),
    }
}

/// What one box test answers for both children.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxResult {
    /// Whether the ray's slab interval in each child box is non-empty within [0, t_hi].
    pub enters: [bool; 2],
    /// The entry distance into each box (meaningful where entered).
    pub near: [f32; 2],
    /// The child to visit first when both are entered: 1 if child 1 is entered strictly
    /// nearer, else 0.
    pub first: usize,
}

/// The slab test of both children of a node, per child and axis
/// `t0 = (min − orig_lo)·inv`, `t1 = (max − orig_hi)·inv`, `lo, hi` = the ordered pair
/// (`lt(t0, t1)` decides), `near` = the larger of 0 and the three `lo` (x, then y, then z),
/// `far` = the smaller of `t_hi` and the three `hi`; entered iff `near ≤ far`.
pub fn box_test(ray: &RaySetup, boxes: &ChildBoxes) -> BoxResult {
    let mut near = [bits(0.0); 2];
    let mut far = [bits(ray.t_hi); 2];
    for a in 0..3 {
        let inv = bits(ray.inv_dir[a]);
        for c in 0..2 {
            let t0 = F.mul(F.sub(bits(boxes.min[a][c]), bits(ray.orig_lo[a])), inv);
            let t1 = F.mul(F.sub(bits(boxes.max[a][c]), bits(ray.orig_hi[a])), inv);
            let ordered = F.lt(t0, t1);
            let (lo, hi) = if ordered { (t0, t1) } else { (t1, t0) };
            near[c] = keep_larger(near[c], lo);
            far[c] = keep_smaller(far[c], hi);
        }
    }
    // near ≤ far: near is never NaN (it starts at 0 and only takes non-NaN values); a NaN far
    // (a NaN bound) enters nothing.
    let enters = [0, 1].map(|c| !F.lt(far[c], near[c]) && !F.is_nan(far[c]));
    BoxResult {
        enters,
        near: near.map(word),
        first: usize::from(F.lt(near[1], near[0])),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(lo: f32, hi: f32) -> ChildBoxes {
        ChildBoxes {
            min: [[lo; 2]; 3],
            max: [[hi; 2]; 3],
        }
    }

    #[test]
    fn a_ray_through_a_box_enters_it_at_the_right_distance() {
        let ray = ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], f32::MAX);
        let mut boxes = unit_box(0.0, 1.0);
        boxes.min[0][1] = 2.0; // child 1 lies beside the ray
        boxes.max[0][1] = 3.0;
        let r = box_test(&ray, &boxes);
        assert_eq!(r.enters, [true, false]);
        // Entry at z = 1 (padded): 4 less a hair.
        assert!(r.near[0] < 4.0 && r.near[0] > 3.999, "{}", r.near[0]);
    }

    #[test]
    fn zero_direction_components_use_the_huge_slope() {
        let ray = ray_setup([0.5, 0.5, 5.0], [0.0, -0.0, -1.0], f32::MAX);
        assert_eq!(ray.inv_dir, [1e30, -1e30, -1.0]);
        assert_eq!(box_test(&ray, &unit_box(0.0, 1.0)).enters, [true, true]);
        // Parallel to a slab and outside it: never enters.
        let ray = ray_setup([1.5, 0.5, 5.0], [0.0, 0.0, -1.0], f32::MAX);
        assert_eq!(box_test(&ray, &unit_box(0.0, 1.0)).enters, [false, false]);
    }

    #[test]
    fn an_origin_inside_enters_at_zero_and_a_short_bound_stops_short() {
        let ray = ray_setup([0.5, 0.5, 0.5], [1.0, 0.0, 0.0], f32::MAX);
        let r = box_test(&ray, &unit_box(0.0, 1.0));
        assert_eq!(r.enters, [true, true]);
        assert_eq!(r.near, [0.0, 0.0]);
        let ray = ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], 2.0);
        assert_eq!(box_test(&ray, &unit_box(0.0, 1.0)).enters, [false, false]);
    }

    #[test]
    fn nan_rays_enter_and_nan_bounds_do_not() {
        let ray = ray_setup([f32::NAN, 0.5, 5.0], [0.0, 0.0, -1.0], f32::MAX);
        assert_eq!(box_test(&ray, &unit_box(0.0, 1.0)).enters, [true, true]);
        let ray = ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], f32::NAN);
        assert_eq!(box_test(&ray, &unit_box(0.0, 1.0)).enters, [false, false]);
    }

    #[test]
    fn an_infinite_bound_is_an_infinite_far_end() {
        let ray = ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], f32::INFINITY);
        assert_eq!(ray.t_hi, f32::INFINITY);
        // FLT_MAX loosened by PAD overflows to +Inf as well.
        assert_eq!(t_hi(f32::MAX, 0.0), f32::INFINITY);
    }

    #[test]
    fn the_nearer_child_goes_first() {
        let ray = ray_setup([0.5, 0.5, 10.0], [0.0, 0.0, -1.0], f32::MAX);
        let mut boxes = unit_box(0.0, 1.0);
        boxes.min[2][1] = 5.0;
        boxes.max[2][1] = 6.0;
        let r = box_test(&ray, &boxes);
        assert_eq!((r.enters, r.first), ([true, true], 1));
    }
}
