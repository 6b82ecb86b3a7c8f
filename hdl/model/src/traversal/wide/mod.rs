//! Wide nodes with quantized child boxes: the compressed BVH the traversal unit walks by
//! default (docs/scene-image.md "Wide nodes").
//!
//! A wide node holds up to `width` children (2, 4 or 8). Their boxes are stored on the node's
//! own grid: an fp32 origin `p` and a power-of-two step `2^e` per axis, and per child and
//! axis two 8-bit codes, so that the child's box is `[p + lo·2^e, p + hi·2^e]` in real
//! numbers. The writer ([`collapse`]) builds the wide tree from the binary BVH's scene image
//! (the binned-SAH tree): each wide node takes a binary node's two children and repeatedly
//! opens the inner child of largest surface area (the one a ray is likeliest to enter, so
//! the one whose box test a wider node saves most often) until it has `width` children;
//! boxes are quantized outward, so every quantized box encloses the binary BVH's padded box.
//! Leaves keep their triangle records (in the same order); a leaf longer than
//! [`MAX_LEAF_TRIANGLES`] (only a degenerate cluster the binary build could not split) is
//! split into a subtree of short leaves.
//!
//! [`check`] is the loader's part: every child's quantized box must enclose the padded
//! bounds of every triangle under it, exactly, since the box test's soundness rests on it.

pub mod box_test;
#[cfg(feature = "strategies")]
pub mod cases;
pub mod image;

use super::scene_image::{ImageTriangle, Link, SceneImage};
use num_bigint::BigInt;
use sw_renderer::bvh::padded_bounds;
use thiserror::Error;

/// Children a wide node may have: the widths the unit is built for.
pub const WIDTHS: [usize; 3] = [2, 4, 8];

/// How the scene memory stores the tree's inner nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NodeFormat {
    /// The binary BVH, both children's boxes in fp32 (64 bytes a node), tested in fp32.
    Bvh2Fp32,
    /// Wide nodes of 2, 4 or 8 children with 8-bit quantized boxes.
    Bvh2Q8,
    Bvh4Q8,
    Bvh8Q8,
}

impl NodeFormat {
    pub const ALL: [NodeFormat; 4] = [
        NodeFormat::Bvh2Fp32,
        NodeFormat::Bvh2Q8,
        NodeFormat::Bvh4Q8,
        NodeFormat::Bvh8Q8,
    ];

    pub fn name(self) -> &'static str {
        match self {
            NodeFormat::Bvh2Fp32 => "bvh2-fp32",
            NodeFormat::Bvh2Q8 => "bvh2-q8",
            NodeFormat::Bvh4Q8 => "bvh4-q8",
            NodeFormat::Bvh8Q8 => "bvh8-q8",
        }
    }

    /// Children per wide node, or `None` for the binary fp32 nodes.
    pub fn width(self) -> Option<usize> {
        match self {
            NodeFormat::Bvh2Fp32 => None,
            NodeFormat::Bvh2Q8 => Some(2),
            NodeFormat::Bvh4Q8 => Some(4),
            NodeFormat::Bvh8Q8 => Some(8),
        }
    }
}

named_choice!(NodeFormat, "node format");
/// The longest leaf a wide node's link holds (its count field is 4 bits).
pub const MAX_LEAF_TRIANGLES: u32 = 15;
/// The smallest and largest grid exponents a node stores (an i8).
const EXP_RANGE: std::ops::RangeInclusive<i32> = -128..=127;

/// A child of a wide node: its box on the node's grid, and what it links to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Child {
    /// Grid codes of the box's lower and upper planes per axis (`lo ≤ hi`).
    pub lo: [u8; 3],
    pub hi: [u8; 3],
    pub link: Link,
}

/// A wide node: what one box test reads.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WideNode {
    /// The grid's origin per axis (fp32).
    pub origin: [f32; 3],
    /// The grid's step per axis is `2^exp`.
    pub exp: [i8; 3],
    /// 1 to `width` children.
    pub children: Vec<Child>,
}

