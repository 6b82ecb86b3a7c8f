//! The MT lane, Verilated and streamed one query per cycle (II = 1), bit for bit against
//! `hw_model::mt_model`, with `valid_out` checked to follow `valid_in` by `latency(depth)`;
//! the fp32 lane also against the f32 reference `sw_renderer::intersect::mt_f32` on queries
//! whose every intermediate is far from fp32's subnormal range.
//! Default run: 20k queries each for fp32 at the maximum depth, fp16 at depth 2 and a fixed
//! format at depth 1. The ~200k-query runs (fp32 at depth 0 and max, fp16, fx32_16):
//! `cargo test --release -p sim --test integration mt_lane_verilator:: -- --ignored`.

use hdl::formats::{fp16, fp32, fx32_16};
use hdl::mt::{query_words, Lane, LaneOutput};
use hdl::regmap::OPERAND_COUNT;
use hw_model::{mt_model, MtQuery, MtResult};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sim::{build, run_pipelined, BuildOptions, ModelSpec};
use sw_renderer::intersect::mt_f32;

/// A value on the grid k·2^-bits with |value| ≤ max.
fn grid(rng: &mut StdRng, max: f32, bits: i32) -> f32 {
    let steps = (max * 2f32.powi(bits)) as i32;
    rng.gen_range(-steps..=steps) as f32 * 2f32.powi(-bits)
}

/// A lower bound for a query whose hit (if any) is near t = 1: mostly 0 (the reference's
/// rays), else around the hit, negative, or NaN/±Inf.
fn t_min(rng: &mut StdRng) -> f32 {
    match rng.gen_range(0..8) {
        0 | 1 => rng.gen_range(0.0..2.0),
        2 => -rng.gen_range(0.0..2.0f32),
        3 => [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1.0][rng.gen_range(0..4)],
        _ => 0.0,
    }
}

/// Random queries of four kinds, in turn, each with a random lower bound (`t_min`):
/// 0. a ray from a random point aimed near the centre of a random triangle, coordinates
///    uniform within ±`scale` (about half hit);
/// 1. the same on the dyadic grid k/16 (exact cancellations, hits on edges and vertices,
///    det = 0 when the triangle is degenerate);
/// 2. a ray in the triangle's plane (edge-on: det ≈ 0) or nearly so;
/// 3. random fp32 bit patterns (NaN, Inf, subnormals, huge and tiny values).
fn queries(n: usize, scale: f32, seed: u64) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| match i % 4 {
            0 | 1 => {
                let on_grid = i % 4 == 1;
                let mut p = |r: f32| {
                    [0; 3].map(|_| {
                        if on_grid {
                            grid(&mut rng, r, 4)
                        } else {
                            rng.gen_range(-r..r)
                        }
                    })
                };
                let (v0, v1, v2, orig) = (p(scale / 2.0), p(scale / 2.0), p(scale / 2.0), p(scale));
                let (a, b) = (rng.gen_range(-0.25..1.0f32), rng.gen_range(-0.25..1.0f32));
                let (a, b) = if on_grid {
                    ((a * 8.0).round() / 8.0, (b * 8.0).round() / 8.0)
                } else {
                    (a, b)
                };
                MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min(&mut rng))
            }
            2 => {
                let mut p = |r: f32| [0; 3].map(|_| rng.gen_range(-r..r));
                let (v0, v1, v2, offset) = (
                    p(scale / 2.0),
                    p(scale / 2.0),
                    p(scale / 2.0),
                    p(1e-3 * scale),
                );
                let (a, b) = (rng.gen_range(-1.0..2.0f32), rng.gen_range(-1.0..2.0f32));
                let orig = [0, 1, 2]
                    .map(|k| v0[k] + a * (v1[k] - v0[k]) + b * (v2[k] - v0[k]) + offset[k]);
                let dir = [0, 1, 2].map(|k| v1[k] - v2[k]);
                MtQuery {
                    orig,
                    dir,
                    v0,
                    v1,
                    v2,
                    t_min: t_min(&mut rng),
                }
            }
            _ => {
                let mut bits = || [0; 3].map(|_| f32::from_bits(rng.gen()));
                MtQuery {
                    orig: bits(),
                    dir: bits(),
                    v0: bits(),
                    v1: bits(),
                    v2: bits(),
                    t_min: f32::from_bits(rng.gen()),
                }
            }
        })
        .collect()
}

