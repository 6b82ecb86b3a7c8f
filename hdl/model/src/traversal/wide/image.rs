//! The scene image of wide nodes (version 3, docs/scene-image.md "Wide nodes"): the header
//! of version 2 with the width K in word 13, N wide node records of [`node_words`]`(K)`
//! words, the triangle records of version 2.
//!
//! A node record: origin x y z (fp32), one word of the exponents x y z (bytes 0–2, two's
//! complement) and the child count (byte 3), the children's codes (6 bytes a child: lo x y z,
//! hi x y z, packed little-endian, 6K bytes), then one link word a child: `first` in bits
//! 0–27, `count` in bits 28–31 (0: an inner node). Slots beyond the count are 0.

use super::super::scene_image::{
    check_links, check_triangles, read_triangles, write_triangles, Header, ImageTriangle, Link,
    SceneImage, SceneImageError, HEADER_WORDS, TRIANGLE_WORDS, VERSION_WIDE,
};
use super::{check, collapse, Child, WideError, WideNode, WideTree, MAX_LEAF_TRIANGLES};

/// Bits of a link word's `first`; `count` takes the 4 bits above.
pub const FIRST_BITS: u32 = 28;

/// A child's link as its record's link word: `first` in bits 0–27, `count` in bits 28–31.
pub fn link_word(link: Link) -> u32 {
    link.first | link.count << FIRST_BITS
}

/// The link a link word holds.
pub fn link_of(word: u32) -> Link {
    Link {
        first: word & ((1 << FIRST_BITS) - 1),
        count: word >> FIRST_BITS,
    }
}

/// Words of a node record of `width` children.
pub fn node_words(width: usize) -> usize {
    4 + 6 * width / 4 + width
}

/// A scene as the unit's memory holds it with wide nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct WideImage {
    pub tree: WideTree,
    /// The binary image's root box (the scene's padded bounds; not walked).
    pub root_box: ([f32; 3], [f32; 3]),
    pub triangles: Vec<ImageTriangle>,
    pub scene_triangles: u32,
}

impl WideImage {
    /// The wide image of a binary one: its tree collapsed to `width` children a node, the
    /// triangle records unchanged. The one writer of the layout.
    pub fn of(image: &SceneImage, width: usize) -> Result<WideImage, WideError> {
        Ok(WideImage {
            tree: collapse(image, width)?,
            root_box: image.root_box,
            triangles: image.triangles.clone(),
            scene_triangles: image.scene_triangles,
        })
    }

    pub fn to_words(&self) -> Vec<u32> {
        let width = self.tree.width;
        let mut w = Vec::with_capacity(self.words());
        w.extend(
            Header {
                version: VERSION_WIDE,
                nodes: self.tree.nodes.len() as u32,
                triangles: self.triangles.len() as u32,
                root: self.tree.root,
                root_box: self.root_box,
                scene_triangles: self.scene_triangles,
                width: width as u32,
            }
            .words(),
        );
        for n in &self.tree.nodes {
            w.extend(n.origin.map(f32::to_bits));
            let exp = n.exp.map(|e| u32::from(e as u8));
            w.push(exp[0] | exp[1] << 8 | exp[2] << 16 | (n.children.len() as u32) << 24);
            let mut codes = vec![0u8; 6 * width];
            for (c, child) in n.children.iter().enumerate() {
                codes[6 * c..6 * c + 3].copy_from_slice(&child.lo);
                codes[6 * c + 3..6 * c + 6].copy_from_slice(&child.hi);
            }
            w.extend(
                codes
                    .chunks(4)
                    .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            );
            for c in 0..width {
                w.push(n.children.get(c).map_or(0, |c| link_word(c.link)));
            }
        }
        write_triangles(&self.triangles, &mut w);
        w
    }

    /// The image's size in words.
    pub fn words(&self) -> usize {
        HEADER_WORDS
            + node_words(self.tree.width) * self.tree.nodes.len()
            + TRIANGLE_WORDS * self.triangles.len()
    }

    /// The image's size in bytes (as loaded).
    pub fn bytes(&self) -> usize {
        4 * self.words()
    }

    /// Reads and checks a word stream: the header as version 2's, every node's child count,
    /// its unused slots 0, links in range and short enough, no node reached twice, the
    /// triangles as version 2's, then [`check`]: codes in order, every child's box enclosing
    /// the padded bounds of the triangles under it.
    pub fn from_words(w: &[u32]) -> Result<WideImage, SceneImageError> {
        let h = Header::read(w, VERSION_WIDE, |width| node_words(width as usize))?;
        let width = h.width as usize;
        let node_at = |k: usize| HEADER_WORDS + node_words(width) * k;
        let mut nodes = Vec::with_capacity(h.nodes as usize);
        for k in 0..h.nodes as usize {
            let i = node_at(k);
            let count = w[i + 3] >> 24;
            if !(1..=width as u32).contains(&count) {
                return Err(SceneImageError::ChildCount {
                    node: k,
                    children: count,
                    width,
                });
            }
            let count = count as usize;
            let bytes: Vec<u8> = (0..6 * width / 4)
                .flat_map(|j| w[i + 4 + j].to_le_bytes())
                .collect();
            let links = i + 4 + 6 * width / 4;
            let unused_code = (6 * count..6 * width).find(|&b| bytes[b] != 0);
            if let Some(b) = unused_code {
                return Err(SceneImageError::Reserved {
                    word: i + 4 + b / 4,
                    value: w[i + 4 + b / 4],
                });
            }
            if let Some(c) = (count..width).find(|&c| w[links + c] != 0) {
                return Err(SceneImageError::Reserved {
                    word: links + c,
                    value: w[links + c],
                });
            }
            let e = w[i + 3].to_le_bytes();
            nodes.push(WideNode {
                origin: [0, 1, 2].map(|a| f32::from_bits(w[i + a])),
                exp: [0, 1, 2].map(|a| e[a] as i8),
                children: (0..count)
                    .map(|c| Child {
                        lo: [0, 1, 2].map(|a| bytes[6 * c + a]),
                        hi: [0, 1, 2].map(|a| bytes[6 * c + 3 + a]),
                        link: link_of(w[links + c]),
                    })
                    .collect(),
            });
        }
        let image = WideImage {
            tree: WideTree {
                width,
                root: h.root,
                nodes,
            },
            root_box: h.root_box,
            triangles: read_triangles(w, node_at(h.nodes as usize), h.triangles)?,
            scene_triangles: h.scene_triangles,
        };
        image.check()?;
        Ok(image)
    }

