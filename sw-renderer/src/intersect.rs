//! The seam: the only place the renderer asks whether rays hit triangles.
//!
//! The renderer hands an [`Intersector`] whole batches of Möller-Trumbore queries (one wavefront
//! of rays times their BVH candidates) so that a deep hardware pipeline stays full. The
//! software reference, [`mt_f32`], is the thesis' test in exactly its operation order; the
//! bit-accurate model and the Verilated hardware must reproduce it bit for bit in fp32.

use crate::rays::EngineError;

/// One ray-triangle test, IEEE fp32 as on the accelerator's bus.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MtQuery {
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    pub v0: [f32; 3],
    pub v1: [f32; 3],
    pub v2: [f32; 3],
    /// The ray's lower bound: a hit needs `t > t_min` (0: the reference's `t > 0`).
    pub t_min: f32,
}

impl MtQuery {
    /// A ray from `orig` towards the point at barycentric `(a, b)` of the triangle `verts`
    /// (`v0 + a·(v1 − v0) + b·(v2 − v0)`, so `t` = 1 there), hits beyond `t_min`: the test
    /// generators' common query.
    pub fn aimed(orig: [f32; 3], verts: [[f32; 3]; 3], (a, b): (f32, f32), t_min: f32) -> MtQuery {
        let [v0, v1, v2] = verts;
        MtQuery {
            orig,
            dir: std::array::from_fn(|k| {
                v0[k] + a * (v1[k] - v0[k]) + b * (v2[k] - v0[k]) - orig[k]
            }),
            v0,
            v1,
            v2,
            t_min,
        }
    }
}

/// The result of one test. `t`, `u`, `v` are whatever the datapath computed, also on a miss
/// (the hardware always computes them); only `hit` says whether they mean anything.
#[derive(Clone, Copy, Debug, Default)]
pub struct MtResult {
    pub hit: bool,
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

impl MtResult {
    /// Bit-for-bit equality (NaNs compare by their bits).
    pub fn same_bits(&self, other: &MtResult) -> bool {
        self.hit == other.hit
            && self.t.to_bits() == other.t.to_bits()
            && self.u.to_bits() == other.u.to_bits()
            && self.v.to_bits() == other.v.to_bits()
    }
}

/// Anything that answers batches of ray-triangle tests. Every intersector is also a
/// [`crate::rays::RayEngine`]: the software BVH gathers its queries.
pub trait Intersector: Send + Sync {
    /// A short name for reports, e.g. "f32", "model fp16", "hw fp32 d3 l4".
    fn name(&self) -> String;
    /// One Möller-Trumbore result per query, in order (results.len() == queries.len()); an
    /// error (a co-simulation failure) ends the render, it is never reported as misses.
    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError>;
}

impl<T: Intersector + ?Sized> Intersector for Box<T> {
    fn name(&self) -> String {
        (**self).name()
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        (**self).intersect_batch(queries, results)
    }
}

/// The reference's `kEpsilon`: determinants closer to zero than this are parallel rays.
pub const DET_EPSILON: f32 = 1e-8;

/// The reference Möller-Trumbore test in `f32`.
///
/// e1 = v1−v0, e2 = v2−v0, p = d×e2, det = e1·p, inv = 1/det, s = o−v0, u = (s·p)·inv,
/// q = s×e1, v = (d·q)·inv, t = (e2·q)·inv. The rejections are written as the C++
/// `if (fabs(det) < eps) …; if (u < 0 || u > 1) …; if (v < 0 || u + v > 1) …` so NaNs fall
/// through them exactly as there; a hit also needs `t > q.t_min` (the reference's `t > 0`
/// at `t_min = 0`). t, u, v are returned on a miss too.
#[inline]
pub fn mt_f32(q: &MtQuery) -> MtResult {
    let mut r = [MtResult::default()];
    mt_lanes::<1>(std::slice::from_ref(q), &mut r);
    r[0]
}

/// Queries per step of [`F32Intersector`]: eight lanes fill two SSE or one AVX register.
const LANES: usize = 8;

/// The software reference intersector: [`mt_f32`] on every query.
#[derive(Clone, Copy, Debug, Default)]
pub struct F32Intersector;

impl Intersector for F32Intersector {
    fn name(&self) -> String {
        "f32".to_string()
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        let mut q = queries.chunks_exact(LANES);
        let mut r = results.chunks_exact_mut(LANES);
        for (q, r) in (&mut q).zip(&mut r) {
            mt_lanes::<LANES>(q, r);
        }
        for (q, r) in q.remainder().iter().zip(r.into_remainder()) {
            *r = mt_f32(q);
        }
        Ok(())
    }
}

/// `N` independent 3-vectors, one per lane: written per component so that the compiler turns
/// every operation into one vector instruction. Each lane computes exactly what
/// [`crate::math::V3`] does.
#[derive(Clone, Copy)]
struct Lanes<const N: usize> {
    x: [f32; N],
    y: [f32; N],
    z: [f32; N],
}

#[inline(always)]
fn lanewise<const N: usize>(a: [f32; N], b: [f32; N], f: impl Fn(f32, f32) -> f32) -> [f32; N] {
    std::array::from_fn(|i| f(a[i], b[i]))
}

impl<const N: usize> Lanes<N> {
    #[inline(always)]
    fn load(queries: &[MtQuery], field: impl Fn(&MtQuery) -> &[f32; 3]) -> Lanes<N> {
        Lanes {
            x: std::array::from_fn(|i| field(&queries[i])[0]),
            y: std::array::from_fn(|i| field(&queries[i])[1]),
            z: std::array::from_fn(|i| field(&queries[i])[2]),
        }
    }

