//! Reducing one ray's Möller-Trumbore results to what the reference's `trace` returned.
//!
//! The reference looped over objects, inside each over triangles, keeping a strictly nearer
//! hit (starting from `kInfinity = FLT_MAX`), then across objects kept a strictly nearer one
//! (starting from the ray's bound). Over a flat list in global order that is exactly: among
//! results with `hit && t < bound && t < FLT_MAX`, the smallest `(t, global index)`, in
//! whatever order the candidates come. A spawned ray may also ignore hits at `t ≤ t_min` and
//! the triangle it leaves ([`Window`]); the reference's rays have `t_min = 0` (a hit already
//! needs `t > 0`) and exclude nothing.

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

/// Which of a ray's Möller-Trumbore hits count: `t_min < t < bound` (and `t < FLT_MAX`), on
/// any triangle but `exclude`. Filtering the results is exact: the intersectors return `t`
/// for every query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    pub t_min: f32,
    pub bound: f32,
    /// Global index of the triangle the ray leaves.
    pub exclude: Option<u32>,
}

impl Window {
    /// The reference's window: every hit below `bound`.
    pub fn below(bound: f32) -> Window {
        Window {
            t_min: 0.0,
            bound,
            exclude: None,
        }
    }

    #[inline]
    pub fn counts(&self, triangle: u32, r: &MtResult) -> bool {
        r.hit
            && self.t_min < r.t
            && r.t < self.bound
            && r.t < NO_BOUND
            && self.exclude != Some(triangle)
    }
}

/// The nearest counting hit among `candidates` (global triangle indices, any order) and their
/// `results`; ties go to the lower global index.
pub fn closest_hit(candidates: &[u32], results: &[MtResult], window: &Window) -> Option<Hit> {
    debug_assert_eq!(candidates.len(), results.len());
    candidates
        .iter()
        .zip(results)
        .filter(|(&triangle, r)| window.counts(triangle, r))
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

/// Whether any result blocks a shadow ray (its window bounded by the light's distance).
pub fn occluded(candidates: &[u32], results: &[MtResult], window: &Window) -> bool {
    debug_assert_eq!(candidates.len(), results.len());
    candidates
        .iter()
        .zip(results)
        .any(|(&triangle, r)| window.counts(triangle, r))
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
        let all = Window::below(NO_BOUND);
        let h = closest_hit(&[7, 9, 3, 1], &results, &all).unwrap();
        assert_eq!((h.triangle, h.t), (3, 1.0));
        let h = closest_hit(&[7, 3, 9, 1], &results, &all).unwrap();
        assert_eq!((h.triangle, h.t), (3, 1.0));
    }

    #[test]
    fn closest_over_two_parts_equals_closest_over_the_whole() {
        let results = [hit(2.0), hit(1.0), hit(1.0), hit(3.0), hit(1.0)];
        let cands = [7, 9, 3, 12, 2];
        let all = Window::below(NO_BOUND);
        let whole = closest_hit(&cands, &results, &all);
        for split in 0..=cands.len() {
            let a = closest_hit(&cands[..split], &results[..split], &all);
            let b = closest_hit(&cands[split..], &results[split..], &all);
            assert_eq!(nearer(a, b), whole);
            assert_eq!(nearer(b, a), whole);
        }
        let h = closest_hit(&[4], &[hit(1.0)], &all);
        assert_eq!(remaining_bound(h, NO_BOUND), 1.0f32.next_up());
        assert_eq!(remaining_bound(None, 7.0), 7.0);
    }

    #[test]
    fn bound_and_flt_max_are_exclusive() {
        assert_eq!(closest_hit(&[0], &[hit(1.0)], &Window::below(1.0)), None);
        let unbounded = Window::below(f32::INFINITY);
        assert_eq!(closest_hit(&[0], &[hit(f32::MAX)], &unbounded), None);
        assert!(!occluded(&[0], &[hit(3.0)], &Window::below(3.0)));
        assert!(occluded(&[0], &[hit(3.0)], &Window::below(3.5)));
        assert!(!occluded(&[0], &[hit(1.0)], &Window::below(f32::NAN)));
    }

    #[test]
    fn hits_at_or_below_t_min_and_on_the_excluded_triangle_do_not_count() {
        let results = [hit(0.5), hit(1.0), hit(2.0)];
        let window = |t_min, exclude| Window {
            t_min,
            bound: NO_BOUND,
            exclude,
        };
        let nearest = |w: Window| closest_hit(&[4, 5, 6], &results, &w).map(|h| h.triangle);
        assert_eq!(nearest(window(0.0, None)), Some(4));
        assert_eq!(nearest(window(0.5, None)), Some(5), "t = t_min is a miss");
        assert_eq!(nearest(window(0.4, Some(4))), Some(5));
        assert_eq!(nearest(window(1.5, Some(6))), None);
        assert!(!occluded(&[6], &[hit(2.0)], &window(0.0, Some(6))));
        assert!(!occluded(&[6], &[hit(2.0)], &window(2.0, None)));
        assert!(occluded(&[6], &[hit(2.0)], &window(1.999, Some(5))));
    }
}
