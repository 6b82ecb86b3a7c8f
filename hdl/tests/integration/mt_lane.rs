//! The MT lane of every format in rust-hdl's simulator, bit for bit against
//! `hw_model::mt_model`, one query per cycle, with `valid_out` checked to be `valid_in`
//! delayed by exactly `latency(depth)`. rust-hdl simulates a ~30-operator design at about a
//! thousand cycles a second, so the default run uses a few dozen queries per format; more:
//! `cargo test --release -p hdl --test integration mt_lane:: -- --ignored`.

use hdl::formats::{self, bf16, e5m14, fp16, fp24, fp32, fx16_10, fx32_16_rnd_sat};
use hdl::mt::{self, simulate_lane, Lane};
use hw_model::{mt_model, HwFormat, MtQuery};
use rand::{rngs::StdRng, Rng, SeedableRng};

fn query(orig: [f32; 3], dir: [f32; 3], v0: [f32; 3], v1: [f32; 3], v2: [f32; 3]) -> MtQuery {
    MtQuery {
        orig,
        dir,
        v0,
        v1,
        v2,
        t_min: 0.0,
    }
}

/// A lower bound for a query whose hit (if any) is near t = 4: mostly 0 (the reference's
/// rays), else on either side of the hit, negative, or NaN/±Inf.
fn random_t_min(rng: &mut StdRng) -> f32 {
    match rng.gen_range(0..8) {
        0 | 1 => rng.gen_range(0.0..8.0),
        2 => -rng.gen_range(0.0..8.0f32),
        3 => [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.gen_range(0..3)],
        _ => 0.0,
    }
}

/// Hand-picked cases on the triangle (0,0,2), (1,0,2), (0,1,2) and some degenerate inputs.
fn edge_cases() -> Vec<MtQuery> {
    let (v0, v1, v2) = ([0.0, 0.0, 2.0], [1.0, 0.0, 2.0], [0.0, 1.0, 2.0]);
    let on = |x: f32, y: f32, dir: [f32; 3]| query([x, y, 0.0], dir, v0, v1, v2);
    let down = [0.0, 0.0, 1.0];
    vec![
        on(0.25, 0.25, down),                                 // hit inside
        on(1.0, 1.0, down),                                   // miss: u + v > 1
        on(-0.5, 0.25, down),                                 // miss: u < 0
        on(0.25, -0.5, down),                                 // miss: v < 0
        on(0.25, 0.25, [0.0, 0.0, -1.0]),                     // behind the ray: t < 0
        on(0.0, 0.0, down),                                   // vertex v0: u = v = 0
        on(0.5, 0.5, down),                                   // edge: u + v = 1
        on(0.0, 0.5, down),                                   // edge: u = 0
        query([0.0, 0.25, 2.0], [1.0, 0.0, 0.0], v0, v1, v2), // edge-on: det = 0
        on(0.25, 0.25, [1.0, 0.0, 1e-9]),                     // det ≈ 0 (below eps in fp32)
        on(0.25, 0.25, [1.0, 0.0, 2e-8]),                     // det just above eps in fp32
        on(0.25, 0.25, [0.0, 0.0, 1e-30]),                    // det underflows in narrow formats
        query([0.1, 0.1, 0.0], down, v0, v0, v2),             // degenerate triangle
        on(0.25, 0.25, [f32::NAN, 0.0, 1.0]),
        on(0.25, 0.25, [0.0, 0.0, f32::INFINITY]),
        on(1e-40, 0.25, down), // subnormal input
        on(3.0e4, 0.25, down), // overflows fp16's and the fixed formats' range
        // The lower bound around the hit at t = 2 (exact in every format).
        MtQuery {
            t_min: 1.75,
            ..on(0.25, 0.25, down)
        }, // hit: t > t_min
        MtQuery {
            t_min: 2.0,
            ..on(0.25, 0.25, down)
        }, // miss: t = t_min
        MtQuery {
            t_min: f32::NAN,
            ..on(0.25, 0.25, down)
        },
        MtQuery {
            t_min: f32::INFINITY,
            ..on(0.25, 0.25, down)
        },
        MtQuery {
            t_min: f32::NEG_INFINITY,
            ..on(0.25, 0.25, down)
        },
        MtQuery {
            t_min: 1e-40,
            ..on(0.25, 0.25, down)
        }, // subnormal: flushed
    ]
}

