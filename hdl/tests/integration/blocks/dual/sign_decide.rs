//! `hdl::dual::sign_decide`: the Plücker lane's decisions, bit for bit the model's
//! `signs::decide` (every row, `miss` and `forward`).

use hdl::dual::decide::{DET_BITS, DET_MARGIN_BITS, NUM_BITS, NUM_MARGIN_BITS};
use hdl::dual::plucker::EDGE_VALUE_BITS;
use hdl::dual::round::SHORT_EXP_BITS;
use hdl::dual::sign_decide::*;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::{Fx, Rows, EXP_MAX};
use hw_model::dual::plucker::{sign_inputs, SignInputs};
use hw_model::dual::signs::decide;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};
use super::decide::{integer, lowest_exponent, query, random, t_min, Input, Seen};
use super::round::{raw, stream, Clocked};

/// One decision's inputs: `Decide`'s and N_w with its own margin.
#[derive(Clone, Copy, Debug)]
struct SignInput {
    x: Input,
    w: (Fx, i128),
}

impl Clocked for SignDecide {
    fn clock(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }
}

fn set(uut: &mut SignDecide, i: SignInput) {
    let exp = |e: i32| raw(i128::from(e), SHORT_EXP_BITS).to_bits();
    let x = i.x;
    uut.det.next = raw(x.det.0.m, DET_BITS).to_bits();
    uut.det_e.next = exp(x.det.0.e);
    uut.det_margin.next = raw(x.det.1, DET_MARGIN_BITS).to_bits();
    for k in 0..3 {
        uut.num[k].next = raw(x.nums[k].0.m, NUM_BITS).to_bits();
        uut.num_e[k].next = exp(x.nums[k].0.e);
        uut.num_margin[k].next = raw(x.nums[k].1, NUM_MARGIN_BITS).to_bits();
    }
    uut.w.next = raw(i.w.0.m, EDGE_VALUE_BITS).to_bits();
    uut.w_e.next = exp(i.w.0.e);
    uut.w_margin.next = raw(i.w.1, NUM_MARGIN_BITS).to_bits();
    uut.t_min.next = u64::from(x.t_min.to_bits()).to_bits();
}

fn rows(uut: &SignDecide) -> Rows {
    Rows {
        parallel: uut.parallel.val(),
        in_range: uut.in_range.val(),
        u_below: uut.u_below.val(),
        u_above: false,
        v_below: uut.v_below.val(),
        uv_above: uut.uv_above.val(),
        t_below: uut.t_below.val(),
    }
}

/// `inputs` streamed through the block one a cycle, each decision against the model's
/// `latency` cycles after its inputs.
fn check_at(inputs: &[SignInput], latency: usize) -> Seen {
    let mut uut = SignDecide::default();
    uut.connect_all();
    let mut seen = Seen::default();
    let zero = (Fx { m: 0, e: 0 }, 0);
    let fill = SignInput {
        x: Input {
            det: zero,
            nums: [zero; 3],
            t_min: 0.0,
        },
        w: zero,
    };
    stream(&mut uut, inputs, latency, fill, set, |uut, i| {
        let want = decide(i.x.det, i.x.nums, i.w, i.x.t_min, WIDTH);
        assert_eq!(rows(uut), want, "{i:?}");
        assert_eq!(uut.miss.val(), want.miss(), "{i:?}");
        assert_eq!(uut.forward.val(), !want.miss(), "{i:?}");
        seen.count(&want);
    });
    seen
}

/// `Decide`'s random inputs with a random N_w near det's grid and its margin.
fn random_input(rng: &mut StdRng) -> SignInput {
    let x = random(rng);
    let e = x.det.0.e + rng.gen_range(-8..=8);
    let w = (
        Fx {
            m: integer(rng, EDGE_VALUE_BITS),
            e,
        },
        integer(rng, NUM_MARGIN_BITS - 1).abs(),
    );
    SignInput { x, w }
}

