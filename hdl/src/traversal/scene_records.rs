//! The scene memory's records, capacity and load errors (the memory itself:
//! [`super::scene_memory`], which re-exports these).
//!
//! Records (bit 0 first; `LF`, `LC` link widths from [`link_first_bits`], [`link_count_bits`]):
//! - node ([`node_record_bits`]): the children's padded boxes as the image orders them, min x0
//!   x1 y0 y1 z0 z1 then max likewise (12 × 32 bits, bits 0–383), then child 0's link first
//!   (`LF`) and count (`LC`), then child 1's. A link first is a node or triangle index, so `LF`
//!   = max(node, triangle address bits); a count reaches the whole capacity, `LC` = triangle
//!   address bits + 1. One read is what one box test needs.
//! - triangle ([`triangle_record_bits`]): v0, v1, v2 (9 × 32 bits, bits 0–287), the casts-shadow
//!   flag (bit 288), the global index ([`INDEX_BITS`], from 289). The image's reserved
//!   word is not stored. One read is what one Möller-Trumbore lane and its hit need.
//!

/// Bits of the boxes in a node record (12 fp32 words).
pub const BOX_BITS: usize = 12 * 32;
/// Bits of the vertices in a triangle record (9 fp32 words).
pub const VERTEX_BITS: usize = 9 * 32;
/// Bits of a global triangle index: a scene (a whole one, or the scene a chunk of it belongs
/// to) has at most 2^24 triangles. A chunk's indices reach beyond its own capacity, so the
/// width does not follow the triangle address bits.
pub const INDEX_BITS: usize = 24;
/// Width of `error_code`.
pub const ERROR_CODE_BITS: usize = 4;

/// What the loader refused, as `error_code` (0: no error).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum LoadError {
    /// Word 0 is not [`MAGIC`](hw_model::traversal::scene_image::MAGIC).
    BadMagic = 1,
    /// Word 1 is not [`VERSION`](hw_model::traversal::scene_image::VERSION) (a wide memory:
    /// [`VERSION_WIDE`](hw_model::traversal::scene_image::VERSION_WIDE)).
    BadVersion = 2,
    /// N (word 2) is beyond the node capacity.
    TooManyNodes = 3,
    /// T (word 3) is beyond the triangle capacity.
    TooManyTriangles = 4,
    /// A link's count is 0 and its first ≥ N (the word is the count; the first precedes it;
    /// a wide link is one word). A wide image's root is not node 0.
    NodeLink = 5,
    /// A link's first + count > T (the word is the count).
    LeafLink = 6,
    /// A triangle's global index ≥ S (header word 12).
    GlobalIndex = 7,
    /// A triangle's flags have a bit other than bit 0.
    BadFlags = 8,
    /// A reserved word is not 0.
    Reserved = 9,
    /// `tlast` before the image's last word.
    EarlyLast = 10,
    /// The image's last word without `tlast` (the rest of the packet is drained).
    MissingLast = 11,
    /// The scene's triangle count S (word 12) is below T or beyond 2^[`INDEX_BITS`].
    SceneTriangles = 12,
    /// A wide image's width K (word 13) is not the memory's.
    Width = 13,
    /// A wide node's child count (byte 3 of its word 3) is 0 or beyond K.
    ChildCount = 14,
}

impl LoadError {
    pub const ALL: [LoadError; 14] = [
        LoadError::BadMagic,
        LoadError::BadVersion,
        LoadError::TooManyNodes,
        LoadError::TooManyTriangles,
        LoadError::NodeLink,
        LoadError::LeafLink,
        LoadError::GlobalIndex,
        LoadError::BadFlags,
        LoadError::Reserved,
        LoadError::EarlyLast,
        LoadError::MissingLast,
        LoadError::SceneTriangles,
        LoadError::Width,
        LoadError::ChildCount,
    ];

    pub fn code(self) -> u64 {
        self as u64
    }

