//! Independent oracles shared by the test files: float decoding and one-rounding from f64
//! bits, written from the SPEC without the model's code; a seeded RNG; edge operands.
#![allow(dead_code)] // each test file uses its own subset

use hw_model::Format;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Asserts that an error message names every one of `parts`.
pub fn says(e: &str, parts: &[&str]) {
    for p in parts {
        assert!(e.contains(p), "`{e}` lacks `{p}`");
    }
}

pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// (exp, man) of a float format.
pub fn em(format: &Format) -> (u32, u32) {
    match *format {
        Format::Float { exp, man } => (exp, man),
        Format::Fixed { .. } => panic!("not a float format"),
    }
}

pub fn canonical_nan(exp: u32, man: u32) -> u64 {
    (((1u64 << exp) - 1) << man) | (1u64 << (man - 1))
}

/// The value of float bits with subnormals flushed (sign kept), as an f64 (exact for man ≤ 52,
/// exponents within f64's range).
pub fn decode(bits: u64, exp: u32, man: u32) -> f64 {
    let sign = if bits >> (exp + man) & 1 == 1 {
        -1.0
    } else {
        1.0
    };
    let ef = (bits >> man) & ((1u64 << exp) - 1);
    let frac = bits & ((1u64 << man) - 1);
    let bias = (1i32 << (exp - 1)) - 1;
    if ef == (1u64 << exp) - 1 {
        return if frac == 0 {
            sign * f64::INFINITY
        } else {
            f64::NAN
        };
    }
    if ef == 0 {
        return sign * 0.0;
    }
    sign * (1.0 + frac as f64 / (1u64 << man) as f64) * 2f64.powi(ef as i32 - bias)
}

/// Rounds an f64 to the float format once: RNE to man+1 bits with an unbounded exponent,
/// then ±Inf above the range and ±0 below the minimum normal; NaN is the canonical NaN.
pub fn round_f64(x: f64, exp: u32, man: u32) -> u64 {
    let exp_ones = (1u64 << exp) - 1;
    let bias = (1i64 << (exp - 1)) - 1;
    let sign = (x.to_bits() >> 63) << (exp + man);
    if x.is_nan() {
        return canonical_nan(exp, man);
    }
    if x.is_infinite() {
        return sign | (exp_ones << man);
    }
    let xb = x.to_bits();
    let xe = ((xb >> 52) & 0x7ff) as i64;
    if xe == 0 {
        return sign; // ±0 (f64 subnormals never occur in these tests' ranges)
    }
    // x = sig53 × 2^(xe − 1075)
    let sig = (xb & ((1u64 << 52) - 1)) | (1u64 << 52);
    let drop = 52 - man;
    let mut keep = sig >> drop;
    let rest = sig & ((1u64 << drop) - 1);
    let half = if drop == 0 { 0 } else { 1u64 << (drop - 1) };
    let mut e2 = xe - 1023; // exponent of the leading bit
    if drop > 0 && (rest > half || (rest == half && keep & 1 == 1)) {
        keep += 1;
        if keep >> (man + 1) != 0 {
            keep >>= 1;
            e2 += 1;
        }
    }
    let biased = e2 + bias;
    if biased >= exp_ones as i64 {
        sign | (exp_ones << man)
    } else if biased <= 0 {
        sign
    } else {
        sign | ((biased as u64) << man) | (keep & ((1u64 << man) - 1))
    }
}

/// Special and boundary operands of a float format.
pub fn float_edges(exp: u32, man: u32) -> Vec<u64> {
    let s = 1u64 << (exp + man);
    let exp_ones = (1u64 << exp) - 1;
    let bias = (1u64 << (exp - 1)) - 1;
    let one = bias << man;
    let frac_max = (1u64 << man) - 1;
    let mut v = vec![
        0,
        exp_ones << man,                    // Inf
        canonical_nan(exp, man),            // NaN
        (exp_ones << man) | 1,              // another NaN
        ((exp_ones - 1) << man) | frac_max, // max normal
        (exp_ones - 1) << man,
        1 << man, // min normal
        (1 << man) | 1,
        (1 << man) | frac_max, // just below 2·min normal
        1,                     // subnormals
        frac_max,
        1u64 << (man - 1),
        one, // 1
        one | 1,
        one | frac_max,
        ((bias - 1) << man) | frac_max, // just below 1
    ];
    if bias > man as u64 + 2 {
        // half an ulp of 1 (an exact tie when added to 1), its neighbours, and 2^(man+1)
        let half_ulp = (bias - man as u64 - 1) << man;
        v.extend([
            half_ulp,
            half_ulp | 1,
            half_ulp - (1 << man),
            (bias + man as u64 + 1) << man,
        ]);
    }
    let positives = v.clone();
    v.extend(positives.iter().map(|b| b | s));
    v
}

/// Random bits of a float format, biased toward interesting operands: uniform bits,
/// exponents near the ends, and values near `near` (cancellation, ties, carries).
pub fn random_float(r: &mut StdRng, exp: u32, man: u32, near: u64) -> u64 {
    let w = 1 + exp + man;
    let all = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
    let exp_ones = (1u64 << exp) - 1;
    match r.gen_range(0..8) {
        0 | 1 => r.gen::<u64>() & all,
        2 => {
            // close to `near`: flip a few low bits, maybe the sign
            let flip = r.gen::<u64>() & ((1u64 << r.gen_range(1..=man.min(20))) - 1);
            (near ^ flip ^ if r.gen() { 1u64 << (exp + man) } else { 0 }) & all
        }
        3 => {
            // exponent within a few of `near`'s, random fraction and sign
            let ne =
                ((near >> man) & exp_ones) as i64 + r.gen_range(-(man as i64) - 3..=man as i64 + 3);
            let ef = ne.clamp(1, exp_ones as i64 - 1) as u64;
            (r.gen::<u64>() & ((1u64 << man) - 1))
                | (ef << man)
                | ((r.gen::<u64>() & 1) << (exp + man))
        }
        4 => {
            // extreme exponents
            let ef = if r.gen() {
                r.gen_range(0..4.min(exp_ones))
            } else {
                exp_ones - r.gen_range(0..4.min(exp_ones))
            };
            (r.gen::<u64>() & ((1u64 << man) - 1))
                | (ef << man)
                | ((r.gen::<u64>() & 1) << (exp + man))
        }
        _ => {
            // ordinary magnitudes around 1
            let bias = (1i64 << (exp - 1)) - 1;
            let span = (bias - 1).min(20);
            let ef = (bias + r.gen_range(-span..=span)) as u64;
            (r.gen::<u64>() & ((1u64 << man) - 1))
                | (ef << man)
                | ((r.gen::<u64>() & 1) << (exp + man))
        }
    }
}