#[test]
fn decisions_of_random_values_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(18);
    let mut inputs: Vec<SignInput> = (0..3000).map(|_| random_input(&mut rng)).collect();
    // The extremes of every input.
    let (dmin, dmax) = (-(1i128 << (DET_BITS - 1)), (1i128 << (DET_BITS - 1)) - 1);
    let (nmin, nmax) = (-(1i128 << (NUM_BITS - 1)), (1i128 << (NUM_BITS - 1)) - 1);
    let (wmin, wmax) = (
        -(1i128 << (EDGE_VALUE_BITS - 1)),
        (1i128 << (EDGE_VALUE_BITS - 1)) - 1,
    );
    let (dm, nm) = (
        (1i128 << DET_MARGIN_BITS) - 1,
        (1i128 << NUM_MARGIN_BITS) - 1,
    );
    for det in [dmin, dmax, 0, 1, -1] {
        for (n, w) in [(nmin, wmin), (nmax, wmax), (0, 0), (1, -1), (-1, 1)] {
            for (ed, en, ew) in [(0, 0, 0), (dm, nm, nm >> 2), (1, 1, 1)] {
                for e in [lowest_exponent(), 0, 3 * EXP_MAX] {
                    inputs.push(SignInput {
                        x: Input {
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
                        },
                        w: (Fx { m: w, e: e - 5 }, ew),
                    });
                }
            }
        }
    }
    // t_min's classes at their edges.
    let base = inputs[0];
    for bits in [
        0u32,
        1,
        0x0b80_0000,
        0x0bff_ffff,
        0x0c00_0000,
        0x0c00_0001,
        0x3f80_0000,
    ] {
        for sign in [0, 1u32 << 31] {
            let mut i = base;
            i.x.t_min = f32::from_bits(bits | sign);
            inputs.push(i);
        }
    }
    // u > 1 is never decided alone (v + w = 1 − u decides it).
    check_at(&inputs, LATENCY).assert_both_ways(5, &["u_above"]);
}

/// The check is tight: the same stream read a cycle early or a cycle late fails.
#[test]
fn a_wrong_latency_fails() {
    let mut rng = StdRng::seed_from_u64(20);
    let inputs: Vec<SignInput> = (0..200).map(|_| random_input(&mut rng)).collect();
    for latency in [LATENCY - 1, LATENCY + 1] {
        let result = std::panic::catch_unwind(|| check_at(&inputs, latency));
        assert!(
            result.is_err(),
            "read at {latency} cycles, the decisions passed"
        );
    }
}

/// The Plücker filter's own values (`plucker::sign_inputs`) of the model tests' queries.
#[test]
fn decisions_of_filter_queries_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(19);
    let mut inputs = Vec::new();
    while inputs.len() < 3000 {
        let q = query(&mut rng);
        let Some(SignInputs { values, w }) = sign_inputs(&q, WIDTH, 1.0) else {
            continue;
        };
        let [det, nu, nv, nt] = values;
        inputs.push(SignInput {
            x: Input {
                det,
                nums: [nu, nv, nt],
                t_min: t_min(&mut rng),
            },
            w,
        });
    }
    // The filter's values are always in range: no exponent comes near the fallback's limits.
    check_at(&inputs, LATENCY).assert_both_ways(5, &["u_above", "in_range"]);
}

/// Verilator lints it clean with the traversal unit's waiver (see `decide`'s lint test).
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&[verilog()], hdl::verilog::UNIT_VERILATOR_WAIVERS);
}

/// yosys xc7 resources of the sign decisions:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture sign_decide_resources`
#[test]
#[ignore]
fn sign_decide_resources() {
    println!("{}", hdl::synth::markdown_table(&[verilog()]).unwrap());
}

fn verilog() -> (String, String) {
    named(SignDecide::default(), "SignDecide", |_| {
        format!("det {DET_BITS} bits, numerators {NUM_BITS} bits")
    })
}
