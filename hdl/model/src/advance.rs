//! Advancing a query's origin along its ray before a narrow datapath (docs/precision.md,
//! "Advancing the origin").
//!
//! Möller-Trumbore's rounding errors grow with |s| = |o − v0|: every product with s carries
//! an error of the format's unit roundoff times |s|·|e|, so a ray from a camera 100 units
//! away misplaces u and v on a triangle one unit wide by about 100 times more than a ray
//! starting beside it, and neighbours sharing an edge leave cracks between them. Moving the
//! origin to where the ray enters the triangle's bounding box, in fp32, makes |s| the size
//! of the box. u and v do not change in exact arithmetic (they do not depend on where on the
//! ray the origin is), t changes by the distance moved, which the lane adds back in fp32.
//!
//! Two forms choose the distance t0 and share the move ([`moved`], [`moved_back`]): per
//! query from the triangle's box ([`Advance::TriangleBox`], the model engine), and per ray
//! and BVH leaf from the leaf's box entry the traversal unit's box test has already computed
//! ([`Advance::LeafBox`]), so that |s| is the leaf's size rather than the triangle's.

use serde::{Deserialize, Serialize};

use crate::mt::{MtQuery, MtResult};
use crate::precision::SpawnChoice;
use crate::Format;

/// Where a lane starts the ray of its Möller-Trumbore test.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Advance {
    /// At the query's origin: the hardware lanes.
    #[default]
    None,
    /// Where the ray enters the triangle's bounding box, if ahead of the origin
    /// ([`advanced`]); the model engine only.
    TriangleBox,
    /// Where the ray enters the BVH leaf holding the triangle, as the traversal unit's box
    /// test computed that entry ([`leaf_start`]); the traversal unit only (outside one there
    /// is no leaf, and the ray stays at its origin: t0 = 0).
    LeafBox,
}

impl Advance {
    pub const ALL: [Advance; 3] = [Advance::None, Advance::TriangleBox, Advance::LeafBox];

    pub fn name(self) -> &'static str {
        match self {
            Advance::None => "none",
            Advance::TriangleBox => "triangle-box",
            Advance::LeafBox => "leaf-box",
        }
    }

    /// The answer of the test `mt` to `q`, the ray started where `self` says (outside a
    /// leaf: [`Advance::run_in_leaf`] without a leaf entry).
    #[inline]
    pub fn run(self, q: &MtQuery, mt: impl FnOnce(&MtQuery) -> MtResult) -> MtResult {
        self.run_in_leaf(q, None, mt)
    }

    /// The answer of the test `mt` to `q` of a BVH leaf the box test entered at
    /// `leaf_entry` (if known), the ray started where `self` says.
    #[inline]
    pub fn run_in_leaf(
        self,
        q: &MtQuery,
        leaf_entry: Option<f32>,
        mt: impl FnOnce(&MtQuery) -> MtResult,
    ) -> MtResult {
        let t0 = match self {
            Advance::None => return mt(q),
            Advance::TriangleBox => triangle_box_entry(q),
            Advance::LeafBox => leaf_start(leaf_entry),
        };
        let r = mt(&moved(q, t0));
        MtResult {
            t: moved_back(r.t, t0),
            ..r
        }
    }
}

named_choice!(Advance, "origin advance");

/// `q` with its origin moved to `o + t0·d` and its `t_min` to `t_min − t0`, and t0 (fp32
/// bits): the largest slab entry `min((lo − o)/d, (hi − o)/d)` of the triangle's bounding box
/// over the axes where it is finite, and at least 0 (an origin inside the box stays). All in
/// fp32, as `(lo − o)·(1/d)`, the operations of the traversal unit's box test (without its
/// padded origins).
pub fn advanced(q: &MtQuery) -> (MtQuery, u64) {
    let t0 = triangle_box_entry(q);
    (moved(q, t0), t0)
}

/// t0 of [`advanced`]: the triangle's bounding box's entry, at least 0 (fp32 bits).
fn triangle_box_entry(q: &MtQuery) -> u64 {
    let f = Format::FP32;
    let finite = |x: u64| f.to_f32(x).is_finite();
    let min = |a: u64, b: u64| if f.lt(b, a) { b } else { a };
    let mut t0 = f.from_f32(0.0);
    for k in 0..3 {
        let (a, b, c) = (q.v0[k], q.v1[k], q.v2[k]);
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let o = f.from_f32(q.orig[k]);
        let inv = f.recip(f.from_f32(q.dir[k]));
        let slab = |x: f32| f.mul(f.sub(f.from_f32(x), o), inv);
        let entry = min(slab(lo), slab(hi));
        if finite(entry) && f.lt(t0, entry) {
            t0 = entry;
        }
    }
    t0
}

