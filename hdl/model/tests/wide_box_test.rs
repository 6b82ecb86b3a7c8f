//! The wide node's quantized box test against an exact oracle: rational arithmetic on the
//! real box (the child's grid planes grown by the ray's padding), the real ray `o + t·d`
//! (slope `1/d`, or the huge slope where the unit uses it), `[0, t_hi]`. Whatever the exact
//! test enters, the quantized test must enter, reporting an entry distance no later than the
//! exact one and a width that holds the exact exit. Inputs are adversarial: rays through
//! grid planes, edges and corners, origins on faces and inside, zero, subnormal and huge
//! direction components, tiny and huge scenes, NaN and infinite values.

use hw_model::traversal::wide::box_test::{wide_box_test, NodeEntry, WideRay};
use hw_model::traversal::wide::cases::{node_inside, random_case};
use hw_model::traversal::wide::{Child, WideNode};
use num_bigint::BigInt;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Every f32 and grid plane is an integer times 2^-SCALE.
const SCALE: i32 = 300;

fn exact(x: f64) -> BigInt {
    // Every value here is an f32 or `p + q·2^e` with e ≥ −128: exact in the scaled integer.
    assert!(x.is_finite());
    let (m, e) = decompose(x);
    let shift = e + SCALE;
    assert!(shift >= 0, "{x} below the oracle's scale");
    BigInt::from(m) << shift as usize
}

/// `x = m · 2^e` exactly.
fn decompose(x: f64) -> (i64, i32) {
    if x == 0.0 {
        return (0, 0);
    }
    let b = x.to_bits();
    let e = ((b >> 52) & 0x7FF) as i32;
    let frac = (b & ((1 << 52) - 1)) as i64;
    let (m, e) = if e == 0 {
        (frac, -1074)
    } else {
        (frac | 1 << 52, e - 1075)
    };
    (if x < 0.0 { -m } else { m }, e)
}

/// `n / d` with `d > 0`.
#[derive(Clone, Debug)]
struct Frac {
    n: BigInt,
    d: BigInt,
}

impl Frac {
    fn new(n: BigInt, d: BigInt) -> Frac {
        if d.sign() == num_bigint::Sign::Minus {
            Frac { n: -n, d: -d }
        } else {
            Frac { n, d }
        }
    }
    fn le(&self, o: &Frac) -> bool {
        &self.n * &o.d <= &o.n * &self.d
    }
    fn of(x: f64) -> Frac {
        Frac::new(exact(x), BigInt::from(1) << SCALE as usize)
    }
}

/// The exact slab interval of the real box `[lo, hi]` (planes scaled by 2^SCALE) within
/// `[0, t_hi]`: `(near, far)`, `far` `None` for +∞; `None` if nothing is entered (NaN t_hi).
fn exact_interval(
    orig: [f32; 3],
    dir: [f32; 3],
    ray: &WideRay,
    lo: &[BigInt; 3],
    hi: &[BigInt; 3],
) -> Option<(Frac, Option<Frac>)> {
    if ray.t_hi.is_nan() {
        return None;
    }
    let mut near = Frac::of(0.0);
    let mut far = ray.t_hi.is_finite().then(|| Frac::of(f64::from(ray.t_hi)));
    for a in 0..3 {
        let o = exact(f64::from(orig[a]));
        // The unit's slope: 1/d, or its huge stand-in where the reciprocal is not finite.
        let huge = ray.inv_dir[a].abs() == 1e30;
        let (num_scale, den) = if huge {
            (
                exact(f64::from(ray.inv_dir[a])),
                BigInt::from(1) << (2 * SCALE) as usize,
            )
        } else {
            (BigInt::from(1), exact(f64::from(dir[a])))
        };
        let t = |plane: &BigInt| Frac::new((plane - &o) * &num_scale, den.clone());
        let (t_lo, t_hi) = (t(&lo[a]), t(&hi[a]));
        let (entry, exit) = if t_lo.le(&t_hi) {
            (t_lo, t_hi)
        } else {
            (t_hi, t_lo)
        };
        if near.le(&entry) {
            near = entry;
        }
        far = Some(match far {
            Some(f) if f.le(&exit) => f,
            _ => exit,
        });
    }
    Some((near, far))
}

