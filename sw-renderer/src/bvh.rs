//! A binned-SAH bounding volume hierarchy that gathers candidate triangles per ray.
//!
//! It never decides a hit itself: it lists every triangle of every leaf whose box the ray
//! enters within [0, bound], and the intersector's results are reduced afterwards
//! (`hit.rs`). For the render to equal the reference's brute-force loop bit for bit, the
//! gathering must be conservative: a triangle the Möller-Trumbore test would report as a
//! counting hit must always be listed. Rounding in that test can place a "hit" slightly off
//! the exact geometry, so boxes are padded by a relative margin (of their own coordinates and
//! of the ray origin's) and the bound is loosened likewise. `tests/bvh_props.rs` checks the
//! result against brute force.

use crate::math::V3;
use crate::world::WorldTriangle;

/// Triangles per leaf the SAH may keep without trying to split.
const MAX_LEAF: usize = 2;
const BINS: usize = 16;
/// Relative padding of boxes and bounds (≈ 840 ulps: far above Möller-Trumbore's rounding).
pub const PAD: f32 = 1e-4;
/// The build never nests deeper, so a fixed traversal stack suffices.
const MAX_DEPTH: usize = 64;

#[derive(Clone, Copy, Debug)]
struct Aabb {
    min: [f32; 3],
    max: [f32; 3],
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    fn grow_point(&mut self, p: [f32; 3]) {
        self.min = [0, 1, 2].map(|a| self.min[a].min(p[a]));
        self.max = [0, 1, 2].map(|a| self.max[a].max(p[a]));
    }

    fn grow(&mut self, b: &Aabb) {
        self.grow_point(b.min);
        self.grow_point(b.max);
    }

    fn area(&self) -> f32 {
        let d = [
            self.max[0] - self.min[0],
            self.max[1] - self.min[1],
            self.max[2] - self.min[2],
        ];
        if d.iter().any(|x| x.is_nan() || *x < 0.0) {
            return 0.0;
        }
        2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0])
    }

    /// Grown by `PAD` times its largest coordinate magnitude.
    fn padded(&self) -> Aabb {
        let (min, max) = padded_bounds(self.min, self.max);
        Aabb { min, max }
    }
}

/// The box `(min, max)` grown by `PAD` times its largest coordinate magnitude (and the
/// smallest normal float): how the BVH pads every box it stores, in f32.
pub fn padded_bounds(min: [f32; 3], max: [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let magnitude = min.iter().chain(&max).fold(0.0f32, |m, x| m.max(x.abs()));
    let pad = PAD * magnitude + f32::MIN_POSITIVE;
    (min.map(|x| x - pad), max.map(|x| x + pad))
}

/// A node of the binary build: a leaf lists `order[first..first + count]`; an inner node
/// (`count == 0`) has its children at `first` and `first + 1`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    first: u32,
    count: u32,
}

/// A child of an inner node: a leaf `order[first..first + count]`, or (`count == 0`) the inner
/// node `first`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Link {
    first: u32,
    count: u32,
}

/// A walk's stack of entered, unvisited subtrees. The build never nests deeper than
/// `MAX_DEPTH`, and a walk pushes at most one subtree per level, so it never overflows.
struct Stack {
    entries: [Pending; MAX_DEPTH + 2],
    len: usize,
}

impl Default for Stack {
    fn default() -> Self {
        Stack {
            entries: [Pending::default(); MAX_DEPTH + 2],
            len: 0,
        }
    }
}

impl Stack {
    #[inline(always)]
    fn push(&mut self, p: Pending) {
        self.entries[self.len] = p;
        self.len += 1;
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Pending> {
        self.len = self.len.checked_sub(1)?;
        Some(self.entries[self.len])
    }

    fn entries(&self) -> &[Pending] {
        &self.entries[..self.len]
    }
}

/// An inner node holding both children's padded boxes side by side, so that one fetch of 64
/// bytes tests both children.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Inner {
    /// `[axis][child]`.
    min: [[f32; 2]; 3],
    max: [[f32; 2]; 3],
    child: [Link; 2],
}

#[derive(Clone, Debug)]
pub struct Bvh {
    root_bounds: Aabb,
    root: Link,
    inner: Vec<Inner>,
    /// Global triangle indices, grouped by leaf.
    order: Vec<u32>,
}

