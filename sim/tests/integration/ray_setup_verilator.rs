//! The traversal unit's ray setup and far end, Verilated and streamed one ray (or bound) per
//! cycle (II = 1), bit for bit against `hw_model::traversal::box_test::{ray_setup, t_hi}`,
//! with `valid_out` and the tag checked to follow `valid_in` and `tag_in` by
//! `latency(depth)`. The rust-hdl simulation of the same blocks (hdl/tests/integration/ray_setup.rs)
//! carries the hand-picked special cases; this one runs many random rays on the generated
//! Verilog. Default: 50k rays at the maximum depth and 50k bounds through the far end at the
//! maximum (just under 60 s from a cold Verilator cache on 2 cores: compiling the ray setup's
//! model dominates); 50k rays at depth 1, 500k at depths 0 and max and 500k bounds at depth 0:
//! `cargo test --release -p sim --test integration ray_setup_verilator:: -- --ignored`.

use hdl::traversal::far_end::{self, far_end_verilog};
use hdl::traversal::ray_setup::{latency, max_depth, ray_setup_verilog, SetupOutput};
use hw_model::traversal::box_test::{ray_setup, t_hi, HUGE_SLOPE, PAD};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sim::{build, run_pipelined, BuildOptions, ModelSpec};

/// A ray: origin, direction, bound.
type Ray = ([f32; 3], [f32; 3], f32);

/// A word that is often special: ±0, a subnormal, ±Inf, NaN, FLT_MAX, else random bits.
fn special_or_random(rng: &mut StdRng) -> f32 {
    const SPECIALS: [f32; 8] = [
        0.0,
        -0.0,
        1e-45,
        -1.1e-38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        f32::MAX,
    ];
    if rng.gen_bool(0.3) {
        SPECIALS[rng.gen_range(0..SPECIALS.len())]
    } else {
        f32::from_bits(rng.gen())
    }
}

/// Random rays, in turn: origins at random scales (a few units to huge) with directions in
/// the unit cube (some components snapped to ±0) and bounds FLT_MAX, +Inf or random; the
/// same with one word of the origin or direction special; and random bit patterns (often
/// special) in every word.
fn rays(n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            if i % 3 == 2 {
                let mut w = || special_or_random(&mut rng);
                return ([w(), w(), w()], [w(), w(), w()], w());
            }
            let scale = [1.0, 10.0, 1e4, 1e20, 1e37][i % 5];
            let mut orig = [0; 3].map(|_| rng.gen_range(-1.0..1.0f32) * scale);
            let mut dir = [0; 3].map(|_| {
                let d = rng.gen_range(-1.0..1.0f32);
                if rng.gen_bool(0.1) {
                    0.0f32.copysign(d)
                } else {
                    d
                }
            });
            if i % 3 == 1 {
                let a = rng.gen_range(0..3);
                if rng.gen_bool(0.5) {
                    orig[a] = special_or_random(&mut rng);
                } else {
                    dir[a] = special_or_random(&mut rng);
                }
            }
            let bound = match i % 4 {
                0 => f32::MAX,
                1 => f32::INFINITY,
                _ => rng.gen_range(0.0..30.0f32) * scale,
            };
            (orig, dir, bound)
        })
        .collect()
}

fn valid_and_tag(i: usize) -> [u64; 2] {
    [u64::from(i % 7 != 6), (i as u64 * 0x9E37) & 0xFFFF]
}

fn port_names(ports: &[sim::verilator::Port]) -> Vec<String> {
    ports.iter().map(|p| p.name.clone()).collect()
}

