//! `rtfpga scene-image`: a scene as the traversal unit's scene memory holds it.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use hw_model::traversal::scene_image::SceneImage;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::engine::{ChunkArgs, SceneMemoryArg};
use crate::report::{self, Line};

#[derive(ClapArgs)]
pub struct Args {
    /// Scene directory with objects.txt, a .toml scene, or a built-in scene name.
    #[arg(long)]
    scene: String,
    /// Write the image's words (little-endian, the order the unit loads them) to this file
    /// (its folder is created).
    #[arg(long)]
    out: Option<PathBuf>,
    /// With --scene-memory, the chunks a unit with that memory loads the scene in are listed.
    #[command(flatten)]
    memory: SceneMemoryArg,
}

pub fn run(a: Args) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
    if let Some(out) = &a.out {
        report::file_out(out)?;
    }
    let prepared = PreparedScene::new(&scene)?;
    let image = SceneImage::new(&prepared);
    let size = |line: Line, image: &SceneImage| {
        line.kv("triangles", image.triangles.len())
            .kv("nodes", image.nodes.len())
            .kv("depth", image.depth())
            .kv("bytes", image.bytes())
    };
    // The chunks first: a memory that cannot hold the scene is an error before any output.
    let chunks = match a.memory.scene_memory {
        // The memory is given, so the lane count that would choose a default is irrelevant.
        Some(_) => Some(hw_model::traversal::capacity::chunks(
            &image,
            a.memory.model_memory(1, &ChunkArgs::default()),
        )?),
        None => None,
    };
    size(Line::new().kv("scene", &scene.name), &image).print();
    if let Some(out) = &a.out {
        let bytes: Vec<u8> = image
            .to_words()
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        std::fs::write(out, bytes).with_context(|| format!("writing {}", out.display()))?;
        Line::new().path("out", out).print();
    }
    if let Some(parts) = chunks {
        Line::new()
            .kv("chunks", parts.len())
            .kv(
                "chunk_bytes",
                parts.iter().map(SceneImage::bytes).sum::<usize>(),
            )
            .print();
        for (k, c) in parts.iter().enumerate() {
            size(Line::new().kv("chunk", k), c).print();
        }
    }
    Ok(())
}
