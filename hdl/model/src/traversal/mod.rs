//! The traversal unit's bit-accurate model: the scene on chip, rays in, hits out.
//!
//! No cycles: for every ray the answer the unit gives and the work it does (box tests,
//! node visits, Möller-Trumbore tests). It is the reference the unit's hardware is checked
//! against, and a fast engine for renders and sweeps ([`TraversalEngine`]).
//!
//! A ray walks the scene image depth first: the root box is tested, then each inner node's
//! two child boxes in one [`box_test`]; when both are entered the farther is pushed on the
//! ray's stack and the nearer visited; a popped subtree entered beyond the current far end
//! is skipped. A leaf's triangles go to the Möller-Trumbore test in the configured format
//! ([`crate::mt_model`]), all of a leaf's before its answers are looked at (as the unit
//! issues them to its lanes); a shadow (any-hit) ray skips triangles that cast no shadow and
//! stops after the first leaf with a counting hit. A ray's excluded triangle (the one a
//! spawned ray leaves) costs no Möller-Trumbore test. A closest-hit ray keeps the reference's
//! reduction (`sw_renderer::hit`: nearest t, then the lower global index; a hit counts if it
//! is in the ray's window `t_min < t < t_max`, `t < FLT_MAX`) and, once it has a hit, culls
//! boxes with the far end of
//! `t.next_up()` so that an equally near hit with a lower index is still found. Box tests are
//! conservative, so in fp32 every answer equals the software renderer's.
//!
//! With [`Advance::LeafBox`] a leaf's queries start at the leaf box's entry distance t0 as
//! the box test that entered the leaf computed it (`crate::advance::leaf_start`): origin
//! `o + t0·d`, `t_min − t0`, the lane's t returned as `t + t0` (fp32). Everything after the
//! lane (the window, the nearest hit, the far end, the answer) sees that returned t.

pub mod box_test;
pub mod capacity;
mod engine;
pub mod packet;
pub mod scene_image;
pub mod schedule;
#[cfg(feature = "strategies")]
pub mod strategies;
pub mod wide;

pub use capacity::{run_passes, CapacityError, ChunkedModel, SceneCapacity, SceneMemory};
pub use engine::TraversalEngine;
pub use packet::{HIT_WORDS, RAY_WORDS};

use sw_renderer::hit::{nearer, remaining_bound, Hit, Window};
use sw_renderer::intersect::MtQuery;
use sw_renderer::rays::Ray;
use thiserror::Error;

use crate::format::Format;
use crate::mt::mt_model_scaled;
use crate::{Advance, Edges};
use box_test::{box_test, ray_setup, t_hi, BoxResult};
use scene_image::{ImageTriangle, Link, SceneImage, SceneImageError, UnitImage};
use wide::box_test::{wide_box_test, NodeEntry, WideRay};
use wide::image::WideImage;
pub use wide::{NodeFormat, WideError, WideTree};

/// Entries of a ray's traversal stack unless configured otherwise: a walk pushes at most one
/// subtree per inner node it passes, and the deepest thesis scene (All materials) is 25
/// inner nodes deep (`rtfpga scene-image`). The software BVH may nest up to 64: a deeper
/// walk is reported as a stack overflow, not cut short.
pub const DEFAULT_STACK_DEPTH: usize = 32;

/// A ray as it enters the unit (fp32 words on the stream).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UnitRay {
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    /// Hits count only below this distance …
    pub t_max: f32,
    /// … and beyond this one (0: every hit, as the thesis).
    pub t_min: f32,
    /// A triangle (global index) that never counts: the one a spawned ray leaves.
    pub exclude: Option<u32>,
    /// Any-hit (a shadow ray: skips non-shadow-casting triangles, stops at the first hit);
    /// else closest-hit.
    pub any_hit: bool,
    /// Returned with the answer: answers leave the unit in any order.
    pub id: u32,
}

impl UnitRay {
    /// The renderer's `ray` as the unit takes it, tagged `id`.
    pub fn of(ray: &Ray, id: u32) -> UnitRay {
        UnitRay {
            orig: ray.orig.to_array(),
            dir: ray.dir.to_array(),
            t_max: ray.bound,
            t_min: ray.t_min,
            exclude: ray.exclude,
            any_hit: ray.shadow,
            id,
        }
    }