/// A wide tree over a scene image's triangle records.
#[derive(Clone, Debug, PartialEq)]
pub struct WideTree {
    pub width: usize,
    /// The root node (node 0), or for a scene without triangles an empty leaf.
    pub root: Link,
    pub nodes: Vec<WideNode>,
}

/// Why a tree cannot be written or loaded.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum WideError {
    #[error("wide nodes of {0} children: the unit is built for {WIDTHS:?}")]
    Width(usize),
    #[error(
        "triangle record {slot} has a non-finite vertex coordinate: its box cannot be quantized"
    )]
    NonFinite { slot: usize },
    #[error("node {node} child {child}: its quantized box [{lo}, {hi}] on axis {axis} does not enclose the padded bounds [{min}, {max}] of the triangles under it")]
    NotEnclosed {
        node: usize,
        child: usize,
        axis: usize,
        lo: f64,
        hi: f64,
        min: f32,
        max: f32,
    },
    #[error("node {node} child {child}: codes {lo} > {hi} on axis {axis}")]
    Inverted {
        node: usize,
        child: usize,
        axis: usize,
        lo: u8,
        hi: u8,
    },
    #[error("node {node} has {children} children; a node of this tree has 1 to {width}")]
    Children {
        node: usize,
        children: usize,
        width: usize,
    },
    #[error("node {node} child {child}: a leaf of {count} triangles; a wide node's leaf holds 1 to {MAX_LEAF_TRIANGLES}")]
    LongLeaf {
        node: usize,
        child: usize,
        count: u32,
    },
}

/// An axis-aligned box in f32.
type Bounds = ([f32; 3], [f32; 3]);

fn union(a: Bounds, b: Bounds) -> Bounds {
    (
        std::array::from_fn(|i| a.0[i].min(b.0[i])),
        std::array::from_fn(|i| a.1[i].max(b.1[i])),
    )
}

fn area((min, max): Bounds) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|a| f64::from(max[a]) - f64::from(min[a]));
    2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
}

/// The padded bounds of `triangles` as the binary BVH pads a leaf (`bvh::padded_bounds`).
pub fn leaf_bounds(triangles: &[ImageTriangle]) -> Bounds {
    let mut b = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for t in triangles {
        for v in t.verts {
            b = union(b, (v, v));
        }
    }
    padded_bounds(b.0, b.1)
}

/// The binary image's view while collapsing: a subtree and its padded box.
#[derive(Clone, Copy)]
struct Candidate {
    link: Link,
    bounds: Bounds,
}

/// The wide tree of `width` children per node over `image`'s binary BVH, its triangle records
/// unchanged. Nodes are numbered depth first, the root 0.
pub fn collapse(image: &SceneImage, width: usize) -> Result<WideTree, WideError> {
    if !WIDTHS.contains(&width) {
        return Err(WideError::Width(width));
    }
    if let Some(slot) =
        (image.triangles.iter()).position(|t| t.verts.iter().flatten().any(|x| !x.is_finite()))
    {
        return Err(WideError::NonFinite { slot });
    }
    let mut tree = WideTree {
        width,
        root: Link::default(),
        nodes: Vec::new(),
    };
    if image.triangles.is_empty() {
        return Ok(tree);
    }
    let root = Candidate {
        link: image.root,
        bounds: image.root_box,
    };
    // A root that is a leaf still gets a node: a ray's first step is always a box test.
    let top = if image.root.is_leaf() {
        vec![root]
    } else {
        open(image, root)
    };
    tree.root = Link { first: 0, count: 0 };
    build(image, &mut tree, top);
    Ok(tree)
}

/// The two children of the binary inner node `c` links to.
fn open(image: &SceneImage, c: Candidate) -> Vec<Candidate> {
    let node = &image.nodes[c.link.first as usize];
    (0..2)
        .map(|k| Candidate {
            link: node.child[k],
            bounds: (
                std::array::from_fn(|a| node.boxes.min[a][k]),
                std::array::from_fn(|a| node.boxes.max[a][k]),
            ),
        })
        .collect()
}

