//! Running a frame: the primary rays of every pixel, the traversal unit's model answering
//! them in batches, shading, accumulation, until every pixel's last ray has returned.
//!
//! The image is split into tiles, each run on its own (in parallel): a tile's rays form a
//! queue; [`RayOrder`] picks the next batch from it, the traversal unit answers the batch,
//! each answer is shaded by the scene's compiled shading programs (as the shader core does,
//! [`super::shader`]; a shadow ray beside it), its settle record applied to its pixel and
//! its spawned rays queued. Pixels are independent and their sums order-independent, so the
//! image depends neither on the tile size nor on the order: the hardware, answering rays out
//! of order, gives the same bits.

use std::ops::AddAssign;

use image::RgbImage;
use rayon::prelude::*;
use sw_renderer::hit::Hit;
use sw_renderer::math::V3;
use sw_renderer::rays::{CastStats, Ray, RayCaster, RayEngine};
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use super::accumulate::Accumulator;
use super::constants::FrameConstants;
use super::shade::{FrameRay, RayKind, Shaded};
use super::shader::{compile, thread, Program, ProgramKind};
use super::{FrameError, FrameLimits};

/// How the next batch is taken from a tile's queue of rays: given a seed (the tile and the
/// step) it may reorder the queue and returns how many rays from its front go to the
/// traversal unit next (at least 1 is taken).
pub type RayOrder<'o> = &'o (dyn Fn(u64, &mut [FrameRay]) -> usize + Sync);

/// The whole queue as one batch, in order: a wavefront per ray-tree level.
pub const WAVEFRONT: RayOrder<'static> = &|_, queue| queue.len();

/// What a frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    pub primary_rays: u64,
    pub reflection_rays: u64,
    pub refraction_rays: u64,
    pub shadow_rays: u64,
    /// Primary, reflection and refraction rays that hit.
    pub hits: u64,
    /// Shadow rays an occluder stopped.
    pub occluded: u64,
    /// Shadow rays not spawned because their contribution was zero.
    pub zero_shadows: u64,
    /// Reflection and refraction rays past the maximum depth (background, not traced).
    pub past_depth: u64,
    /// Glass hits with total internal reflection (no refraction ray).
    pub total_internal: u64,
    /// The shader core's threads by program kind (`ProgramKind::ALL`'s order).
    pub threads: [ShaderLoad; ProgramKind::ALL.len()],
    /// What the traversal unit's model did.
    pub cast: CastStats,
}

impl FrameStats {
    pub fn rays(&self) -> u64 {
        self.primary_rays + self.reflection_rays + self.refraction_rays + self.shadow_rays
    }

    /// Contributions added to pixels: a miss's, an unoccluded shadow ray's, a ray past the
    /// depth's background.
    pub fn contributions(&self) -> u64 {
        let cast = self.rays() - self.shadow_rays;
        (cast - self.hits) + (self.shadow_rays - self.occluded) + self.past_depth
    }

    /// The threads of programs of `kind`.
    pub fn shader(&self, kind: ProgramKind) -> ShaderLoad {
        self.threads[kind.index()]
    }

    pub fn of_kind(&self, kind: RayKind) -> u64 {
        match kind {
            RayKind::Primary => self.primary_rays,
            RayKind::Reflection => self.reflection_rays,
            RayKind::Refraction => self.refraction_rays,
            RayKind::Shadow => self.shadow_rays,
        }
    }

    fn count(&mut self, kind: RayKind) {
        *match kind {
            RayKind::Primary => &mut self.primary_rays,
            RayKind::Reflection => &mut self.reflection_rays,
            RayKind::Refraction => &mut self.refraction_rays,
            RayKind::Shadow => &mut self.shadow_rays,
        } += 1;
    }
}

