//! `hdl::traversal::leaf_advance` in rust-hdl's simulator, bit for bit against the fp32
//! reference `hw_model::advance::moved`, one ray a cycle, with `valid_out` and the tag
//! checked to be `valid_in` and `tag_in` delayed by exactly `latency(depth)`; at depth 0, 1
//! and the maximum. Then its Verilog through Verilator's lint, and (ignored) its yosys
//! resources.

use hdl::traversal::leaf_advance::*;
use hdl::verilog::verilator_lint;
use hw_model::advance::moved;
use hw_model::MtQuery;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

#[test]
fn leaf_advance_latency_is_a_multiplication_and_an_addition() {
    assert_eq!(max_depth(), 5);
    let l: Vec<usize> = (0..=max_depth() + 1).map(latency).collect();
    let s = AdvanceSchedule::new(2);
    assert_eq!(s.latency, s.mul + s.add);
    assert_eq!(l[0], 0);
    assert!(l.windows(2).all(|w| w[0] <= w[1]), "{l:?}");
    assert_eq!(l[max_depth()], l[max_depth() + 1]);
}

/// Rays of the thesis' scales (origins within ±200, directions of any length, t0 from 0 to
/// 300 as a leaf entry is), with bit patterns of any kind (NaN, ±Inf, subnormals) every
/// fourth case.
fn cases(n: usize, seed: u64) -> Vec<AdvanceInput> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let mut any = || f32::from_bits(rng.gen());
            if i % 4 == 3 {
                return AdvanceInput {
                    orig: [any(), any(), any()],
                    dir: [any(), any(), any()],
                    t_min: any(),
                    t0: any(),
                    ..AdvanceInput::default()
                };
            }
            let mut r = |lo: f32, hi: f32| rng.gen_range(lo..hi);
            AdvanceInput {
                orig: [r(-200.0, 200.0), r(-200.0, 200.0), r(-200.0, 200.0)],
                dir: [r(-2.0, 2.0), r(-2.0, 2.0), r(-2.0, 2.0)],
                t_min: if i % 2 == 0 { 0.0 } else { r(0.0, 0.1) },
                t0: if i % 8 == 0 { 0.0 } else { r(0.0, 300.0) },
                ..AdvanceInput::default()
            }
        })
        .collect()
}

fn check(depth: usize, seed: u64) {
    let lat = latency(depth);
    let rays: Vec<AdvanceInput> = cases(400, seed)
        .into_iter()
        .enumerate()
        .map(|(i, r)| AdvanceInput {
            valid: i % 7 != 5,
            tag: (i * 37 % 65536) as u16,
            ..r
        })
        .collect();
    let out = simulate_leaf_advance(depth, &rays, lat);
    for (i, r) in rays.iter().enumerate() {
        let q = MtQuery {
            orig: r.orig,
            dir: r.dir,
            v0: [0.0; 3],
            v1: [0.0; 3],
            v2: [0.0; 3],
            t_min: r.t_min,
        };
        let want = moved(&q, u64::from(r.t0.to_bits()));
        let got = out[i + lat];
        assert_eq!(
            (got.valid, got.tag),
            (r.valid, r.tag),
            "depth {depth}, ray {i}"
        );
        assert_eq!(
            (got.moved, got.t_min),
            (want.orig.map(f32::to_bits), want.t_min.to_bits()),
            "depth {depth}, ray {i}: {r:?}"
        );
    }
}

#[test]
fn leaf_advance_moves_the_origin_as_the_model_does() {
    for (depth, seed) in [(0, 1), (1, 2), (max_depth(), 3)] {
        check(depth, seed);
    }
}

#[test]
fn leaf_advance_passes_verilator_lint() {
    let v = leaf_advance_verilog(max_depth());
    assert!(v.contains("t_min_out") && v.contains("moved"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("leaf advance: {e}"));
}

/// yosys xc7 resources and register-to-register logic depth at depths 1 and max:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture leaf_advance_resources`
#[test]
#[ignore]
fn leaf_advance_resources() {
    let designs = [1, max_depth()].map(|depth| {
        (
            format!("leaf advance depth {depth} (latency {})", latency(depth)),
            leaf_advance_verilog(depth),
        )
    });
    println!("{}", hdl::synth::markdown_table(&designs).unwrap());
}