/// Builds lane `L` at `depth`, streams `queries` through it with `valid_in` low every
/// seventh cycle, checks the valid line and every result against `mt_model` and returns the
/// results. Prints the simulation rate.
fn run_lane<L: Lane>(verilog: String, depth: usize, queries: &[MtQuery]) -> Vec<MtResult> {
    let latency = L::latency(depth);
    let built = build(&ModelSpec::rust_hdl(verilog), &BuildOptions::default()).unwrap();
    let mut sim = built.instantiate();
    let names =
        |ports: &[sim::verilator::Port]| ports.iter().map(|p| p.name.clone()).collect::<Vec<_>>();
    let mut want_inputs = vec!["valid_in".to_string()];
    want_inputs.extend((0..OPERAND_COUNT).map(|i| format!("query${i}")));
    assert_eq!(names(&sim.interface().inputs), want_inputs);
    assert_eq!(
        names(&sim.interface().outputs),
        ["valid_out", "hit", "t", "u", "v"]
    );
    let inputs: Vec<[u64; OPERAND_COUNT + 1]> = queries
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let mut words = [u64::from(i % 7 != 6); OPERAND_COUNT + 1];
            for (w, q) in words[1..].iter_mut().zip(query_words(q)) {
                *w = u64::from(q);
            }
            words
        })
        .collect();
    let start = std::time::Instant::now();
    let out: Vec<[u64; 5]> = run_pipelined(&mut sim, &inputs, latency).unwrap();
    eprintln!(
        "{} depth {depth} (latency {latency}): {} queries, {:.2} M queries/s",
        L::NAME,
        queries.len(),
        queries.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    let mut hits = 0;
    let results: Vec<MtResult> = queries
        .iter()
        .zip(&inputs)
        .zip(&out)
        .map(|((q, input), o)| {
            let lane = LaneOutput {
                valid: o[0] != 0,
                hit: o[1] != 0,
                t: o[2] as u32,
                u: o[3] as u32,
                v: o[4] as u32,
            };
            assert_eq!(
                u64::from(lane.valid),
                input[0],
                "{} depth {depth}: valid_out of {q:?}",
                L::NAME
            );
            let (got, want) = (lane.result(), mt_model(&L::FORMAT, q));
            assert!(
                got.same_bits(&want),
                "{} depth {depth}: {q:?}\n lane  {got:?}\n model {want:?}",
                L::NAME
            );
            hits += usize::from(got.hit);
            got
        })
        .collect();
    assert!(
        hits * 10 > queries.len(),
        "{}: only {hits} hits: the generator no longer aims at triangles",
        L::NAME
    );
    results
}

/// The fp32 lane equals the f32 reference (NaN matching any NaN) on the grid queries and
/// the realistic ones, whose intermediates stay far above the subnormal range.
fn check_against_f32(queries: &[MtQuery], lane: &[MtResult]) {
    let same = |x: f32, y: f32| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan());
    for (i, (q, got)) in queries
        .iter()
        .zip(lane)
        .enumerate()
        .filter(|(i, _)| i % 4 <= 1)
    {
        let want = mt_f32(q);
        assert!(
            got.hit == want.hit
                && same(got.t, want.t)
                && same(got.u, want.u)
                && same(got.v, want.v),
            "query {i} {q:?}:\n lane {got:?}\n f32  {want:?}"
        );
    }
}

fn fp32_at(depth: usize, n: usize, seed: u64) {
    let q = queries(n, 100.0, seed);
    let lane = run_lane::<fp32::MtLane>(fp32::mt_lane_verilog(depth), depth, &q);
    check_against_f32(&q, &lane);
}

#[test]
fn fp32_lane_at_max_depth_matches_model_and_f32_reference() {
    fp32_at(hdl::mt::max_depth(fp32::HW), 20_000, 1);
}

#[test]
fn fp16_lane_matches_the_model() {
    run_lane::<fp16::MtLane>(fp16::mt_lane_verilog(2), 2, &queries(20_000, 8.0, 2));
}

#[test]
fn fixed_lane_matches_the_model() {
    run_lane::<fx32_16::MtLane>(fx32_16::mt_lane_verilog(1), 1, &queries(20_000, 8.0, 3));
}

/// `cargo test --release -p sim --test integration mt_lane_verilator:: -- --ignored`
#[test]
#[ignore]
fn lanes_match_the_model_on_200k_queries() {
    fp32_at(0, 200_000, 10);
    fp32_at(hdl::mt::max_depth(fp32::HW), 200_000, 11);
    let fp16_max = hdl::mt::max_depth(fp16::HW);
    run_lane::<fp16::MtLane>(
        fp16::mt_lane_verilog(fp16_max),
        fp16_max,
        &queries(200_000, 8.0, 12),
    );
    run_lane::<fx32_16::MtLane>(fx32_16::mt_lane_verilog(3), 3, &queries(200_000, 8.0, 13));
}
