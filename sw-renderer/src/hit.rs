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
    let mut best: Option<Hit> = None;
    for (&triangle, r) in candidates.iter().zip(results) {
        if !counts(r, bound) {
            continue;
        }
        let better = match best {
            None => true,
            Some(b) => r.t < b.t || (r.t == b.t && triangle < b.triangle),
        };
        if better {
            best = Some(Hit {
                triangle,
                t: r.t,
                u: r.u,
                v: r.v,
            });
        }
    }
    best
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
    fn bound_and_flt_max_are_exclusive() {
        assert_eq!(closest_hit(&[0], &[hit(1.0)], 1.0), None);
        assert_eq!(closest_hit(&[0], &[hit(f32::MAX)], f32::INFINITY), None);
        assert!(!occluded(&[hit(3.0)], 3.0));
        assert!(occluded(&[hit(3.0)], 3.5));
        assert!(!occluded(&[hit(1.0)], f32::NAN));
    }
}
