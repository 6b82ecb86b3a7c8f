//! The scene image: the BVH and triangles of a prepared scene as the traversal unit's scene
//! memory holds them, in one binary layout (`docs/scene-image.md`).
//!
//! This module is that layout's one definition: the writer ([`SceneImage::new`], from the
//! software BVH), the word stream loaded over AXI4-Stream ([`SceneImage::to_words`]) and the
//! loader that checks a word stream before anything walks it ([`SceneImage::from_words`]).
//! The unit's model, its hardware and the harness read the same types.
//!
//! Every field is a little-endian 32-bit word. In order:
//! - header, [`HEADER_WORDS`] words: magic, version, node count N, triangle count T, the
//!   root's link (first, count), the root's padded box (min x y z, max x y z), the scene's
//!   triangle count S (global indices are below it: S = T for a whole scene, more for a
//!   chunk of a larger one), 3 reserved 0;
//! - N inner nodes of [`NODE_WORDS`] words: both children's padded boxes, `min[axis][child]`
//!   (x0 x1 y0 y1 z0 z1) then `max[axis][child]`, then the links (first, count) of child 0
//!   and child 1;
//! - T triangles of [`TRIANGLE_WORDS`] words: v0, v1, v2 (x y z each, world space), the
//!   global triangle index, flags (bit 0: casts shadows), 1 reserved 0.
//!
//! A link `(first, count)` is an inner node `first` if `count == 0`, else the leaf of
//! triangle records `first .. first + count` (triangles are stored in leaf order).
//!
//! Version 3 holds wide nodes instead ([`super::wide::image`], docs/wide-nodes.md): header
//! word 13 is the node width K, the nodes are wide records, the triangles as above.
//! [`UnitImage::from_words`] reads either version.

use sw_renderer::bvh::Bvh;
use sw_renderer::trace::PreparedScene;
use sw_renderer::world::WorldTriangle;
use thiserror::Error;

/// "RTSI" as a little-endian word.
pub const MAGIC: u32 = u32::from_le_bytes(*b"RTSI");
/// Version 2: header word 12 holds the scene's triangle count (chunks of a larger scene).
pub const VERSION: u32 = 2;
/// Version 3: wide nodes (header word 13: their width).
pub const VERSION_WIDE: u32 = 3;
pub const HEADER_WORDS: usize = 16;
pub const NODE_WORDS: usize = 16;
pub const TRIANGLE_WORDS: usize = 12;
/// Flag bit of a triangle record: shadow rays test it.
pub const CASTS_SHADOW: u32 = 1;

/// A child of an inner node (or the root).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Link {
    pub first: u32,
    /// 0: the inner node `first`; else a leaf of this many triangle records from `first`.
    pub count: u32,
}

impl Link {
    pub fn is_leaf(self) -> bool {
        self.count > 0
    }
}

/// The two child boxes of an inner node, `[axis][child]` (padded by the BVH).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ChildBoxes {
    pub min: [[f32; 2]; 3],
    pub max: [[f32; 2]; 3],
}

/// An inner node: what one box test reads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageNode {
    pub boxes: ChildBoxes,
    pub child: [Link; 2],
}

/// A triangle record: what one Möller-Trumbore test reads, and what its hit reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageTriangle {
    pub verts: [[f32; 3]; 3],
    /// The global triangle index (`world.rs`): ties between equal hits go to the lower one.
    pub index: u32,
    pub casts_shadow: bool,
}

/// A scene as the traversal unit's memory holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneImage {
    pub root: Link,
    /// The root's padded box (min, max).
    pub root_box: ([f32; 3], [f32; 3]),
    pub nodes: Vec<ImageNode>,
    pub triangles: Vec<ImageTriangle>,
    /// Triangles of the whole scene: every global index is below it (`triangles.len()` for a
    /// whole scene; a chunk keeps its scene's global indices).
    pub scene_triangles: u32,
}

