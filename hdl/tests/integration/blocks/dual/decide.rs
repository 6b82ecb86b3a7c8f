//! `hdl::dual::decide`: step 5 of the bfp filter, bit for bit the model's `decide` (every
//! row of the decision table, `miss` and `forward`).

use hdl::dual::decide::*;
use hdl::dual::round::SHORT_EXP_BITS;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::{decide, values, widths, Fx, Rows, Vector, EXP_MAX, SUM_MIN};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::MtQuery;

use super::common::{lint_clean, named, near_parallel};
use super::round::{raw, stream, Clocked};

/// One decision's inputs: det and N_u, N_v, N_t with their margins, and t_min.
#[derive(Clone, Copy, Debug)]
pub(super) struct Input {
    pub det: (Fx, i128),
    pub nums: [(Fx, i128); 3],
    pub t_min: f32,
}

impl Clocked for Decide {
    fn clock(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }
}

/// Drives one decision's inputs.
fn set(uut: &mut Decide, x: Input) {
    let exp = |e: i32| raw(i128::from(e), SHORT_EXP_BITS).to_bits();
    uut.det.next = raw(x.det.0.m, DET_BITS).to_bits();
    uut.det_e.next = exp(x.det.0.e);
    uut.det_margin.next = raw(x.det.1, DET_MARGIN_BITS).to_bits();
    for k in 0..3 {
        uut.num[k].next = raw(x.nums[k].0.m, NUM_BITS).to_bits();
        uut.num_e[k].next = exp(x.nums[k].0.e);
        uut.num_margin[k].next = raw(x.nums[k].1, NUM_MARGIN_BITS).to_bits();
    }
    uut.t_min.next = u64::from(x.t_min.to_bits()).to_bits();
}

/// The block's rows, `miss` and `forward`.
fn rows(uut: &Decide) -> (Rows, bool, bool) {
    let rows = Rows {
        parallel: uut.parallel.val(),
        in_range: uut.in_range.val(),
        u_below: uut.u_below.val(),
        u_above: uut.u_above.val(),
        v_below: uut.v_below.val(),
        uv_above: uut.uv_above.val(),
        t_below: uut.t_below.val(),
    };
    (rows, uut.miss.val(), uut.forward.val())
}

/// How often each row (and `miss`) was seen false and true.
#[derive(Default, Debug)]
pub(super) struct Seen([[usize; 2]; 8]);

impl Seen {
    pub(super) fn count(&mut self, r: &Rows) {
        let flags = [
            r.parallel,
            r.in_range,
            r.u_below,
            r.u_above,
            r.v_below,
            r.uv_above,
            r.t_below,
            r.miss(),
        ];
        for (i, f) in flags.into_iter().enumerate() {
            self.0[i][usize::from(f)] += 1;
        }
    }

    /// Every row but those named in `always` fired and did not fire, each at least `n`
    /// times.
    pub(super) fn assert_both_ways(&self, n: usize, always: &[&str]) {
        let names = [
            "parallel", "in_range", "u_below", "u_above", "v_below", "uv_above", "t_below", "miss",
        ];
        for (name, counts) in names.iter().zip(self.0) {
            assert!(
                always.contains(name) || counts.iter().all(|&c| c >= n),
                "row {name} seen false/true {counts:?} times: {self:?}"
            );
        }
    }
}

/// `inputs` streamed through the block one a cycle, each decision against the model's
/// exactly [`LATENCY`] cycles after its inputs; what the model decided is counted.
fn check(inputs: &[Input]) -> Seen {
    check_at(inputs, LATENCY)
}

/// [`check`] with the outputs read `latency` cycles after the inputs.
fn check_at(inputs: &[Input], latency: usize) -> Seen {
    let mut uut = Decide::default();
    uut.connect_all();
    let mut seen = Seen::default();
    let zero = Input {
        det: (Fx { m: 0, e: 0 }, 0),
        nums: [(Fx { m: 0, e: 0 }, 0); 3],
        t_min: 0.0,
    };
    stream(&mut uut, inputs, latency, zero, set, |uut, x| {
        let want = decide(x.det.0, x.det.1, x.nums, x.t_min).expect("no i128 overflow");
        let (rows, miss, forward) = rows(uut);
        assert_eq!(rows, want, "{x:?}");
        assert_eq!(miss, want.miss(), "{x:?}");
        assert_eq!(forward, !want.miss(), "{x:?}");
        seen.count(&want);
    });
    seen
}