    /// Which hits count (the renderer's rule, `sw_renderer::hit::Window`).
    pub fn window(&self) -> Window {
        Window {
            t_min: self.t_min,
            bound: self.t_max,
            exclude: self.exclude,
        }
    }
}

/// Work the unit did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UnitCounters {
    pub rays: u64,
    /// Inner nodes and leaves visited.
    pub node_visits: u64,
    /// Box tests (two children each; the root's box counts as one).
    pub box_tests: u64,
    pub mt_tests: u64,
}

impl std::ops::AddAssign for UnitCounters {
    fn add_assign(&mut self, o: UnitCounters) {
        self.rays += o.rays;
        self.node_visits += o.node_visits;
        self.box_tests += o.box_tests;
        self.mt_tests += o.mt_tests;
    }
}

/// What stops the unit.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TraversalError {
    #[error(
        "ray {id}: traversal stack overflow: it needs more than {capacity} entries (the scene's tree is {depth} inner nodes deep); configure a deeper stack"
    )]
    StackOverflow {
        id: u32,
        capacity: usize,
        depth: usize,
    },
}

/// The unit with a scene loaded.
#[derive(Clone, Debug)]
pub struct TraversalModel {
    format: Format,
    /// Möller-Trumbore sees every coordinate times 2^scale_exp (box tests stay fp32).
    scale_exp: i32,
    /// Where a leaf's Möller-Trumbore queries start (`None` or `LeafBox`).
    advance: Advance,
    stack_depth: usize,
    image: UnitImage,
}

impl TraversalModel {
    /// A unit computing Möller-Trumbore in `format`, with `stack_depth` stack entries per
    /// ray, holding `image` of either node format (checked by its `from_words` or `check`).
    pub fn new(format: Format, stack_depth: usize, image: impl Into<UnitImage>) -> TraversalModel {
        TraversalModel {
            format,
            scale_exp: 0,
            advance: Advance::None,
            stack_depth,
            image: image.into(),
        }
    }

    /// The unit holding its binary image's tree in `nodes`: the wide ones written from it
    /// (`WideImage::of`) and read back through their word stream (so the loader's checks
    /// run). A wide image stays as it is; so does a binary one asked for `bvh2-fp32`.
    pub fn with_nodes(self, nodes: NodeFormat) -> Result<TraversalModel, SceneImageError> {
        let image = match (&self.image, nodes.width()) {
            (UnitImage::Binary(binary), Some(width)) => {
                let words = WideImage::of(binary, width)?.to_words();
                UnitImage::Wide(WideImage::from_words(&words)?)
            }
            _ => return Ok(self),
        };
        Ok(TraversalModel { image, ..self })
    }

    /// The unit starting its Möller-Trumbore queries where `advance` says (the hardware
    /// builds `None` and `LeafBox`; `TriangleBox` is the model engine's).
    pub fn advanced(self, advance: Advance) -> TraversalModel {
        TraversalModel { advance, ..self }
    }

    /// The unit with its Möller-Trumbore queries scaled by 2^`scale_exp`
    /// (`crate::mt::scale_query`).
    pub fn scaled(self, scale_exp: i32) -> TraversalModel {
        TraversalModel { scale_exp, ..self }
    }

    pub fn image(&self) -> &UnitImage {
        &self.image
    }

    /// The answer to `ray`: its closest hit, or for an any-hit ray some counting hit.
    pub fn trace(
        &self,
        ray: &UnitRay,
        counters: &mut UnitCounters,
    ) -> Result<Option<Hit>, TraversalError> {
        self.walk(ray, counters, &mut |_| {})
    }

