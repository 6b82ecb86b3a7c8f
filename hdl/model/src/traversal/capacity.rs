//! The unit's scene memory has a capacity; a scene larger than it renders by chunked passes.
//!
//! A chunk is a subtree of the scene's BVH that fits the memory, written as a self-contained
//! scene image (its own header, nodes and triangle records, the global triangle indices
//! kept, its root box the one its parent stored). [`chunks`] splits greedily from the root:
//! a subtree that fits is one chunk, a larger inner node is split into its children, in
//! depth-first order (child 0 first). A leaf larger than the memory cannot be split.
//!
//! Each pass loads one chunk and runs every ray that still needs it, with what it found so
//! far carried over ([`Carry`]): a closest-hit ray's t_max becomes `remaining_bound` of its
//! nearest hit (`t.next_up()`), exactly the far end the unchunked walk culls with, so a hit
//! as near in a later chunk with a lower global index still wins; the answers are folded by
//! the reference's reduction (`hit::nearer`). An any-hit ray leaves after its first
//! counting hit. So closest hits are the unchunked unit's bit for bit, and occlusion is the
//! same (which occluder answers may differ; the renderer only asks whether there is one).
//!
//! Every ray visits every chunk: the walk of a chunk starts with its root box, so a ray that
//! misses a chunk, or reaches it only beyond its nearest hit so far, costs one box test in
//! that pass. That is the simplest sound design; its price is the ray's trip to every chunk
//! (the ARM packs and folds it once per pass), which the projection measures as most of what
//! chunking costs (BENCHMARKS.md). A top-level tree of chunk boxes walked per ray would keep
//! rays from chunks they cannot need, at the price of a second walk and per-ray routing.

use std::fmt;

use super::scene_image::{ImageNode, Link, SceneImage, SceneImageError};
use sw_renderer::hit::{nearer, remaining_bound, Hit};
use sw_renderer::rays::CastStats;
use thiserror::Error;

use super::wide::collapse;
use super::{NodeFormat, TraversalError, TraversalModel, UnitCounters, UnitRay};
use crate::format::Format;
use crate::Advance;

/// What the unit's scene memory holds: inner nodes and triangle records.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneCapacity {
    pub nodes: u32,
    pub triangles: u32,
}

impl SceneCapacity {
    /// What `image` needs.
    pub fn of(image: &SceneImage) -> SceneCapacity {
        SceneCapacity {
            nodes: image.nodes.len() as u32,
            triangles: image.triangles.len() as u32,
        }
    }

    pub fn holds(self, need: SceneCapacity) -> bool {
        need.nodes <= self.nodes && need.triangles <= self.triangles
    }
}

impl fmt::Display for SceneCapacity {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "{} nodes and {} triangles",
            thousands(self.nodes),
            thousands(self.triangles)
        )
    }
}

/// `3876` as "3,876".
fn thousands(n: u32) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// How the unit's scene memory takes a scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneMemory {
    /// Any scene fits (until the RTL's capacity is known).
    #[default]
    Unbounded,
    /// A scene must fit whole (chunked passes disabled).
    Whole(SceneCapacity),
    /// A scene that does not fit renders by chunked passes.
    Chunked(SceneCapacity),
}

/// A scene this unit cannot render.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("scene needs {need}; this unit holds {holds}; {why}")]
pub struct CapacityError {
    pub need: SceneCapacity,
    pub holds: SceneCapacity,
    pub why: Why,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Why {
    ChunkingDisabled,
    /// A BVH leaf of this many triangles: no chunk holds it.
    LeafTooLarge(u32),
}

impl fmt::Display for Why {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Why::ChunkingDisabled => write!(f, "chunked passes are disabled"),
            Why::LeafTooLarge(n) => write!(
                f,
                "its BVH has a leaf of {} triangles, so no split into chunks fits",
                thousands(*n)
            ),
        }
    }
}

/// What the binary image (or subtree) `image` needs when the unit holds it in `nodes`: its
/// triangles, and its binary nodes or the wide nodes it collapses to.
pub fn needs(image: &SceneImage, nodes: NodeFormat) -> SceneCapacity {
    match nodes.width() {
        None => SceneCapacity::of(image),
        Some(width) => SceneCapacity {
            nodes: collapse(image, width).map_or(u32::MAX, |t| t.nodes.len() as u32),
            triangles: image.triangles.len() as u32,
        },
    }
}

