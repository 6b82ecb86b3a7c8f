//! The traversal unit's model as the renderer's ray engine.

use sw_renderer::hit::Hit;
use sw_renderer::rays::{CastStats, EngineError, Ray, RayCaster, RayEngine};
use sw_renderer::scene_image::SceneImage;
use sw_renderer::trace::PreparedScene;

use super::schedule::{schedule, UnitTiming};
use super::{Step, TraversalModel, UnitCounters, UnitRay};
use crate::catalogue::catalogue;
use crate::format::Format;

/// Renders through [`TraversalModel`]: the scene image is written from the renderer's BVH,
/// loaded through its word stream (so the loader's checks run), and every wavefront's rays
/// are answered by the model, its Möller-Trumbore queries scaled by 2^`scale_exp`; with
/// `timing`, each wavefront is also timed by the schedule model (`CastStats::cycles`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraversalEngine {
    pub format: Format,
    pub stack_depth: usize,
    pub scale_exp: i32,
    pub timing: Option<UnitTiming>,
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
            model: TraversalModel::new(self.format, self.stack_depth, image).scaled(self.scale_exp),
            timing: self.timing,
        }))
    }
}

struct Caster {
    model: TraversalModel,
    timing: Option<UnitTiming>,
}

impl RayCaster for Caster {
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError> {
        assert_eq!(rays.len(), hits.len(), "one answer per ray");
        let mut counters = UnitCounters::default();
        let mut walks: Vec<Vec<Step>> = Vec::new();
        for (id, (ray, hit)) in rays.iter().zip(hits.iter_mut()).enumerate() {
            let unit_ray = UnitRay {
                orig: ray.orig.to_array(),
                dir: ray.dir.to_array(),
                t_max: ray.bound,
                t_min: ray.t_min,
                exclude: ray.exclude,
                any_hit: ray.shadow,
                id: id as u32,
            };
            *hit = match self.timing {
                None => self.model.trace(&unit_ray, &mut counters)?,
                Some(_) => {
                    let mut walk = Vec::new();
                    let hit = self
                        .model
                        .walk(&unit_ray, &mut counters, &mut |s| walk.push(s))?;
                    walks.push(walk);
                    hit
                }
            };
        }
        Ok(CastStats {
            mt_tests: counters.mt_tests,
            batches: 1,
            box_tests: counters.box_tests,
            node_visits: counters.node_visits,
            cycles: self.timing.map_or(0, |t| schedule(&t, &walks).cycles),
        })
    }
}
