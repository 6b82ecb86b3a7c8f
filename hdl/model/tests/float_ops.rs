//! Float operators against independent references: exact f64 arithmetic rounded once by the
//! test's own rounding (innocuous double rounding for ≤ 24-bit significands), native f32 / f64
//! and the `half` crate with flush-to-zero applied around them, and f64 comparison.

mod common;

use common::*;
use half::f16;
use hw_model::Format;
use rand::rngs::StdRng;
use rand::Rng;

/// Formats whose exact results f64 holds within double-rounding safety (man ≤ 23, exp ≤ 8).
const ORACLE_FORMATS: &[(u32, u32)] = &[
    (8, 23),
    (8, 15),
    (8, 7),
    (5, 10),
    (2, 1),
    (3, 2),
    (4, 3),
    (6, 12),
    (7, 20),
    (8, 1),
    (3, 23),
];

#[derive(Clone, Copy, Debug)]
enum Op {
    Add,
    Sub,
    Mul,
    Recip,
}

const OPS: [Op; 4] = [Op::Add, Op::Sub, Op::Mul, Op::Recip];

fn model(format: &Format, op: Op, a: u64, b: u64) -> u64 {
    match op {
        Op::Add => format.add(a, b),
        Op::Sub => format.sub(a, b),
        Op::Mul => format.mul(a, b),
        Op::Recip => format.recip(a),
    }
}

fn exact(op: Op, a: f64, b: f64) -> f64 {
    match op {
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Mul => a * b,
        Op::Recip => 1.0 / a,
    }
}

fn check_against_f64(format: &Format, op: Op, a: u64, b: u64) {
    let (e, m) = em(format);
    let got = model(format, op, a, b);
    let want = round_f64(exact(op, decode(a, e, m), decode(b, e, m)), e, m);
    assert_eq!(
        got, want,
        "{format} {op:?}({a:#x}, {b:#x}): got {got:#x}, want {want:#x}"
    );
}

fn operand_pair(r: &mut StdRng, e: u32, m: u32) -> (u64, u64) {
    let a = random_float(r, e, m, 0);
    let b = random_float(r, e, m, a);
    (a, b)
}

#[test]
fn edge_operands_match_exact_rounding() {
    for &(e, m) in ORACLE_FORMATS {
        let format = Format::Float { exp: e, man: m };
        let edges = float_edges(e, m);
        for &a in &edges {
            for &b in &edges {
                for op in OPS {
                    check_against_f64(&format, op, a, b);
                }
            }
        }
    }
}

#[test]
fn random_operands_match_exact_rounding() {
    let mut r = rng(1);
    for &(e, m) in ORACLE_FORMATS {
        let format = Format::Float { exp: e, man: m };
        for _ in 0..25_000 {
            let (a, b) = operand_pair(&mut r, e, m);
            for op in OPS {
                check_against_f64(&format, op, a, b);
            }
        }
    }
}

/// Hand-picked cases whose expected bits are known without any oracle.
#[test]
fn known_fp32_results() {
    let f = Format::Float { exp: 8, man: 23 };
    // 1 + 2^-24 is an exact tie: to even (1.0); 1+2^-23 + 2^-24 ties up to 1+2^-22.
    assert_eq!(f.add(0x3f80_0000, 0x3380_0000), 0x3f80_0000);
    assert_eq!(f.add(0x3f80_0001, 0x3380_0000), 0x3f80_0002);
    // x + (−x) = +0, −0 + −0 = −0
    assert_eq!(f.add(0x4040_0000, 0xc040_0000), 0);
    assert_eq!(f.add(0x8000_0000, 0x8000_0000), 0x8000_0000);
    // 0 × Inf and Inf − Inf are the canonical NaN
    assert_eq!(f.mul(0, 0x7f80_0000), 0x7fc0_0000);
    assert_eq!(f.sub(0x7f80_0000, 0x7f80_0000), 0x7fc0_0000);
    // a subnormal operand is ±0: subnormal + subnormal = 0, subnormal × 2^100 = 0
    assert_eq!(f.add(0x0000_0001, 0x0000_0001), 0);
    assert_eq!(f.mul(0x8000_0010, 0x7100_0000), 0x8000_0000);
    // min normal × (1 − 2^-24) rounds (24 bits, unbounded exponent) to 2^-127·(2 − 2^-23):
    // below min normal, so flushed, although IEEE with subnormals gives min normal.
    assert_eq!(f.mul(0x0080_0000, 0x3f7f_ffff), 0);
    // overflow and recip of the extremes
    assert_eq!(f.mul(0x7f7f_ffff, 0x4000_0000), 0x7f80_0000);
    assert_eq!(f.recip(0x8000_0000), 0xff80_0000);
    assert_eq!(f.recip(0x7f80_0000), 0);
    assert_eq!(f.recip(0x7f7f_ffff), 0); // 1/max ≈ 2^-128: flushed
    assert_eq!(f.recip(0x4040_0000), 0x3eaa_aaab); // 1/3
                                                   // neg flips the sign only
    assert_eq!(f.neg(0x3f80_0000), 0xbf80_0000);
}

