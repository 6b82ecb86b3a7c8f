//! The scene memory's driver side: the checks before an image is streamed, and the memory's
//! status turned into an error that names what is wrong and the sizes.
//!
//! The split: the memory checks every word as it passes (`scene_memory`); what needs the whole
//! tree — a node reached twice (a cycle or a shared subtree), duplicate global indices — is
//! [`check_before_load`]'s, which runs the software's checking loader
//! (`SceneImage::from_words`) and the capacity check on the words before they are streamed.

use hw_model::traversal::scene_image::{
    SceneImage, SceneImageError, HEADER_WORDS, MAGIC, NODE_WORDS, TRIANGLE_WORDS, VERSION,
};
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
    let (max_nodes, max_triangles) = config.capacity();
    let (nodes, triangles) = (image.nodes.len(), image.triangles.len());
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
    Ok(image)
}

/// Where stream word `word` is in an image of `nodes` nodes: header, node or triangle field.
pub fn word_place(word: u32, nodes: u32) -> String {
    let word = word as u64;
    let (header, node, triangle) = (
        HEADER_WORDS as u64,
        NODE_WORDS as u64,
        TRIANGLE_WORDS as u64,
    );
    if word < header {
        return format!("header word {word}");
    }
    let in_nodes = word - header;
    if in_nodes < node * u64::from(nodes) {
        let (k, w) = (in_nodes / node, in_nodes % node);
        let field = match w {
            0..=11 => "box",
            12 | 14 => "link first",
            _ => "link count",
        };
        let child = if w < 12 {
            String::new()
        } else {
            format!(" of child {}", (w - 12) / 2)
        };
        return format!("node {k} word {w}: {field}{child}");
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
    // A link's first is the word before its count.
    let first = (word as usize)
        .checked_sub(1)
        .and_then(|i| words.get(i))
        .copied()
        .unwrap_or_default();
    let detail = match error {
        LoadError::BadMagic => {
            format!("found {value:#010x}, not the magic word {MAGIC:#010x} (\"RTSI\")")
        }
        LoadError::BadVersion => format!("version {value}; this memory reads version {VERSION}"),
        LoadError::TooManyNodes => format!(
            "{value} inner nodes, but this memory holds {max_nodes} ({} address bits)",
            config.node_bits
        ),
        LoadError::TooManyTriangles => format!(
            "{value} triangles, but this memory holds {max_triangles} ({} address bits)",
            config.triangle_bits
        ),
        LoadError::NodeLink => {
            format!("links to inner node {first}, but there are {n} nodes")
        }
        LoadError::LeafLink => {
            format!("links to triangles {first}..{first}+{value}, but there are {t} triangles")
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
            image_words(n, t)
        ),
        LoadError::SceneTriangles => format!(
            "the scene's triangle count is {value}; it must be at least the image's {t} \
             triangles and at most {} (global indices have {INDEX_BITS} bits)",
            1u64 << INDEX_BITS
        ),
        LoadError::MissingLast => format!(
            "no tlast on the image's last word (the header's {n} nodes and {t} triangles need \
             {} words)",
            image_words(n, t)
        ),
    };
    Err(SceneMemoryError::Refused {
        error,
        word,
        place: word_place(word, n),
        detail,
    })
}

/// Words of an image of `n` nodes and `t` triangles.
fn image_words(n: u32, t: u32) -> u64 {
    HEADER_WORDS as u64 + NODE_WORDS as u64 * u64::from(n) + TRIANGLE_WORDS as u64 * u64::from(t)
}