impl AddAssign for FrameStats {
    fn add_assign(&mut self, o: FrameStats) {
        self.primary_rays += o.primary_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.shadow_rays += o.shadow_rays;
        self.hits += o.hits;
        self.occluded += o.occluded;
        self.zero_shadows += o.zero_shadows;
        self.past_depth += o.past_depth;
        self.total_internal += o.total_internal;
        for (a, b) in self.threads.iter_mut().zip(o.threads) {
            *a += b;
        }
        self.cast += o.cast;
    }
}

/// Threads of one kind of shading program and the instructions they issued (the shader core
/// issues one a cycle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShaderLoad {
    pub threads: u64,
    pub instructions: u64,
}

impl AddAssign for ShaderLoad {
    fn add_assign(&mut self, o: ShaderLoad) {
        self.threads += o.threads;
        self.instructions += o.instructions;
    }
}

#[derive(Clone, Debug)]
pub struct FrameOutput {
    pub image: RgbImage,
    pub stats: FrameStats,
}

/// A rectangle of pixels.
#[derive(Clone, Copy, Debug)]
struct Tile {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
}

impl Tile {
    fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    fn pixels(&self) -> usize {
        (self.width() * (self.y1 - self.y0)) as usize
    }
}

/// The frame unit with a scene loaded: its constants, its shading programs and its traversal
/// unit.
pub struct Frame<'a> {
    constants: FrameConstants,
    program: Program,
    caster: Box<dyn RayCaster + 'a>,
    scene: String,
}

