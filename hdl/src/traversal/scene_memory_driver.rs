//! The scene memory's driver side: the checks before an image is streamed, and the memory's
//! status turned into an error that names what is wrong and the sizes.
//!
//! The split: the memory checks every word as it passes (`scene_memory`, `wide_scene_memory`);
//! what needs the whole tree — a node reached twice (a cycle or a shared subtree), duplicate
//! global indices, a wide child's box enclosing its triangles — is [`check_before_load`]'s
//! ([`check_before_load_wide`]'s), which runs the software's checking loader
//! (`SceneImage::from_words`, `WideImage::from_words`) and the capacity check on the words
//! before they are streamed.

use hw_model::traversal::scene_image::{
    SceneImage, SceneImageError, HEADER_WORDS, MAGIC, NODE_WORDS, TRIANGLE_WORDS, VERSION,
    VERSION_WIDE,
};
use hw_model::traversal::wide::image::{link_of, node_words, WideImage};
use hw_model::traversal::wide::NodeFormat;
use thiserror::Error;

use super::scene_memory::{capacity_for, LoadError, INDEX_BITS};

/// A scene memory's address bits: its capacity is [`capacity_for`] them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryConfig {
    pub node_bits: usize,
    pub triangle_bits: usize,
}

impl MemoryConfig {
    /// (nodes, triangles) it holds.
    pub fn capacity(self) -> (usize, usize) {
        capacity_for(self.node_bits, self.triangle_bits)
    }
}

/// The memory's status outputs after a load.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadStatus {
    pub loading: bool,
    pub loaded: bool,
    pub error_code: u64,
    pub error_word: u32,
    pub error_value: u32,
    /// The header's N and T as the memory read them.
    pub nodes: u32,
    pub triangles: u32,
}

#[derive(Debug, Error, PartialEq)]
pub enum SceneMemoryError {
    #[error(transparent)]
    Image(#[from] SceneImageError),
    #[error(
        "scene of {nodes} inner nodes and {triangles} triangles does not fit a scene memory of \
         {max_nodes} nodes and {max_triangles} triangles ({node_bits} and {triangle_bits} \
         address bits)"
    )]
    TooBig {
        nodes: usize,
        triangles: usize,
        max_nodes: usize,
        max_triangles: usize,
        node_bits: usize,
        triangle_bits: usize,
    },
    #[error(
        "a scene image of {image}-wide nodes cannot load into a memory of {memory}-wide nodes"
    )]
    Width { image: usize, memory: usize },
    #[error("scene memory refused the image at stream word {word} ({place}): {detail}")]
    Refused {
        error: LoadError,
        word: u32,
        place: String,
        detail: String,
    },
    #[error("scene memory reports error code {code}, which no load error has (word {word})")]
    UnknownCode { code: u64, word: u32 },
    #[error("scene memory did not finish the load of {words} words (still loading: {loading})")]
    NotLoaded { words: usize, loading: bool },
}

/// What the driver checks before streaming `words` into a memory of `config`: the whole
/// image (`SceneImage::from_words`: sizes, links, no node reached twice, indices a
/// permutation) and that it fits.
pub fn check_before_load(
    words: &[u32],
    config: MemoryConfig,
) -> Result<SceneImage, SceneMemoryError> {
    let image = SceneImage::from_words(words)?;
    fits(config, image.nodes.len(), image.triangles.len())?;
    Ok(image)
}

/// Whether `nodes` and `triangles` fit a memory of `config`.
fn fits(config: MemoryConfig, nodes: usize, triangles: usize) -> Result<(), SceneMemoryError> {
    let (max_nodes, max_triangles) = config.capacity();
    if nodes > max_nodes || triangles > max_triangles {
        return Err(SceneMemoryError::TooBig {
            nodes,
            triangles,
            max_nodes,
            max_triangles,
            node_bits: config.node_bits,
            triangle_bits: config.triangle_bits,
        });
    }
    Ok(())
}

