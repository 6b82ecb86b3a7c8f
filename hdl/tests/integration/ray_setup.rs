//! The traversal unit's ray setup and far end in rust-hdl's simulator, bit for bit against
//! `hw_model::traversal::box_test::{ray_setup, t_hi}`, one ray (or bound) per cycle, with
//! `valid_out` and the tag checked to be `valid_in` and `tag_in` delayed by exactly
//! `latency(depth)`; at depth 0, 1 and the maximum. Then their Verilog through Verilator's
//! lint, and (ignored, slow) the ray setup's yosys resources:
//! `cargo test --release -p hdl --test integration ray_setup:: -- --ignored --nocapture`.

use hdl::traversal::far_end::{self, far_end_verilog, simulate_far_end, FarInput, FarOutput};
use hdl::traversal::ray_setup::{
    latency, max_depth, ray_setup_verilog, schedule, simulate_ray_setup, SetupInput, SetupOutput,
};
use hw_model::traversal::box_test::{ray_setup, t_hi, RaySetup, HUGE_SLOPE, PAD};
use rand::{rngs::StdRng, Rng, SeedableRng};

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;
const MAX: f32 = f32::MAX;
/// The smallest and the largest fp32 subnormal, and the smallest normal.
const TINY: f32 = 1e-45;
const SUB: f32 = 1.1e-38;
const MIN: f32 = f32::MIN_POSITIVE;

/// A ray: origin, direction, bound.
type Ray = ([f32; 3], [f32; 3], f32);

/// The special cases: NaN, ±Inf, ±0 and subnormal components in the origin, the
/// direction and the bound; bound = FLT_MAX and +Inf; huge origins whose pad (and o ± pad)
/// overflows; ties and NaNs in the magnitude fold.
fn special_rays() -> Vec<Ray> {
    let o = [0.5, 0.5, 5.0];
    let d = [0.0, 0.0, -1.0];
    let mut v: Vec<Ray> = vec![
        (o, d, MAX),
        (o, [0.3, -0.7, 0.2], 10.0),
        ([0.0; 3], [1.0; 3], MAX), // pad = 0
        ([-0.0; 3], [-0.0; 3], -0.0),
        ([-0.0, 0.0, -0.0], [0.0, -0.0, 1.0], 0.0),
        // The magnitude fold: each axis the largest, ties of ±x, NaNs and infinities.
        ([7.0, -3.0, 2.0], d, MAX),
        ([1.0, -7.0, 2.0], d, MAX),
        ([1.0, 3.0, -7.0], d, MAX),
        ([-2.0, 2.0, -2.0], d, MAX),
        ([NAN, 2.0, 1.0], d, MAX),
        ([1.0, NAN, 3.0], d, MAX),
        ([1.0, 2.0, -NAN], d, MAX),
        ([NAN, NAN, NAN], d, MAX),
        ([INF, 1.0, 1.0], d, MAX),
        ([1.0, -INF, NAN], d, MAX),
        ([NAN, -INF, INF], d, MAX),
        // Subnormal origins (flushed: magnitude +0 or the other axes').
        ([SUB, TINY, -SUB], d, MAX),
        ([SUB, -TINY, 1e-30], d, MAX),
        ([MIN, -SUB, 0.0], d, MAX),
        // Huge origins: pad ~3.4e34, o + pad overflows at FLT_MAX; a huge pad in t_hi.
        ([MAX, 0.0, 0.0], d, MAX),
        ([-MAX, 1.0, -1.0], d, 1.0),
        ([3.4e38, -3.4e38, 1e38], d, 2.0),
        ([1e38, 2e38, 3e38], [1.0, 1.0, 1.0], 3e38),
        ([-3e38, 0.5, 5.0], [1.0, 0.0, -1.0], 1e30),
        // Directions: ±0, subnormals (flushed: the huge slope, with d's sign), NaN of either
        // sign, ±Inf (slope ±0), huge (slope flushed to ±0), tiny normal (a huge slope that
        // is still finite), exact powers of two.
        (o, [0.0, -0.0, 1.0], MAX),
        (o, [TINY, -TINY, SUB], MAX),
        (o, [-SUB, MIN, -MIN], MAX),
        (o, [NAN, -NAN, 1.0], MAX),
        (o, [INF, -INF, 2.0], MAX),
        (o, [MAX, -1e38, 3e38], MAX),
        (o, [1.2e-38, -2e-38, 1e-37], MAX),
        (o, [0.25, -4.0, 1024.0], MAX),
        (o, [3.0, -7.0, 1e-30], MAX),
        // Bounds: FLT_MAX and +Inf (t_hi = +Inf), −Inf, NaN of either sign, ±0, subnormals,
        // negative, near the overflow of the loosening.
        (o, d, INF),
        (o, d, -INF),
        (o, d, NAN),
        (o, d, -NAN),
        (o, d, 0.0),
        (o, d, -0.0),
        (o, d, SUB),
        (o, d, -TINY),
        (o, d, -3.0),
        (o, d, 3.4e38),
        (o, d, 3.402e38),
        (o, d, -MAX),
        ([MAX, MAX, MAX], d, MAX),
        ([INF, 0.0, 0.0], d, -INF),
        ([-INF, 0.0, 0.0], d, 1.0),
        ([NAN, 0.0, 0.0], d, NAN),
    ];
    // Every special in every position of the origin and the direction.
    for x in [NAN, -NAN, INF, -INF, 0.0, -0.0, TINY, -SUB, MAX, -1.5] {
        for a in 0..3 {
            let mut orig = o;
            let mut dir = d;
            orig[a] = x;
            dir[a] = x;
            v.push((orig, d, 4.0));
            v.push((o, dir, 4.0));
        }
    }
    v
}