/// Why a word stream is not a scene image the unit may walk.
#[derive(Debug, Error, PartialEq)]
pub enum SceneImageError {
    #[error("scene image of {words} words is shorter than its {HEADER_WORDS}-word header")]
    TooShort { words: usize },
    #[error("scene image starts with {found:#010x}, not the magic word {MAGIC:#010x} (\"RTSI\")")]
    BadMagic { found: u32 },
    #[error("scene image version {found}; this unit reads version {VERSION} (binary nodes) and {VERSION_WIDE} (wide nodes)")]
    BadVersion { found: u32 },
    #[error(
        "scene image of {words} words, but its header's {nodes} nodes and {triangles} triangles need {expected}"
    )]
    SizeMismatch {
        words: usize,
        nodes: u32,
        triangles: u32,
        expected: u64,
    },
    #[error("scene image word {word}: reserved, must be 0, holds {value:#x}")]
    Reserved { word: usize, value: u32 },
    #[error("scene image: {from} links to inner node {first}, but there are {nodes} nodes")]
    NodeOutOfRange {
        from: String,
        first: u32,
        nodes: u32,
    },
    #[error(
        "scene image: {from} links to triangles {first}..{first}+{count}, but there are {triangles} triangles"
    )]
    LeafOutOfRange {
        from: String,
        first: u32,
        count: u32,
        triangles: u32,
    },
    #[error(
        "scene image: {from} links to node {node} again: the tree has a cycle or a shared subtree"
    )]
    ReachedTwice { from: String, node: u32 },
    #[error("scene image: triangle record {slot} has global index {index}, but the scene has {scene_triangles} triangles")]
    IndexOutOfRange {
        slot: usize,
        index: u32,
        scene_triangles: u32,
    },
    #[error("scene image: {triangles} triangle records, but the scene has only {scene_triangles}")]
    MoreThanTheScene {
        triangles: u32,
        scene_triangles: u32,
    },
    #[error("scene image: triangle records {first} and {second} both have global index {index}")]
    DuplicateIndex {
        index: u32,
        first: usize,
        second: usize,
    },
    #[error("scene image: triangle record {slot} has flags {flags:#x}; only bit 0 (casts shadows) is defined")]
    UnknownFlags { slot: usize, flags: u32 },
    #[error(
        "scene image: wide nodes of {width} children; the unit reads widths {:?}",
        super::wide::WIDTHS
    )]
    BadWidth { width: u32 },
    #[error("scene image: node {node} has {children} children; a node of width {width} has 1 to {width}")]
    ChildCount {
        node: usize,
        children: u32,
        width: usize,
    },
    #[error("scene image: {from} links to a leaf of {count} triangles; a wide node's leaf holds 1 to {}", super::wide::MAX_LEAF_TRIANGLES)]
    LongLeaf { from: String, count: u32 },
    #[error("scene image: the root of wide nodes is inner node 0, not {first}+{count}")]
    WideRoot { first: u32, count: u32 },
    #[error("scene image: {0}")]
    Wide(#[from] super::wide::WideError),
}

impl SceneImage {
    /// The image of `scene`: its BVH's inner nodes and root, its triangles in leaf order with
    /// their global index and shadow flag. The one writer of the layout.
    pub fn new(scene: &PreparedScene) -> SceneImage {
        SceneImage::from_bvh(&scene.bvh, &scene.world.triangles, scene.casts_shadow())
    }

    /// The image of `bvh` built over `triangles`, with their shadow flags.
    pub fn from_bvh(bvh: &Bvh, triangles: &[WorldTriangle], casts_shadow: &[bool]) -> SceneImage {
        let ((first, count), root_box, inner, order) = bvh.parts();
        let link = |(first, count)| Link { first, count };
        SceneImage {
            root: link((first, count)),
            root_box,
            nodes: inner
                .map(|(min, max, child)| ImageNode {
                    boxes: ChildBoxes { min, max },
                    child: child.map(link),
                })
                .collect(),
            triangles: order
                .iter()
                .map(|&t| ImageTriangle {
                    verts: triangles[t as usize].verts.map(|v| v.to_array()),
                    index: t,
                    casts_shadow: casts_shadow[t as usize],
                })
                .collect(),
            scene_triangles: triangles.len() as u32,
        }
    }

    /// Words of the image: header, nodes, triangles.
    pub fn to_words(&self) -> Vec<u32> {
        let mut w = Vec::with_capacity(self.words());
        let f = |x: f32| x.to_bits();
        w.extend(
            Header {
                version: VERSION,
                nodes: self.nodes.len() as u32,
                triangles: self.triangles.len() as u32,
                root: self.root,
                root_box: self.root_box,
                scene_triangles: self.scene_triangles,
                width: 0,
            }
            .words(),
        );
        for n in &self.nodes {
            w.extend(n.boxes.min.iter().flatten().map(|&x| f(x)));
            w.extend(n.boxes.max.iter().flatten().map(|&x| f(x)));
            for c in n.child {
                w.extend([c.first, c.count]);
            }
        }
        write_triangles(&self.triangles, &mut w);
        w
    }