/// Appends the wide node over `children` (binary subtrees, opened further up to the tree's
/// width) and its descendants; returns its index.
fn build(image: &SceneImage, tree: &mut WideTree, mut children: Vec<Candidate>) -> u32 {
    while children.len() < tree.width {
        let widest = (children.iter().enumerate())
            .filter(|(_, c)| !c.link.is_leaf())
            .max_by(|(_, a), (_, b)| area(a.bounds).total_cmp(&area(b.bounds)));
        let Some((k, _)) = widest else { break };
        let c = children.remove(k);
        children.splice(k..k, open(image, c));
    }
    let index = tree.nodes.len();
    tree.nodes.push(WideNode::default());
    let bounds = children.iter().map(|c| c.bounds).reduce(union).unwrap();
    let grid = Grid::new(bounds);
    let mut node = WideNode {
        origin: grid.origin,
        exp: grid.exp.map(|e| e as i8),
        children: Vec::with_capacity(children.len()),
    };
    for c in children {
        let link = if c.link.is_leaf() {
            if c.link.count > MAX_LEAF_TRIANGLES {
                Link {
                    first: split_leaf(image, tree, c.link),
                    count: 0,
                }
            } else {
                c.link
            }
        } else {
            Link {
                first: build(image, tree, open(image, c)),
                count: 0,
            }
        };
        let (lo, hi) = grid.quantize(c.bounds);
        node.children.push(Child { lo, hi, link });
    }
    tree.nodes[index] = node;
    index as u32
}

/// A leaf too long for a link, as a subtree of short leaves over its records in order
/// (their boxes the padded bounds of their triangles); returns the subtree's node.
fn split_leaf(image: &SceneImage, tree: &mut WideTree, leaf: Link) -> u32 {
    let (first, count) = (leaf.first, leaf.count);
    let parts = tree.width as u32;
    let part = count.div_ceil(parts).max(1);
    let children = (0..parts)
        .map(|k| (first + k * part, part.min(count.saturating_sub(k * part))))
        .filter(|&(_, n)| n > 0)
        .map(|(first, count)| Candidate {
            link: Link { first, count },
            bounds: leaf_bounds(&image.triangles[first as usize..(first + count) as usize]),
        })
        .collect();
    build(image, tree, children)
}

/// A node's grid: origin and exponent per axis, with exact quantization.
struct Grid {
    origin: [f32; 3],
    exp: [i32; 3],
}

/// Scale at which every f32 and every grid plane `q·2^e` (`e ≥ −128`) is an integer.
const SCALE: u32 = 160;

/// `x · 2^SCALE` exactly.
fn exact(x: f32) -> BigInt {
    let b = x.to_bits();
    let e = ((b >> 23) & 0xFF) as i32;
    let m = i64::from(if e == 0 {
        b & 0x7F_FFFF
    } else {
        b & 0x7F_FFFF | 0x80_0000
    });
    let m = if b >> 31 == 1 { -m } else { m };
    let shift = e.max(1) - 150 + SCALE as i32;
    BigInt::from(m) << shift as usize
}

/// `2^(e + SCALE)`.
fn step(e: i32) -> BigInt {
    BigInt::from(1) << (e + SCALE as i32) as usize
}

/// `floor(n / d)` and `ceil(n / d)` for `d > 0`.
fn floor_div(n: &BigInt, d: &BigInt) -> BigInt {
    let q = n / d;
    if n.sign() == num_bigint::Sign::Minus && &q * d != *n {
        q - 1
    } else {
        q
    }
}

fn ceil_div(n: &BigInt, d: &BigInt) -> BigInt {
    -floor_div(&-n, d)
}

impl Grid {
    /// The grid of `bounds`: its lower corner, and per axis the finest step whose 255 steps
    /// reach its upper corner.
    fn new((min, max): Bounds) -> Grid {
        let exp = std::array::from_fn(|a| {
            let extent = exact(max[a]) - exact(min[a]);
            let reaches = |e: i32| step(e) * 255 >= extent;
            let mut e = *EXP_RANGE.start();
            // Bisect on the integer exponent: `reaches` is monotone.
            let mut hi = *EXP_RANGE.end();
            while e < hi {
                let mid = (e + hi).div_euclid(2);
                if reaches(mid) {
                    hi = mid;
                } else {
                    e = mid + 1;
                }
            }
            e
        });
        Grid { origin: min, exp }
    }

