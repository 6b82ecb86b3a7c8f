//! Random and adversarial wide node tests (feature `strategies`): nodes at every scale with
//! children of every shape, and rays aimed at their corners, edges and faces from inside,
//! nearby and far away, with zero, subnormal and huge direction components — the inputs the
//! box test's soundness test (hw-model), the RTL's tests (hdl) and its co-simulation (sim)
//! share; and whole node tests ([`random_test`]) for the RTL, special words included.

use crate::traversal::scene_image::Link;
use rand::rngs::StdRng;
use rand::Rng;

use super::box_test::{wide_box_test, NodeEntry, WideRay, WIDTH_MIN, WIDTH_UNBOUNDED};
use super::{Child, WideNode};

/// A uniform value in `(−magnitude, magnitude)`.
pub fn f32_of(rng: &mut StdRng, magnitude: f32) -> f32 {
    let x: f32 = rng.gen_range(-1.0..1.0);
    x * magnitude
}

/// An adversarial direction component.
pub fn component(rng: &mut StdRng) -> f32 {
    match rng.gen_range(0..10) {
        0 => 0.0,
        1 => -0.0,
        2 => f32::from_bits(rng.gen_range(1..0x80_0000)) * if rng.gen() { 1.0 } else { -1.0 },
        3 => f32_of(rng, 1e-6),
        4 => f32_of(rng, 1e20),
        _ => f32_of(rng, 1.0),
    }
}

/// A node, and a ray with its hit bound.
#[derive(Clone, Debug)]
pub struct Case {
    pub node: WideNode,
    pub orig: [f32; 3],
    pub dir: [f32; 3],
    pub bound: f32,
}

/// A node of 1 to `width` random children (a quarter of their sides flat) on a grid near
/// `scale`, its origin within `4·scale`.
pub fn random_node(rng: &mut StdRng, width: usize, scale: f32) -> WideNode {
    let exp_base = scale.log2().floor() as i32 - 8;
    WideNode {
        origin: std::array::from_fn(|_| f32_of(rng, scale * 4.0)),
        exp: std::array::from_fn(|_| (exp_base + rng.gen_range(-3..=1)).clamp(-128, 127) as i8),
        children: (0..rng.gen_range(1..=width))
            .map(|k| {
                let lo: [u8; 3] = std::array::from_fn(|_| rng.gen());
                let hi = std::array::from_fn(|a| {
                    if rng.gen_range(0..4) == 0 {
                        lo[a]
                    } else {
                        rng.gen_range(lo[a]..=255)
                    }
                });
                Child {
                    lo,
                    hi,
                    link: Link {
                        first: k as u32,
                        count: 1,
                    },
                }
            })
            .collect(),
    }
}

/// A point of the child's box: a corner, an edge or face point, or inside (rounded to f32).
pub fn box_point(rng: &mut StdRng, node: &WideNode, child: &Child) -> [f32; 3] {
    std::array::from_fn(|a| {
        let q = match rng.gen_range(0..3) {
            0 => f64::from(child.lo[a]),
            1 => f64::from(child.hi[a]),
            _ => rng.gen_range(f64::from(child.lo[a])..=f64::from(child.hi[a])),
        };
        (f64::from(node.origin[a]) + q * 2f64.powi(i32::from(node.exp[a]))) as f32
    })
}

/// A node of up to `width` children at a scale from 2^-40 to 2^40 and a ray aimed at one of
/// its children or passing by, with an infinite, huge, small, zero or random bound.
pub fn random_case(rng: &mut StdRng, width: usize) -> Case {
    let scale = 2f32.powi(rng.gen_range(-40..40));
    let node = random_node(rng, width, scale);
    let child = node.children[rng.gen_range(0..node.children.len())];
    let (orig, dir) = match rng.gen_range(0..5) {
        // Aimed at a corner, edge or face point of a child, from outside or inside, or from
        // far away (where the fp32 offset α is large against the node: its rounding matters).
        0..=2 => {
            let target = box_point(rng, &node, &child);
            let far = 2f32.powi(rng.gen_range(3..20));
            let orig = match rng.gen_range(0..3) {
                0 => box_point(rng, &node, &child),
                1 => std::array::from_fn(|a| node.origin[a] + f32_of(rng, scale * 8.0)),
                _ => std::array::from_fn(|a| node.origin[a] + f32_of(rng, scale * far)),
            };
            let dir = std::array::from_fn(|a| target[a] - orig[a]);
            (orig, dir)
        }
        // An origin on a face or corner, any direction.
        3 => (
            box_point(rng, &node, &child),
            std::array::from_fn(|_| component(rng)),
        ),
        _ => (
            std::array::from_fn(|a| node.origin[a] + f32_of(rng, scale * 8.0)),
            std::array::from_fn(|_| component(rng)),
        ),
    };
    let bound = match rng.gen_range(0..5) {
        0 => f32::INFINITY,
        1 => f32::MAX,
        2 => rng.gen_range(0.0..2.0),
        3 => 0.0,
        _ => rng.gen_range(0.0..1e6),
    };
    Case {
        node,
        orig,
        dir,
        bound,
    }
}