/// An entered subtree a walk has not visited yet, with the ray's entry distance into its box.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pending {
    link: Link,
    near: f32,
}

/// A ray prepared for box tests.
#[derive(Clone, Copy, Debug)]
pub struct BoxRay {
    /// The origin moved by the ray's padding towards, and away from, every box side.
    orig_lo: [f32; 3],
    orig_hi: [f32; 3],
    inv_dir: [f32; 3],
    t_hi: f32,
}

impl BoxRay {
    /// `bound` is the hit bound of the ray (`hit::NO_BOUND` or a light distance).
    pub fn new(orig: V3, dir: V3, bound: f32) -> BoxRay {
        let o = orig.to_array();
        // Extra padding from the origin's magnitude (rounding in s = o − v0).
        let pad = PAD * o.iter().fold(0.0f32, |m, x| m.max(x.abs()));
        BoxRay {
            orig_lo: o.map(|x| x + pad),
            orig_hi: o.map(|x| x - pad),
            // Huge instead of infinite slopes for (near) zero components: no 0·∞ NaNs.
            inv_dir: dir.to_array().map(|d| {
                let inv = 1.0 / d;
                if inv.is_finite() {
                    inv
                } else {
                    1e30f32.copysign(d)
                }
            }),
            t_hi: bound + bound.abs() * PAD + pad,
        }
    }

    /// Slab test of one axis: the ray's parameter interval inside [min, max]. Written as
    /// selects (no NaN can arise: the slopes are finite) so that they compile to min/max.
    #[inline(always)]
    fn slab(&self, axis: usize, min: f32, max: f32) -> (f32, f32) {
        let t0 = (min - self.orig_lo[axis]) * self.inv_dir[axis];
        let t1 = (max - self.orig_hi[axis]) * self.inv_dir[axis];
        let lo = if t0 < t1 { t0 } else { t1 };
        let hi = if t0 < t1 { t1 } else { t0 };
        (lo, hi)
    }

    /// Slab test against [0, t_hi]: the entry distance if the ray enters the box.
    fn entry(&self, b: &Aabb) -> Option<f32> {
        let mut near = 0.0f32;
        let mut far = self.t_hi;
        for a in 0..3 {
            let (lo, hi) = self.slab(a, b.min[a], b.max[a]);
            near = if lo > near { lo } else { near };
            far = if hi < far { hi } else { far };
        }
        (near <= far).then_some(near)
    }

    /// The same test for both children of `node`: whether each is entered, and where.
    #[inline(always)]
    fn enters_children(&self, node: &Inner) -> ([bool; 2], [f32; 2]) {
        let mut near = [0.0f32; 2];
        let mut far = [self.t_hi; 2];
        for a in 0..3 {
            for c in 0..2 {
                let (lo, hi) = self.slab(a, node.min[a][c], node.max[a][c]);
                near[c] = if lo > near[c] { lo } else { near[c] };
                far[c] = if hi < far[c] { hi } else { far[c] };
            }
        }
        ([near[0] <= far[0], near[1] <= far[1]], near)
    }
}

