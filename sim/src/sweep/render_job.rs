//! Rendering for the sweep: the f32 reference of each scene (the `prepare` job, once per
//! scene) and loading it back for the jobs that compare against it.

use anyhow::{Context, Result};
use image::RgbImage;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::RayEngine;
use sw_renderer::render::{render, save_png, RenderOptions, RenderOutput};
use sw_renderer::spawn::SpawnPolicy;

use super::config::{SceneSpec, SweepConfig};
use super::layout::{parent_dir, Layout};

/// Renders `scene` at the sweep's size with `engine`, spawning rays by `spawn`.
pub fn render_scene(
    config: &SweepConfig,
    scene: &SceneSpec,
    engine: &dyn RayEngine,
    spawn: SpawnPolicy,
) -> Result<RenderOutput> {
    let loaded = scene.load()?;
    let opts = RenderOptions {
        width: Some(config.width),
        height: Some(config.height),
        spawn,
        ..Default::default()
    };
    render(&loaded, engine, &opts)
        .with_context(|| format!("rendering {} ({})", scene.label, engine.name()))
}

/// The `prepare` job: the f32 reference of every scene (the thesis' spawning, as the golden
/// images), saved as PNG.
pub fn prepare(config: &SweepConfig, layout: &Layout) -> Result<()> {
    for scene in &config.scenes {
        let out = render_scene(config, scene, &F32Intersector, SpawnPolicy::Thesis)?;
        let path = layout.reference(&scene.label);
        parent_dir(&path)?;
        save_png(&out.image, &path)?;
    }
    Ok(())
}

/// The reference render of `scene` written by `prepare`.
pub fn reference(layout: &Layout, scene: &SceneSpec) -> Result<RgbImage> {
    let path = layout.reference(&scene.label);
    let image = image::open(&path).with_context(|| {
        format!(
            "reading the reference render {} (run the `prepare` job first)",
            path.display()
        )
    })?;
    Ok(image.to_rgb8())
}