    /// The codes of `bounds` rounded outward onto the grid.
    fn quantize(&self, (min, max): Bounds) -> ([u8; 3], [u8; 3]) {
        let code = |v: BigInt| -> u8 { u8::try_from(v).expect("within the grid") };
        let lo = std::array::from_fn(|a| {
            code(floor_div(
                &(exact(min[a]) - exact(self.origin[a])),
                &step(self.exp[a]),
            ))
        });
        let hi = std::array::from_fn(|a| {
            code(ceil_div(
                &(exact(max[a]) - exact(self.origin[a])),
                &step(self.exp[a]),
            ))
        });
        (lo, hi)
    }
}

/// Whether the real box of `child` on `node`'s grid encloses `bounds`, per axis: the first
/// axis where it does not.
fn not_enclosed(node: &WideNode, child: &Child, (min, max): Bounds) -> Option<usize> {
    (0..3).find(|&a| {
        let p = exact(node.origin[a]);
        let s = step(i32::from(node.exp[a]));
        let lo = &p + &s * child.lo[a];
        let hi = &p + &s * child.hi[a];
        lo > exact(min[a]) || hi < exact(max[a])
    })
}

/// The loader's checks of a tree whose links are already known to be in range and acyclic
/// (`SceneImage::check`): 1 to `width` children a node, codes in order, leaves no longer
/// than [`MAX_LEAF_TRIANGLES`], and every child's box enclosing the padded bounds of the
/// triangles under it.
pub fn check(tree: &WideTree, triangles: &[ImageTriangle]) -> Result<(), WideError> {
    if triangles.is_empty() {
        return Ok(());
    }
    // Post-order: the bounds under each node, children before parents.
    let mut under: Vec<Option<Bounds>> = vec![None; tree.nodes.len()];
    let mut todo = vec![(tree.root.first as usize, false)];
    while let Some((n, children_done)) = todo.pop() {
        let node = &tree.nodes[n];
        if !children_done {
            if !(1..=tree.width).contains(&node.children.len()) {
                return Err(WideError::Children {
                    node: n,
                    children: node.children.len(),
                    width: tree.width,
                });
            }
            todo.push((n, true));
            todo.extend(
                (node.children.iter())
                    .filter(|c| !c.link.is_leaf())
                    .map(|c| (c.link.first as usize, false)),
            );
            continue;
        }
        let mut all: Option<Bounds> = None;
        for (k, c) in node.children.iter().enumerate() {
            if let Some(axis) = (0..3).find(|&a| c.lo[a] > c.hi[a]) {
                return Err(WideError::Inverted {
                    node: n,
                    child: k,
                    axis,
                    lo: c.lo[axis],
                    hi: c.hi[axis],
                });
            }
            let bounds = if c.link.is_leaf() {
                if c.link.count > MAX_LEAF_TRIANGLES {
                    return Err(WideError::LongLeaf {
                        node: n,
                        child: k,
                        count: c.link.count,
                    });
                }
                let range = c.link.first as usize..(c.link.first + c.link.count) as usize;
                leaf_bounds(&triangles[range])
            } else {
                under[c.link.first as usize].expect("children first")
            };
            if let Some(axis) = not_enclosed(node, c, bounds) {
                let (lo, hi) = box_test::child_box(node, c);
                return Err(WideError::NotEnclosed {
                    node: n,
                    child: k,
                    axis,
                    lo: lo[axis],
                    hi: hi[axis],
                    min: bounds.0[axis],
                    max: bounds.1[axis],
                });
            }
            all = Some(all.map_or(bounds, |b| union(b, bounds)));
        }
        under[n] = all;
    }
    Ok(())
}