impl Bvh {
    pub fn build(triangles: &[WorldTriangle]) -> Bvh {
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let mut b = Aabb::EMPTY;
                t.verts.iter().for_each(|v| b.grow_point(v.to_array()));
                b
            })
            .collect();
        let centroids: Vec<[f32; 3]> = boxes
            .iter()
            .map(|b| [0, 1, 2].map(|a| 0.5 * b.min[a] + 0.5 * b.max[a]))
            .collect();
        let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
        let mut nodes = vec![Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        }];
        let mut work = vec![(0usize, 0usize, order.len(), 0usize)];

        while let Some((node, start, end, depth)) = work.pop() {
            let mut bounds = Aabb::EMPTY;
            let mut centre_bounds = Aabb::EMPTY;
            for &t in &order[start..end] {
                bounds.grow(&boxes[t as usize]);
                centre_bounds.grow_point(centroids[t as usize]);
            }
            let leaf = Node {
                bounds: bounds.padded(),
                first: start as u32,
                count: (end - start) as u32,
            };
            let split = if end - start <= 1 || depth >= MAX_DEPTH {
                None
            } else {
                best_split(
                    &order[start..end],
                    &boxes,
                    &centroids,
                    &centre_bounds,
                    bounds.area(),
                )
            };
            match split {
                Some((axis, bin)) => {
                    let slice = &mut order[start..end];
                    let (lo, extent) = (
                        centre_bounds.min[axis],
                        centre_bounds.max[axis] - centre_bounds.min[axis],
                    );
                    let mut mid = start
                        + partition(slice, |t| {
                            bin_of(centroids[t as usize][axis], lo, extent) < bin
                        });
                    if barely_shrinks(&order[start..end], mid - start, &boxes, &bounds) {
                        mid = start
                            + median_split(&mut order[start..end], &centroids, &centre_bounds);
                    }
                    let left = nodes.len();
                    nodes.push(Node {
                        bounds: Aabb::EMPTY,
                        first: 0,
                        count: 0,
                    });
                    nodes.push(Node {
                        bounds: Aabb::EMPTY,
                        first: 0,
                        count: 0,
                    });
                    nodes[node] = Node {
                        bounds: bounds.padded(),
                        first: left as u32,
                        count: 0,
                    };
                    work.push((left, start, mid, depth + 1));
                    work.push((left + 1, mid, end, depth + 1));
                }
                None => nodes[node] = leaf,
            }
        }
        let (root, inner) = pack(&nodes);
        Bvh {
            root_bounds: nodes[0].bounds,
            root,
            inner,
            order,
        }
    }

    /// Appends to `out` every triangle of every leaf the ray enters, for which `keep` holds.
    pub fn candidates(&self, ray: &BoxRay, keep: impl Fn(u32) -> bool, out: &mut Vec<u32>) {
        let mut stack = Stack::default();
        if let Some(root) = self.root(ray) {
            stack.push(root);
        }
        self.walk(ray, &mut stack, |leaf| {
            out.extend(self.leaf(leaf).iter().copied().filter(|&t| keep(t)));
            true
        });
    }

    /// A first pass of [`Bvh::candidates`]: the leaves the ray enters, nearer boxes first,
    /// until at least `enough` triangles are gathered. The subtrees it has not visited go to
    /// `pending`, for [`Bvh::remaining_candidates`].
    pub fn nearest_candidates(
        &self,
        ray: &BoxRay,
        keep: impl Fn(u32) -> bool,
        enough: usize,
        out: &mut Vec<u32>,
        pending: &mut Vec<Pending>,
    ) {
        let start = out.len();
        let mut stack = Stack::default();
        if let Some(root) = self.root(ray) {
            stack.push(root);
        }
        self.walk(ray, &mut stack, |leaf| {
            out.extend(self.leaf(leaf).iter().copied().filter(|&t| keep(t)));
            out.len() - start < enough
        });
        pending.extend_from_slice(stack.entries());
    }

    /// The second pass: what [`Bvh::candidates`] gathers for `ray` but the first pass (with
    /// the same origin and direction, and a bound at least as large) did not.
    ///
    /// Entry distances do not depend on the bound, so a pending subtree is entered within the
    /// new bound exactly if its entry distance is. With the first pass' nearest hit `h`, and
    /// the bound `h.t.next_up()`, both passes together hold every triangle whose hit is at
    /// least as near as `h`: the closest hit over both is the closest hit over all.
    pub fn remaining_candidates(
        &self,
        ray: &BoxRay,
        keep: impl Fn(u32) -> bool,
        pending: &[Pending],
        out: &mut Vec<u32>,
    ) {
        let mut stack = Stack::default();
        pending.iter().for_each(|&p| stack.push(p));
        self.walk(ray, &mut stack, |leaf| {
            out.extend(self.leaf(leaf).iter().copied().filter(|&t| keep(t)));
            true
        });
    }

    fn root(&self, ray: &BoxRay) -> Option<Pending> {
        if self.order.is_empty() {
            return None;
        }
        ray.entry(&self.root_bounds).map(|near| Pending {
            link: self.root,
            near,
        })
    }

    fn leaf(&self, leaf: Link) -> &[u32] {
        &self.order[leaf.first as usize..(leaf.first + leaf.count) as usize]
    }

    /// Visits the leaves under the subtrees on `stack` (entered ones; the top first) that the
    /// ray enters, the nearer-entered child of each inner node first, until `visit` returns
    /// false; what is left unvisited stays on `stack`.
    #[inline(always)]
    fn walk(&self, ray: &BoxRay, stack: &mut Stack, mut visit: impl FnMut(Link) -> bool) {
        while let Some(Pending { mut link, near }) = stack.pop() {
            if near > ray.t_hi {
                continue;
            }
            loop {
                if link.count > 0 {
                    if !visit(link) {
                        return;
                    }
                    break;
                }
                let node = &self.inner[link.first as usize];
                let (enters, near) = ray.enters_children(node);
                match enters {
                    [true, true] => {
                        let nearer = usize::from(near[1] < near[0]);
                        let farther = 1 - nearer;
                        stack.push(Pending {
                            link: node.child[farther],
                            near: near[farther],
                        });
                        link = node.child[nearer];
                    }
                    [true, false] => link = node.child[0],
                    [false, true] => link = node.child[1],
                    [false, false] => break,
                }
            }
        }
    }

    pub fn node_count(&self) -> usize {
        2 * self.inner.len() + 1
    }

    /// The tree in flat parts, for a reader that lays it out elsewhere: the root's link and
    /// padded box, the inner nodes (`(min, max, children)`, boxes `[axis][child]`, a child
    /// `(first, count)`: an inner node if `count == 0`, else `order[first..first + count]`),
    /// and the triangle order.
    #[allow(clippy::type_complexity)]
    pub fn parts(
        &self,
    ) -> (
        (u32, u32),
        ([f32; 3], [f32; 3]),
        impl Iterator<Item = ([[f32; 2]; 3], [[f32; 2]; 3], [(u32, u32); 2])> + '_,
        &[u32],
    ) {
        let link = |l: Link| (l.first, l.count);
        (
            link(self.root),
            (self.root_bounds.min, self.root_bounds.max),
            self.inner
                .iter()
                .map(move |n| (n.min, n.max, n.child.map(link))),
            &self.order,
        )
    }
}

