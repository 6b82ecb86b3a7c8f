//! The traversal unit's model as the renderer's ray engine.

use sw_renderer::hit::Hit;
use sw_renderer::rays::{CastStats, EngineError, Ray, RayCaster, RayEngine};
use sw_renderer::scene_image::SceneImage;
use sw_renderer::trace::PreparedScene;

use super::capacity::{Carry, ChunkedModel, SceneMemory};
use super::schedule::{schedule, UnitTiming};
use super::{Step, UnitCounters, UnitRay};
use crate::catalogue::catalogue;
use crate::format::Format;

/// Renders through [`TraversalModel`](super::TraversalModel): the scene image is written
/// from the renderer's BVH, split for the unit's scene `memory` (`capacity`: whole if it
/// fits, else chunks, else an error naming the sizes), each part loaded through its word
/// stream (so the loader's checks run), and every wavefront's rays are answered by the model,
/// pass by pass, its Möller-Trumbore queries scaled by 2^`scale_exp`; with `timing`, each
/// pass is also timed by the schedule model (`CastStats::cycles`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraversalEngine {
    pub format: Format,
    pub stack_depth: usize,
    pub scale_exp: i32,
    pub timing: Option<UnitTiming>,
    pub memory: SceneMemory,
}

impl RayEngine for TraversalEngine {
    /// "traversal model fp32" (the catalogue name where there is one).
    fn name(&self) -> String {
        let label = catalogue()
            .iter()
            .find(|n| n.format == self.format)
            .map_or_else(|| self.format.to_string(), |n| n.name.to_string());
        format!("traversal model {label}")
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a PreparedScene,
    ) -> Result<Box<dyn RayCaster + 'a>, EngineError> {
        let image = SceneImage::from_words(&SceneImage::new(scene).to_words())?;
        Ok(Box::new(Caster {
            model: ChunkedModel::new(
                self.format,
                self.stack_depth,
                self.scale_exp,
                &image,
                self.memory,
            )?,
            timing: self.timing,
        }))
    }
}

struct Caster {
    model: ChunkedModel,
    timing: Option<UnitTiming>,
}

impl RayCaster for Caster {
    /// One pass per chunk, each with the rays that still need it. A resident scene (one
    /// chunk) stays loaded; chunks are loaded again for every wavefront.
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError> {
        assert_eq!(rays.len(), hits.len(), "one answer per ray");
        let unit_rays: Vec<UnitRay> = (rays.iter().enumerate())
            .map(|(id, ray)| UnitRay {
                orig: ray.orig.to_array(),
                dir: ray.dir.to_array(),
                t_max: ray.bound,
                t_min: ray.t_min,
                exclude: ray.exclude,
                any_hit: ray.shadow,
                id: id as u32,
            })
            .collect();
        let mut carry = vec![Carry::default(); rays.len()];
        let mut counters = UnitCounters::default();
        let mut stats = CastStats {
            batches: 1,
            ..CastStats::default()
        };
        let chunks = self.model.chunks();
        for (k, chunk) in chunks.iter().enumerate() {
            if !carry.iter().any(Carry::pending) {
                break;
            }
            stats.passes += 1;
            if chunks.len() > 1 {
                stats.chunk_loads += 1;
                stats.loaded_bytes += chunk.image().bytes() as u64;
            }
            let mut walks = Vec::new();
            for (ray, carry) in unit_rays.iter().zip(carry.iter_mut()) {
                let mut walk = Vec::new();
                let record = &mut |s: Step| {
                    if self.timing.is_some() {
                        walk.push(s)
                    }
                };
                if self.model.pass(k, ray, carry, &mut counters, record)? && self.timing.is_some() {
                    walks.push(walk);
                }
            }
            if let Some(t) = &self.timing {
                stats.cycles += schedule(t, &walks).cycles;
            }
        }
        for (hit, carry) in hits.iter_mut().zip(&carry) {
            *hit = carry.answer();
        }
        stats.mt_tests = counters.mt_tests;
        stats.box_tests = counters.box_tests;
        stats.node_visits = counters.node_visits;
        stats.ray_passes = counters.rays;
        Ok(stats)
    }
}
