//! `hdl::dual::to_block`.

use hdl::dual::to_block::*;
use hdl::dual::translate::FIELD_BITS;
use hw_model::dual::bfp::Block as ModelBlock;
use hw_model::dual::bfp::{split, to_block, translate, Fx, DROP_WINDOW, GUARD_BITS};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};

/// The fields' bias of an fp32 significand (its last bit's exponent is field − 150);
/// `Translate`'s differences sit GUARD_BITS lower.
const SIGNIFICAND_BIAS: i32 = 150;
const DIFF_BIAS: i32 = SIGNIFICAND_BIAS + GUARD_BITS;
const FIELD_MAX: i32 = (1 << FIELD_BITS) - 1;

/// Sign-extends the low `width` bits of `raw`.
fn signed(raw: u64, width: usize) -> i128 {
    let shift = 64 - width;
    i128::from(((raw << shift) as i64) >> shift)
}

/// The block's answer for `x[k]`·2^(`f[k]` − bias), as the model's value (`None`: zero).
fn run<const IW: usize, const W: usize>(
    uut: &mut ToBlock<IW, W>,
    x: [i64; 3],
    f: [i32; 3],
    bias: i32,
) -> Option<ModelBlock> {
    for k in 0..3 {
        uut.x[k].next = (x[k] as u64 & ((1u64 << IW) - 1)).to_bits();
        uut.f[k].next = (f[k] as u64).to_bits();
    }
    uut.clock.next = Clock { clk: false };
    assert!(simulate(uut, 100));
    uut.clock.next = Clock { clk: true };
    assert!(simulate(uut, 100));
    if uut.zero.val() {
        return None;
    }
    let e = uut.e.val().to_u64() as i32 - bias;
    let below = uut.below.val().to_u64() as i32;
    Some(ModelBlock {
        m: std::array::from_fn(|k| signed(uut.m[k].val().to_u64(), W)),
        e,
        // The last bit is implicit: the model's lsb must be where the block says.
        lsb: e - (W as i32 - 1),
        dropped: (below != 0).then_some(e - below),
    })
}

/// One vector through the block and the model.
fn check<const IW: usize, const W: usize>(
    uut: &mut ToBlock<IW, W>,
    x: [i64; 3],
    f: [i32; 3],
    bias: i32,
) {
    let v: [Fx; 3] = std::array::from_fn(|k| Fx {
        m: i128::from(x[k]),
        e: f[k] - bias,
    });
    let want = to_block(v, W as u32);
    assert_eq!(run(uut, x, f, bias), want, "{x:?} at fields {f:?}");
}

/// An IW-bit signed integer of a random bit count (zeros and extremes included).
fn component(rng: &mut StdRng, width: usize) -> i64 {
    let bits = rng.gen_range(0..=width);
    match bits {
        0 => [0, -1][rng.gen_range(0..2)],
        _ => rng.gen_range(-(1i64 << (bits - 1))..1i64 << (bits - 1)),
    }
}

/// Fields near each other (partial drops), far apart (whole and far-below drops), or at
/// the ends of the range.
fn fields(rng: &mut StdRng, spread: i32) -> [i32; 3] {
    let base = rng.gen_range(0..=FIELD_MAX);
    std::array::from_fn(|_| match rng.gen_range(0..8) {
        0 => rng.gen_range(0..=FIELD_MAX),
        1 => [0, FIELD_MAX][rng.gen_range(0..2)],
        _ => (base + rng.gen_range(-spread..=spread)).clamp(0, FIELD_MAX),
    })
}

