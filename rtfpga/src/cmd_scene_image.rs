//! `rtfpga scene-image`: a scene as the traversal unit's scene memory holds it.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use hw_model::traversal::scene_image::{SceneImage, NODE_WORDS, TRIANGLE_WORDS};
use hw_model::traversal::wide::image::{node_words, WideImage};
use hw_model::traversal::wide::NodeFormat;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::engine::{choice, ChunkArgs, SceneMemoryArg};
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
    /// How the image stores the tree's inner nodes: bvh2-fp32 (binary, fp32 boxes: scene
    /// image version 2), or wide nodes of 2, 4 or 8 children with 8-bit quantized boxes
    /// (version 3; docs/scene-image.md).
    #[arg(long, default_value = "bvh2-fp32", value_parser = choice::<NodeFormat>())]
    nodes: NodeFormat,
}

/// A scene image in the node format asked for.
enum Image {
    Binary(SceneImage),
    Wide(WideImage),
}

impl Image {
    fn of(image: &SceneImage, nodes: NodeFormat) -> Result<Image> {
        Ok(match nodes.width() {
            None => Image::Binary(image.clone()),
            Some(width) => Image::Wide(
                WideImage::of(image, width)
                    .with_context(|| format!("writing the {} tree", nodes.name()))?,
            ),
        })
    }

    /// Its sizes as key=value pairs: triangles, inner nodes, tree depth, bytes in all and
    /// bytes a node and a triangle record.
    fn sizes(&self, line: Line) -> Line {
        let (triangles, nodes, depth, bytes, node_words) = match self {
            Image::Binary(i) => (
                i.triangles.len(),
                i.nodes.len(),
                i.depth(),
                i.bytes(),
                NODE_WORDS,
            ),
            Image::Wide(i) => (
                i.triangles.len(),
                i.tree.nodes.len(),
                i.depth(),
                i.bytes(),
                node_words(i.tree.width),
            ),
        };
        line.kv("triangles", triangles)
            .kv("nodes", nodes)
            .kv("depth", depth)
            .kv("bytes", bytes)
            .kv("node_bytes", 4 * node_words)
            .kv("triangle_bytes", 4 * TRIANGLE_WORDS)
    }

    fn to_words(&self) -> Vec<u32> {
        match self {
            Image::Binary(i) => i.to_words(),
            Image::Wide(i) => i.to_words(),
        }
    }

    fn bytes(&self) -> usize {
        match self {
            Image::Binary(i) => i.bytes(),
            Image::Wide(i) => i.bytes(),
        }
    }
}

pub fn run(a: Args) -> Result<()> {
    let scene = Scene::load(&a.scene)?;
    if let Some(out) = &a.out {
        report::file_out(out)?;
    }
    let prepared = PreparedScene::new(&scene)?;
    let binary = SceneImage::new(&prepared);
    // The chunks first: a memory that cannot hold the scene is an error before any output.
    let chunks = match a.memory.scene_memory {
        // The memory is given, so the lane count that would choose a default is irrelevant.
        Some(_) => Some(
            hw_model::traversal::capacity::chunks(
                &binary,
                a.memory.model_memory(1, a.nodes, &ChunkArgs::default()),
                a.nodes,
            )?
            .iter()
            .map(|c| Image::of(c, a.nodes))
            .collect::<Result<Vec<_>>>()?,
        ),
        None => None,
    };
    let image = Image::of(&binary, a.nodes)?;
    image
        .sizes(
            Line::new()
                .kv("scene", &scene.name)
                .kv("node_format", a.nodes.name()),
        )
        .print();
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
            .kv("chunk_bytes", parts.iter().map(Image::bytes).sum::<usize>())
            .print();
        for (k, c) in parts.iter().enumerate() {
            c.sizes(Line::new().kv("chunk", k)).print();
        }
    }
    Ok(())
}
