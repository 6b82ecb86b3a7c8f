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
    /// ([`advanced`]); model-only so far.
    TriangleBox,
}

impl Advance {
    pub const ALL: [Advance; 2] = [Advance::None, Advance::TriangleBox];

    pub fn name(self) -> &'static str {
        match self {
            Advance::None => "none",
            Advance::TriangleBox => "triangle-box",
        }
    }

    /// The answer of the test `mt` to `q`, the ray started where `self` says.
    #[inline]
    pub fn run(self, q: &MtQuery, mt: impl FnOnce(&MtQuery) -> MtResult) -> MtResult {
        match self {
            Advance::None => mt(q),
            Advance::TriangleBox => {
                let (moved, t0) = advanced(q);
                let r = mt(&moved);
                let f = Format::FP32;
                MtResult {
                    t: f.to_f32(f.add(f.from_f32(r.t), t0)),
                    ..r
                }
            }
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
    let moved = std::array::from_fn(|k| {
        let (o, d) = (f.from_f32(q.orig[k]), f.from_f32(q.dir[k]));
        f.to_f32(f.add(o, f.mul(t0, d)))
    });
    let t_min = f.to_f32(f.sub(f.from_f32(q.t_min), t0));
    (
        MtQuery {
            orig: moved,
            t_min,
            ..*q
        },
        t0,
    )
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
}