/// Random rays: origins at random scales (a few units to huge), directions in the unit cube
/// with components sometimes snapped to ±0, bounds FLT_MAX, +Inf or random; one in five made
/// of random bit patterns in every word.
fn random_rays(n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let w = |rng: &mut StdRng| f32::from_bits(rng.gen());
            if i % 5 == 4 {
                return (
                    [0; 3].map(|_| w(&mut rng)),
                    [0; 3].map(|_| w(&mut rng)),
                    w(&mut rng),
                );
            }
            let scale = [1.0, 10.0, 1e4, 1e20][i % 4];
            let orig = [0; 3].map(|_| rng.gen_range(-1.0..1.0f32) * scale);
            let dir = [0; 3].map(|_| {
                let d = rng.gen_range(-1.0..1.0f32);
                if rng.gen_bool(0.1) {
                    0.0f32.copysign(d)
                } else {
                    d
                }
            });
            let bound = match i % 3 {
                0 => MAX,
                1 => INF,
                _ => rng.gen_range(0.0..30.0f32) * scale,
            };
            (orig, dir, bound)
        })
        .collect()
}

fn rays(random: usize, seed: u64) -> Vec<Ray> {
    let mut v = special_rays();
    v.extend(random_rays(random, seed));
    v
}

/// Valid low every seventh input, the tag counting in a scrambled order.
fn valid(i: usize) -> bool {
    i % 7 != 6
}

fn tag(i: usize) -> u16 {
    (i as u16).wrapping_mul(0x9E37) ^ 0x5A5A
}

/// Checks a stream's outputs: `valid_out` and the tag are the inputs' `lat` cycles earlier
/// (`valid_out` low before), and `check(cycle, input index)` the rest of every valid one.
fn check_stream<O>(
    what: &str,
    lat: usize,
    inputs: &[(bool, u16)],
    out: &[O],
    fields: impl Fn(&O) -> (bool, u16),
    mut check: impl FnMut(usize, usize, &O),
) {
    let first_valid = out
        .iter()
        .position(|o| fields(o).0)
        .expect("valid_out never rose");
    assert_eq!(first_valid - 3, lat, "{what}: observed latency");
    for (cycle, o) in out.iter().enumerate() {
        let (v, t) = fields(o);
        let Some(c) = cycle.checked_sub(lat) else {
            assert!(!v, "{what}: valid_out in cycle {cycle}");
            continue;
        };
        let (want_valid, want_tag) = inputs.get(c).copied().unwrap_or((false, 0));
        assert_eq!(v, want_valid, "{what}: valid_out in cycle {cycle}");
        if v {
            assert_eq!(t, want_tag, "{what}: tag in cycle {cycle}");
            check(cycle, c, o);
        }
    }
}