fn ftz32(x: f32) -> f32 {
    if x.is_subnormal() {
        0.0f32.copysign(x)
    } else {
        x
    }
}

fn native_f32(op: Op, a: f32, b: f32) -> f32 {
    match op {
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Mul => a * b,
        Op::Recip => 1.0 / a,
    }
}

/// The one allowed difference from native IEEE rounding + flushing: an exact result just
/// below the minimum normal that native rounding lifts to ±min normal, which the format
/// (rounding with an unbounded exponent) sees as tiny and flushes.
fn in_ftz_window(
    got: u64,
    want: u64,
    min_normal_bits: u64,
    sign_bit: u64,
    exact_below_min: bool,
) -> bool {
    got & !sign_bit == 0
        && want & !sign_bit == min_normal_bits
        && got == want & sign_bit
        && exact_below_min
}

/// fp32 against native f32 with inputs and outputs flushed; true if the pair hit the window.
fn check_fp32_native(op: Op, a: u64, b: u64) -> bool {
    let format = Format::Float { exp: 8, man: 23 };
    let (fa, fb) = (
        ftz32(f32::from_bits(a as u32)),
        ftz32(f32::from_bits(b as u32)),
    );
    let native = ftz32(native_f32(op, fa, fb));
    let got = model(&format, op, a, b);
    if native.is_nan() {
        assert_eq!(got, 0x7fc0_0000, "{op:?}({a:#x}, {b:#x})");
        return false;
    }
    let want = native.to_bits() as u64;
    if got == want {
        return false;
    }
    let exact = exact(op, fa as f64, fb as f64).abs();
    assert!(
        in_ftz_window(
            got,
            want,
            0x0080_0000,
            1 << 31,
            exact < f32::MIN_POSITIVE as f64
        ),
        "{op:?}({a:#x}, {b:#x}): got {got:#x}, native {want:#x}"
    );
    true
}

#[test]
fn fp32_matches_native_f32_with_ftz() {
    let mut r = rng(2);
    let edges = float_edges(8, 23);
    let mut pairs: Vec<(u64, u64)> = edges
        .iter()
        .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
        .collect();
    pairs.extend((0..100_000).map(|_| operand_pair(&mut r, 8, 23)));
    // Results just below min normal: products of min-normal-ish by just-below-one values.
    pairs.extend((0..2_000).map(|_| {
        (
            0x0080_0000 | r.gen_range(0..8u64),
            0x3f7f_fff0 | r.gen_range(0..16u64),
        )
    }));
    let window: usize = pairs
        .iter()
        .map(|&(a, b)| {
            OPS.iter()
                .filter(|&&op| check_fp32_native(op, a, b))
                .count()
        })
        .sum();
    assert!(
        window > 0,
        "the test never reached the FTZ window it means to exercise"
    );
}