/// A node inside `child`'s box on `parent`'s grid: its grid starts at the child's lower
/// corner (rounded up into the box) and spans at most the child's extent.
pub fn node_inside(rng: &mut StdRng, parent: &WideNode, child: &Child, width: usize) -> WideNode {
    let mut node = random_node(rng, width, 1.0);
    for a in 0..3 {
        let step = 2f64.powi(i32::from(parent.exp[a]));
        let lo = f64::from(parent.origin[a]) + f64::from(child.lo[a]) * step;
        let hi = f64::from(parent.origin[a]) + f64::from(child.hi[a]) * step;
        let mut origin = lo as f32;
        if f64::from(origin) < lo {
            origin = origin.next_up();
        }
        let room = hi - f64::from(origin);
        // The finest step of the child's grid: 255 of them fit the room.
        let e = if room > 0.0 {
            ((room / 255.0).log2().floor() as i32).clamp(-128, 127)
        } else {
            -128
        };
        node.origin[a] = origin;
        node.exp[a] = e as i8;
        if room <= 0.0 {
            // A flat child: its descendants sit on one plane.
            node.children
                .iter_mut()
                .for_each(|c| (c.lo[a], c.hi[a]) = (0, 0));
        }
    }
    node
}

/// One box test of a wide node: the ray, the node and where the walk entered it.
#[derive(Clone, Debug)]
pub struct NodeTest {
    pub ray: WideRay,
    pub node: WideNode,
    pub at: NodeEntry,
}

/// An fp32 word that is often special: ±0, ±∞, NaN, a subnormal, the largest finite value,
/// a power of two from 2^-126 to 2^127, a random finite value or random bits.
pub fn special_word(rng: &mut StdRng) -> f32 {
    let sign = if rng.gen() { 1.0 } else { -1.0 };
    sign * match rng.gen_range(0..9) {
        0 => 0.0,
        1 => f32::INFINITY,
        2 => f32::NAN,
        3 => f32::from_bits(rng.gen_range(1..0x80_0000)),
        4 => f32::MAX,
        5 => 2f32.powi(rng.gen_range(-126..=127)),
        6 => {
            let magnitude = 2f32.powi(rng.gen_range(-40..40));
            f32_of(rng, magnitude)
        }
        _ => f32::from_bits(rng.gen()),
    }
}

/// A node test of up to `width` children, in turn: a [`random_case`] at the root; one level
/// below it (a node inside a child the root's test entered, entered where that test said);
/// a random case entered anywhere (any `t0`, any width exponent); and a random case whose
/// ray and entry words are [`special_word`]s (with inverted codes too) — words the ray setup
/// and a walk never produce, which the stage must still answer as the model does.
pub fn random_test(rng: &mut StdRng, width: usize) -> NodeTest {
    let case = random_case(rng, width);
    let ray = WideRay::new(case.orig, case.dir, case.bound);
    match rng.gen_range(0..4) {
        0 => NodeTest {
            ray,
            node: case.node,
            at: NodeEntry::ROOT,
        },
        1 => {
            let entered = wide_box_test(&ray, &case.node, NodeEntry::ROOT);
            let Some(e) = entered.get(rng.gen_range(0..entered.len().max(1))) else {
                return NodeTest {
                    ray,
                    node: case.node,
                    at: NodeEntry::ROOT,
                };
            };
            let child = case.node.children[e.slot];
            NodeTest {
                ray,
                node: node_inside(rng, &case.node, &child, width),
                at: e.entry,
            }
        }
        2 => NodeTest {
            ray,
            node: case.node,
            at: NodeEntry {
                t0: if rng.gen() {
                    rng.gen_range(0.0..1e3)
                } else {
                    special_word(rng)
                },
                width_exp: rng.gen_range(WIDTH_MIN..=WIDTH_UNBOUNDED),
            },
        },
        _ => {
            let mut node = case.node;
            for c in &mut node.children {
                if rng.gen_range(0..4) == 0 {
                    c.lo = std::array::from_fn(|_| rng.gen());
                    c.hi = std::array::from_fn(|_| rng.gen());
                }
            }
            let word = |rng: &mut StdRng, x: f32| if rng.gen() { special_word(rng) } else { x };
            let ray = WideRay {
                orig: ray.orig.map(|x| word(rng, x)),
                inv_dir: ray.inv_dir.map(|x| word(rng, x)),
                pad_t: ray.pad_t.map(|x| word(rng, x)),
                pad: ray.pad,
                t_hi: word(rng, ray.t_hi),
            };
            NodeTest {
                ray,
                node,
                at: NodeEntry {
                    t0: word(rng, 0.0),
                    width_exp: rng.gen_range(WIDTH_MIN..=WIDTH_UNBOUNDED),
                },
            }
        }
    }
}
