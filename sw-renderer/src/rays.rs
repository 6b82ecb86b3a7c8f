//! The ray-level seam: rays in, closest hits (or occlusion) out.
//!
//! An engine that holds the scene answers rays, not ray-triangle pairs. [`RayEngine`] is
//! asked once per render to [`RayEngine::prepare`] a [`RayCaster`] for the prepared scene
//! (where a hardware unit loads its scene memory); the caster then answers one wavefront of
//! rays at a time. Two kinds of implementation:
//! - every [`Intersector`] is an engine: the software BVH gathers candidates and the
//!   intersector answers the Möller-Trumbore queries ([`BvhCaster`]);
//! - a traversal unit (its bit-accurate model, or the Verilated hardware) walks the BVH
//!   itself.
//!
//! All of them return the reference's hits: for a closest-hit ray the smallest
//! `(t, global triangle index)` among hits in its window (`t_min < t < bound`, not on the
//! triangle it excludes: `hit::Window`); for a shadow ray whether any shadow-casting triangle
//! is hit in its window. `t_min` and the exclusion only remove hits: BVH candidates and box
//! culling do not change. Calls are fallible: an engine error is an
//! error, never a silent miss.

use std::ops::{AddAssign, Range};

use crate::bvh::{BoxRay, Pending};
use crate::hit::{closest_hit, nearer, remaining_bound, Hit, Window};
use crate::intersect::{Intersector, MtQuery, MtResult};
use crate::math::V3;
use crate::trace::PreparedScene;

/// What an engine reports when it cannot answer (a co-simulation failure, a scene the
/// hardware cannot hold, a stack overflow): the render stops with it.
pub type EngineError = Box<dyn std::error::Error + Send + Sync + 'static>;

/// One ray of a wavefront.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub orig: V3,
    pub dir: V3,
    /// Hits count only below this distance (`hit::NO_BOUND`, or a light's distance).
    pub bound: f32,
    /// A shadow ray: any hit of a shadow-casting triangle answers it (any-hit); other rays
    /// want the closest hit of any triangle.
    pub shadow: bool,
    /// Hits count only beyond this distance (0 for the reference's rays).
    pub t_min: f32,
    /// The triangle (global index) a spawned ray leaves: it never counts.
    pub exclude: Option<u32>,
}

impl Ray {
    /// Which hits count.
    pub fn window(&self) -> Window {
        Window {
            t_min: self.t_min,
            bound: self.bound,
            exclude: self.exclude,
        }
    }
}

/// Work an engine did for a wavefront.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CastStats {
    /// Ray-triangle (Möller-Trumbore) tests.
    pub mt_tests: u64,
    /// Intersector batches (BVH engines) or wavefronts (traversal units).
    pub batches: u64,
    /// Box tests of a traversal unit (both children of an inner node, or the root box; 0
    /// where the software BVH walks).
    pub box_tests: u64,
    /// Inner nodes and leaves a traversal unit visited (0 where the software BVH walks).
    pub node_visits: u64,
    /// Clock cycles of a traversal unit (simulated or from its schedule model; 0 for
    /// software).
    pub cycles: u64,
    /// A traversal unit whose scene memory holds only part of the scene: passes (one per
    /// wavefront and loaded chunk; a resident scene makes one per wavefront) …
    pub passes: u64,
    /// … rays sent into the unit, once for every pass they take part in …
    pub ray_passes: u64,
    /// … chunks loaded into its scene memory and their bytes (0 while the whole scene stays
    /// resident).
    pub chunk_loads: u64,
    pub loaded_bytes: u64,
}

impl AddAssign for CastStats {
    fn add_assign(&mut self, o: CastStats) {
        self.mt_tests += o.mt_tests;
        self.batches += o.batches;
        self.box_tests += o.box_tests;
        self.node_visits += o.node_visits;
        self.cycles += o.cycles;
        self.passes += o.passes;
        self.ray_passes += o.ray_passes;
        self.chunk_loads += o.chunk_loads;
        self.loaded_bytes += o.loaded_bytes;
    }
}

/// Builds casters for prepared scenes.
pub trait RayEngine: Sync {
    /// A short name for reports, e.g. "f32", "model fp16", "traversal model fp32".
    fn name(&self) -> String;
    /// A caster for `scene`: where a hardware unit loads its scene memory (and refuses a
    /// scene it cannot hold).
    fn prepare<'a>(
        &'a self,
        scene: &'a PreparedScene,
    ) -> Result<Box<dyn RayCaster + 'a>, EngineError>;
}

/// Answers wavefronts of rays against one scene.
pub trait RayCaster: Sync {
    /// For every ray its answer in `hits` (`hits.len() == rays.len()`): the closest hit, or
    /// for a shadow ray some occluding hit (`None`: unoccluded).
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError>;
}

impl<I: Intersector> RayEngine for I {
    fn name(&self) -> String {
        Intersector::name(self)
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a PreparedScene,
    ) -> Result<Box<dyn RayCaster + 'a>, EngineError> {
        Ok(Box::new(BvhCaster { scene, isect: self }))
    }
}