/// The soak: 1M random operand pairs per operator and catalogue float format against exact
/// rounding, and 1M more for fp32 against native f32. Run with
/// `cargo test --release -p hw-model --test float_ops -- --ignored soak`.
#[test]
#[ignore]
fn soak_catalogue_floats_1m_per_op() {
    let mut r = rng(7);
    for named in hw_model::catalogue() {
        let Format::Float { exp, man } = named.format else {
            continue;
        };
        for _ in 0..1_000_000 {
            let (a, b) = operand_pair(&mut r, exp, man);
            for op in OPS {
                check_against_f64(&named.format, op, a, b);
            }
        }
    }
    for _ in 0..1_000_000 {
        let (a, b) = operand_pair(&mut r, 8, 23);
        for op in OPS {
            check_fp32_native(op, a, b);
        }
    }
}

#[test]
fn fp16_matches_half_crate_with_ftz() {
    let format = Format::Float { exp: 5, man: 10 };
    let ftz16 = |x: f16| {
        if x.is_normal() || x.is_nan() || x.is_infinite() || x.to_bits() & 0x7fff == 0 {
            x
        } else {
            f16::from_bits(x.to_bits() & 0x8000)
        }
    };
    let mut r = rng(3);
    let mut pairs: Vec<(u64, u64)> = (0..0x1_0000u64)
        .map(|a| (a, r.gen::<u16>() as u64))
        .collect();
    pairs.extend((0..50_000).map(|_| operand_pair(&mut r, 5, 10)));
    for (a, b) in pairs {
        for op in OPS {
            let (ha, hb) = (
                ftz16(f16::from_bits(a as u16)),
                ftz16(f16::from_bits(b as u16)),
            );
            let native = ftz16(match op {
                Op::Add => ha + hb,
                Op::Sub => ha - hb,
                Op::Mul => ha * hb,
                Op::Recip => f16::ONE / ha,
            });
            let got = model(&format, op, a, b);
            if native.is_nan() {
                assert_eq!(got, 0x7e00, "{op:?}({a:#x}, {b:#x})");
                continue;
            }
            let want = native.to_bits() as u64;
            let exact_below =
                exact(op, ha.to_f64(), hb.to_f64()).abs() < f16::MIN_POSITIVE.to_f64();
            assert!(
                got == want || in_ftz_window(got, want, 0x0400, 0x8000, exact_below),
                "{op:?}({a:#x}, {b:#x}): got {got:#x}, half {want:#x}"
            );
        }
    }
}

/// The widest format (e11m52) exercises the u128 paths; native f64 is its reference.
#[test]
fn fp64_matches_native_f64_with_ftz() {
    let format = Format::Float { exp: 11, man: 52 };
    let ftz64 = |x: f64| {
        if x.is_subnormal() {
            0.0f64.copysign(x)
        } else {
            x
        }
    };
    let mut r = rng(4);
    let edges = float_edges(11, 52);
    let mut pairs: Vec<(u64, u64)> = edges
        .iter()
        .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
        .collect();
    pairs.extend((0..50_000).map(|_| operand_pair(&mut r, 11, 52)));
    for (a, b) in pairs {
        for op in OPS {
            let (fa, fb) = (ftz64(f64::from_bits(a)), ftz64(f64::from_bits(b)));
            let native = ftz64(exact(op, fa, fb));
            let got = model(&format, op, a, b);
            if native.is_nan() {
                assert_eq!(got, canonical_nan(11, 52), "{op:?}({a:#x}, {b:#x})");
                continue;
            }
            let want = native.to_bits();
            // No exact value to bound here: accept the window's shape alone.
            assert!(
                got == want || in_ftz_window(got, want, 1 << 52, 1 << 63, true),
                "{op:?}({a:#x}, {b:#x}): got {got:#x}, native {want:#x}"
            );
        }
    }
}

#[test]
fn lt_matches_f64_comparison() {
    let mut r = rng(5);
    for &(e, m) in ORACLE_FORMATS.iter().chain(&[(11, 52)]) {
        let format = Format::Float { exp: e, man: m };
        let edges = float_edges(e, m);
        let mut pairs: Vec<(u64, u64)> = edges
            .iter()
            .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
            .collect();
        pairs.extend((0..10_000).map(|_| operand_pair(&mut r, e, m)));
        for (a, b) in pairs {
            let want = decode(a, e, m) < decode(b, e, m);
            assert_eq!(format.lt(a, b), want, "{format} lt({a:#x}, {b:#x})");
            assert_eq!(format.is_nan(a), decode(a, e, m).is_nan());
        }
    }
}

