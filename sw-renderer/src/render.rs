//! Rendering a scene through an intersector: tiles in parallel, each traced as a wavefront.
//!
//! Tiles are independent and every pixel's arithmetic is fixed, so the image does not depend
//! on the thread count, the tile size or how the intersector splits its batches.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use image::RgbImage;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use thiserror::Error;

use crate::camera::Camera;
use crate::math::V3;
use crate::rays::{EngineError, RayEngine};
use crate::scene::Scene;
use crate::shade::to_rgb8;
use crate::spawn::SpawnPolicy;
use crate::trace::{trace_rays, PreparedScene, TraceStats};
use crate::world::WorldError;

#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Overrides the scene's width.
    pub width: Option<u32>,
    /// Overrides the scene's height.
    pub height: Option<u32>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Edge of the square pixel tiles; one tile's rays form one wavefront (bigger tiles mean
    /// bigger intersector batches).
    pub tile_size: u32,
    /// How secondary and shadow rays are spawned.
    pub spawn: SpawnPolicy,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: None,
            height: None,
            progress: false,
            tile_size: 32,
            spawn: SpawnPolicy::Thesis,
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub trace: TraceStats,
    /// Preparing world geometry and building the BVH.
    pub prepare_time: Duration,
    /// Tracing and shading all tiles.
    pub render_time: Duration,
}

#[derive(Clone, Debug)]
pub struct RenderOutput {
    pub image: RgbImage,
    pub stats: RenderStats,
}

#[derive(Debug, Error)]
pub enum RenderError {
    #[error("cannot render scene `{scene}`: {source}")]
    World { scene: String, source: WorldError },
    #[error("cannot render scene `{scene}` at {width}×{height}: width, height and tile size must be positive")]
    EmptyImage {
        scene: String,
        width: u32,
        height: u32,
    },
    #[error("cannot render scene `{scene}` with {engine}: {source}")]
    Engine {
        scene: String,
        engine: String,
        source: EngineError,
    },
    #[error("cannot write PNG {}: {source}", path.display())]
    Save {
        path: PathBuf,
        source: image::ImageError,
    },
}

pub fn render(
    scene: &Scene,
    engine: &dyn RayEngine,
    opts: &RenderOptions,
) -> Result<RenderOutput, RenderError> {
    let width = opts.width.unwrap_or(scene.options.width);
    let height = opts.height.unwrap_or(scene.options.height);
    if width == 0 || height == 0 || opts.tile_size == 0 {
        return Err(RenderError::EmptyImage {
            scene: scene.name.clone(),
            width,
            height,
        });
    }
    let start = Instant::now();
    let mut prepared = PreparedScene::new(scene).map_err(|source| RenderError::World {
        scene: scene.name.clone(),
        source,
    })?;
    prepared.spawn = opts.spawn;
    let camera = Camera::new(
        scene.options.camera_to_world,
        scene.options.fov_deg,
        width,
        height,
    );
    let engine_error = |source| RenderError::Engine {
        scene: scene.name.clone(),
        engine: engine.name(),
        source,
    };
    let caster = engine.prepare(&prepared).map_err(engine_error)?;
    let prepare_time = start.elapsed();

    let tiles = tiles(width, height, opts.tile_size);
    let progress = if opts.progress {
        let bar =
            ProgressBar::with_draw_target(Some(tiles.len() as u64), ProgressDrawTarget::stderr());
        if let Ok(style) =
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} tiles {elapsed}/{eta}")
        {
            bar.set_style(style);
        }
        bar.set_message(format!("{} ({})", scene.name, engine.name()));
        bar
    } else {
        ProgressBar::hidden()
    };

    let start = Instant::now();
    let traced: Result<Vec<(Vec<V3>, TraceStats)>, EngineError> = tiles
        .par_iter()
        .map(|tile| {
            let rays: Vec<(V3, V3)> = tile
                .pixels()
                .map(|(i, j)| (camera.origin, camera.direction(i, j)))
                .collect();
            let out = trace_rays(&prepared, caster.as_ref(), &rays);
            progress.inc(1);
            out
        })
        .collect();
    progress.finish_and_clear();
    let traced = traced.map_err(engine_error)?;

    let mut image = RgbImage::new(width, height);
    let mut trace = TraceStats::default();
    for (tile, (colours, stats)) in tiles.iter().zip(traced) {
        for ((i, j), c) in tile.pixels().zip(colours) {
            image.put_pixel(i, j, image::Rgb(to_rgb8(c)));
        }
        trace += stats;
    }
    Ok(RenderOutput {
        image,
        stats: RenderStats {
            trace,
            prepare_time,
            render_time: start.elapsed(),
        },
    })
}

pub fn save_png(image: &RgbImage, path: &Path) -> Result<(), RenderError> {
    image
        .save_with_format(path, image::ImageFormat::Png)
        .map_err(|source| RenderError::Save {
            path: path.to_path_buf(),
            source,
        })
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
    /// Pixels (i, j) row by row.
    fn pixels(self) -> impl Iterator<Item = (u32, u32)> {
        (self.y0..self.y1).flat_map(move |j| (self.x0..self.x1).map(move |i| (i, j)))
    }
}

fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let mut tiles = Vec::new();
    for y0 in (0..height).step_by(size as usize) {
        for x0 in (0..width).step_by(size as usize) {
            tiles.push(Tile {
                x0,
                y0,
                x1: (x0 + size).min(width),
                y1: (y0 + size).min(height),
            });
        }
    }
    tiles
}