    /// The error of an `error_code`, `None` for 0 or a code no error has.
    pub fn from_code(code: u64) -> Option<LoadError> {
        LoadError::ALL.into_iter().find(|e| e.code() == code)
    }
}

/// Nodes and triangles a memory with these address bits holds.
pub fn capacity_for(node_bits: usize, triangle_bits: usize) -> (usize, usize) {
    (1 << node_bits, 1 << triangle_bits)
}

/// The address bits of the scene memory a unit of `lanes` fp32 Möller-Trumbore lanes (depth
/// 5) carries on the XC7Z020: the largest power-of-two memory whose block RAM fits beside the
/// lanes and the slot stacks (yosys; docs/scene-image.md, "Resources and what fits the
/// XC7Z020"). Narrower formats' lanes use less block RAM, so this is their safe choice too.
pub fn zynq_address_bits(lanes: usize) -> (usize, usize) {
    if lanes <= 1 {
        (12, 13)
    } else {
        (11, 12)
    }
}

/// The smallest (node, triangle) address bits whose [`capacity_for`] holds `nodes` and
/// `triangles` (at least 1 bit each: a RAM has an address).
pub fn address_bits_for(nodes: usize, triangles: usize) -> (usize, usize) {
    let bits = |n: usize| (n.max(2) - 1).ilog2() as usize + 1;
    (bits(nodes), bits(triangles))
}

/// `LF`: a link's first is a node or a triangle index.
pub const fn link_first_bits(node_bits: usize, triangle_bits: usize) -> usize {
    if node_bits > triangle_bits {
        node_bits
    } else {
        triangle_bits
    }
}

/// `LC`: a leaf's count reaches the triangle capacity itself.
pub const fn link_count_bits(triangle_bits: usize) -> usize {
    triangle_bits + 1
}

/// `NW`: boxes and two links.
pub const fn node_record_bits(node_bits: usize, triangle_bits: usize) -> usize {
    BOX_BITS + 2 * (link_first_bits(node_bits, triangle_bits) + link_count_bits(triangle_bits))
}

// The triangle read spells the flag's and the index's bits as numbers (hdl_gen leaks a named
// const into the Verilog).
const _: () = assert!(VERTEX_BITS == 288);

/// `TW`: vertices, the flag (bit [`VERTEX_BITS`]) and the global index (from the next bit).
pub const fn triangle_record_bits() -> usize {
    VERTEX_BITS + 1 + INDEX_BITS
}

/// Wide node records (version 3, `--nodes bvh2-q8 | bvh4-q8 | bvh8-q8`; the memory:
/// [`super::wide_scene_memory`]), bit 0 first: the image's node words 0 to 3 + 1.5·K as they
/// arrive ([`wide_head_bits`]: origin x y z in bits 0–95, exponents x y z in bits 96–119, the
/// child count in bits 120–127, then 6 code bytes a child: lo x y z, hi x y z), then K links
/// of [`wide_link_bits`] each: `first` (`LF` bits) and `count` ([`WIDE_COUNT_BITS`] above it).
pub const WIDE_COUNT_BITS: usize = 32 - hw_model::traversal::wide::image::FIRST_BITS as usize;
const _: () =
    assert!(hw_model::traversal::wide::MAX_LEAF_TRIANGLES as usize == (1 << WIDE_COUNT_BITS) - 1);

/// `HB`: a wide node record's origin, exponents, count and codes.
pub const fn wide_head_bits(width: usize) -> usize {
    128 + 48 * width
}

/// `LK`: a wide node's link: a node or triangle index and a leaf's count.
pub const fn wide_link_bits(node_bits: usize, triangle_bits: usize) -> usize {
    link_first_bits(node_bits, triangle_bits) + WIDE_COUNT_BITS
}

/// `NW` of a wide node record of `width` children.
pub const fn wide_node_record_bits(width: usize, node_bits: usize, triangle_bits: usize) -> usize {
    wide_head_bits(width) + width * wide_link_bits(node_bits, triangle_bits)
}