/// The child's exact box on the node's grid, grown by `pad` (scaled by 2^SCALE).
fn child_planes(node: &WideNode, child: &Child, pad: f32) -> ([BigInt; 3], [BigInt; 3]) {
    let pad = exact(f64::from(pad));
    let plane = |a: usize, q: u8| {
        exact(f64::from(node.origin[a]))
            + (BigInt::from(q) << (i32::from(node.exp[a]) + SCALE) as usize)
    };
    (
        std::array::from_fn(|a| plane(a, child.lo[a]) - &pad),
        std::array::from_fn(|a| plane(a, child.hi[a]) + &pad),
    )
}

/// Checks `node`'s test at `at` for `ray` against the exact test, every exit also capped at
/// `cap` (the parent's exact exit: a node's children lie in its box); returns per child its
/// exact `(near, far)` where entered.
fn check(
    node: &WideNode,
    orig: [f32; 3],
    dir: [f32; 3],
    ray: &WideRay,
    at: NodeEntry,
    cap: Option<&Frac>,
) -> Vec<Option<(Frac, Option<Frac>)>> {
    let got = wide_box_test(ray, node, at);
    let mut exact_entered = Vec::new();
    for (slot, child) in node.children.iter().enumerate() {
        let (lo, hi) = child_planes(node, child, ray.pad);
        let Some((near, far)) = exact_interval(orig, dir, ray, &lo, &hi) else {
            exact_entered.push(None);
            continue;
        };
        // Within the node's own window: from t0, up to its exit.
        let t0 = Frac::of(f64::from(at.t0));
        let near = if near.le(&t0) { t0 } else { near };
        let far = match (far, cap) {
            (Some(f), Some(c)) if c.le(&f) => Some(c.clone()),
            (None, Some(c)) => Some(c.clone()),
            (f, _) => f,
        };
        if !far.as_ref().is_none_or(|f| near.le(f)) {
            exact_entered.push(None);
            continue;
        }
        let Some(e) = got.iter().find(|e| e.slot == slot) else {
            panic!(
                "child {slot} entered exactly but not by the quantized test:\n node {node:?}\n orig {orig:?} dir {dir:?} ray {ray:?} at {at:?}"
            );
        };
        assert!(
            Frac::of(f64::from(e.entry.t0)).le(&near),
            "child {slot}: entry {} beyond the exact entry {near:?}; {orig:?} {dir:?} {node:?}",
            e.entry.t0,
        );
        if let (Some(far), true) = (&far, e.entry.width_exp < 511) {
            let reach = f64::from(e.entry.t0) + 2f64.powi(i32::from(e.entry.width_exp));
            assert!(
                far.le(&Frac::of(reach)),
                "child {slot}: exit {far:?} beyond t0 + 2^w = {reach}"
            );
        }
        exact_entered.push(Some((near, far)));
    }
    exact_entered
}

fn run(seed: u64, cases: usize, padded: bool) -> (usize, usize) {
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut exact, mut got) = (0, 0);
    for _ in 0..cases {
        let width = [2, 4, 8][rng.gen_range(0..3)];
        let case = random_case(&mut rng, width);
        let mut ray = WideRay::new(case.orig, case.dir, case.bound);
        if !padded {
            // A unit without the origin's padding: the rounding margins alone must hold.
            ray.pad = 0.0;
            ray.pad_t = [0.0; 3];
        }
        let entered = check(&case.node, case.orig, case.dir, &ray, NodeEntry::ROOT, None);
        exact += entered.iter().flatten().count();
        let quantized = wide_box_test(&ray, &case.node, NodeEntry::ROOT);
        got += quantized.len();
        // One level down, from where the walk enters a child.
        for e in quantized {
            let Some((_, far)) = &entered[e.slot] else {
                continue;
            };
            let child = case.node.children[e.slot];
            let inner = node_inside(&mut rng, &case.node, &child, width);
            check(&inner, case.orig, case.dir, &ray, e.entry, far.as_ref());
        }
    }
    (exact, got)
}

#[test]
fn the_quantized_test_enters_every_child_the_exact_test_enters() {
    let cases = 30_000;
    let (exact, got) = run(39, cases, true);
    // Not trivially "enter everything": most children entered are entered exactly.
    assert!(exact > cases / 4, "{exact} of {cases}");
    assert!(
        got < exact * 3 / 2 + cases / 10,
        "{got} entered, {exact} exact"
    );
}

#[test]
fn without_the_origins_padding_the_rounding_margins_hold_alone() {
    run(40, 30_000, false);
}
