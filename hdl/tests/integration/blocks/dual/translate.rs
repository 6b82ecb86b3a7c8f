//! `hdl::dual::translate`.

use hdl::dual::translate::*;
use hw_model::dual::bfp::GUARD_BITS;
use hw_model::dual::bfp::{translate, Fx};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};

/// The block's answer for (a, b), as the model's value.
fn run(uut: &mut Translate, a: f32, b: f32) -> Fx {
    uut.a.next = a.to_bits().to_bits();
    uut.b.next = b.to_bits().to_bits();
    uut.clock.next = Clock { clk: false };
    assert!(simulate(uut, 100));
    uut.clock.next = Clock { clk: true };
    assert!(simulate(uut, 100));
    let raw = uut.d.val().to_u64() as i64;
    // Sign-extend the two's-complement difference.
    let shift = 64 - DIFF_BITS;
    Fx {
        m: i128::from((raw << shift) >> shift),
        e: uut.e.val().to_u64() as i32 - 150 - GUARD_BITS,
    }
}

/// Random fp32 bit patterns (any exponent, subnormals, zeros of both signs) and pairs of
/// nearby exponents, where the guard bits matter.
#[test]
fn translation_equals_the_model_bit_for_bit() {
    let mut uut = Translate::default();
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(17);
    let finite = |rng: &mut StdRng| loop {
        let x = f32::from_bits(rng.gen());
        if x.is_finite() {
            return x;
        }
    };
    let special = [
        0.0f32,
        -0.0,
        1.0,
        -1.0,
        f32::MIN_POSITIVE,
        1e-40,
        -1e-40,
        f32::MAX,
    ];
    for k in 0..20_000 {
        let a = if k % 7 == 0 {
            special[k % special.len()]
        } else {
            finite(&mut rng)
        };
        let near = a * rng.gen_range(-40.0f32..40.0);
        let b = match k % 3 {
            0 => finite(&mut rng),
            // Within a few binades of a, either sign.
            1 if near.is_finite() => near,
            _ => special[(k / 3) % special.len()],
        };
        let want = translate(a, b).unwrap();
        assert_eq!(run(&mut uut, a, b), want, "{a:e} - {b:e}");
    }
}

/// Its Verilog is what Vivado would read: Verilator lints it clean (reserved words and
/// widths included).
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(
        &[named(Translate::default(), "Translate", |_| {
            format!("fp32 − fp32 → {DIFF_BITS} bits")
        })],
        &[],
    );
}