    /// The structural checks of [`WideImage::from_words`] on an image in memory.
    pub fn check(&self) -> Result<(), SceneImageError> {
        check_triangles(&self.triangles, self.scene_triangles)?;
        let tree = &self.tree;
        let root = tree.root;
        if !self.triangles.is_empty() && root != (Link { first: 0, count: 0 }) {
            return Err(SceneImageError::WideRoot {
                first: root.first,
                count: root.count,
            });
        }
        for (k, n) in tree.nodes.iter().enumerate() {
            if let Some((c, child)) =
                (n.children.iter().enumerate()).find(|(_, c)| c.link.count > MAX_LEAF_TRIANGLES)
            {
                return Err(SceneImageError::LongLeaf {
                    from: format!("node {k} child {c}"),
                    count: child.link.count,
                });
            }
        }
        check_links(
            root,
            self.triangles.len() as u32,
            tree.nodes.len() as u32,
            |node| {
                let children = &tree.nodes[node as usize].children;
                children.iter().map(|c| c.link).collect()
            },
        )?;
        Ok(check(tree, &self.triangles)?)
    }

    /// Inner nodes on the longest path from the root to a leaf (a walk holds at most
    /// `width − 1` stack entries per level).
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        if self.triangles.is_empty() {
            return 0;
        }
        let mut todo = vec![(self.tree.root, 0usize)];
        while let Some((link, d)) = todo.pop() {
            if link.is_leaf() {
                deepest = deepest.max(d);
                continue;
            }
            for c in &self.tree.nodes[link.first as usize].children {
                todo.push((c.link, d + 1));
            }
        }
        deepest
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sw_renderer::scene::Scene;
    use sw_renderer::trace::PreparedScene;

    fn image(name: &str, width: usize) -> WideImage {
        let scene = Scene::load(name).unwrap();
        let binary = SceneImage::new(&PreparedScene::new(&scene).unwrap());
        WideImage::of(&binary, width).unwrap()
    }

    fn reject(w: &[u32]) -> String {
        WideImage::from_words(w).unwrap_err().to_string()
    }

    #[test]
    fn wide_images_round_trip_through_their_words() {
        for width in super::super::WIDTHS {
            let img = image("glasses", width);
            let words = img.to_words();
            assert_eq!(words.len(), img.words());
            assert_eq!(WideImage::from_words(&words).unwrap(), img);
            assert!(img.tree.nodes.len() > 5 && img.depth() >= 2);
        }
        // A scene whose binary root is a leaf still has a node.
        let img = image("simple_plane", 4);
        assert_eq!(img.tree.nodes.len(), 1);
        assert_eq!(WideImage::from_words(&img.to_words()).unwrap(), img);
    }

    #[test]
    fn damaged_wide_images_are_refused_naming_what_is_wrong() {
        let img = image("glasses", 4);
        let good = img.to_words();
        let n0 = HEADER_WORDS;
        let mut w = good.clone();
        w[13] = 3;
        assert!(
            reject(&w).contains("wide nodes of 3 children"),
            "{}",
            reject(&w)
        );
        let mut w = good.clone();
        w[n0 + 3] &= 0x00FF_FFFF;
        assert!(
            reject(&w).contains("node 0 has 0 children"),
            "{}",
            reject(&w)
        );
        // A child's box shrunk below what it holds.
        let mut w = good.clone();
        let lo = n0 + 4;
        w[lo] = (w[lo] & !0xFF) | 0xFF;
        assert!(
            reject(&w).contains("does not enclose") || reject(&w).contains("codes 255 >"),
            "{}",
            reject(&w)
        );
        // A link to a node that does not exist, and one back to the root: a cycle.
        let links = n0 + 4 + 6;
        let inner = (0..4)
            .find(|&c| good[links + c] >> FIRST_BITS == 0)
            .unwrap();
        let mut w = good.clone();
        w[links + inner] = 9999;
        assert!(
            reject(&w).contains("links to inner node 9999"),
            "{}",
            reject(&w)
        );
        let mut w = good.clone();
        w[links + inner] = 0;
        assert!(
            reject(&w).contains("links to node 0 again"),
            "{}",
            reject(&w)
        );
        // A leaf too long for a wide link cannot be written: its count has 4 bits.
        let mut long = img.clone();
        long.tree.nodes[0].children[0].link = Link {
            first: 0,
            count: 16,
        };
        assert!(long
            .check()
            .unwrap_err()
            .to_string()
            .contains("a leaf of 16 triangles"));
    }
}