/// The scene images the unit loads for `image` when it holds trees in `nodes`: the image
/// itself if it fits (or the memory is unbounded), else its chunks in depth-first order.
pub fn chunks(
    image: &SceneImage,
    memory: SceneMemory,
    nodes: NodeFormat,
) -> Result<Vec<SceneImage>, CapacityError> {
    let need = needs(image, nodes);
    let holds = match memory {
        SceneMemory::Unbounded => return Ok(vec![image.clone()]),
        SceneMemory::Whole(c) | SceneMemory::Chunked(c) if c.holds(need) => {
            return Ok(vec![image.clone()])
        }
        SceneMemory::Whole(holds) => {
            return Err(CapacityError {
                need,
                holds,
                why: Why::ChunkingDisabled,
            })
        }
        SceneMemory::Chunked(holds) => holds,
    };
    let subtree = subtree_needs(image);
    let need_of = |link: Link, root_box| match (link.is_leaf(), nodes.width()) {
        (true, None) => SceneCapacity {
            nodes: 0,
            triangles: link.count,
        },
        (false, None) => subtree[link.first as usize],
        // Wide nodes: what the subtree collapses to (a leaf alone gets a node).
        (_, Some(_)) => needs(&extract(image, link, root_box), nodes),
    };
    let mut out = Vec::new();
    let mut todo = vec![(image.root, image.root_box)];
    while let Some((link, root_box)) = todo.pop() {
        if holds.holds(need_of(link, root_box)) {
            out.push(extract(image, link, root_box));
        } else if link.is_leaf() {
            return Err(CapacityError {
                need,
                holds,
                why: Why::LeafTooLarge(link.count),
            });
        } else {
            let node = &image.nodes[link.first as usize];
            let b = &node.boxes;
            let child_box = |c: usize| (b.min.map(|a| a[c]), b.max.map(|a| a[c]));
            // Child 1 below child 0: chunks come in depth-first order.
            todo.push((node.child[1], child_box(1)));
            todo.push((node.child[0], child_box(0)));
        }
    }
    Ok(out)
}

/// For every inner node reachable from the root, what its subtree needs. Without recursion:
/// a checked image may be deeper than the thread's stack.
fn subtree_needs(image: &SceneImage) -> Vec<SceneCapacity> {
    let mut preorder = Vec::new();
    let mut todo = vec![image.root];
    while let Some(link) = todo.pop() {
        if !link.is_leaf() && !image.triangles.is_empty() {
            preorder.push(link.first as usize);
            todo.extend(image.nodes[link.first as usize].child);
        }
    }
    let mut need = vec![SceneCapacity::default(); image.nodes.len()];
    // Children come after their parent in preorder.
    for &k in preorder.iter().rev() {
        let mut n = SceneCapacity {
            nodes: 1,
            triangles: 0,
        };
        for c in image.nodes[k].child {
            let (nodes, triangles) = match c.is_leaf() {
                true => (0, c.count),
                false => (
                    need[c.first as usize].nodes,
                    need[c.first as usize].triangles,
                ),
            };
            n.nodes += nodes;
            n.triangles += triangles;
        }
        need[k] = n;
    }
    need
}

/// The subtree at `root` as a self-contained image: nodes renumbered in depth-first order,
/// triangle records in leaf order, global indices and the scene's triangle count kept.
fn extract(image: &SceneImage, root: Link, root_box: ([f32; 3], [f32; 3])) -> SceneImage {
    let mut nodes: Vec<ImageNode> = Vec::new();
    let mut triangles = Vec::new();
    let mut new_root = Link::default();
    // (link in the scene, where its new link goes: the root, or a node's child slot)
    let mut todo = vec![(root, None::<(usize, usize)>)];
    while let Some((link, parent)) = todo.pop() {
        let new = if link.is_leaf() {
            let first = triangles.len() as u32;
            let leaf = link.first as usize..(link.first + link.count) as usize;
            triangles.extend_from_slice(&image.triangles[leaf]);
            Link {
                first,
                count: link.count,
            }
        } else {
            let node = &image.nodes[link.first as usize];
            let k = nodes.len();
            nodes.push(ImageNode {
                boxes: node.boxes,
                child: [Link::default(); 2],
            });
            todo.push((node.child[1], Some((k, 1))));
            todo.push((node.child[0], Some((k, 0))));
            Link {
                first: k as u32,
                count: 0,
            }
        };
        match parent {
            Some((k, c)) => nodes[k].child[c] = new,
            None => new_root = new,
        }
    }
    SceneImage {
        root: new_root,
        root_box,
        nodes,
        triangles,
        scene_triangles: image.scene_triangles,
    }
}

/// What a ray carries from pass to pass.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Carry {
    best: Option<Hit>,
    /// An any-hit ray with its answer.
    occluded: bool,
}

impl Carry {
    /// `ray` as the next pass sends it, `None` once it has its answer: a closest-hit ray
    /// bounded by `remaining_bound` of its nearest hit so far.
    fn next(&self, ray: &UnitRay) -> Option<UnitRay> {
        (!self.occluded).then(|| UnitRay {
            t_max: remaining_bound(self.best, ray.t_max),
            ..*ray
        })
    }

