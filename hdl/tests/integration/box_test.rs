//! The traversal unit's box test in rust-hdl's simulator, bit for bit against
//! `hw_model::traversal::box_test::box_test`, one test per cycle, with `valid_out` and the tag
//! checked to be `valid_in` and `tag_in` delayed by exactly `latency(depth)`; at depth 0, 1
//! and the maximum. Then its Verilog through Verilator's lint, and (ignored, slow) its yosys
//! resources: `cargo test --release -p hdl --test integration box_test:: -- --ignored --nocapture`.

use hdl::traversal::box_test::{
    box_test_verilog, latency, max_depth, schedule, simulate_box_test, BoxInput, BoxOutput,
};
use hw_model::traversal::box_test::{box_test, ray_setup, BoxResult, ChildBoxes, RaySetup};
use rand::{rngs::StdRng, Rng, SeedableRng};

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;
/// The smallest and the largest fp32 subnormal.
const TINY: f32 = 1e-45;
const SUB: f32 = 1.1e-38;

fn cube(lo: f32, hi: f32) -> ChildBoxes {
    ChildBoxes {
        min: [[lo; 2]; 3],
        max: [[hi; 2]; 3],
    }
}

/// Child 0 is `a`, child 1 is `b` ([min, max] per axis).
fn pair(a: [[f32; 2]; 3], b: [[f32; 2]; 3]) -> ChildBoxes {
    ChildBoxes {
        min: [0, 1, 2].map(|k| [a[k][0], b[k][0]]),
        max: [0, 1, 2].map(|k| [a[k][1], b[k][1]]),
    }
}

/// A ray setup whose fields are given as they are, not derived from a ray: the block takes
/// any words, so specials the ray setup never produces (an infinite or zero slope, a NaN
/// t_hi) are tested too.
fn raw(orig_lo: [f32; 3], orig_hi: [f32; 3], inv_dir: [f32; 3], t_hi: f32) -> RaySetup {
    RaySetup {
        orig_lo,
        orig_hi,
        inv_dir,
        pad: 0.0,
        t_hi,
    }
}

