//! The work of one frame, counted from a real software render of the scene.
//!
//! The ray tree (primary, reflection, refraction and shadow rays) is the reference's: the
//! project's renderer reproduces the thesis images bit for bit, so it casts the same rays.
//! Only the number of ray-triangle tests depends on how candidates are found:
//! - the thesis' renderer had no acceleration structure: every ray was tested against every
//!   triangle, except that shadow rays skip reflection+refraction objects
//!   (the reference renderer's intersection loop); which object a ray hits does not change how
//!   many triangles it is tested against, so the count follows from the rays by kind;
//! - the project's renderer tests only the BVH's candidates (`TraceStats::mt_queries`).

use hw_model::traversal::TraversalEngine;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::{MaterialKind, Scene};

use super::ProjectionError;

/// How the renderer finds the triangles a ray is tested against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    /// Every triangle (shadow rays: every shadow-casting triangle), as the thesis did.
    BruteForce,
    /// The candidates of the project's BVH.
    Bvh,
}

/// Counts of one frame of one scene at one size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Workload {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub primary_rays: u64,
    pub reflection_rays: u64,
    pub refraction_rays: u64,
    pub shadow_rays: u64,
    /// All triangles of the scene.
    pub triangles: u64,
    /// Triangles of objects that are not reflection+refraction (what shadow rays test).
    pub shadow_casting_triangles: u64,
    /// Möller-Trumbore tests of the BVH render.
    pub bvh_tests: u64,
    /// Intersector batches of the BVH render (one per wavefront level per tile).
    pub batches: u64,
    /// The traversal unit's work on the same frame, where measured ([`Workload::with_unit`]).
    pub unit: Option<UnitWork>,
}

/// What the traversal unit does for a frame: its model's counters and its schedule model's
/// cycles (wavefront by wavefront, as the renderer sends them).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnitWork {
    pub box_tests: u64,
    pub node_visits: u64,
    pub mt_tests: u64,
    pub cycles: u64,
    /// Wavefronts (one per level of a tile's ray tree).
    pub wavefronts: u64,
    /// Passes: one per wavefront and chunk of the scene in the unit (one per wavefront while
    /// the whole scene is resident): DMA transfers each way.
    pub passes: u64,
    /// Rays sent into the unit, once per pass they take part in.
    pub ray_passes: u64,
    /// Bytes of the whole scene image.
    pub image_bytes: u64,
    /// Chunks loaded during the frame (0: the whole image is loaded once before it) …
    pub chunk_loads: u64,
    /// … and the bytes loaded into the unit's scene memory for the frame, either way.
    pub loaded_bytes: u64,
}

impl Workload {
    /// Renders `scene` at `width`×`height` with the f32 reference and counts its work.
    pub fn measure(scene: &Scene, width: u32, height: u32) -> Result<Workload, ProjectionError> {
        let opts = RenderOptions {
            width: Some(width),
            height: Some(height),
            ..Default::default()
        };
        let stats = render(scene, &F32Intersector, &opts)
            .map_err(|e| ProjectionError::Render(e.to_string()))?
            .stats
            .trace;
        let shadow_casting = scene
            .objects
            .iter()
            .filter(|o| o.material.kind != MaterialKind::ReflectionRefraction)
            .map(|o| o.mesh.triangles.len() as u64)
            .sum();
        Ok(Workload {
            scene: scene.name.clone(),
            width,
            height,
            primary_rays: stats.primary_rays,
            reflection_rays: stats.reflection_rays,
            refraction_rays: stats.refraction_rays,
            shadow_rays: stats.shadow_rays,
            triangles: scene.triangle_count() as u64,
            shadow_casting_triangles: shadow_casting,
            bvh_tests: stats.cast.mt_tests,
            batches: stats.cast.batches,
            unit: None,
        })
    }

    /// Adds the traversal unit's work: the same frame rendered through `engine` (whose
    /// `timing` must be set, for the cycles) in square tiles of `tile_size` pixels (a tile's
    /// level of rays is one wavefront).
    pub fn with_unit(
        mut self,
        scene: &Scene,
        engine: &TraversalEngine,
        tile_size: u32,
    ) -> Result<Workload, ProjectionError> {
        if engine.timing.is_none() {
            return Err(ProjectionError::Invalid(
                "the traversal unit's projection needs its timing (format with hardware)".into(),
            ));
        }
        let opts = RenderOptions {
            width: Some(self.width),
            height: Some(self.height),
            tile_size,
            ..Default::default()
        };
        let stats = render(scene, engine, &opts)
            .map_err(|e| ProjectionError::Render(e.to_string()))?
            .stats
            .trace;
        let prepared = sw_renderer::trace::PreparedScene::new(scene)
            .map_err(|e| ProjectionError::Scene(e.to_string()))?;
        let image_bytes =
            hw_model::traversal::scene_image::SceneImage::new(&prepared).bytes() as u64;
        let c = stats.cast;
        self.unit = Some(UnitWork {
            box_tests: c.box_tests,
            node_visits: c.node_visits,
            mt_tests: c.mt_tests,
            cycles: c.cycles,
            wavefronts: c.batches,
            passes: c.passes,
            ray_passes: c.ray_passes,
            image_bytes,
            chunk_loads: c.chunk_loads,
            loaded_bytes: match c.chunk_loads {
                0 => image_bytes,
                _ => c.loaded_bytes,
            },
        });
        Ok(self)
    }

    pub fn rays(&self) -> u64 {
        self.primary_rays + self.reflection_rays + self.refraction_rays + self.shadow_rays
    }

    /// Tests of the thesis' renderer: Σ over rays of the triangles it tests.
    pub fn brute_force_tests(&self) -> u64 {
        (self.primary_rays + self.reflection_rays + self.refraction_rays) * self.triangles
            + self.shadow_rays * self.shadow_casting_triangles
    }

    pub fn tests(&self, traversal: Traversal) -> u64 {
        match traversal {
            Traversal::BruteForce => self.brute_force_tests(),
            Traversal::Bvh => self.bvh_tests,
        }
    }
}