/// t0 of [`Advance::LeafBox`] (fp32 bits): the leaf box's entry as the box test computed it
/// (from the origin moved by its pad, so a little before the unpadded box), if it is finite
/// and positive, else 0 (no leaf known, an origin inside the box, or an entry distance that
/// overflowed: the ray stays where it is).
pub fn leaf_start(leaf_entry: Option<f32>) -> u64 {
    let f = Format::FP32;
    let zero = f.from_f32(0.0);
    match leaf_entry.map(|t| f.from_f32(t)) {
        Some(t) if f.to_f32(t).is_finite() && f.lt(zero, t) => t,
        _ => zero,
    }
}

/// `q` with its origin moved to `o + t0·d` and its `t_min` to `t_min − t0`, in fp32 (RNE,
/// subnormals flushed): the one move of every form of the advance, and what the traversal
/// unit's advance block computes.
pub fn moved(q: &MtQuery, t0: u64) -> MtQuery {
    let f = Format::FP32;
    let orig = std::array::from_fn(|k| {
        let (o, d) = (f.from_f32(q.orig[k]), f.from_f32(q.dir[k]));
        f.to_f32(f.add(o, f.mul(t0, d)))
    });
    let t_min = f.to_f32(f.sub(f.from_f32(q.t_min), t0));
    MtQuery { orig, t_min, ..*q }
}

/// The moved ray's `t` as the query's own: `t + t0` in fp32.
pub fn moved_back(t: f32, t0: u64) -> f32 {
    let f = Format::FP32;
    f.to_f32(f.add(f.from_f32(t), t0))
}

/// The advance a model render of one format gets unless one is asked for: triangle-box under
/// the format-aware policy (measured: it is what takes e5m14 past 40 dB, docs/precision.md),
/// none under the thesis policy (the thesis' lane, equal to the golden images in fp32). Other
/// engines and dual-precision pairs have the hardware's lane only ([`Advance::None`]). The CLI's
/// default and the sweep's lanes both come from here.
pub fn default_for(spawn: SpawnChoice) -> Advance {
    match spawn {
        SpawnChoice::FormatAware => Advance::TriangleBox,
        SpawnChoice::Thesis => Advance::None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn query(orig: [f32; 3], dir: [f32; 3]) -> MtQuery {
        MtQuery {
            orig,
            dir,
            v0: [1.0, 2.0, 10.0],
            v1: [3.0, 2.0, 10.0],
            v2: [1.0, 4.0, 12.0],
            t_min: 0.5,
        }
    }

    #[test]
    fn the_origin_moves_to_the_box_entry_and_not_backwards() {
        // Along +z from z = 0: the box spans z 10..12, entered at t = 10.
        let (moved, t0) = advanced(&query([2.0, 3.0, 0.0], [0.0, 0.0, 1.0]));
        assert_eq!(Format::FP32.to_f32(t0), 10.0);
        assert_eq!(moved.orig, [2.0, 3.0, 10.0]);
        assert_eq!(moved.t_min, -9.5);
        // From inside the box, or moving away from it: no move.
        for (o, d) in [
            ([2.0, 3.0, 11.0], [0.0, 0.0, 1.0]),
            ([2.0, 3.0, 0.0], [0.0, 0.0, -1.0]),
        ] {
            let (moved, t0) = advanced(&query(o, d));
            assert_eq!((moved.orig, Format::FP32.to_f32(t0)), (o, 0.0));
        }
    }

    #[test]
    fn the_distance_moved_is_added_back_to_t() {
        let q = query([2.0, 3.0, 0.0], [0.0, 0.0, 1.0]);
        let fp32 = Format::FP32;
        let r = Advance::TriangleBox.run(&q, |m| crate::mt_model(&fp32, m));
        let plain = crate::mt_model(&fp32, &q);
        assert!(r.hit && plain.hit);
        assert_eq!((r.t, r.u, r.v), (plain.t, plain.u, plain.v));
    }

    #[test]
    fn a_leaf_entry_moves_the_ray_only_when_finite_and_ahead() {
        let f = Format::FP32;
        for (entry, t0) in [
            (Some(10.0), 10.0),
            (Some(0.0), 0.0),
            (Some(-3.0), 0.0),
            (Some(f32::INFINITY), 0.0),
            (Some(f32::NAN), 0.0),
            (None, 0.0),
        ] {
            assert_eq!(f.to_f32(leaf_start(entry)), t0, "{entry:?}");
        }
        // The leaf's entry moves the ray as the triangle's box does: the same answer here,
        // where both boxes are entered at z = 10.
        let q = query([2.0, 3.0, 0.0], [0.0, 0.0, 1.0]);
        let fp16 = crate::lookup("fp16").unwrap();
        let test = |m: &MtQuery| crate::mt_model(&fp16, m);
        let leaf = Advance::LeafBox.run_in_leaf(&q, Some(10.0), test);
        let triangle = Advance::TriangleBox.run(&q, test);
        let bits = |r: &MtResult| (r.hit, r.t.to_bits(), r.u.to_bits(), r.v.to_bits());
        assert_eq!(bits(&leaf), bits(&triangle));
        assert!(leaf.hit);
        assert_eq!(leaf.t, 11.0); // (2, 3) lies on the triangle's plane at z = 11
    }
}