/// Candidates the first pass gathers per ray (nearest leaves first): enough that it usually
/// holds the ray's hit, which then bounds the second pass.
const FIRST_PASS_CANDIDATES: usize = 8;

/// The software BVH gathering candidates for an [`Intersector`].
///
/// Each wavefront takes two intersector batches: the first with every ray's nearest leaves,
/// the second with the rest of its candidates, bounded by the first batch's nearest hit
/// (shadow rays already blocked are done). The union of both holds every triangle a single
/// unbounded gathering would have listed that can matter, so the hits are the same.
pub struct BvhCaster<'a, I: Intersector + ?Sized> {
    pub scene: &'a PreparedScene,
    pub isect: &'a I,
}

impl<I: Intersector + ?Sized> RayCaster for BvhCaster<'_, I> {
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError> {
        assert_eq!(rays.len(), hits.len(), "one answer per ray");
        let scene = self.scene;
        let mut stats = CastStats::default();
        let (mut first, mut rest) = (Batch::default(), Batch::default());
        let mut pending: Vec<Pending> = Vec::new();
        let mut pending_ranges: Vec<Range<usize>> = Vec::with_capacity(rays.len());
        for ray in rays {
            let start = pending.len();
            first.add_nearest(scene, ray, &mut pending);
            pending_ranges.push(start..pending.len());
        }
        first.run(self.isect, &mut stats)?;
        for (k, (ray, hit)) in rays.iter().zip(hits.iter_mut()).enumerate() {
            *hit = first.closest(k, &ray.window());
            if ray.shadow && hit.is_some() {
                rest.add_nothing();
            } else {
                let bound = remaining_bound(*hit, ray.bound);
                rest.add_rest(scene, ray, bound, &pending[pending_ranges[k].clone()]);
            }
        }
        rest.run(self.isect, &mut stats)?;
        for (k, (ray, hit)) in rays.iter().zip(hits.iter_mut()).enumerate() {
            *hit = nearer(*hit, rest.closest(k, &ray.window()));
        }
        Ok(stats)
    }
}

/// One intersector batch: per ray a range of candidate triangles and their queries.
#[derive(Default)]
struct Batch {
    candidates: Vec<u32>,
    ranges: Vec<Range<usize>>,
    queries: Vec<MtQuery>,
    results: Vec<MtResult>,
}

impl Batch {
    /// The ray's nearest leaves (the first pass); its unvisited subtrees go to `pending`.
    fn add_nearest(&mut self, scene: &PreparedScene, ray: &Ray, pending: &mut Vec<Pending>) {
        let start = self.candidates.len();
        scene.bvh.nearest_candidates(
            &BoxRay::new(ray.orig, ray.dir, ray.bound),
            |t| scene.tests(ray.shadow, t),
            FIRST_PASS_CANDIDATES,
            &mut self.candidates,
            pending,
        );
        self.add_queries(scene, ray, start);
    }

    /// The ray's other candidates up to `bound`, from the first pass' `pending` subtrees.
    fn add_rest(&mut self, scene: &PreparedScene, ray: &Ray, bound: f32, pending: &[Pending]) {
        let start = self.candidates.len();
        scene.bvh.remaining_candidates(
            &BoxRay::new(ray.orig, ray.dir, bound),
            |t| scene.tests(ray.shadow, t),
            pending,
            &mut self.candidates,
        );
        self.add_queries(scene, ray, start);
    }

    fn add_nothing(&mut self) {
        let end = self.candidates.len();
        self.ranges.push(end..end);
    }

    /// Queries for the candidates from `start` on, as the ray's range.
    fn add_queries(&mut self, scene: &PreparedScene, ray: &Ray, start: usize) {
        let (o, d) = (ray.orig.to_array(), ray.dir.to_array());
        self.queries
            .extend(self.candidates[start..].iter().map(|&t| {
                let [v0, v1, v2] = scene.world.triangles[t as usize].verts;
                MtQuery {
                    orig: o,
                    dir: d,
                    v0: v0.to_array(),
                    v1: v1.to_array(),
                    v2: v2.to_array(),
                    // The lanes apply the lower bound too; the window check below stays
                    // (the f32 reference needs it, and it is exact).
                    t_min: ray.t_min,
                }
            }));
        self.ranges.push(start..self.candidates.len());
    }

    fn run<I: Intersector + ?Sized>(
        &mut self,
        isect: &I,
        stats: &mut CastStats,
    ) -> Result<(), EngineError> {
        if self.queries.is_empty() {
            return Ok(());
        }
        self.results.resize(self.queries.len(), MtResult::default());
        isect.intersect_batch(&self.queries, &mut self.results)?;
        stats.batches += 1;
        stats.mt_tests += self.queries.len() as u64;
        Ok(())
    }

    /// The nearest counting hit of ray `k` in this batch.
    fn closest(&self, k: usize, window: &Window) -> Option<Hit> {
        let r = self.ranges[k].clone();
        closest_hit(&self.candidates[r.clone()], &self.results[r], window)
    }
}