    /// [`TraversalModel::trace`], telling `step` each step of the walk in order (what the
    /// schedule model times).
    pub fn walk(
        &self,
        ray: &UnitRay,
        counters: &mut UnitCounters,
        step: &mut dyn FnMut(Step),
    ) -> Result<Option<Hit>, TraversalError> {
        counters.rays += 1;
        let img = match &self.image {
            _ if self.image.triangles().is_empty() => return Ok(None),
            UnitImage::Wide(wide) => return self.walk_wide(wide, ray, counters, step),
            UnitImage::Binary(img) => img,
        };
        let mut setup = ray_setup(ray.orig, ray.dir, ray.t_max);
        let root = root_boxes(img);
        counters.box_tests += 1;
        step(Step::Box);
        let entered = box_test(&setup, &root);
        // A subtree and the distance at which the box test entered it.
        let mut stack: Vec<(Link, f32)> = Vec::with_capacity(self.stack_depth);
        if entered.enters[0] {
            stack.push((img.root, entered.near[0]));
        }
        let window = ray.window();
        let mut best: Option<Hit> = None;
        while let Some((mut link, mut entry)) = stack.pop() {
            step(Step::Pop);
            if setup.t_hi < entry {
                continue;
            }
            loop {
                counters.node_visits += 1;
                if link.is_leaf() {
                    let leaf = link.first as usize..(link.first + link.count) as usize;
                    let triangles = &img.triangles[leaf];
                    let answer = self.leaf(ray, &window, entry, triangles, counters, &mut best);
                    step(Step::leaf(triangles, &answer));
                    match answer {
                        Leaf::Occluded(hit) => return Ok(Some(hit)),
                        Leaf::Closer => {
                            setup.t_hi = t_hi(remaining_bound(best, ray.t_max), setup.pad)
                        }
                        Leaf::Same => {}
                    }
                    break;
                }
                let node = &img.nodes[link.first as usize];
                counters.box_tests += 1;
                step(Step::Box);
                let BoxResult {
                    enters,
                    near,
                    first,
                } = box_test(&setup, &node.boxes);
                match enters {
                    [true, true] => {
                        if stack.len() == self.stack_depth {
                            return Err(TraversalError::StackOverflow {
                                id: ray.id,
                                capacity: self.stack_depth,
                                depth: img.depth(),
                            });
                        }
                        stack.push((node.child[1 - first], near[1 - first]));
                        (link, entry) = (node.child[first], near[first]);
                    }
                    [true, false] => (link, entry) = (node.child[0], near[0]),
                    [false, true] => (link, entry) = (node.child[1], near[1]),
                    [false, false] => break,
                }
            }
        }
        Ok(best)
    }
}

impl TraversalModel {
    /// The walk of a wide tree: each inner node's children tested in one box test, the
    /// nearest entered taken, the others pushed farthest first (so popped nearest first),
    /// each with where the walk enters it; a popped child entered beyond the far end is
    /// skipped. The first step is the root node's test.
    fn walk_wide(
        &self,
        image: &WideImage,
        ray: &UnitRay,
        counters: &mut UnitCounters,
        step: &mut dyn FnMut(Step),
    ) -> Result<Option<Hit>, TraversalError> {
        let setup = ray_setup(ray.orig, ray.dir, ray.t_max);
        let mut wide_ray = WideRay::from_setup(ray.orig, &setup);
        let window = ray.window();
        let mut best: Option<Hit> = None;
        let mut stack: Vec<(Link, NodeEntry)> = Vec::with_capacity(self.stack_depth);
        let tree = &image.tree;
        let (mut link, mut at) = (tree.root, NodeEntry::ROOT);
        loop {
            counters.node_visits += 1;
            if link.is_leaf() {
                let leaf = link.first as usize..(link.first + link.count) as usize;
                let triangles = &image.triangles[leaf];
                let answer = self.leaf(ray, &window, at.t0, triangles, counters, &mut best);
                step(Step::leaf(triangles, &answer));
                match answer {
                    Leaf::Occluded(hit) => return Ok(Some(hit)),
                    Leaf::Closer => {
                        wide_ray.t_hi = t_hi(remaining_bound(best, ray.t_max), setup.pad)
                    }
                    Leaf::Same => {}
                }
            } else {
                let node = &tree.nodes[link.first as usize];
                counters.box_tests += 1;
                step(Step::Box);
                let entered = wide_box_test(&wide_ray, node, at);
                if let Some((nearest, rest)) = entered.split_first() {
                    if stack.len() + rest.len() > self.stack_depth {
                        return Err(TraversalError::StackOverflow {
                            id: ray.id,
                            capacity: self.stack_depth,
                            depth: image.depth(),
                        });
                    }
                    for e in rest.iter().rev() {
                        stack.push((node.children[e.slot].link, e.entry));
                    }
                    (link, at) = (node.children[nearest.slot].link, nearest.entry);
                    continue;
                }
            }
            // Every pop is a step, the empty stack's too: the unit learns there that the
            // walk is over (the binary walk's root box needs none).
            loop {
                step(Step::Pop);
                let Some((next, entry)) = stack.pop() else {
                    return Ok(best);
                };
                if wide_ray.t_hi < entry.t0 {
                    continue;
                }
                (link, at) = (next, entry);
                break;
            }
        }
    }
}