/// Random components at random fields, then the special vectors.
fn random_and_special<const IW: usize, const W: usize>(
    uut: &mut ToBlock<IW, W>,
    bias: i32,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    let spread = (IW + W) as i32;
    for _ in 0..1500 {
        let x = std::array::from_fn(|_| component(&mut rng, IW));
        check(uut, x, fields(&mut rng, spread), bias);
    }
    let (min, max) = (-(1i64 << (IW - 1)), (1i64 << (IW - 1)) - 1);
    let special = [0, 1, -1, 2, -2, min, max, min + 1, max - 1];
    for &a in &special {
        for &b in &special {
            for f in [
                [0, 0, 0],
                [FIELD_MAX; 3],
                [FIELD_MAX, 0, 0],
                [100, 100 - spread, 3],
            ] {
                check(uut, [a, b, a ^ b], f, bias);
            }
        }
    }
    // The drop window: a part just inside, at and beyond DROP_WINDOW below the block.
    let w = W as i32;
    for d in DROP_WINDOW - 3..DROP_WINDOW + 3 {
        for x in [1, -1, 3, -3] {
            check(uut, [max, x, 0], [200, 200 + w - 1 - d, 0], bias);
        }
    }
}

#[test]
fn dir_blocks_equal_the_model_bit_for_bit() {
    let mut uut = DirToBlock::default();
    uut.connect_all();
    random_and_special(&mut uut, SIGNIFICAND_BIAS, 2);
    // Directions as the filter reads them: fp32 significands at their exponents.
    let mut rng = StdRng::seed_from_u64(20);
    for _ in 0..1000 {
        let dir: [f32; 3] = std::array::from_fn(|_| match rng.gen_range(0..6) {
            0 => 0.0,
            1 => f32::from_bits(rng.gen::<u32>() & 0x807f_ffff),
            _ => rng.gen_range(-1.0f32..1.0) * 2f32.powi(rng.gen_range(-60..60)),
        });
        let v = dir.map(|c| split(c).unwrap());
        let x = v.map(|c| c.m as i64);
        let f = v.map(|c| c.e + SIGNIFICAND_BIAS);
        check(&mut uut, x, f, SIGNIFICAND_BIAS);
    }
}

/// e1, e2 and s as the filter reads them: `translate`'s differences of random points.
fn translated<const W: usize>(
    uut: &mut ToBlock<{ hdl::dual::translate::DIFF_BITS }, W>,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..1000 {
        let point = |rng: &mut StdRng| -> f32 {
            rng.gen_range(-1.0f32..1.0) * 2f32.powi(rng.gen_range(-30..30))
        };
        let v0 = point(&mut rng);
        let d: [Fx; 3] = std::array::from_fn(|_| {
            let p = match rng.gen_range(0..4) {
                0 => v0,
                1 => v0 * (1.0 + rng.gen_range(-1e-5f32..1e-5)),
                _ => point(&mut rng),
            };
            translate(p, v0).unwrap()
        });
        check(
            uut,
            d.map(|c| c.m as i64),
            d.map(|c| c.e + DIFF_BIAS),
            DIFF_BIAS,
        );
    }
}

#[test]
fn edge_blocks_equal_the_model_bit_for_bit() {
    let mut uut = EdgeToBlock::default();
    uut.connect_all();
    random_and_special(&mut uut, DIFF_BIAS, 3);
    translated(&mut uut, 30);
}

#[test]
fn s_blocks_equal_the_model_bit_for_bit() {
    let mut uut = SToBlock::default();
    uut.connect_all();
    random_and_special(&mut uut, DIFF_BIAS, 4);
    translated(&mut uut, 40);
}

/// Its Verilog, at each of the three widths, is what Vivado would read: Verilator lints it
/// clean.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the three conversions:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture to_block_resources`
#[test]
#[ignore]
fn to_block_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}

/// Each conversion's label (with its widths) and Verilog.
fn verilogs() -> Vec<(String, String)> {
    fn shape<const IW: usize, const W: usize>(_: &ToBlock<IW, W>) -> String {
        format!("3 × {IW} → {W} bits")
    }
    vec![
        named(DirToBlock::default(), "dir (DirToBlock)", shape),
        named(EdgeToBlock::default(), "e1 or e2 (EdgeToBlock)", shape),
        named(SToBlock::default(), "s (SToBlock)", shape),
    ]
}