/// The special cases: rays from `ray_setup` and raw setups against boxes.
fn special_cases() -> Vec<(RaySetup, ChildBoxes)> {
    let unit = cube(0.0, 1.0);
    let down = |x: f32, y: f32| ray_setup([x, y, 5.0], [0.0, 0.0, -1.0], f32::MAX);
    let beside = pair([[0.0, 1.0]; 3], [[2.0, 3.0], [0.0, 1.0], [0.0, 1.0]]);
    let behind = pair([[0.0, 1.0]; 3], [[0.0, 1.0], [0.0, 1.0], [5.0, 6.0]]);
    let stacked = pair([[0.0, 1.0]; 3], [[0.0, 1.0], [0.0, 1.0], [2.0, 3.0]]);
    let mut v = vec![
        // Plain hits and misses, child 1 nearer, a tie.
        (down(0.5, 0.5), unit),
        (down(0.5, 0.5), beside),
        (down(0.5, 0.5), behind),
        (down(0.5, 0.5), stacked),
        (down(1.5, 0.5), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, 1.0], f32::MAX), unit), // pointing away
        // Zero direction components (±0): the huge slope, inside and outside the slab.
        (
            ray_setup([0.5, 0.5, 5.0], [0.0, -0.0, -1.0], f32::MAX),
            unit,
        ),
        (
            ray_setup([1.5, 0.5, 5.0], [-0.0, 0.0, -1.0], f32::MAX),
            unit,
        ),
        (ray_setup([0.5, 0.5, 0.5], [0.0, 0.0, 0.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -0.0], f32::MAX), unit),
        // Rays starting inside a box (near = 0), and a short bound.
        (ray_setup([0.5, 0.5, 0.5], [1.0, 0.0, 0.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 0.5], [-0.3, 0.7, 0.1], 0.01), behind),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], 2.0), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], 4.0), unit), // just reaches it
        // Degenerate boxes: min == max on one axis (flat), on all axes (a point).
        (
            down(0.5, 0.5),
            pair([[0.0, 1.0], [0.0, 1.0], [2.0, 2.0]], [[0.5, 0.5]; 3]),
        ),
        (
            down(0.5, 0.5),
            pair(
                [[0.5, 0.5], [0.0, 1.0], [0.0, 1.0]],
                [[0.5, 0.5], [0.5, 0.5], [0.0, 1.0]],
            ),
        ),
        (
            ray_setup([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], f32::MAX),
            pair([[1.0, 1.0]; 3], [[0.0, 0.0]; 3]),
        ),
        // Inverted boxes (min > max) on one and on all axes.
        (
            down(0.5, 0.5),
            pair([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0]], [[1.0, 0.0]; 3]),
        ),
        (down(0.5, 0.5), cube(1.0, 0.0)),
        // NaN and ±Inf in the origin, the direction and the bound.
        (ray_setup([NAN, 0.5, 5.0], [0.0, 0.0, -1.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [NAN, 0.0, -1.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], NAN), unit),
        (ray_setup([INF, 0.5, 5.0], [0.0, 0.0, -1.0], f32::MAX), unit),
        (ray_setup([0.5, -INF, 5.0], [0.0, 1.0, 0.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -INF], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [INF, -INF, 1.0], f32::MAX), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], INF), unit),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], -INF), unit),
        // … and in the bounds.
        (down(0.5, 0.5), pair([[NAN, 1.0]; 3], [[0.0, NAN]; 3])),
        (down(0.5, 0.5), pair([[-INF, INF]; 3], [[0.0, INF]; 3])),
        (down(0.5, 0.5), pair([[-INF, -INF]; 3], [[INF, INF]; 3])),
        // Subnormals in the origin, the direction and the bounds (flushed to zero).
        (
            ray_setup([SUB, TINY, 5.0], [0.0, 0.0, -1.0], f32::MAX),
            unit,
        ),
        (
            ray_setup([0.5, 0.5, 5.0], [TINY, -SUB, -1.0], f32::MAX),
            unit,
        ),
        (ray_setup([0.5, 0.5, 5.0], [0.0, 0.0, -1.0], SUB), unit),
        (down(0.5, 0.5), pair([[-SUB, SUB]; 3], [[TINY, 1.0]; 3])),
        // Huge values whose differences and products overflow.
        (
            ray_setup([-3e38, 0.5, 5.0], [1.0, 0.0, -1.0], f32::MAX),
            pair(
                [[3e38, 3.4e38], [0.0, 1.0], [0.0, 1.0]],
                [[-3.4e38, 3.4e38]; 3],
            ),
        ),
        (
            ray_setup([0.5, 0.5, 5.0], [1e-30, 0.0, -1e-30], f32::MAX),
            pair([[1e10, 2e10], [0.0, 1.0], [0.0, 1.0]], [[-1e30, 1e30]; 3]),
        ),
        (
            ray_setup([1e38, 1e38, 1e38], [-1.0, -1.0, -1.0], f32::MAX),
            unit,
        ),
    ];
    // Raw setups: zero, infinite, NaN and subnormal slopes; NaN, −0, subnormal t_hi.
    let o = [0.5, 0.5, 5.0];
    for inv in [
        [0.0, 0.0, -1.0],
        [-0.0, INF, -1.0],
        [INF, -INF, -1.0],
        [NAN, 0.0, -1.0],
        [SUB, TINY, -1.0],
        [1e30, -1e30, 1e30],
    ] {
        v.push((raw(o, o, inv, 1e30), unit));
    }
    for t_hi in [NAN, -NAN, -0.0, 0.0, TINY, -1.0, INF] {
        v.push((raw(o, o, [1e30, 1e30, -1.0], t_hi), unit));
        v.push((raw([0.5; 3], [0.5; 3], [1.0, 1.0, 1.0], t_hi), unit));
    }
    v
}

/// Random tests: rays from random origins in random directions with random bounds, against
/// boxes around points near the ray (about half are entered, some inverted), and one in five
/// made of random bit patterns.
fn random_cases(n: usize, seed: u64) -> Vec<(RaySetup, ChildBoxes)> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            if i % 5 == 4 {
                let mut w = || f32::from_bits(rng.gen());
                let ray = raw([w(), w(), w()], [w(), w(), w()], [w(), w(), w()], w());
                let boxes = ChildBoxes {
                    min: [[w(), w()], [w(), w()], [w(), w()]],
                    max: [[w(), w()], [w(), w()], [w(), w()]],
                };
                return (ray, boxes);
            }
            let orig = [0; 3].map(|_| rng.gen_range(-10.0..10.0f32));
            let dir = [0; 3].map(|_| rng.gen_range(-1.0..1.0f32));
            let bound = match i % 3 {
                0 => f32::MAX,
                1 => INF,
                _ => rng.gen_range(0.0..30.0),
            };
            let mut boxes = ChildBoxes::default();
            for c in 0..2 {
                let t = rng.gen_range(-5.0..20.0f32);
                for k in 0..3 {
                    let centre = orig[k] + t * dir[k] + rng.gen_range(-1.0..1.0f32);
                    let half = rng.gen_range(-0.2..2.0f32);
                    boxes.min[k][c] = centre - half;
                    boxes.max[k][c] = centre + half;
                }
            }
            (ray_setup(orig, dir, bound), boxes)
        })
        .collect()
}

