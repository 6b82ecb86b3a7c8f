//! `hdl::dual::margin`.

use hdl::dual::margin::*;
use hdl::dual::to_block::BELOW_BITS;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::{
    blocks, margin_units, widths, Block as ModelBlock, Vector, DET, DROP_WINDOW, N_T, N_U, N_V,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::MtQuery;

use super::common::{lint_clean, named};

/// The block's margin for the dropped distances `below` of a, b, c, x (0: nothing dropped).
fn run<const MB: usize>(uut: &mut Margin<MB>, below: [i32; 4]) -> i128 {
    for (input, b) in uut.below.iter_mut().zip(below) {
        input.next = (b as u64).to_bits();
    }
    uut.clock.next = Clock { clk: false };
    assert!(simulate(uut, 100));
    uut.clock.next = Clock { clk: true };
    assert!(simulate(uut, 100));
    i128::from(uut.margin.val().to_u64())
}

/// One input through the block and the model.
fn check<const MB: usize>(uut: &mut Margin<MB>, value: [Vector; 4], below: [i32; 4]) {
    let dropped = below.map(|b| (b != 0).then_some(b));
    let want = margin_units(WIDTH, value, dropped, 1.0).expect("the model's margin fits i128");
    assert_eq!(run(uut, below), want, "{value:?} below {below:?}");
}

/// The smallest distance a vector's dropped part has: its own W − 1 (at its last bit).
fn smallest(v: Vector) -> i32 {
    widths(WIDTH)[v as usize] as i32 - 1
}

/// Each input over every value its 7 bits hold (0, the legal W − 1..=DROP_WINDOW and the
/// values `ToBlock` never gives), the others at 0, at their smallest and at DROP_WINDOW.
fn sweeps<const MB: usize>(uut: &mut Margin<MB>, value: [Vector; 4]) {
    for k in 0..4 {
        for others in 0..3 {
            for b in 0..1 << BELOW_BITS {
                let below = std::array::from_fn(|j| match (j == k, others) {
                    (true, _) => b,
                    (false, 0) => 0,
                    (false, 1) => smallest(value[j]),
                    _ => DROP_WINDOW,
                });
                check(uut, value, below);
            }
        }
    }
}

/// Random legal combinations: each distance 0 (a third of the time) or in its vector's
/// W − 1..=DROP_WINDOW, with the ends weighted up.
fn random<const MB: usize>(uut: &mut Margin<MB>, value: [Vector; 4], count: usize, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..count {
        let below = value.map(|v| match rng.gen_range(0..8) {
            0..=2 => 0,
            3 => smallest(v),
            4 => DROP_WINDOW,
            _ => rng.gen_range(smallest(v)..=DROP_WINDOW),
        });
        check(uut, value, below);
    }
}

/// The six blocks (dir, e1, e2, s, p, q) the model's steps 1 to 3 (`blocks`) give a random
/// query, or `None` where the model forwards it (a zero vector, an exponent out of range).
fn filter_blocks(rng: &mut StdRng) -> Option<[ModelBlock; 6]> {
    let point = |rng: &mut StdRng| -> f32 {
        rng.gen_range(-1.0f32..1.0) * 2f32.powi(rng.gen_range(-20..20))
    };
    let v0: [f32; 3] = std::array::from_fn(|_| point(rng));
    // Vertices and origins near v0 (small edges, grazing rays), far, or on it.
    let near = |rng: &mut StdRng| -> [f32; 3] {
        let scale = 2f32.powi(rng.gen_range(-24..4));
        std::array::from_fn(|k| match rng.gen_range(0..6) {
            0 => v0[k],
            1 => point(rng),
            _ => v0[k] + rng.gen_range(-1.0f32..1.0) * scale * v0[k].abs().max(1e-3),
        })
    };
    let (v1, v2, orig) = (near(rng), near(rng), near(rng));
    let dir: [f32; 3] = std::array::from_fn(|_| match rng.gen_range(0..6) {
        0 => 0.0,
        _ => rng.gen_range(-1.0f32..1.0) * 2f32.powi(rng.gen_range(-10..10)),
    });
    // A ray of its own direction, not one aimed at the triangle.
    let mut q = MtQuery::aimed(orig, [v0, v1, v2], (0.0, 0.0), 0.0);
    q.dir = dir;
    blocks(&q, WIDTH)
}

/// The distances `ToBlock` (and the cut) give for the blocks of random queries.
fn filter_shaped<const MB: usize>(
    uut: &mut Margin<MB>,
    value: [Vector; 4],
    count: usize,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut checked, mut dropped) = (0, [0; 4]);
    while checked < count {
        let Some(blocks) = filter_blocks(&mut rng) else {
            continue;
        };
        let below = value.map(|v| {
            let b = blocks[v as usize];
            b.dropped.map_or(0, |d| b.e - d)
        });
        for (k, &b) in below.iter().enumerate() {
            assert!(
                b == 0 || (smallest(value[k])..=DROP_WINDOW).contains(&b),
                "{value:?}: {b} is not a distance ToBlock gives"
            );
            dropped[k] += usize::from(b != 0);
        }
        check(uut, value, below);
        checked += 1;
    }
    // The queries exercise both cases of every input.
    assert!(dropped.iter().all(|&d| 0 < d && d < count), "{dropped:?}");
}

fn all<const MB: usize>(mut uut: Margin<MB>, value: [Vector; 4], seed: u64) {
    uut.connect_all();
    sweeps(&mut uut, value);
    random(&mut uut, value, RANDOM, seed);
    filter_shaped(&mut uut, value, 2000, seed + 100);
}

/// Random combinations per kind.
const RANDOM: usize = 20_000;

#[test]
fn det_margins_equal_the_model_bit_for_bit() {
    all(DetMargin::det(), DET, 1);
}

#[test]
fn u_margins_equal_the_model_bit_for_bit() {
    all(UMargin::n_u(), N_U, 2);
}

#[test]
fn v_margins_equal_the_model_bit_for_bit() {
    all(VMargin::n_v(), N_V, 3);
}

#[test]
fn t_margins_equal_the_model_bit_for_bit() {
    all(TMargin::n_t(), N_T, 4);
}

/// A block built for one kind refuses another kind's width.
#[test]
#[should_panic(expected = "Margin<")]
fn a_margin_checks_its_width() {
    let _ = DetMargin::new(N_U);
}

/// Its Verilog, for each kind, is what Vivado would read: Verilator lints it clean.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the four margins:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture margin_resources`
#[test]
#[ignore]
fn margin_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}

/// Each kind's label (with its width) and Verilog.
fn verilogs() -> Vec<(String, String)> {
    fn shape<const MB: usize>(_: &Margin<MB>) -> String {
        format!("4 × {BELOW_BITS} → {MB} bits")
    }
    vec![
        named(DetMargin::det(), "det (DetMargin)", shape),
        named(UMargin::n_u(), "N_u (UMargin)", shape),
        named(VMargin::n_v(), "N_v (VMargin)", shape),
        named(TMargin::n_t(), "N_t (TMargin)", shape),
    ]
}
