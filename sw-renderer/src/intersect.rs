//! The seam: the only place the renderer asks whether rays hit triangles.
//!
//! The renderer hands an [`Intersector`] whole batches of Möller-Trumbore queries (one wavefront
//! of rays times their BVH candidates) so that a deep hardware pipeline stays full. The
//! software reference, [`mt_f32`], is the thesis' test in exactly its operation order; the
//! bit-accurate model and the Verilated hardware must reproduce it bit for bit in fp32.

pub use hw_model::mt::{MtQuery, MtResult};

use crate::math::V3;

/// Anything that answers batches of ray-triangle tests.
pub trait Intersector: Send + Sync {
    /// A short name for reports, e.g. "f32", "model fp16", "hw fp32 d3 l4".
    fn name(&self) -> String;
    /// One Möller-Trumbore result per query, in order (results.len() == queries.len()).
    fn intersect_batch(&self, queries: &[MtQuery], results: &mut [MtResult]);
}

/// The reference's `kEpsilon`: determinants closer to zero than this are parallel rays.
pub const DET_EPSILON: f32 = 1e-8;

/// The reference Möller-Trumbore test in `f32`.
///
/// e1 = v1−v0, e2 = v2−v0, p = d×e2, det = e1·p, inv = 1/det, s = o−v0, u = (s·p)·inv,
/// q = s×e1, v = (d·q)·inv, t = (e2·q)·inv. The rejections are written as the C++
/// `if (fabs(det) < eps) …; if (u < 0 || u > 1) …; if (v < 0 || u + v > 1) …` so NaNs fall
/// through them exactly as there; a hit also needs t > 0. t, u, v are returned on a miss too.
#[inline]
// The rejections stay in the C++ form on purpose: their NaN behaviour is the specification.
#[allow(clippy::nonminimal_bool, clippy::manual_range_contains)]
pub fn mt_f32(q: &MtQuery) -> MtResult {
    let orig = V3::from_array(q.orig);
    let dir = V3::from_array(q.dir);
    let v0 = V3::from_array(q.v0);
    let e1 = V3::from_array(q.v1) - v0;
    let e2 = V3::from_array(q.v2) - v0;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    let inv = 1.0 / det;
    let s = orig - v0;
    let u = s.dot(p) * inv;
    let qv = s.cross(e1);
    let v = dir.dot(qv) * inv;
    let t = e2.dot(qv) * inv;
    let parallel = det < DET_EPSILON && det > -DET_EPSILON;
    let hit = !parallel && !(u < 0.0 || u > 1.0) && !(v < 0.0 || u + v > 1.0) && t > 0.0;
    MtResult { hit, t, u, v }
}

/// The software reference intersector: [`mt_f32`] on every query.
#[derive(Clone, Copy, Debug, Default)]
pub struct F32Intersector;

impl Intersector for F32Intersector {
    fn name(&self) -> String {
        "f32".to_string()
    }

    fn intersect_batch(&self, queries: &[MtQuery], results: &mut [MtResult]) {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        for (q, r) in queries.iter().zip(results.iter_mut()) {
            *r = mt_f32(q);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn query(orig: [f32; 3], dir: [f32; 3]) -> MtQuery {
        MtQuery {
            orig,
            dir,
            v0: [0.0, 0.0, 0.0],
            v1: [1.0, 0.0, 0.0],
            v2: [0.0, 1.0, 0.0],
        }
    }

    #[test]
    fn hits_inside_with_expected_t_u_v() {
        let r = mt_f32(&query([0.25, 0.5, 2.0], [0.0, 0.0, -1.0]));
        assert!(r.hit);
        assert_eq!((r.t, r.u, r.v), (2.0, 0.25, 0.5));
    }

    #[test]
    fn misses_outside_behind_and_parallel_but_still_reports_t_u_v() {
        let outside = mt_f32(&query([0.75, 0.5, 2.0], [0.0, 0.0, -1.0]));
        assert!(!outside.hit);
        assert_eq!((outside.u, outside.v), (0.75, 0.5));
        let behind = mt_f32(&query([0.25, 0.25, -2.0], [0.0, 0.0, -1.0]));
        assert!(!behind.hit);
        assert_eq!(behind.t, -2.0);
        let parallel = mt_f32(&query([0.25, 0.25, 1.0], [1.0, 0.0, 0.0]));
        assert!(!parallel.hit);
    }

    #[test]
    fn both_windings_hit_no_culling() {
        let mut q = query([0.25, 0.25, 1.0], [0.0, 0.0, -1.0]);
        std::mem::swap(&mut q.v1, &mut q.v2);
        let r = mt_f32(&q);
        assert!(r.hit);
        assert_eq!(r.t, 1.0);
    }

    #[test]
    fn nan_inputs_fall_through_the_barycentric_rejections_but_t_test_rejects() {
        // A NaN origin makes u, v, t NaN: the u/v rejections do not fire, t > 0 is false.
        let r = mt_f32(&query([f32::NAN, 0.25, 1.0], [0.0, 0.0, -1.0]));
        assert!(r.u.is_nan() && !r.hit);
    }

    #[test]
    fn batch_answers_in_order() {
        let qs = [
            query([0.25, 0.25, 1.0], [0.0, 0.0, -1.0]),
            query([2.0, 2.0, 1.0], [0.0, 0.0, -1.0]),
        ];
        let mut rs = [MtResult::default(); 2];
        F32Intersector.intersect_batch(&qs, &mut rs);
        assert!(rs[0].hit && !rs[1].hit);
    }
}