/// Rays from random points towards random points near a random triangle (about half hit),
/// then random bit patterns; all coordinates within ±4 so the fixed formats can hold them;
/// random lower bounds (`random_t_min`).
fn random_queries(n: usize, seed: u64) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            if i % 4 == 3 {
                let t_min = f32::from_bits(rng.gen());
                let mut bits = || [0; 3].map(|_| f32::from_bits(rng.gen()));
                return MtQuery {
                    t_min,
                    ..query(bits(), bits(), bits(), bits(), bits())
                };
            }
            let mut point = |r: f32| [0; 3].map(|_| rng.gen_range(-r..r));
            let (v0, v1, v2, orig, target) =
                (point(2.0), point(2.0), point(2.0), point(4.0), point(0.5));
            let centre = [0, 1, 2].map(|k| (v0[k] + v1[k] + v2[k]) / 3.0 + target[k]);
            let dir = [0, 1, 2].map(|k| (centre[k] - orig[k]) / 4.0);
            MtQuery {
                t_min: random_t_min(&mut rng),
                ..query(orig, dir, v0, v1, v2)
            }
        })
        .collect()
}

/// Streams `queries` through `L` at `depth` with a gap in `valid_in` every fifth cycle and
/// checks every result and the valid line against the model and `latency(depth)`.
fn check<L: Lane>(depth: usize, queries: &[MtQuery]) {
    let latency = L::latency(depth);
    assert_eq!(
        mt::latency(L::HW, depth),
        latency,
        "{} runtime latency table",
        L::NAME
    );
    // Three idle cycles first, so the first valid_out edge measures the latency.
    let inputs: Vec<(bool, MtQuery)> = (0..3)
        .map(|_| (false, MtQuery::default()))
        .chain(queries.iter().enumerate().map(|(i, q)| (i % 5 != 4, *q)))
        .collect();
    let out = simulate_lane::<L>(depth, &inputs, latency);
    let first_valid = out
        .iter()
        .position(|o| o.valid)
        .expect("valid_out never rose");
    assert_eq!(
        first_valid - 3,
        latency,
        "{} depth {depth}: observed latency",
        L::NAME
    );
    let hits = out.iter().filter(|o| o.valid && o.hit).count();
    let valid = out.iter().filter(|o| o.valid).count();
    eprintln!(
        "{} depth {depth}: latency {latency}, {hits} hits of {valid} valid queries",
        L::NAME
    );
    assert!(
        hits >= 3 && valid - hits >= 3,
        "{} depth {depth}: only {hits} hits of {valid}",
        L::NAME
    );
    for (cycle, o) in out.iter().enumerate() {
        let Some(c) = cycle.checked_sub(latency) else {
            assert!(
                !o.valid,
                "{} depth {depth}: valid_out in cycle {cycle}",
                L::NAME
            );
            continue;
        };
        let (valid, q) = inputs
            .get(c)
            .copied()
            .unwrap_or((false, MtQuery::default()));
        assert_eq!(
            o.valid,
            valid,
            "{} depth {depth}: valid_out in cycle {cycle}",
            L::NAME
        );
        let want = mt_model(&L::FORMAT, &q);
        assert!(
            o.result().same_bits(&want),
            "{} depth {depth}: {q:?}\n lane  {:?}\n model {want:?}",
            L::NAME,
            o.result()
        );
    }
}

fn check_format<L: Lane>(depth: usize, random: usize, seed: u64) {
    let mut queries = edge_cases();
    queries.extend(random_queries(random, seed));
    check::<L>(depth, &queries);
}

/// One test a format (at `depth`, with `random` random queries after the edge cases), and
/// `CHECKED`, the formats covered.
macro_rules! lane_tests {
    ($($test:ident: $fmt:ident, depth $depth:expr, random $random:expr;)*) => {
        $(
            #[test]
            fn $test() {
                check_format::<formats::$fmt::MtLane>($depth, $random, stringify!($fmt).len() as u64);
            }
        )*
        const CHECKED: &[&str] = &[$(formats::$fmt::NAME),*];
    };
}

lane_tests! {
    fp32_lane_matches_the_model: fp32, depth 1, random 64;
    fp24_lane_matches_the_model: fp24, depth 1, random 64;
    bf16_lane_matches_the_model: bf16, depth 1, random 64;
    fp16_lane_matches_the_model_combinational: fp16, depth 0, random 64;
    fp16_lane_matches_the_model: fp16, depth 2, random 64;
    fx16_10_lane_matches_the_model: fx16_10, depth 1, random 64;
    fx16_10_rnd_sat_lane_matches_the_model: fx16_10_rnd_sat, depth 1, random 64;
    fx16_13_lane_matches_the_model: fx16_13, depth 1, random 64;
    fx16_13_rnd_sat_lane_matches_the_model: fx16_13_rnd_sat, depth 1, random 64;
    fx21_12_lane_matches_the_model: fx21_12, depth 1, random 64;
    fx21_12_rnd_sat_lane_matches_the_model: fx21_12_rnd_sat, depth 1, random 64;
    fx25_10_lane_matches_the_model: fx25_10, depth 0, random 64;
    fx25_10_rnd_sat_lane_matches_the_model: fx25_10_rnd_sat, depth 2, random 64;
    fx32_16_lane_matches_the_model: fx32_16, depth 1, random 64;
    fx32_16_rnd_sat_lane_matches_the_model: fx32_16_rnd_sat, depth 1, random 64;
    fx32_20_lane_matches_the_model: fx32_20, depth 1, random 64;
    fx32_20_rnd_sat_lane_matches_the_model: fx32_20_rnd_sat, depth 3, random 64;
    e5m14_lane_matches_the_model: e5m14, depth 1, random 64;
    e5m14_lane_matches_the_model_deepest: e5m14, depth mt::max_depth(e5m14::HW), random 64;
}