/// Streams `rays` through the ray setup at `depth` (three idle cycles first, a gap in
/// `valid_in` every seventh cycle, the tag counting) and checks every output cycle against
/// `model` and `latency(depth)`.
fn check_setup_with(depth: usize, rays: &[Ray], model: impl Fn(&Ray) -> RaySetup) -> usize {
    let lat = latency(depth);
    let inputs: Vec<SetupInput> = (0..3)
        .map(|_| SetupInput::default())
        .chain(
            rays.iter()
                .enumerate()
                .map(|(i, &(orig, dir, bound))| SetupInput {
                    valid: valid(i),
                    tag: tag(i),
                    orig,
                    dir,
                    bound,
                }),
        )
        .collect();
    let start = std::time::Instant::now();
    let out = simulate_ray_setup(depth, &inputs, lat);
    let flags: Vec<_> = inputs.iter().map(|x| (x.valid, x.tag)).collect();
    let mut checked = 0;
    check_stream(
        &format!("ray setup depth {depth}"),
        lat,
        &flags,
        &out,
        |o: &SetupOutput| (o.valid, o.tag),
        |_, c, o| {
            let x = &inputs[c];
            let want = model(&(x.orig, x.dir, x.bound));
            assert!(
                o.same_bits(&want),
                "depth {depth}, ray {}: {:?} {:?} {:?}\n block {:?}\n model {want:?}",
                c - 3,
                x.orig,
                x.dir,
                x.bound,
                o.result()
            );
            checked += 1;
        },
    );
    eprintln!(
        "ray setup depth {depth}: latency {lat}, {checked} rays in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    checked
}

fn check_setup(depth: usize, rays: &[Ray]) {
    let model = |&(orig, dir, bound): &Ray| ray_setup(orig, dir, bound);
    let checked = check_setup_with(depth, rays, model);
    assert_eq!(checked, (0..rays.len()).filter(|&i| valid(i)).count());
}

#[test]
fn ray_setup_matches_the_model_combinational() {
    check_setup(0, &rays(3000, 1));
}

#[test]
fn ray_setup_matches_the_model_at_depth_1() {
    check_setup(1, &rays(3000, 2));
}

#[test]
fn ray_setup_matches_the_model_at_max_depth() {
    check_setup(max_depth(), &rays(3000, 3));
}

/// The special rays exercise what they are meant to: huge slopes of both signs, infinite and
/// NaN words in every output field, pads that overflow.
#[test]
fn the_special_rays_reach_the_special_outputs() {
    let setups: Vec<RaySetup> = special_rays()
        .iter()
        .map(|&(o, d, b)| ray_setup(o, d, b))
        .collect();
    let any = |f: &dyn Fn(&RaySetup) -> bool| setups.iter().any(f);
    assert!(any(&|s| s.inv_dir.contains(&HUGE_SLOPE)));
    assert!(any(&|s| s.inv_dir.contains(&-HUGE_SLOPE)));
    assert!(any(&|s| s
        .inv_dir
        .iter()
        .any(|x| x.to_bits() == 0x8000_0000)));
    assert!(any(&|s| s.pad == INF));
    assert!(any(&|s| s.pad.is_finite() && s.orig_lo.contains(&INF)));
    assert!(any(&|s| s.orig_hi.iter().any(|x| x.is_nan())));
    assert!(any(&|s| s.t_hi == INF && s.pad.is_finite()));
    assert!(any(&|s| s.t_hi.is_nan()));
    assert!(any(&|s| s.t_hi < 0.0 && s.t_hi.is_finite()));
    assert!(any(&|s| s.t_hi.to_bits() == 0));
}

/// The harness fails when the block and the reference disagree: against a model that gives
/// a zero direction the positive huge slope whatever its sign, the first −0 is reported.
#[test]
#[should_panic(expected = "model RaySetup")]
fn a_wrong_ray_setup_model_is_caught() {
    let unsigned_huge = |&(orig, dir, bound): &Ray| {
        let mut s = ray_setup(orig, dir, bound);
        s.inv_dir = s
            .inv_dir
            .map(|x| if x == -HUGE_SLOPE { HUGE_SLOPE } else { x });
        s
    };
    check_setup_with(1, &special_rays()[..5], unsigned_huge);
}

#[test]
fn latency_table() {
    let max = max_depth();
    let l: Vec<usize> = (0..=max).map(latency).collect();
    let f: Vec<usize> = (0..=far_end::max_depth()).map(far_end::latency).collect();
    println!("ray setup latency at depth 0..={max}: {l:?}");
    println!(
        "far end latency at depth 0..={}: {f:?}",
        far_end::max_depth()
    );
    for l in [&l, &f] {
        assert_eq!(l[0], 0, "a combinational block");
        assert!(l.windows(2).all(|w| w[0] < w[1]), "{l:?}");
    }
    assert_eq!(latency(max + 1), l[max], "depth beyond max_depth");
    assert_eq!(far_end::latency(max + 1), f[far_end::max_depth()]);
    // The far end is on the longest path: its bound enters when its pad (3·lt + mul) can
    // still join it in time, or at once.
    for depth in 0..=max {
        let s = schedule(depth);
        assert_eq!(s.latency, s.t_hi, "depth {depth}");
        assert_eq!(
            s.latency,
            (3 * s.lt + s.mul).max(s.far.pad_slack()) + s.add,
            "depth {depth}"
        );
    }
}

/// The far end's special cases: bounds and pads at every special value, and the pads of
/// real rays.
fn far_cases() -> Vec<(f32, f32)> {
    let specials = [
        0.0, -0.0, TINY, -SUB, MIN, 1.0, -3.0, 1e30, 3.4e38, 3.402e38, MAX, -MAX, INF, -INF, NAN,
        -NAN,
    ];
    let mut v = Vec::new();
    for &b in &specials {
        for &p in &specials {
            v.push((b, p));
        }
    }
    for &(o, d, b) in &special_rays() {
        v.push((b, ray_setup(o, d, b).pad));
    }
    v
}

fn random_far_cases(n: usize, seed: u64) -> Vec<(f32, f32)> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            if i % 3 == 2 {
                (f32::from_bits(rng.gen()), f32::from_bits(rng.gen()))
            } else {
                let bound = rng.gen_range(0.0..100.0f32);
                (bound, PAD * rng.gen_range(0.0..100.0f32))
            }
        })
        .collect()
}