#[test]
fn f32_conversions_round_once_and_round_trip() {
    let mut r = rng(6);
    for &(e, m) in ORACLE_FORMATS.iter().chain(&[(11, 52)]) {
        let format = Format::Float { exp: e, man: m };
        for _ in 0..20_000 {
            // from_f32: flush a subnormal input, then one rounding
            let x = f32::from_bits(r.gen());
            let want = round_f64(ftz32(x) as f64, e, m);
            assert_eq!(
                format.from_f32(x),
                want,
                "{format} from_f32({:#x})",
                x.to_bits()
            );
            // to_f32 of a format value: one rounding to fp32 (exact when the format fits)
            let bits = random_float(&mut r, e, m, 0);
            let got = format.to_f32(bits).to_bits() as u64;
            assert_eq!(
                got,
                round_f64(decode(bits, e, m), 8, 23),
                "{format} to_f32({bits:#x})"
            );
            // to_f64 is exact; from_f64 ∘ to_f64 is the identity on non-NaN values
            assert_eq!(
                format.to_f64(bits).to_bits(),
                decode(bits, e, m).to_bits(),
                "{format} to_f64({bits:#x})"
            );
            if !decode(bits, e, m).is_nan() {
                assert_eq!(
                    format.from_f64(format.to_f64(bits)),
                    round_f64(decode(bits, e, m), e, m)
                );
            }
            if e <= 8 && m <= 23 {
                assert_eq!(
                    format.from_f32(format.to_f32(bits)),
                    round_f64(decode(bits, e, m), e, m)
                );
            }
        }
    }
}

/// √x of fp32 as the model computes it, from the reference: f64 `sqrt` (correctly rounded)
/// rounded once to f32 (double rounding is innocuous for a square root: 53 ≥ 2·24 + 2), with
/// the SPEC's flushing and NaN rules: a subnormal operand is ±0, √−0 = −0, below zero NaN.
fn sqrt_reference(bits: u32) -> u32 {
    let x = ftz32(f32::from_bits(bits));
    if x.is_nan() || x < 0.0 || x == f32::NEG_INFINITY {
        return 0x7fc0_0000;
    }
    ((x as f64).sqrt() as f32).to_bits()
}

/// Every fp32 in [1, 4): every significand with both exponent parities, which is every case
/// the integer root sees (other exponents only shift the result's).
#[test]
fn fp32_sqrt_is_correctly_rounded_on_every_operand_in_one_to_four() {
    for bits in 1.0f32.to_bits()..4.0f32.to_bits() {
        let got = hw_model::fp32::Fp32::from_bits(bits).sqrt().bits();
        assert_eq!(got, sqrt_reference(bits), "sqrt({bits:#x})");
    }
}

#[test]
fn fp32_sqrt_of_random_and_special_operands() {
    let mut r = rng(8);
    let specials = float_edges(8, 23).into_iter().map(|b| b as u32);
    let negatives = float_edges(8, 23)
        .into_iter()
        .map(|b| b as u32 | 0x8000_0000);
    let random = (0..200_000).map(|_| r.gen::<u32>());
    for bits in specials.chain(negatives).chain(random) {
        let got = hw_model::fp32::Fp32::from_bits(bits).sqrt().bits();
        assert_eq!(got, sqrt_reference(bits), "sqrt({bits:#x})");
    }
    let sqrt = |x: f32| hw_model::fp32::Fp32::new(x).sqrt().f32();
    assert_eq!(sqrt(-0.0).to_bits(), 0x8000_0000);
    assert_eq!(sqrt(1e-40).to_bits(), 0, "a subnormal operand is +0");
    assert_eq!(sqrt(f32::INFINITY), f32::INFINITY);
    assert_eq!(sqrt(4.0), 2.0);
    assert_eq!(sqrt(2.0), std::f32::consts::SQRT_2);
}