/// A t_min: mostly 0, at times random of either sign, tiny (below 2^-102 and subnormal),
/// huge, near the hits' t, or not finite.
pub(super) fn t_min(rng: &mut StdRng) -> f32 {
    match rng.gen_range(0..16) {
        0..=6 => 0.0,
        7 | 8 => rng.gen_range(0.0..2.0),
        9 => rng.gen_range(-2.0..0.0),
        10 => f32::from_bits(rng.gen_range(0..0x0d00_0000)) * [1.0, -1.0][rng.gen_range(0..2)],
        11 => rng.gen_range(0.5f32..1.5) * 2f32.powi(rng.gen_range(-30..30)),
        12 => [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0][rng.gen_range(0..4)],
        _ => 1.0 + rng.gen_range(-1e-6f32..1e-6),
    }
}

/// An integer of `width` signed bits and a random bit count.
pub(super) fn integer(rng: &mut StdRng, width: usize) -> i128 {
    let bits = rng.gen_range(0..=width);
    match bits {
        0 => [0, -1][rng.gen_range(0..2)],
        _ => rng.gen_range(-(1i128 << (bits - 1))..1i128 << (bits - 1)),
    }
}

/// The values' last bits' exponents the filter produces: a triple of block exponents in
/// range less the widest mantissa pair.
pub(super) fn exponent(rng: &mut StdRng) -> i32 {
    rng.gen_range(lowest_exponent()..=3 * EXP_MAX)
}

/// The lowest: SUM_MIN less the widest mantissa pair.
pub(super) fn lowest_exponent() -> i32 {
    let w = widths(WIDTH);
    SUM_MIN - (w[Vector::S as usize] + w[Vector::P as usize]) as i32
}

/// Random values and margins of the block's full widths at filter exponents.
pub(super) fn random(rng: &mut StdRng) -> Input {
    let e = exponent(rng);
    let margin = |rng: &mut StdRng, bits: usize| integer(rng, bits + 1).abs().min((1 << bits) - 1);
    let det = (
        Fx {
            m: integer(rng, DET_BITS),
            e,
        },
        margin(rng, DET_MARGIN_BITS),
    );
    let nums = std::array::from_fn(|_| {
        let e = e + rng.gen_range(-8..=8);
        (
            Fx {
                m: integer(rng, NUM_BITS),
                e,
            },
            margin(rng, NUM_MARGIN_BITS),
        )
    });
    Input {
        det,
        nums,
        t_min: t_min(rng),
    }
}

fn point(rng: &mut StdRng, size: f32) -> [f32; 3] {
    std::array::from_fn(|_| rng.gen_range(-size..size))
}

/// A query of the model tests' mix: aimed rays near the triangle's edges, near-parallel
/// rays (det near the fallback's 1e-8), origins a few ulps off the plane, random rays;
/// sizes from 2^-12 to 2^12.
pub(super) fn query(rng: &mut StdRng) -> MtQuery {
    let size = 2f32.powi(rng.gen_range(-12..=12));
    let v0 = point(rng, size);
    let spread = size * 2f32.powi(-rng.gen_range(0..8));
    let add = |a: [f32; 3], b: [f32; 3]| std::array::from_fn(|k| a[k] + b[k]);
    let (v1, v2) = (add(v0, point(rng, spread)), add(v0, point(rng, spread)));
    let edge = |rng: &mut StdRng| match rng.gen_range(0..4) {
        0 => rng.gen_range(-1e-4..1e-4),
        1 => 1.0 + rng.gen_range(-1e-4..1e-4),
        _ => rng.gen_range(-0.2..1.2),
    };
    let (a, b) = (edge(rng), edge(rng));
    let t_min = t_min(rng);
    let orig = add(v0, point(rng, size * 4.0));
    let mut q = MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min);
    match rng.gen_range(0..6) {
        // Near-parallel: the direction in the plane plus a little of the normal.
        0 | 1 => {
            q.dir = near_parallel(rng, [v0, v1, v2]);
        }
        // The origin a few ulps off the plane: t near 0.
        2 => {
            let target = q.dir.map(|d| d * 1e-7);
            q.orig = add(add(orig, q.dir), target);
            q.dir = point(rng, 1.0);
        }
        // A ray that passes behind its origin.
        3 => q.dir = q.dir.map(|d| -d),
        _ => {}
    }
    q
}