/// What [`check_before_load_wide`] checks before streaming `words` into a memory of `config`
/// holding `width`-wide nodes: the whole image (`WideImage::from_words`: sizes, links, no node
/// reached twice, every child's box enclosing its triangles), its width and that it fits.
pub fn check_before_load_wide(
    words: &[u32],
    config: MemoryConfig,
    width: usize,
) -> Result<WideImage, SceneMemoryError> {
    let image = WideImage::from_words(words)?;
    if image.tree.width != width {
        return Err(SceneMemoryError::Width {
            image: image.tree.width,
            memory: width,
        });
    }
    fits(config, image.tree.nodes.len(), image.triangles.len())?;
    Ok(image)
}

/// What the driver checks before streaming `words` into a memory of `config` holding
/// `layout`'s nodes ([`check_before_load`] or [`check_before_load_wide`]), and the image's
/// tree depth.
pub fn check_before_load_in(
    words: &[u32],
    config: MemoryConfig,
    layout: NodeLayout,
) -> Result<usize, SceneMemoryError> {
    Ok(match layout {
        NodeLayout::Binary => check_before_load(words, config)?.depth(),
        NodeLayout::Wide(width) => check_before_load_wide(words, config, width)?.depth(),
    })
}

/// How a memory's image lays out its nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeLayout {
    /// Version 2: binary nodes of fp32 boxes.
    Binary,
    /// Version 3: wide nodes of this many children.
    Wide(usize),
}

impl NodeLayout {
    /// The layout of a memory holding `nodes`.
    pub fn of(nodes: NodeFormat) -> NodeLayout {
        match nodes.width() {
            Some(width) => NodeLayout::Wide(width),
            None => NodeLayout::Binary,
        }
    }

    fn version(self) -> u32 {
        match self {
            NodeLayout::Binary => VERSION,
            NodeLayout::Wide(_) => VERSION_WIDE,
        }
    }

    fn node_words(self) -> u64 {
        match self {
            NodeLayout::Binary => NODE_WORDS as u64,
            NodeLayout::Wide(width) => node_words(width) as u64,
        }
    }

    /// The field of a node's word `w`.
    fn node_field(self, w: u64) -> String {
        match self {
            NodeLayout::Binary => {
                let field = match w {
                    0..=11 => "box",
                    12 | 14 => "link first",
                    _ => "link count",
                };
                match w {
                    0..=11 => field.to_string(),
                    _ => format!("{field} of child {}", (w - 12) / 2),
                }
            }
            NodeLayout::Wide(width) => {
                let links = self.node_words() - width as u64;
                match w {
                    0..=2 => "grid origin".to_string(),
                    3 => "exponents and child count".to_string(),
                    _ if w < links => "child box codes".to_string(),
                    _ => format!("link of child {}", w - links),
                }
            }
        }
    }
}

/// Where stream word `word` is in an image of `nodes` nodes: header, node or triangle field.
pub fn word_place(word: u32, nodes: u32) -> String {
    word_place_in(word, nodes, NodeLayout::Binary)
}

/// [`word_place`] in an image of `layout`.
pub fn word_place_in(word: u32, nodes: u32, layout: NodeLayout) -> String {
    let word = word as u64;
    let (header, node, triangle) = (
        HEADER_WORDS as u64,
        layout.node_words(),
        TRIANGLE_WORDS as u64,
    );
    if word < header {
        return format!("header word {word}");
    }
    let in_nodes = word - header;
    if in_nodes < node * u64::from(nodes) {
        let (k, w) = (in_nodes / node, in_nodes % node);
        return format!("node {k} word {w}: {}", layout.node_field(w));
    }
    let in_tris = in_nodes - node * u64::from(nodes);
    let (k, w) = (in_tris / triangle, in_tris % triangle);
    let field = match w {
        0..=8 => "vertex",
        9 => "global index",
        10 => "flags",
        _ => "reserved",
    };
    format!("triangle record {k} word {w}: {field}")
}

/// The memory's `status` after `words` were streamed into a memory of `config`: `Ok` when
/// it holds the scene, else the error naming the word, what is wrong and the sizes.
pub fn status_result(
    status: &LoadStatus,
    words: &[u32],
    config: MemoryConfig,
) -> Result<(), SceneMemoryError> {
    status_result_in(status, words, config, NodeLayout::Binary)
}