    #[inline(always)]
    fn sub(self, o: Lanes<N>) -> Lanes<N> {
        Lanes {
            x: lanewise(self.x, o.x, |a, b| a - b),
            y: lanewise(self.y, o.y, |a, b| a - b),
            z: lanewise(self.z, o.z, |a, b| a - b),
        }
    }

    /// As [`crate::math::V3::dot`]: `x·x' + y·y'` then `+ z·z'`.
    #[inline(always)]
    fn dot(self, o: Lanes<N>) -> [f32; N] {
        std::array::from_fn(|i| self.x[i] * o.x[i] + self.y[i] * o.y[i] + self.z[i] * o.z[i])
    }

    /// As [`crate::math::V3::cross`].
    #[inline(always)]
    fn cross(self, o: Lanes<N>) -> Lanes<N> {
        Lanes {
            x: std::array::from_fn(|i| self.y[i] * o.z[i] - self.z[i] * o.y[i]),
            y: std::array::from_fn(|i| self.z[i] * o.x[i] - self.x[i] * o.z[i]),
            z: std::array::from_fn(|i| self.x[i] * o.y[i] - self.y[i] * o.x[i]),
        }
    }
}

/// The Möller-Trumbore test of [`mt_f32`] on `N` queries at once (`queries.len() == N`).
#[inline(always)]
// The rejections stay in the C++ form on purpose: their NaN behaviour is the specification
// (non-short-circuit `&`/`|` evaluate the same comparisons, without branches).
#[allow(clippy::nonminimal_bool, clippy::manual_range_contains)]
fn mt_lanes<const N: usize>(queries: &[MtQuery], results: &mut [MtResult]) {
    let orig = Lanes::<N>::load(queries, |q| &q.orig);
    let dir = Lanes::<N>::load(queries, |q| &q.dir);
    let v0 = Lanes::<N>::load(queries, |q| &q.v0);
    let e1 = Lanes::<N>::load(queries, |q| &q.v1).sub(v0);
    let e2 = Lanes::<N>::load(queries, |q| &q.v2).sub(v0);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    let inv = det.map(|d| 1.0 / d);
    let s = orig.sub(v0);
    let u = lanewise(s.dot(p), inv, |a, b| a * b);
    let qv = s.cross(e1);
    let v = lanewise(dir.dot(qv), inv, |a, b| a * b);
    let t = lanewise(e2.dot(qv), inv, |a, b| a * b);
    let t_min: [f32; N] = std::array::from_fn(|i| queries[i].t_min);
    for (i, r) in results.iter_mut().enumerate().take(N) {
        let parallel = (det[i] < DET_EPSILON) & (det[i] > -DET_EPSILON);
        let hit = !parallel
            & !((u[i] < 0.0) | (u[i] > 1.0))
            & !((v[i] < 0.0) | (u[i] + v[i] > 1.0))
            & (t[i] > t_min[i]);
        *r = MtResult {
            hit,
            t: t[i],
            u: u[i],
            v: v[i],
        };
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
            t_min: 0.0,
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

    /// The test written with the renderer's `V3` arithmetic, query by query.
    #[allow(clippy::nonminimal_bool, clippy::manual_range_contains)]
    fn mt_v3(q: &MtQuery) -> MtResult {
        use crate::math::V3;
        let (orig, dir, v0) = (
            V3::from_array(q.orig),
            V3::from_array(q.dir),
            V3::from_array(q.v0),
        );
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
        let hit = !parallel && !(u < 0.0 || u > 1.0) && !(v < 0.0 || u + v > 1.0) && t > q.t_min;
        MtResult { hit, t, u, v }
    }

    #[test]
    fn lanes_equal_the_v3_arithmetic_bit_for_bit() {
        use rand::rngs::StdRng;
        use rand::{Rng, SeedableRng};
        let mut rng = StdRng::seed_from_u64(7);
        let mut p = |scale: f32| std::array::from_fn(|_| rng.gen_range(-scale..scale));
        // Random rays, every other one aimed inside its triangle; some degenerate (NaN, zero
        // direction, flat triangle).
        let mut queries: Vec<MtQuery> = (0..10_003)
            .map(|i| {
                let (orig, v0, v1, v2) = (p(3.0), p(1.0), p(1.0), p(1.0));
                let (a, b) = (p(0.5)[0].abs(), p(0.5)[0].abs());
                // Every third with a lower bound around the hit's t = 1.
                let t_min = if i % 3 == 0 { p(2.0)[0] } else { 0.0 };
                let q = MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min);
                if i % 2 == 0 {
                    q
                } else {
                    MtQuery { dir: p(1.0), ..q }
                }
            })
            .collect();
        queries[5].orig[0] = f32::NAN;
        queries[9].dir = [0.0; 3];
        queries[17].v2 = queries[17].v1;
        let mut got = vec![MtResult::default(); queries.len()];
        F32Intersector.intersect_batch(&queries, &mut got).unwrap();
        let bits = |r: &MtResult| (r.hit, r.t.to_bits(), r.u.to_bits(), r.v.to_bits());
        let mut hits = 0;
        for (q, g) in queries.iter().zip(&got) {
            let want = mt_v3(q);
            assert!(
                bits(g) == bits(&want) || (g.t.is_nan() && want.t.is_nan() && g.hit == want.hit),
                "{q:?}: {g:?} vs {want:?}"
            );
            assert_eq!(bits(&mt_f32(q)), bits(g));
            hits += usize::from(g.hit);
        }
        assert!(hits > 3000, "{hits} hits");
    }

    #[test]
    fn a_hit_needs_t_above_t_min() {
        let at = |t_min| {
            mt_f32(&MtQuery {
                t_min,
                ..query([0.25, 0.5, 2.0], [0.0, 0.0, -1.0])
            })
        };
        assert!(at(0.0).hit && at(1.999).hit && at(-1.0).hit && at(f32::NEG_INFINITY).hit);
        for t_min in [2.0, 3.0, f32::INFINITY, f32::NAN] {
            let r = at(t_min);
            assert!(!r.hit, "t_min {t_min}");
            assert_eq!((r.t, r.u, r.v), (2.0, 0.25, 0.5), "t, u, v still computed");
        }
    }

    #[test]
    fn aimed_queries_hit_their_point_at_t_1() {
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let r = mt_f32(&MtQuery::aimed([0.0, 0.0, 4.0], tri, (0.25, 0.5), 0.0));
        assert!(r.hit);
        assert_eq!((r.t, r.u, r.v), (1.0, 0.25, 0.5));
    }

    #[test]
    fn batch_answers_in_order() {
        let qs = [
            query([0.25, 0.25, 1.0], [0.0, 0.0, -1.0]),
            query([2.0, 2.0, 1.0], [0.0, 0.0, -1.0]),
        ];
        let mut rs = [MtResult::default(); 2];
        F32Intersector.intersect_batch(&qs, &mut rs).unwrap();
        assert!(rs[0].hit && !rs[1].hit);
    }
}