/// Builds the ray setup at `depth`, streams `rays` through it with `valid_in` low every
/// seventh cycle and checks every output against the model and `latency(depth)`.
fn run(depth: usize, rays: &[Ray]) {
    let lat = latency(depth);
    let built = build(
        &ModelSpec::rust_hdl(ray_setup_verilog(depth)),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut sim = built.instantiate();
    let mut want_inputs = vec!["valid_in".to_string(), "tag_in".to_string()];
    for field in ["orig", "dir"] {
        want_inputs.extend((0..3).map(|i| format!("{field}${i}")));
    }
    want_inputs.push("bound".into());
    assert_eq!(port_names(&sim.interface().inputs), want_inputs);
    let mut want_outputs = vec!["valid_out".to_string(), "tag_out".to_string()];
    for field in ["orig_lo", "orig_hi", "inv_dir"] {
        want_outputs.extend((0..3).map(|i| format!("{field}${i}")));
    }
    want_outputs.extend(["pad".into(), "t_hi".into()]);
    assert_eq!(port_names(&sim.interface().outputs), want_outputs);
    let word = |x: f32| u64::from(x.to_bits());
    let inputs: Vec<[u64; 9]> = rays
        .iter()
        .enumerate()
        .map(|(i, (orig, dir, bound))| {
            let mut w = valid_and_tag(i).to_vec();
            w.extend(orig.map(word));
            w.extend(dir.map(word));
            w.push(word(*bound));
            w.try_into().unwrap()
        })
        .collect();
    let start = std::time::Instant::now();
    let out: Vec<[u64; 13]> = run_pipelined(&mut sim, &inputs, lat).unwrap();
    eprintln!(
        "ray setup depth {depth} (latency {lat}): {} rays, {:.2} M rays/s",
        rays.len(),
        rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    let mut huge = 0;
    for ((&(orig, dir, bound), input), o) in rays.iter().zip(&inputs).zip(&out) {
        let w3 = |k: usize| [o[k] as u32, o[k + 1] as u32, o[k + 2] as u32];
        let got = SetupOutput {
            valid: o[0] != 0,
            tag: o[1] as u16,
            orig_lo: w3(2),
            orig_hi: w3(5),
            inv_dir: w3(8),
            pad: o[11] as u32,
            t_hi: o[12] as u32,
        };
        assert_eq!(u64::from(got.valid), input[0], "depth {depth}: valid_out");
        assert_eq!(u64::from(got.tag), input[1], "depth {depth}: tag_out");
        let want = ray_setup(orig, dir, bound);
        assert!(
            got.same_bits(&want),
            "depth {depth}: {orig:?} {dir:?} {bound:?}\n block {:?}\n model {want:?}",
            got.result()
        );
        huge += usize::from(want.inv_dir.iter().any(|x| x.abs() == HUGE_SLOPE));
    }
    assert!(
        huge * 20 > rays.len(),
        "only {huge} huge slopes: the generator no longer makes zero directions"
    );
}

/// The far end alone at `depth` (bound and pad together): `n` random bounds with pads of
/// real rays, random words and specials.
fn run_far_end(depth: usize, n: usize, seed: u64) {
    let lat = far_end::latency(depth);
    let built = build(
        &ModelSpec::rust_hdl(far_end_verilog(depth)),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut sim = built.instantiate();
    assert_eq!(
        port_names(&sim.interface().inputs),
        ["valid_in", "tag_in", "bound", "pad"]
    );
    assert_eq!(
        port_names(&sim.interface().outputs),
        ["valid_out", "tag_out", "t_hi"]
    );
    let mut rng = StdRng::seed_from_u64(seed);
    let cases: Vec<(f32, f32)> = (0..n)
        .map(|i| match i % 3 {
            0 => (rng.gen_range(0.0..1e3f32), PAD * rng.gen_range(0.0..1e3f32)),
            1 => (
                special_or_random(&mut rng),
                PAD * rng.gen_range(0.0..1.0f32),
            ),
            _ => (special_or_random(&mut rng), special_or_random(&mut rng)),
        })
        .collect();
    let inputs: Vec<[u64; 4]> = cases
        .iter()
        .enumerate()
        .map(|(i, &(b, p))| {
            let [v, t] = valid_and_tag(i);
            [v, t, u64::from(b.to_bits()), u64::from(p.to_bits())]
        })
        .collect();
    let out: Vec<[u64; 3]> = run_pipelined(&mut sim, &inputs, lat).unwrap();
    for ((&(bound, pad), input), o) in cases.iter().zip(&inputs).zip(&out) {
        assert_eq!(
            (o[0], o[1]),
            (input[0], input[1]),
            "depth {depth}: valid, tag"
        );
        let want = t_hi(bound, pad);
        assert_eq!(
            o[2] as u32,
            want.to_bits(),
            "depth {depth}: bound {bound:e} pad {pad:e}: block {:e} model {want:e}",
            f32::from_bits(o[2] as u32)
        );
    }
}

#[test]
fn ray_setup_at_max_depth_matches_the_model() {
    run(max_depth(), &rays(50_000, 2));
}

#[test]
fn far_end_at_max_depth_matches_the_model() {
    run_far_end(far_end::max_depth(), 50_000, 3);
}

/// `cargo test --release -p sim --test integration ray_setup_verilator:: -- --ignored`
#[test]
#[ignore]
fn ray_setup_at_depth_1_matches_the_model() {
    run(1, &rays(50_000, 1));
}

/// `cargo test --release -p sim --test integration ray_setup_verilator:: -- --ignored`
#[test]
#[ignore]
fn ray_setup_matches_the_model_on_500k_rays() {
    run(0, &rays(500_000, 10));
    run(max_depth(), &rays(500_000, 11));
    run_far_end(0, 500_000, 12);
}