/// Every format with rust-hdl operators has its lane checked above.
#[test]
fn every_format_with_operators_is_checked() {
    for name in HwFormat::all().map(HwFormat::name) {
        assert!(
            CHECKED.contains(&name),
            "format {name} has a lane but no lane test"
        );
    }
}

#[test]
fn latency_table_answers_every_format() {
    for name in HwFormat::all() {
        let max = mt::max_depth(name);
        let latencies: Vec<usize> = (0..=max + 1).map(|d| mt::latency(name, d)).collect();
        assert_eq!(latencies[0], 0, "{name}: a combinational lane");
        assert!(
            latencies.windows(2).all(|w| w[0] <= w[1]),
            "{name}: {latencies:?}"
        );
        assert_eq!(
            latencies[max],
            latencies[max + 1],
            "{name}: depth beyond max_depth"
        );
        assert!(
            latencies[max - 1] < latencies[max],
            "{name}: max_depth is the smallest saturating depth"
        );
    }
}

/// `cargo test --release -p hdl --test integration mt_lane:: -- --ignored`
#[test]
#[ignore]
fn every_lane_matches_the_model_on_more_queries_and_depths() {
    for depth in [0, 1, 3] {
        let seed = 10 * depth as u64;
        check_format::<fp32::MtLane>(depth, 300, seed + 1);
        check_format::<fp24::MtLane>(depth, 300, seed + 2);
        check_format::<bf16::MtLane>(depth, 300, seed + 3);
        check_format::<fp16::MtLane>(depth, 300, seed + 4);
        check_format::<fx16_10::MtLane>(depth, 300, seed + 5);
        check_format::<fx32_16_rnd_sat::MtLane>(depth, 300, seed + 6);
        check_format::<e5m14::MtLane>(depth, 300, seed + 7);
    }
    check_format::<fp32::MtLane>(usize::MAX, 100, 50);
}

/// Latency of every format's lane at depths 0, 1, 2 and max (printed; run with --nocapture).
#[test]
fn latency_table() {
    println!(
        "| format | max depth | latency d=0 | d=1 | d=2 | d=max |\n|---|---:|---:|---:|---:|---:|"
    );
    for name in HwFormat::all() {
        let max = mt::max_depth(name);
        let l: Vec<usize> = [0, 1, 2, max]
            .iter()
            .map(|&d| mt::latency(name, d))
            .collect();
        println!(
            "| {name} | {max} | {} | {} | {} | {} |",
            l[0], l[1], l[2], l[3]
        );
    }
}

/// yosys xc7 resources and register-to-register logic depth of the fp32 lane at depths 1, 2,
/// 4, 6 (every adder stage registered) and max, and the fp16 lane at 1 and max (slow: minutes
/// per fp32 synthesis), checked against the issue's
/// resource goal of at most 60 DSP48E1 per fp32 lane:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture mt_lane::lane_resources`
#[test]
#[ignore]
fn lane_resources() {
    use hdl::synth::{synthesize, SynthOptions, SynthReport};
    let lanes = [
        (
            fp32::HW,
            fp32::mt_lane_verilog as fn(usize) -> String,
            &[1, 2, 4, 6][..],
        ),
        (fp16::HW, fp16::mt_lane_verilog, &[1][..]),
    ];
    println!("{}", SynthReport::markdown_header());
    for (name, verilog, depths) in lanes {
        let max = mt::max_depth(name);
        for &depth in depths.iter().chain([max].iter()) {
            let report =
                synthesize(&verilog(depth), hdl::verilog::TOP, &SynthOptions::default()).unwrap();
            let latency = mt::latency(name, depth);
            println!(
                "{}",
                report.markdown_row(&format!("{name} depth {depth} (latency {latency})"))
            );
            if name == fp32::HW {
                assert!(
                    report.dsp48e1 <= 60,
                    "fp32 lane at depth {depth}: {} DSP48E1",
                    report.dsp48e1
                );
            }
        }
    }
}