#[test]
fn decisions_of_random_values_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(8);
    let mut inputs: Vec<Input> = (0..2000).map(|_| random(&mut rng)).collect();
    // The extremes of every input.
    let (dmin, dmax) = (-(1i128 << (DET_BITS - 1)), (1i128 << (DET_BITS - 1)) - 1);
    let (nmin, nmax) = (-(1i128 << (NUM_BITS - 1)), (1i128 << (NUM_BITS - 1)) - 1);
    let (dm, nm) = (
        (1i128 << DET_MARGIN_BITS) - 1,
        (1i128 << NUM_MARGIN_BITS) - 1,
    );
    for det in [dmin, dmax, 0, 1, -1] {
        for n in [nmin, nmax, 0, 1, -1] {
            for (ed, en) in [(0, 0), (dm, nm), (1, 1)] {
                for e in [lowest_exponent(), 0, 3 * EXP_MAX] {
                    let x = Input {
                        det: (Fx { m: det, e }, ed),
                        nums: [
                            (Fx { m: n, e }, en),
                            (
                                Fx {
                                    m: (-n).min(nmax),
                                    e,
                                },
                                en,
                            ),
                            (Fx { m: n, e: e + 3 }, en),
                        ],
                        t_min: 0.5,
                    };
                    inputs.push(x);
                }
            }
        }
    }
    check(&inputs).assert_both_ways(5, &[]);
}

/// The check is tight: the same stream read a cycle early or a cycle late fails.
#[test]
fn a_wrong_latency_fails() {
    let mut rng = StdRng::seed_from_u64(10);
    let inputs: Vec<Input> = (0..200).map(|_| random(&mut rng)).collect();
    for latency in [LATENCY - 1, LATENCY + 1] {
        let result = std::panic::catch_unwind(|| check_at(&inputs, latency));
        assert!(
            result.is_err(),
            "read at {latency} cycles, the decisions passed"
        );
    }
}

#[test]
fn decisions_of_filter_queries_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(9);
    let mut inputs = Vec::new();
    while inputs.len() < 3000 {
        let q = query(&mut rng);
        let Some([det, nu, nv, nt]) = values(&q, WIDTH, 1.0) else {
            continue;
        };
        // The filter's values fit the block's widths.
        assert!(det.0.m.abs() < 1 << (DET_BITS - 1) && det.1 < 1 << DET_MARGIN_BITS);
        for (v, m) in [nu, nv, nt] {
            assert!(v.m.abs() < 1 << (NUM_BITS - 1) && m < 1 << NUM_MARGIN_BITS);
        }
        inputs.push(Input {
            det,
            nums: [nu, nv, nt],
            t_min: q.t_min,
        });
    }
    check(&inputs).assert_both_ways(5, &[]);
}

/// Its Verilog is what Vivado would read: Verilator lints it clean but for UNOPTFLAT, the
/// traversal unit's waiver: the kernel is one `always` block that drives its blocks' inputs
/// and reads their outputs (the multiplier's product, a comparator's result), which
/// Verilator sees as a loop although no signal depends on itself.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&[verilog()], hdl::verilog::UNIT_VERILATOR_WAIVERS);
}

/// yosys xc7 resources of the decisions:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture decide_resources`
#[test]
#[ignore]
fn decide_resources() {
    println!("{}", hdl::synth::markdown_table(&[verilog()]).unwrap());
}

fn verilog() -> (String, String) {
    named(Decide::default(), "Decide", |_| {
        format!("det {DET_BITS} bits, numerators {NUM_BITS} bits")
    })
}
