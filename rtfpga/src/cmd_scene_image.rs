//! `rtfpga scene-image`: a scene as the traversal unit's scene memory holds it.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use hw_model::traversal::scene_image::SceneImage;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::engine::MemoryArgs;

#[derive(ClapArgs)]
pub struct Args {
    /// Scene directory with objects.txt, a .toml scene, or a built-in scene name.
    #[arg(long)]
    scene: String,
    /// Write the image's words (little-endian, the order the unit loads them) to this file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also list the chunks a traversal unit holding NODES,TRIANGLES loads the scene in.
    #[command(flatten)]
    memory: MemoryArgs,
}

pub fn run(a: Args) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
    let prepared = PreparedScene::new(&scene)?;
    let image = SceneImage::new(&prepared);
    if let Some(out) = &a.out {
        let bytes: Vec<u8> = image
            .to_words()
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        std::fs::write(out, bytes).with_context(|| format!("writing {}", out.display()))?;
    }
    println!(
        "scene={} triangles={} nodes={} depth={} bytes={}",
        scene.name,
        image.triangles.len(),
        image.nodes.len(),
        image.depth(),
        image.bytes()
    );
    if a.memory.scene_capacity.is_some() {
        // The capacity is given, so the lane count that would choose a default is irrelevant.
        let parts = hw_model::traversal::capacity::chunks(&image, a.memory.memory(1))?;
        println!(
            "chunks={} chunk_bytes={}",
            parts.len(),
            parts.iter().map(SceneImage::bytes).sum::<usize>()
        );
        for (k, c) in parts.iter().enumerate() {
            println!(
                "chunk={k} triangles={} nodes={} depth={} bytes={}",
                c.triangles.len(),
                c.nodes.len(),
                c.depth(),
                c.bytes()
            );
        }
    }
    Ok(())
}