    /// The image's size in words.
    pub fn words(&self) -> usize {
        HEADER_WORDS + NODE_WORDS * self.nodes.len() + TRIANGLE_WORDS * self.triangles.len()
    }

    /// Reads and checks a word stream: sizes, magic and version, every link in range, no
    /// node reached twice (so no cycle), global indices a permutation, no unknown flags or
    /// reserved bits. What passes can be walked without an out-of-range access or a loop.
    pub fn from_words(w: &[u32]) -> Result<SceneImage, SceneImageError> {
        let h = Header::read(w, VERSION, |_| NODE_WORDS)?;
        let f = |i: usize| f32::from_bits(w[i]);
        let pairs = |i: usize| [[f(i), f(i + 1)], [f(i + 2), f(i + 3)], [f(i + 4), f(i + 5)]];
        let link = |i: usize| Link {
            first: w[i],
            count: w[i + 1],
        };
        let node_at = |k: usize| HEADER_WORDS + NODE_WORDS * k;
        let image = SceneImage {
            root: h.root,
            root_box: h.root_box,
            nodes: (0..h.nodes as usize)
                .map(|k| {
                    let i = node_at(k);
                    ImageNode {
                        boxes: ChildBoxes {
                            min: pairs(i),
                            max: pairs(i + 6),
                        },
                        child: [link(i + 12), link(i + 14)],
                    }
                })
                .collect(),
            triangles: read_triangles(w, node_at(h.nodes as usize), h.triangles)?,
            scene_triangles: h.scene_triangles,
        };
        image.check()?;
        Ok(image)
    }

    /// The structural checks of [`SceneImage::from_words`] on an image in memory.
    pub fn check(&self) -> Result<(), SceneImageError> {
        check_triangles(&self.triangles, self.scene_triangles)?;
        check_links(
            self.root,
            self.triangles.len() as u32,
            self.nodes.len() as u32,
            |node| self.nodes[node as usize].child.to_vec(),
        )
    }

    /// Inner nodes on the longest path from the root to a leaf: the traversal stack a ray
    /// may need (a walk pushes at most one subtree per inner node it passes). Assumes
    /// [`SceneImage::check`] passed.
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut todo = vec![(self.root, 0usize)];
        while let Some((link, d)) = todo.pop() {
            if link.is_leaf() || self.triangles.is_empty() {
                deepest = deepest.max(d);
                continue;
            }
            for &c in &self.nodes[link.first as usize].child {
                todo.push((c, d + 1));
            }
        }
        deepest
    }

    /// The image's size in bytes (as loaded).
    pub fn bytes(&self) -> usize {
        4 * self.words()
    }
}

/// The header of either version.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Header {
    pub version: u32,
    pub nodes: u32,
    pub triangles: u32,
    pub root: Link,
    pub root_box: ([f32; 3], [f32; 3]),
    pub scene_triangles: u32,
    /// Wide nodes' width (version 3); 0 in version 2, whose word 13 is reserved.
    pub width: u32,
}

impl Header {
    pub fn words(&self) -> [u32; HEADER_WORDS] {
        let f = |x: f32| x.to_bits();
        let (min, max) = self.root_box;
        [
            MAGIC,
            self.version,
            self.nodes,
            self.triangles,
            self.root.first,
            self.root.count,
            f(min[0]),
            f(min[1]),
            f(min[2]),
            f(max[0]),
            f(max[1]),
            f(max[2]),
            self.scene_triangles,
            self.width,
            0,
            0,
        ]
    }

    /// Reads and checks the header of a `version` image whose nodes take `node_words(width)`
    /// words each: magic, version, the stream's length, reserved words.
    pub fn read(
        w: &[u32],
        version: u32,
        node_words: impl Fn(u32) -> usize,
    ) -> Result<Header, SceneImageError> {
        if w.len() < HEADER_WORDS {
            return Err(SceneImageError::TooShort { words: w.len() });
        }
        if w[0] != MAGIC {
            return Err(SceneImageError::BadMagic { found: w[0] });
        }
        if w[1] != version {
            return Err(SceneImageError::BadVersion { found: w[1] });
        }
        let reserved_from = if version == VERSION { 13 } else { 14 };
        (reserved_from..HEADER_WORDS).try_for_each(|word| reserved(w, word))?;
        let width = if version == VERSION { 0 } else { w[13] };
        if version == VERSION_WIDE && !super::wide::WIDTHS.contains(&(width as usize)) {
            return Err(SceneImageError::BadWidth { width });
        }
        let (nodes, triangles) = (w[2], w[3]);
        let expected = HEADER_WORDS as u64
            + node_words(width) as u64 * u64::from(nodes)
            + TRIANGLE_WORDS as u64 * u64::from(triangles);
        if w.len() as u64 != expected {
            return Err(SceneImageError::SizeMismatch {
                words: w.len(),
                nodes,
                triangles,
                expected,
            });
        }
        let f = |i: usize| f32::from_bits(w[i]);
        let xyz = |i: usize| [f(i), f(i + 1), f(i + 2)];
        Ok(Header {
            version,
            nodes,
            triangles,
            root: Link {
                first: w[4],
                count: w[5],
            },
            root_box: (xyz(6), xyz(9)),
            scene_triangles: w[12],
            width,
        })
    }
}