fn check_far_with(depth: usize, cases: &[(f32, f32)], model: impl Fn(f32, f32) -> f32) {
    let lat = far_end::latency(depth);
    let inputs: Vec<FarInput> = (0..3)
        .map(|_| FarInput::default())
        .chain(cases.iter().enumerate().map(|(i, &(bound, pad))| FarInput {
            valid: valid(i),
            tag: tag(i),
            bound,
            pad,
        }))
        .collect();
    let out = simulate_far_end(depth, &inputs, lat);
    let flags: Vec<_> = inputs.iter().map(|x| (x.valid, x.tag)).collect();
    check_stream(
        &format!("far end depth {depth}"),
        lat,
        &flags,
        &out,
        |o: &FarOutput| (o.valid, o.tag),
        |_, c, o| {
            let x = &inputs[c];
            let want = model(x.bound, x.pad);
            assert_eq!(
                o.t_hi,
                want.to_bits(),
                "depth {depth}, case {}: bound {:e} pad {:e}: block {:e}, model t_hi {want:e}",
                c - 3,
                x.bound,
                x.pad,
                f32::from_bits(o.t_hi)
            );
        },
    );
}

#[test]
fn far_end_matches_the_model() {
    for depth in [0, 1, far_end::max_depth()] {
        let mut cases = far_cases();
        cases.extend(random_far_cases(1000, depth as u64));
        check_far_with(depth, &cases, t_hi);
    }
}

/// Against a model that forgets the pad, the first case with a nonzero pad is reported.
#[test]
#[should_panic(expected = "model t_hi")]
fn a_wrong_far_end_model_is_caught() {
    check_far_with(1, &far_cases(), |bound, _| t_hi(bound, 0.0));
}

#[test]
fn ray_setup_verilog_passes_verilator_lint() {
    for depth in [0, 1, max_depth()] {
        let v = ray_setup_verilog(depth);
        for port in [
            "valid_in",
            "tag_in",
            "orig$2",
            "dir$2",
            "bound",
            "valid_out",
            "tag_out",
            "orig_lo$2",
            "orig_hi$2",
            "inv_dir$2",
            "pad",
            "t_hi",
        ] {
            assert!(v.contains(port), "depth {depth}: no port {port}");
        }
        if let Err(e) = hdl::verilog::verilator_lint(&v) {
            panic!("depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

#[test]
fn far_end_verilog_passes_verilator_lint() {
    for depth in [0, 1, far_end::max_depth()] {
        let v = far_end_verilog(depth);
        for port in ["valid_in", "tag_in", "bound", "pad", "valid_out", "t_hi"] {
            assert!(v.contains(port), "depth {depth}: no port {port}");
        }
        if let Err(e) = hdl::verilog::verilator_lint(&v) {
            panic!("depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// yosys xc7 resources and register-to-register logic depth at depths 1 and max:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture ray_setup::ray_setup_resources`
#[test]
#[ignore]
fn ray_setup_resources() {
    let designs = [1, max_depth()].map(|depth| {
        (
            format!("ray setup depth {depth} (latency {})", latency(depth)),
            ray_setup_verilog(depth),
        )
    });
    println!("{}", hdl::synth::markdown_table(&designs).unwrap());
}