/// One step of a ray's walk, in the order the unit takes them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// A box test: the root's box, or an inner node's two child boxes.
    Box,
    /// A leaf of `triangles`, each issued to the lane in a cycle of its own: tested, or
    /// skipped (a non-shadow-caster for an any-hit ray, the excluded triangle), which takes
    /// its issue cycle and the lane's latency all the same. `nearer`: the leaf made a
    /// closest-hit ray's hit nearer, so the unit recomputes its far end before the next step.
    Leaf { triangles: u32, nearer: bool },
    /// A subtree taken from the stack (then skipped if entered beyond the far end); in a
    /// wide walk also the empty stack's pop that ends it.
    Pop,
}

impl Step {
    /// The step of a leaf of `triangles` that answered `answer`.
    fn leaf(triangles: &[ImageTriangle], answer: &Leaf) -> Step {
        Step::Leaf {
            triangles: triangles.len() as u32,
            nearer: matches!(answer, Leaf::Closer),
        }
    }
}

/// What a leaf did to the ray's answer.
enum Leaf {
    /// An any-hit ray found a counting hit: its answer.
    Occluded(Hit),
    /// A closest-hit ray's nearest hit changed.
    Closer,
    Same,
}

impl TraversalModel {
    /// Tests every triangle of a leaf (an any-hit ray skips the non-shadow-casters), as the
    /// unit issues a whole leaf to its lanes before it looks at the answers; the first
    /// counting hit in leaf order answers an any-hit ray. `entry`: where the box test entered
    /// the leaf.
    fn leaf(
        &self,
        ray: &UnitRay,
        window: &Window,
        entry: f32,
        triangles: &[ImageTriangle],
        counters: &mut UnitCounters,
        best: &mut Option<Hit>,
    ) -> Leaf {
        let mut answer = Leaf::Same;
        for tri in triangles {
            if (ray.any_hit && !tri.casts_shadow) || ray.exclude == Some(tri.index) {
                continue;
            }
            counters.mt_tests += 1;
            let query = MtQuery {
                orig: ray.orig,
                dir: ray.dir,
                v0: tri.verts[0],
                v1: tri.verts[1],
                v2: tri.verts[2],
                t_min: window.t_min,
            };
            // The unit's lanes are the hardware's: exact edges.
            let r = self.advance.run_in_leaf(&query, Some(entry), |q| {
                mt_model_scaled(&self.format, self.scale_exp, Edges::Exact, q)
            });
            // The fp32 words compare as IEEE floats: t is never subnormal (the datapath
            // flushes), so this is the hardware's comparison too.
            if !window.counts(tri.index, &r) {
                continue;
            }
            let hit = Hit {
                triangle: tri.index,
                t: r.t,
                u: r.u,
                v: r.v,
            };
            if ray.any_hit {
                if !matches!(answer, Leaf::Occluded(_)) {
                    answer = Leaf::Occluded(hit);
                }
                continue;
            }
            let closer = nearer(*best, Some(hit));
            if closer != *best {
                *best = closer;
                answer = Leaf::Closer;
            }
        }
        answer
    }
}

/// The root's box as a box test's child 0 (child 1 is the same box, and ignored).
fn root_boxes(img: &SceneImage) -> box_test::ChildBoxes {
    let (min, max) = img.root_box;
    box_test::ChildBoxes {
        min: min.map(|x| [x, x]),
        max: max.map(|x| [x, x]),
    }
}