/// Word `word` of `w` must be 0.
pub(crate) fn reserved(w: &[u32], word: usize) -> Result<(), SceneImageError> {
    match w[word] {
        0 => Ok(()),
        value => Err(SceneImageError::Reserved { word, value }),
    }
}

/// Appends the triangle records' words.
pub(crate) fn write_triangles(triangles: &[ImageTriangle], w: &mut Vec<u32>) {
    for t in triangles {
        w.extend(t.verts.iter().flatten().map(|&x| x.to_bits()));
        w.extend([t.index, u32::from(t.casts_shadow), 0]);
    }
}

/// `count` triangle records from word `at`, their flags and reserved words checked.
pub(crate) fn read_triangles(
    w: &[u32],
    at: usize,
    count: u32,
) -> Result<Vec<ImageTriangle>, SceneImageError> {
    (0..count as usize)
        .map(|k| {
            let i = at + TRIANGLE_WORDS * k;
            let f = |i: usize| f32::from_bits(w[i]);
            let xyz = |i: usize| [f(i), f(i + 1), f(i + 2)];
            if w[i + 10] & !CASTS_SHADOW != 0 {
                return Err(SceneImageError::UnknownFlags {
                    slot: k,
                    flags: w[i + 10],
                });
            }
            reserved(w, i + 11)?;
            Ok(ImageTriangle {
                verts: [xyz(i), xyz(i + 3), xyz(i + 6)],
                index: w[i + 9],
                casts_shadow: w[i + 10] & CASTS_SHADOW != 0,
            })
        })
        .collect()
}

/// The triangle records' global indices: below the scene's count, each once.
pub(crate) fn check_triangles(
    triangles: &[ImageTriangle],
    scene_triangles: u32,
) -> Result<(), SceneImageError> {
    let t = triangles.len() as u32;
    if t > scene_triangles {
        return Err(SceneImageError::MoreThanTheScene {
            triangles: t,
            scene_triangles,
        });
    }
    if let Some((slot, tri)) =
        (triangles.iter().enumerate()).find(|(_, tri)| tri.index >= scene_triangles)
    {
        return Err(SceneImageError::IndexOutOfRange {
            slot,
            index: tri.index,
            scene_triangles,
        });
    }
    // Sorted (index, slot) pairs, not a table of S entries: S is a word of the stream.
    let mut by_index: Vec<(u32, usize)> = (triangles.iter().enumerate())
        .map(|(slot, tri)| (tri.index, slot))
        .collect();
    by_index.sort_unstable();
    // The first slot (in record order) whose index an earlier record already has.
    if let Some((index, first, second)) = by_index
        .windows(2)
        .filter(|p| p[0].0 == p[1].0)
        .map(|p| (p[0].0, p[0].1, p[1].1))
        .min_by_key(|&(_, _, second)| second)
    {
        return Err(SceneImageError::DuplicateIndex {
            index,
            first,
            second,
        });
    }
    Ok(())
}