/// [`status_result`] of a memory holding `layout`'s nodes.
pub fn status_result_in(
    status: &LoadStatus,
    words: &[u32],
    config: MemoryConfig,
    layout: NodeLayout,
) -> Result<(), SceneMemoryError> {
    if status.error_code == 0 {
        return match status.loaded {
            true => Ok(()),
            false => Err(SceneMemoryError::NotLoaded {
                words: words.len(),
                loading: status.loading,
            }),
        };
    }
    let (word, value) = (status.error_word, status.error_value);
    let error = LoadError::from_code(status.error_code).ok_or(SceneMemoryError::UnknownCode {
        code: status.error_code,
        word,
    })?;
    let (max_nodes, max_triangles) = config.capacity();
    let (n, t) = (status.nodes, status.triangles);
    // A binary link's first is the word before its count; a wide link is one word.
    let (first, count) = match layout {
        NodeLayout::Binary => {
            let first = (word as usize).checked_sub(1).and_then(|i| words.get(i));
            (first.copied().unwrap_or_default(), value)
        }
        NodeLayout::Wide(_) => (link_of(value).first, link_of(value).count),
    };
    let version = layout.version();
    let detail = match error {
        LoadError::BadMagic => {
            format!("found {value:#010x}, not the magic word {MAGIC:#010x} (\"RTSI\")")
        }
        LoadError::BadVersion => format!("version {value}; this memory reads version {version}"),
        LoadError::TooManyNodes => format!(
            "{value} inner nodes, but this memory holds {max_nodes} ({} address bits)",
            config.node_bits
        ),
        LoadError::TooManyTriangles => format!(
            "{value} triangles, but this memory holds {max_triangles} ({} address bits)",
            config.triangle_bits
        ),
        LoadError::NodeLink if layout != NodeLayout::Binary && (word as usize) < HEADER_WORDS => {
            format!(
                "the root of a wide image is node 0, link (0, 0), and a scene of {t} triangles \
                 has nodes ({n})"
            )
        }
        LoadError::NodeLink => {
            format!("links to inner node {first}, but there are {n} nodes")
        }
        LoadError::LeafLink => {
            format!("links to triangles {first}..{first}+{count}, but there are {t} triangles")
        }
        LoadError::Width => {
            let memory = match layout {
                NodeLayout::Wide(width) => width.to_string(),
                NodeLayout::Binary => "binary".to_string(),
            };
            format!("nodes of {value} children; this memory holds {memory}-wide nodes")
        }
        LoadError::ChildCount => {
            let width = match layout {
                NodeLayout::Wide(width) => width,
                NodeLayout::Binary => 2,
            };
            format!(
                "{} children; a node of this memory has 1 to {width}",
                value >> 24
            )
        }
        LoadError::GlobalIndex => {
            let scene = words.get(12).copied().unwrap_or_default();
            format!("global index {value}, but the scene has {scene} triangles")
        }
        LoadError::BadFlags => {
            format!("flags {value:#x}; only bit 0 (casts shadows) is defined")
        }
        LoadError::Reserved => format!("reserved, must be 0, holds {value:#x}"),
        LoadError::EarlyLast => format!(
            "tlast before the image's last word (the header's {n} nodes and {t} triangles need \
             {} words)",
            image_words(n, t, layout)
        ),
        LoadError::SceneTriangles => format!(
            "the scene's triangle count is {value}; it must be at least the image's {t} \
             triangles and at most {} (global indices have {INDEX_BITS} bits)",
            1u64 << INDEX_BITS
        ),
        LoadError::MissingLast => format!(
            "no tlast on the image's last word (the header's {n} nodes and {t} triangles need \
             {} words)",
            image_words(n, t, layout)
        ),
    };
    Err(SceneMemoryError::Refused {
        error,
        word,
        place: word_place_in(word, n, layout),
        detail,
    })
}

/// Words of an image of `n` nodes and `t` triangles.
fn image_words(n: u32, t: u32, layout: NodeLayout) -> u64 {
    HEADER_WORDS as u64 + layout.node_words() * u64::from(n) + TRIANGLE_WORDS as u64 * u64::from(t)
}