/// The binary nodes as inner nodes with their children's boxes, and the root's link.
fn pack(nodes: &[Node]) -> (Link, Vec<Inner>) {
    let mut inner_index = vec![0u32; nodes.len()];
    let mut count = 0;
    for (i, node) in nodes.iter().enumerate() {
        if node.count == 0 {
            inner_index[i] = count;
            count += 1;
        }
    }
    let link = |i: usize| match nodes[i].count {
        0 => Link {
            first: inner_index[i],
            count: 0,
        },
        n => Link {
            first: nodes[i].first,
            count: n,
        },
    };
    let inner = nodes
        .iter()
        // A lone root with no triangles is no inner node.
        .filter(|node| node.count == 0 && nodes.len() > 1)
        .map(|node| {
            let c = [node.first as usize, node.first as usize + 1];
            Inner {
                min: [0, 1, 2].map(|a| c.map(|i| nodes[i].bounds.min[a])),
                max: [0, 1, 2].map(|a| c.map(|i| nodes[i].bounds.max[a])),
                child: c.map(link),
            }
        })
        .collect();
    (link(0), inner)
}

fn bin_of(c: f32, lo: f32, extent: f32) -> usize {
    (((c - lo) / extent * BINS as f32) as usize).min(BINS - 1)
}

/// The SAH-best (axis, first right bin), or `None` if a leaf is cheaper (or nothing splits).
fn best_split(
    tris: &[u32],
    boxes: &[Aabb],
    centroids: &[[f32; 3]],
    centre_bounds: &Aabb,
    parent_area: f32,
) -> Option<(usize, usize)> {
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        let lo = centre_bounds.min[axis];
        let extent = centre_bounds.max[axis] - lo;
        let splittable = extent > 0.0 && extent.is_finite();
        if !splittable {
            continue;
        }
        let mut bins = [(Aabb::EMPTY, 0usize); BINS];
        for &t in tris {
            let b = &mut bins[bin_of(centroids[t as usize][axis], lo, extent)];
            b.0.grow(&boxes[t as usize]);
            b.1 += 1;
        }
        // Sweep from the right to get the right-side costs, then from the left.
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut n) = (Aabb::EMPTY, 0usize);
        for i in (1..BINS).rev() {
            acc.grow(&bins[i].0);
            n += bins[i].1;
            right_cost[i] = if n == 0 {
                f32::INFINITY
            } else {
                acc.area() * n as f32
            };
        }
        let (mut acc, mut n) = (Aabb::EMPTY, 0usize);
        for i in 1..BINS {
            acc.grow(&bins[i - 1].0);
            n += bins[i - 1].1;
            if n == 0 || n == tris.len() {
                continue;
            }
            let cost = acc.area() * n as f32 + right_cost[i];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    let (cost, axis, bin) = best?;
    // Traversal costs about one triangle test; a leaf costs one test per triangle.
    let split_cost = 1.0 + cost / parent_area.max(f32::MIN_POSITIVE);
    let leaf_cost = tris.len() as f32;
    if tris.len() <= MAX_LEAF && split_cost >= leaf_cost {
        None
    } else {
        Some((axis, bin))
    }
}

