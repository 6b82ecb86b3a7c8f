//! Reducing one ray's Möller-Trumbore results to what the reference's `trace` returned.
//!
//! The reference looped over objects, inside each over triangles, keeping a strictly nearer
//! hit (starting from `kInfinity = FLT_MAX`), then across objects kept a strictly nearer one
//! (starting from the ray's bound). Over a flat list in global order that is exactly: among
//! results with `hit && t < bound && t < FLT_MAX`, the smallest `(t, global index)`, in
//! whatever order the candidates come.

use crate::intersect::MtResult;

/// The reference's `kInfinity`: the bound of primary and secondary rays and of distant lights.
pub const NO_BOUND: f32 = f32::MAX;

/// The nearest intersection of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Global triangle index (see `world.rs`).
    pub triangle: u32,
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

#[inline]
fn counts(r: &MtResult, bound: f32) -> bool {
    r.hit && r.t < bound && r.t < NO_BOUND
}

/// The nearest counting hit among `candidates` (global triangle indices, any order) and their
/// `results`; ties go to the lower global index.
pub fn closest_hit(candidates: &[u32], results: &[MtResult], bound: f32) -> Option<Hit> {
    debug_assert_eq!(candidates.len(), results.len());
    candidates
        .iter()
        .zip(results)
        .filter(|(_, r)| counts(r, bound))
        .fold(None, |best, (&triangle, r)| {
            let hit = Hit {
                triangle,
                t: r.t,
                u: r.u,
                v: r.v,
            };
            nearer(best, Some(hit))
        })
}

/// The nearer of two hits (ties go to the lower global index): how closest hits over two
/// candidate sets combine into the closest hit over their union.
pub fn nearer(a: Option<Hit>, b: Option<Hit>) -> Option<Hit> {
    match (a, b) {
        (Some(x), Some(y)) => {
            let y_nearer = y.t < x.t || (y.t == x.t && y.triangle < x.triangle);
            Some(if y_nearer { y } else { x })
        }
        (x, None) => x,
        (None, y) => y,
    }
}

/// The bound for gathering the rest of a ray's candidates once `first` is its nearest hit so
/// far: hits exactly as near as `first` must still be found (the lower index wins a tie).
pub fn remaining_bound(first: Option<Hit>, bound: f32) -> f32 {
    first.map_or(bound, |h| h.t.next_up())
}

/// Whether any result blocks a shadow ray bounded by the light's distance.
pub fn occluded(results: &[MtResult], bound: f32) -> bool {
    results.iter().any(|r| counts(r, bound))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hit(t: f32) -> MtResult {
        MtResult {
            hit: true,
            t,
            u: 0.1,
            v: 0.2,
        }
    }

    #[test]
    fn nearest_wins_and_ties_go_to_the_lower_index_whatever_the_order() {
        let results = [
            hit(2.0),
            hit(1.0),
            hit(1.0),
            MtResult {
                hit: false,
                t: 0.5,
                u: 0.0,
                v: 0.0,
            },
        ];
        let h = closest_hit(&[7, 9, 3, 1], &results, NO_BOUND).unwrap();
        assert_eq!((h.triangle, h.t), (3, 1.0));
        let h = closest_hit(&[7, 3, 9, 1], &results, NO_BOUND).unwrap();
        assert_eq!((h.triangle, h.t), (3, 1.0));
    }

    #[test]
    fn closest_over_two_parts_equals_closest_over_the_whole() {
        let results = [hit(2.0), hit(1.0), hit(1.0), hit(3.0), hit(1.0)];
        let cands = [7, 9, 3, 12, 2];
        let whole = closest_hit(&cands, &results, NO_BOUND);
        for split in 0..=cands.len() {
            let a = closest_hit(&cands[..split], &results[..split], NO_BOUND);
            let b = closest_hit(&cands[split..], &results[split..], NO_BOUND);
            assert_eq!(nearer(a, b), whole);
            assert_eq!(nearer(b, a), whole);
        }
        let h = closest_hit(&[4], &[hit(1.0)], NO_BOUND);
        assert_eq!(remaining_bound(h, NO_BOUND), 1.0f32.next_up());
        assert_eq!(remaining_bound(None, 7.0), 7.0);
    }

    #[test]
    fn bound_and_flt_max_are_exclusive() {
        assert_eq!(closest_hit(&[0], &[hit(1.0)], 1.0), None);
        assert_eq!(closest_hit(&[0], &[hit(f32::MAX)], f32::INFINITY), None);
        assert!(!occluded(&[hit(3.0)], 3.0));
        assert!(occluded(&[hit(3.0)], 3.5));
        assert!(!occluded(&[hit(1.0)], f32::NAN));
    }
}