    fn fold(&mut self, ray: &UnitRay, hit: Option<Hit>) {
        self.occluded = ray.any_hit && hit.is_some();
        self.best = nearer(self.best, hit);
    }
}

/// The chunked passes of one wavefront: the one pass loop of every unit engine (the model's
/// and the Verilated unit's). Pass `k` (one per entry of `chunk_bytes`, the loaded chunk
/// images' sizes) sends the rays that still need it, each with what it carries, to
/// `pass(k, rays, answers)`, which answers them in order; `hits` gets every ray's folded
/// answer. Returns the passes, chunk loads and loaded bytes (no loads while one chunk, the
/// whole scene, stays resident).
pub fn run_passes<E>(
    chunk_bytes: &[u64],
    rays: &[UnitRay],
    hits: &mut [Option<Hit>],
    mut pass: impl FnMut(usize, &[UnitRay], &mut [Option<Hit>]) -> Result<(), E>,
) -> Result<CastStats, E> {
    assert_eq!(rays.len(), hits.len(), "one answer per ray");
    let mut carry = vec![Carry::default(); rays.len()];
    let mut stats = CastStats::default();
    let (mut sent, mut index, mut answers) = (Vec::new(), Vec::new(), Vec::new());
    for (k, &bytes) in chunk_bytes.iter().enumerate() {
        sent.clear();
        index.clear();
        for (i, (ray, c)) in rays.iter().zip(&carry).enumerate() {
            if let Some(r) = c.next(ray) {
                sent.push(r);
                index.push(i);
            }
        }
        if sent.is_empty() {
            break;
        }
        stats.passes += 1;
        if chunk_bytes.len() > 1 {
            stats.chunk_loads += 1;
            stats.loaded_bytes += bytes;
        }
        answers.clear();
        answers.resize(sent.len(), None);
        pass(k, &sent, &mut answers)?;
        for (&i, &hit) in index.iter().zip(&answers) {
            carry[i].fold(&rays[i], hit);
        }
    }
    for (hit, c) in hits.iter_mut().zip(&carry) {
        *hit = c.best;
    }
    Ok(stats)
}

/// The unit with a scene in chunks (one chunk: the scene resident).
#[derive(Clone, Debug)]
pub struct ChunkedModel {
    chunks: Vec<TraversalModel>,
}

impl ChunkedModel {
    /// `image` split for `memory`, each chunk loaded through its word stream (the loader's
    /// checks run on what the unit would load), walked in `format` with `stack_depth` entries
    /// and Möller-Trumbore queries scaled by 2^`scale_exp`.
    pub fn new(
        format: Format,
        stack_depth: usize,
        scale_exp: i32,
        image: &SceneImage,
        memory: SceneMemory,
        nodes: NodeFormat,
    ) -> Result<ChunkedModel, sw_renderer::rays::EngineError> {
        let chunks = chunks(image, memory, nodes)?
            .iter()
            .map(|c| {
                let loaded = SceneImage::from_words(&c.to_words())?;
                TraversalModel::new(format, stack_depth, loaded)
                    .scaled(scale_exp)
                    .with_nodes(nodes)
            })
            .collect::<Result<_, SceneImageError>>()?;
        Ok(ChunkedModel { chunks })
    }

    /// Every chunk starting its Möller-Trumbore queries where `advance` says
    /// ([`TraversalModel::advanced`]).
    pub fn advanced(self, advance: Advance) -> ChunkedModel {
        let chunks = self.chunks.into_iter().map(|c| c.advanced(advance));
        ChunkedModel {
            chunks: chunks.collect(),
        }
    }

    pub fn chunks(&self) -> &[TraversalModel] {
        &self.chunks
    }

    /// The sizes of the chunk images, as [`run_passes`] takes them.
    pub fn chunk_bytes(&self) -> Vec<u64> {
        (self.chunks.iter())
            .map(|c| c.image().bytes() as u64)
            .collect()
    }

    /// The answer to `ray` after every pass.
    pub fn trace(
        &self,
        ray: &UnitRay,
        counters: &mut UnitCounters,
    ) -> Result<Option<Hit>, TraversalError> {
        let mut hit = [None];
        run_passes(
            &self.chunk_bytes(),
            std::slice::from_ref(ray),
            &mut hit,
            |k, rays, answers| {
                for (r, a) in rays.iter().zip(answers) {
                    *a = self.chunks[k].walk(r, counters, &mut |_| {})?;
                }
                Ok(())
            },
        )?;
        Ok(hit[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_print_with_thousands_separators() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(3876), "3,876");
        assert_eq!(thousands(1_261_760), "1,261,760");
        let c = SceneCapacity {
            nodes: 2048,
            triangles: 4096,
        };
        assert_eq!(c.to_string(), "2,048 nodes and 4,096 triangles");
    }
}