/// Every link reached from `root` in range (a node below `nodes`, a leaf within `triangles`
/// records) and no node reached twice (so no cycle); an empty scene has no root. `children`
/// lists a node's links.
pub(crate) fn check_links(
    root: Link,
    triangles: u32,
    nodes: u32,
    children: impl Fn(u32) -> Vec<Link>,
) -> Result<(), SceneImageError> {
    if triangles == 0 {
        // An empty scene: nothing to walk, and no node may claim otherwise.
        return match (nodes, root) {
            (0, Link { first: 0, count: 0 }) => Ok(()),
            _ => Err(SceneImageError::LeafOutOfRange {
                from: "the root of an empty scene".into(),
                first: root.first,
                count: root.count,
                triangles: 0,
            }),
        };
    }
    let mut reached = vec![false; nodes as usize];
    let mut todo = vec![("the root".to_string(), root)];
    while let Some((from, link)) = todo.pop() {
        if link.is_leaf() {
            if u64::from(link.first) + u64::from(link.count) > u64::from(triangles) {
                return Err(SceneImageError::LeafOutOfRange {
                    from,
                    first: link.first,
                    count: link.count,
                    triangles,
                });
            }
            continue;
        }
        let node = link.first;
        let seen =
            reached
                .get_mut(node as usize)
                .ok_or_else(|| SceneImageError::NodeOutOfRange {
                    from: from.clone(),
                    first: node,
                    nodes,
                })?;
        if *seen {
            return Err(SceneImageError::ReachedTwice { from, node });
        }
        *seen = true;
        for (c, child) in children(node).into_iter().enumerate() {
            todo.push((format!("node {node} child {c}"), child));
        }
    }
    Ok(())
}

/// A scene image of either version, as the unit loads it.
#[derive(Clone, Debug, PartialEq)]
pub enum UnitImage {
    Binary(SceneImage),
    Wide(super::wide::image::WideImage),
}

impl UnitImage {
    /// Reads and checks a word stream of either version.
    pub fn from_words(w: &[u32]) -> Result<UnitImage, SceneImageError> {
        match w.get(1) {
            Some(&VERSION_WIDE) if w.first() == Some(&MAGIC) => Ok(UnitImage::Wide(
                super::wide::image::WideImage::from_words(w)?,
            )),
            _ => Ok(UnitImage::Binary(SceneImage::from_words(w)?)),
        }
    }

    pub fn to_words(&self) -> Vec<u32> {
        match self {
            UnitImage::Binary(i) => i.to_words(),
            UnitImage::Wide(i) => i.to_words(),
        }
    }

    pub fn triangles(&self) -> &[ImageTriangle] {
        match self {
            UnitImage::Binary(i) => &i.triangles,
            UnitImage::Wide(i) => &i.triangles,
        }
    }

    /// Inner nodes held.
    pub fn nodes(&self) -> usize {
        match self {
            UnitImage::Binary(i) => i.nodes.len(),
            UnitImage::Wide(i) => i.tree.nodes.len(),
        }
    }

    /// Inner nodes on the longest path from the root to a leaf.
    pub fn depth(&self) -> usize {
        match self {
            UnitImage::Binary(i) => i.depth(),
            UnitImage::Wide(i) => i.depth(),
        }
    }

    /// The image's size in bytes (as loaded).
    pub fn bytes(&self) -> usize {
        match self {
            UnitImage::Binary(i) => i.bytes(),
            UnitImage::Wide(i) => i.bytes(),
        }
    }
}

impl From<SceneImage> for UnitImage {
    fn from(i: SceneImage) -> UnitImage {
        UnitImage::Binary(i)
    }
}