/// Whether splitting `tris` after `mid` leaves the side with more triangles with a box of
/// about the parent's: where large triangles overlap a dense cluster (a backdrop under
/// teapots), the binned SAH peels a few triangles off level after level, building chains 60
/// deep; halving the triangles instead keeps the tree shallow.
fn barely_shrinks(tris: &[u32], mid: usize, boxes: &[Aabb], parent: &Aabb) -> bool {
    let larger = if mid * 2 < tris.len() {
        &tris[mid..]
    } else {
        &tris[..mid]
    };
    let mut b = Aabb::EMPTY;
    larger.iter().for_each(|&t| b.grow(&boxes[t as usize]));
    b.area() > 0.9 * parent.area()
}

/// Splits `tris` in halves by centroid along the axis of the largest centroid extent;
/// returns the size of the first half.
fn median_split(tris: &mut [u32], centroids: &[[f32; 3]], centre_bounds: &Aabb) -> usize {
    let extent = |a: usize| centre_bounds.max[a] - centre_bounds.min[a];
    let axis = (0..3).fold(0, |best, a| if extent(a) > extent(best) { a } else { best });
    let mid = tris.len() / 2;
    tris.select_nth_unstable_by(mid, |&a, &b| {
        centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
    });
    mid
}

/// Moves the elements for which `left` holds to the front; returns how many there are.
fn partition(slice: &mut [u32], left: impl Fn(u32) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..slice.len() {
        if left(slice[i]) {
            slice.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(x: f32) -> WorldTriangle {
        WorldTriangle {
            verts: [
                V3::new(x, 0.0, 0.0),
                V3::new(x + 0.5, 0.0, 0.0),
                V3::new(x, 0.5, 0.0),
            ],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: 0,
        }
    }

    #[test]
    fn splits_a_row_of_triangles_and_gathers_only_nearby_leaves() {
        let tris: Vec<_> = (0..64).map(|i| tri(i as f32)).collect();
        let bvh = Bvh::build(&tris);
        assert!(bvh.node_count() > 15);
        let mut out = Vec::new();
        let ray = BoxRay::new(V3::new(10.1, 0.1, 1.0), V3::new(0.0, 0.0, -1.0), f32::MAX);
        bvh.candidates(&ray, |_| true, &mut out);
        assert!(out.contains(&10));
        assert!(out.len() <= 8, "gathered {out:?}");
        out.clear();
        bvh.candidates(&ray, |t| t != 10, &mut out);
        assert!(!out.contains(&10));
    }

    #[test]
    fn bound_excludes_far_leaves() {
        let tris: Vec<_> = (0..64).map(|i| tri(i as f32)).collect();
        let bvh = Bvh::build(&tris);
        let mut out = Vec::new();
        let ray = BoxRay::new(V3::new(-1.0, 0.1, 0.0), V3::new(1.0, 0.0, 0.0), 5.0);
        bvh.candidates(&ray, |_| true, &mut out);
        assert!(out.contains(&3) && !out.contains(&40), "gathered {out:?}");
    }
}