impl<'a> Frame<'a> {
    /// `scene` (prepared as `prepared`) loaded for a `width`×`height` frame checked against
    /// `limits`, its rays answered by `traversal` (the traversal unit's model; it loads the
    /// scene image from `prepared`).
    pub fn new(
        scene: &Scene,
        prepared: &'a PreparedScene,
        traversal: &'a dyn RayEngine,
        width: u32,
        height: u32,
        limits: &FrameLimits,
    ) -> Result<Frame<'a>, FrameError> {
        let constants = FrameConstants::load(scene, prepared, width, height, limits)?;
        let program = compile(&constants).map_err(|source| FrameError::Compile {
            scene: scene.name.clone(),
            source,
        })?;
        let caster = traversal
            .prepare(prepared)
            .map_err(|source| FrameError::Traversal {
                scene: scene.name.clone(),
                source,
            })?;
        Ok(Frame {
            constants,
            program,
            caster,
            scene: scene.name.clone(),
        })
    }

    pub fn constants(&self) -> &FrameConstants {
        &self.constants
    }

    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The number of tiles of edge `tile_size` (≥ 1) [`Frame::render`] runs.
    pub fn tile_count(&self, tile_size: u32) -> usize {
        self.tiles(tile_size).len()
    }

    fn tiles(&self, size: u32) -> Vec<Tile> {
        let (w, h) = (self.constants.width, self.constants.height);
        let size = size.max(1);
        let mut tiles = Vec::new();
        for y0 in (0..h).step_by(size as usize) {
            for x0 in (0..w).step_by(size as usize) {
                tiles.push(Tile {
                    x0,
                    y0,
                    x1: (x0 + size).min(w),
                    y1: (y0 + size).min(h),
                });
            }
        }
        tiles
    }

    /// Renders the frame in tiles of edge `tile_size`, each tile's batches taken by `order`;
    /// `done` is called after each tile.
    pub fn render(
        &self,
        tile_size: u32,
        order: RayOrder,
        done: &(dyn Fn() + Sync),
    ) -> Result<FrameOutput, FrameError> {
        let tiles = self.tiles(tile_size);
        let rendered = (tiles.par_iter().enumerate())
            .map(|(k, tile)| {
                let out = self.tile(k as u64, tile, order);
                done();
                out
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut image = RgbImage::new(self.constants.width, self.constants.height);
        let mut stats = FrameStats::default();
        for (tile, (pixels, s)) in tiles.iter().zip(rendered) {
            for (k, rgb) in pixels.into_iter().enumerate() {
                let (i, j) = (k as u32 % tile.width(), k as u32 / tile.width());
                image.put_pixel(tile.x0 + i, tile.y0 + j, image::Rgb(rgb));
            }
            stats += s;
        }
        Ok(FrameOutput { image, stats })
    }

    /// The traversal unit's answers to `batch`, into `hits`.
    pub fn cast(
        &self,
        batch: &[FrameRay],
        hits: &mut Vec<Option<Hit>>,
    ) -> Result<CastStats, FrameError> {
        let rays: Vec<Ray> = batch.iter().map(unit_ray).collect();
        hits.clear();
        hits.resize(batch.len(), None);
        (self.caster.cast(&rays, hits)).map_err(|source| FrameError::Traversal {
            scene: self.scene.clone(),
            source,
        })
    }

    /// One tile: its pixels' colours (row by row) and what it did.
    fn tile(
        &self,
        index: u64,
        tile: &Tile,
        order: RayOrder,
    ) -> Result<(Vec<[u8; 3]>, FrameStats), FrameError> {
        let c = &self.constants;
        let local = |pixel: u32| {
            let (i, j) = (pixel % c.width, pixel / c.width);
            ((j - tile.y0) * tile.width() + (i - tile.x0)) as usize
        };
        let mut acc = Accumulator::new(tile.pixels());
        let mut colours: Vec<Option<[u8; 3]>> = vec![None; tile.pixels()];
        let mut queue: Vec<FrameRay> = Vec::with_capacity(tile.pixels());
        for j in tile.y0..tile.y1 {
            for i in tile.x0..tile.x1 {
                let ray = FrameRay::primary(c, i, j);
                acc.issue(local(ray.pixel));
                queue.push(ray);
            }
        }
        let mut stats = FrameStats::default();
        let mut hits = Vec::new();
        let mut shaded = Shaded::default();
        for step in 0u64.. {
            if queue.is_empty() {
                break;
            }
            let n = order(index << 32 | step, &mut queue).clamp(1, queue.len());
            let batch: Vec<FrameRay> = queue.drain(..n).collect();
            stats.cast += self.cast(&batch, &mut hits)?;
            for (ray, hit) in batch.iter().zip(&hits) {
                stats.count(ray.kind());
                match (ray.kind(), hit) {
                    (RayKind::Shadow, Some(_)) => stats.occluded += 1,
                    (RayKind::Shadow, None) | (_, None) => {}
                    (_, Some(_)) => stats.hits += 1,
                }
                shaded.clear();
                let (settle, issued) =
                    thread::shade(&self.program, c, ray, hit.as_ref(), &mut shaded).map_err(
                        |source| FrameError::Thread {
                            scene: self.scene.clone(),
                            source,
                        },
                    )?;
                if let Some(t) = issued {
                    stats.threads[t.kind.index()] += ShaderLoad {
                        threads: 1,
                        instructions: u64::from(t.instructions),
                    };
                }
                queue.extend_from_slice(&shaded.spawned);
                let p = local(ray.pixel);
                if let Some(rgb) = acc.settle(p, &settle) {
                    colours[p] = Some(rgb);
                }
            }
        }
        stats.zero_shadows = shaded.zero_shadows;
        stats.past_depth = shaded.past_depth;
        stats.total_internal = shaded.total_internal;
        let pixels = colours
            .into_iter()
            .map(|c| c.expect("every pixel retires its last ray once the queue is empty"))
            .collect();
        Ok((pixels, stats))
    }
}

/// A frame ray as the traversal unit takes it: t_min 0 and nothing excluded (the thesis'
/// spawning, by the bias).
pub(crate) fn unit_ray(r: &FrameRay) -> Ray {
    Ray {
        orig: V3::from_array(r.orig.to_f32()),
        dir: V3::from_array(r.dir.to_f32()),
        bound: r.t_max.f32(),
        shadow: r.kind() == RayKind::Shadow,
        t_min: 0.0,
        exclude: None,
    }
}
