//! The traversal unit's model as the renderer's ray engine.

use super::scene_image::SceneImage;
use sw_renderer::hit::Hit;
use sw_renderer::rays::{CastStats, EngineError, Ray, RayCaster, RayEngine};
use sw_renderer::trace::PreparedScene;

use super::capacity::{run_passes, ChunkedModel, SceneMemory};
use super::schedule::{schedule, UnitTiming};
use super::{NodeFormat, Step, TraversalError, UnitCounters, UnitRay};
use crate::catalogue::catalogue;
use crate::format::Format;
use crate::Advance;

/// Renders through [`TraversalModel`](super::TraversalModel): the scene image is written
/// from the renderer's BVH, split for the unit's scene `memory` (`capacity`: whole if it
/// fits, else chunks, else an error naming the sizes), each part loaded through its word
/// stream (so the loader's checks run), and every wavefront's rays are answered by the model,
/// pass by pass, its Möller-Trumbore queries scaled by 2^`scale_exp` and started where
/// `advance` says ([`TraversalModel::advanced`](super::TraversalModel::advanced)); with `timing`, each
/// pass is also timed by the schedule model (`CastStats::cycles`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraversalEngine {
    pub format: Format,
    pub stack_depth: usize,
    pub scale_exp: i32,
    pub advance: Advance,
    pub timing: Option<UnitTiming>,
    pub memory: SceneMemory,
    /// How the scene memory stores the tree's inner nodes.
    pub nodes: NodeFormat,
}

impl TraversalEngine {
    /// The unit's model in `format` as the frame unit's tests and tools take it: the default
    /// stack, unscaled queries, no advance, untimed, the whole scene resident (chunking changes
    /// no answer), binary fp32 nodes.
    pub fn resident(format: Format) -> TraversalEngine {
        TraversalEngine {
            format,
            stack_depth: super::DEFAULT_STACK_DEPTH,
            scale_exp: 0,
            advance: Advance::None,
            timing: None,
            memory: SceneMemory::Unbounded,
            nodes: NodeFormat::Bvh2Fp32,
        }
    }
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
        if let Some(t) = &self.timing {
            t.check()?;
        }
        let image = SceneImage::from_words(&SceneImage::new(scene).to_words())?;
        Ok(Box::new(Caster {
            model: ChunkedModel::new(
                self.format,
                self.stack_depth,
                self.scale_exp,
                &image,
                self.memory,
                self.nodes,
            )?
            .advanced(self.advance),
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
        let unit_rays: Vec<UnitRay> = (rays.iter().enumerate())
            .map(|(id, ray)| UnitRay::of(ray, id as u32))
            .collect();
        let chunks = self.model.chunks();
        let mut counters = UnitCounters::default();
        let mut cycles = 0;
        let mut stats = run_passes(
            &self.model.chunk_bytes(),
            &unit_rays,
            hits,
            |k, rays, answers| {
                let mut walks = Vec::new();
                for (ray, answer) in rays.iter().zip(answers) {
                    let mut walk = Vec::new();
                    let record = &mut |s: Step| {
                        if self.timing.is_some() {
                            walk.push(s)
                        }
                    };
                    *answer = chunks[k].walk(ray, &mut counters, record)?;
                    if self.timing.is_some() {
                        walks.push(walk);
                    }
                }
                if let Some(t) = &self.timing {
                    cycles += schedule(t, &walks).cycles;
                }
                Ok::<_, TraversalError>(())
            },
        )?;
        stats.batches = 1;
        stats.cycles = cycles;
        stats.mt_tests = counters.mt_tests;
        stats.box_tests = counters.box_tests;
        stats.node_visits = counters.node_visits;
        stats.ray_passes = counters.rays;
        Ok(stats)
    }
}