/// Streams `cases` through the block at `depth` (three idle cycles first, a gap in
/// `valid_in` every seventh cycle, the tag counting) and checks every output cycle against
/// `model` and `latency(depth)`.
fn check_with(
    depth: usize,
    cases: &[(RaySetup, ChildBoxes)],
    model: impl Fn(&RaySetup, &ChildBoxes) -> BoxResult,
) -> Vec<BoxOutput> {
    let lat = latency(depth);
    let inputs: Vec<BoxInput> = (0..3)
        .map(|_| BoxInput::idle())
        .chain(cases.iter().enumerate().map(|(i, &(ray, boxes))| BoxInput {
            valid: i % 7 != 6,
            tag: (i as u16).wrapping_mul(0x9E37) ^ 0x5A5A,
            ray,
            boxes,
        }))
        .collect();
    let out = simulate_box_test(depth, &inputs, lat);
    let first_valid = out
        .iter()
        .position(|o| o.valid)
        .expect("valid_out never rose");
    assert_eq!(first_valid - 3, lat, "depth {depth}: observed latency");
    for (cycle, o) in out.iter().enumerate() {
        let Some(c) = cycle.checked_sub(lat) else {
            assert!(!o.valid, "depth {depth}: valid_out in cycle {cycle}");
            continue;
        };
        let x = inputs.get(c).copied().unwrap_or_else(BoxInput::idle);
        assert_eq!(
            o.valid, x.valid,
            "depth {depth}: valid_out in cycle {cycle}"
        );
        if !x.valid {
            continue;
        }
        assert_eq!(o.tag, x.tag, "depth {depth}: tag in cycle {cycle}");
        let want = model(&x.ray, &x.boxes);
        assert!(
            o.same_bits(&want),
            "depth {depth}, test {}: {:?} {:?}\n block {:?}\n model {want:?}",
            c - 3,
            x.ray,
            x.boxes,
            o.result()
        );
    }
    out
}

/// [`check_with`] the model, and that the stream held entered and missed boxes and both
/// visiting orders (so the comparison had something to tell apart).
fn check(depth: usize, cases: &[(RaySetup, ChildBoxes)]) {
    let out = check_with(depth, cases, box_test);
    let valid: Vec<_> = out.iter().filter(|o| o.valid).collect();
    let entered = valid.iter().filter(|o| o.enters[0]).count();
    let both_first1 = valid
        .iter()
        .filter(|o| o.enters == [true, true] && o.first)
        .count();
    eprintln!(
        "depth {depth}: latency {}, {} tests, child 0 entered in {entered}, child 1 first in {both_first1}",
        latency(depth),
        valid.len()
    );
    assert!(
        entered >= 5 && valid.len() - entered >= 5,
        "{entered} of {}",
        valid.len()
    );
    assert!(both_first1 >= 2, "{both_first1}");
}

fn cases(random: usize, seed: u64) -> Vec<(RaySetup, ChildBoxes)> {
    let mut v = special_cases();
    v.extend(random_cases(random, seed));
    v
}

#[test]
fn box_test_matches_the_model_combinational() {
    check(0, &cases(2000, 1));
}

#[test]
fn box_test_matches_the_model_at_depth_1() {
    check(1, &cases(2000, 2));
}

#[test]
fn box_test_matches_the_model_at_max_depth() {
    check(max_depth(), &cases(2000, 3));
}

/// The harness fails when the block and the reference disagree: against a model that
/// swaps the children's answers (and with them `first`), the first test with different
/// children is reported.
#[test]
#[should_panic(expected = "model BoxResult")]
fn a_wrong_model_is_caught() {
    let swapped = |ray: &RaySetup, boxes: &ChildBoxes| {
        let r = box_test(ray, boxes);
        BoxResult {
            enters: [r.enters[1], r.enters[0]],
            near: [r.near[1], r.near[0]],
            first: r.first,
        }
    };
    check_with(1, &special_cases()[..4], swapped);
}

#[test]
fn latency_table() {
    let max = max_depth();
    let l: Vec<usize> = (0..=max).map(latency).collect();
    println!("box test latency at depth 0..={max}: {l:?}");
    assert_eq!(l[0], 0, "a combinational block");
    assert!(l.windows(2).all(|w| w[0] < w[1]), "{l:?}");
    assert_eq!(latency(max + 1), l[max], "depth beyond max_depth");
    // The schedule's parts add up to it: sub, mul, lt (order), three fold steps, lt.
    let s = schedule(max);
    assert_eq!(s.sub + s.mul + 5 * s.lt, s.latency);
}

#[test]
fn box_test_verilog_passes_verilator_lint() {
    for depth in [0, 1, max_depth()] {
        let v = box_test_verilog(depth);
        for port in [
            "valid_in",
            "tag_in",
            "t_hi",
            "min$5",
            "valid_out",
            "near$1",
            "first",
        ] {
            assert!(v.contains(port), "depth {depth}: no port {port}");
        }
        if let Err(e) = hdl::verilog::verilator_lint(&v) {
            panic!("depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// yosys xc7 resources and register-to-register logic depth at depths 1 and max:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture box_test::box_test_resources`
#[test]
#[ignore]
fn box_test_resources() {
    let designs = [1, max_depth()].map(|depth| {
        (
            format!("box test depth {depth} (latency {})", latency(depth)),
            box_test_verilog(depth),
        )
    });
    println!("{}", hdl::synth::markdown_table(&designs).unwrap());
}