impl From<super::wide::image::WideImage> for UnitImage {
    fn from(i: super::wide::image::WideImage) -> UnitImage {
        UnitImage::Wide(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sw_renderer::scene::Scene;

    fn image(name: &str) -> SceneImage {
        let scene = Scene::load(name).unwrap();
        SceneImage::new(&PreparedScene::new(&scene).unwrap())
    }

    #[test]
    fn the_image_of_a_scene_round_trips_through_its_words() {
        let img = image("glasses");
        let words = img.to_words();
        assert_eq!(words.len(), img.words());
        assert_eq!(SceneImage::from_words(&words).unwrap(), img);
        assert!(img.nodes.len() > 10 && img.depth() >= 4);
        // Every global index once, and shadow flags as the scene says.
        let mut idx: Vec<u32> = img.triangles.iter().map(|t| t.index).collect();
        idx.sort_unstable();
        assert!(idx.iter().enumerate().all(|(k, &i)| k as u32 == i));
    }

    fn reject(words: &[u32]) -> String {
        SceneImage::from_words(words).unwrap_err().to_string()
    }

    #[test]
    fn damaged_images_are_refused_naming_what_is_wrong() {
        let img = image("simple_plane");
        let good = img.to_words();
        assert!(reject(&good[..5]).contains("shorter than its 16-word header"));
        let mut w = good.clone();
        w[0] ^= 1;
        assert!(reject(&w).contains("magic"));
        let mut w = good.clone();
        w[1] = 7;
        assert!(reject(&w).contains("version 7"));
        let mut w = good.clone();
        w.push(0);
        assert!(reject(&w).contains("need"), "{}", reject(&w));
        let mut w = good.clone();
        w[13] = 5;
        assert!(reject(&w).contains("word 13: reserved"));
        let t0 = HEADER_WORDS + NODE_WORDS * img.nodes.len();
        let mut w = good.clone();
        w[t0 + 10] = 2;
        assert!(reject(&w).contains("flags 0x2"));
        let mut w = good.clone();
        w[t0 + 9] = 1_000_000;
        assert!(reject(&w).contains("global index 1000000"));
        let mut w = good.clone();
        w[t0 + 9] = w[t0 + TRIANGLE_WORDS + 9];
        assert!(reject(&w).contains("both have global index"));
        let mut w = good.clone();
        w[12] = 1;
        assert!(reject(&w).contains("2 triangle records, but the scene has only 1"));
    }

    /// A chunk keeps its scene's global indices: they may reach beyond its own records, up
    /// to the scene's count in word 12 (which the loader never allocates by).
    #[test]
    fn a_chunk_holds_global_indices_below_its_scenes_count() {
        let mut img = small();
        img.scene_triangles = 1000;
        img.triangles[0].index = 999;
        let w = img.to_words();
        assert_eq!(w[12], 1000);
        assert_eq!(SceneImage::from_words(&w).unwrap(), img);
        img.triangles[1].index = 1000;
        assert!(reject(&img.to_words())
            .contains("triangle record 1 has global index 1000, but the scene has 1000 triangles"));
        let mut img = small();
        img.scene_triangles = u32::MAX;
        img.triangles[2].index = u32::MAX - 1;
        img.triangles[1].index = u32::MAX - 1;
        assert!(reject(&img.to_words())
            .contains("triangle records 1 and 2 both have global index 4294967294"));
    }

    /// A hand-made image: root → node 0 → (node 1, leaf 0..1), node 1 → (leaf 1..2, leaf 2..3).
    fn small() -> SceneImage {
        let tri = |index| ImageTriangle {
            verts: [[0.0; 3]; 3],
            index,
            casts_shadow: true,
        };
        let leaf = |first| Link { first, count: 1 };
        SceneImage {
            root: Link { first: 0, count: 0 },
            root_box: ([0.0; 3], [1.0; 3]),
            nodes: vec![
                ImageNode {
                    boxes: ChildBoxes::default(),
                    child: [Link { first: 1, count: 0 }, leaf(0)],
                },
                ImageNode {
                    boxes: ChildBoxes::default(),
                    child: [leaf(1), leaf(2)],
                },
            ],
            triangles: vec![tri(2), tri(0), tri(1)],
            scene_triangles: 3,
        }
    }

    #[test]
    fn links_out_of_range_and_cycles_are_refused() {
        assert_eq!(small().check(), Ok(()));
        assert_eq!(small().depth(), 2);
        let mut img = small();
        img.nodes[1].child[1] = Link { first: 9, count: 0 };
        assert!(reject(&img.to_words())
            .contains("node 1 child 1 links to inner node 9, but there are 2 nodes"));
        let mut img = small();
        img.nodes[1].child[0] = Link { first: 2, count: 2 };
        assert!(reject(&img.to_words()).contains("node 1 child 0 links to triangles 2..2+2"));
        let mut img = small();
        img.nodes[1].child[0] = Link {
            first: u32::MAX,
            count: 2,
        };
        assert!(reject(&img.to_words()).contains("but there are 3 triangles"));
        let mut img = small();
        img.nodes[1].child[1] = Link { first: 0, count: 0 };
        assert!(reject(&img.to_words()).contains("links to node 0 again"));
        let mut img = small();
        img.nodes[1].child[1] = Link { first: 1, count: 0 };
        assert!(reject(&img.to_words()).contains("node 1 child 1 links to node 1 again"));
        let mut img = small();
        img.root = Link { first: 2, count: 0 };
        assert!(reject(&img.to_words()).contains("the root links to inner node 2"));
    }

    #[test]
    fn an_empty_scene_has_an_empty_image() {
        let img = SceneImage {
            root: Link::default(),
            root_box: ([0.0; 3], [0.0; 3]),
            nodes: vec![],
            triangles: vec![],
            scene_triangles: 0,
        };
        assert_eq!(SceneImage::from_words(&img.to_words()).unwrap(), img);
        let mut bad = img.to_words();
        bad[5] = 1;
        assert!(reject(&bad).contains("empty scene"));
    }
}
