//! The rust-hdl operators, Verilated, streamed one vector per cycle (II = 1) and checked bit
//! for bit against `hw_model`, at 0 and at the maximum number of pipeline stages.
//! Default run: 50k vectors per case, fp32 multiply, fp16 add and fx32_16_rnd_sat multiply;
//! the table reciprocal on every fp24 input and every fp32 fraction.
//! The ≥1M-vector run over every operator of fp32, fp16 and fx32_16_rnd_sat:
//! `cargo test --release -p sim --test integration operators_verilator:: -- --ignored`.

use hdl::formats::{fp16, fp24, fp32, fx32_16_rnd_sat};
use hdl::operator::Operator;
use hw_model::Format;
use rand::{rngs::StdRng, Rng, SeedableRng};
use rust_hdl::prelude::*;
use sim::{build, run_pipelined, BuildOptions, ModelSpec};

/// Random operand pairs: half uniformly random bit patterns, half pairs of close values
/// (cancellation in add/sub, ties in rounding) with random signs.
fn vectors(format: Format, n: usize, seed: u64) -> Vec<[u64; 2]> {
    let width = format.width();
    // Bits that make "close" operands: the fraction field of a float, the low half of a fixed.
    let man = match format {
        Format::Float { man, .. } => man,
        Format::Fixed { .. } => width / 2,
    };
    let mask = (1u64 << width) - 1;
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let a = rng.gen::<u64>() & mask;
            let b = if i % 2 == 0 {
                rng.gen::<u64>() & mask
            } else {
                (a ^ (rng.gen::<u64>() & ((1 << man) - 1))
                    ^ (rng.gen_range(0..2u64) << (width - 1)))
                    & mask
            };
            [a, b]
        })
        .collect()
}

/// Builds operator `T` with `stages` registers, streams `vectors` through it and compares
/// every result with `model`. Returns the simulated vectors per second.
fn check<T: Operator>(
    what: &str,
    stages: usize,
    vectors: &[[u64; 2]],
    model: impl Fn(u64, u64) -> u64,
) -> f64 {
    let mut op = T::new(stages);
    op.connect_all();
    let built = build(
        &ModelSpec::rust_hdl(generate_verilog(&op)),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut sim = built.instantiate();
    let inputs: Vec<&str> = sim
        .interface()
        .inputs
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    let start = std::time::Instant::now();
    let out: Vec<[u64; 1]> = if T::B_WIDTH == 0 {
        assert_eq!(inputs, ["a"]);
        let a: Vec<[u64; 1]> = vectors.iter().map(|v| [v[0]]).collect();
        run_pipelined(&mut sim, &a, stages).unwrap()
    } else {
        assert_eq!(inputs, ["a", "b"]);
        run_pipelined(&mut sim, vectors, stages).unwrap()
    };
    let rate = vectors.len() as f64 / start.elapsed().as_secs_f64();
    for (v, y) in vectors.iter().zip(&out) {
        let want = model(v[0], v[1]);
        assert_eq!(
            y[0], want,
            "{what} stages={stages}: a={:#x} b={:#x} gave {:#x}, model {want:#x}",
            v[0], v[1], y[0]
        );
    }
    rate
}

macro_rules! check_format {
    ($fmt:ident, $n:expr) => {{
        let f = $fmt::FORMAT;
        let v = vectors(f, $n, 0x5eed);
        for stages in [0, usize::MAX] {
            let s = |max: usize| stages.min(max);
            let r = check::<$fmt::Mul>(
                concat!(stringify!($fmt), " mul"),
                s($fmt::Mul::max_stages()),
                &v,
                |a, b| f.mul(a, b),
            );
            println!(
                "{} mul stages={}: {:.2} M vectors/s",
                stringify!($fmt),
                s($fmt::Mul::max_stages()),
                r / 1e6
            );
            let r = check::<$fmt::Add>(
                concat!(stringify!($fmt), " add"),
                s($fmt::Add::max_stages()),
                &v,
                |a, b| f.add(a, b),
            );
            println!(
                "{} add stages={}: {:.2} M vectors/s",
                stringify!($fmt),
                s($fmt::Add::max_stages()),
                r / 1e6
            );
            check::<$fmt::Sub>(
                concat!(stringify!($fmt), " sub"),
                s($fmt::Sub::max_stages()),
                &v,
                |a, b| f.sub(a, b),
            );
            check::<$fmt::Lt>(
                concat!(stringify!($fmt), " lt"),
                s($fmt::Lt::max_stages()),
                &v,
                |a, b| u64::from(f.lt(a, b)),
            );
            let r = check::<$fmt::Recip>(
                concat!(stringify!($fmt), " recip"),
                s($fmt::Recip::max_stages()),
                &v,
                |a, _| f.recip(a),
            );
            println!(
                "{} recip stages={}: {:.2} M vectors/s",
                stringify!($fmt),
                s($fmt::Recip::max_stages()),
                r / 1e6
            );
            check::<$fmt::ToF32>(
                concat!(stringify!($fmt), " to_f32"),
                s($fmt::ToF32::max_stages()),
                &v,
                |a, _| u64::from(f.to_f32(a).to_bits()),
            );
            let fp32_bits = vectors(fp32::FORMAT, v.len(), 0xf32);
            check::<$fmt::FromF32>(
                concat!(stringify!($fmt), " from_f32"),
                s($fmt::FromF32::max_stages()),
                &fp32_bits,
                |a, _| f.from_f32(f32::from_bits(a as u32)),
            );
        }
    }};
}

/// fp32 multiply, fp16 add and a fixed-point multiply at 0 and max stages (six Verilator
/// builds, cached after the first run); the ignored test below covers every operator.
#[test]
fn fp32_mul_and_fp16_add_match_the_model() {
    for stages in [0, usize::MAX] {
        let f = fp32::FORMAT;
        let s = stages.min(fp32::Mul::max_stages());
        check::<fp32::Mul>("fp32 mul", s, &vectors(f, 50_000, 1), |a, b| f.mul(a, b));
        let f = fp16::FORMAT;
        let s = stages.min(fp16::Add::max_stages());
        check::<fp16::Add>("fp16 add", s, &vectors(f, 50_000, 2), |a, b| f.add(a, b));
        let f = fx32_16_rnd_sat::FORMAT;
        let s = stages.min(fx32_16_rnd_sat::Mul::max_stages());
        check::<fx32_16_rnd_sat::Mul>("fx32_16_rnd_sat mul", s, &vectors(f, 50_000, 3), |a, b| {
            f.mul(a, b)
        });
    }
}

/// The table reciprocal at max stages on every fp24 bit pattern and on every fp32 fraction
/// at the exponents of 1.x, of the smallest normals (result near overflow) and of the
/// largest finite values (result subnormal, flushed): each of the table's segments and
/// offsets against the model's correctly rounded reciprocal.
#[test]
fn recip_of_every_fraction_matches_the_model() {
    let f = fp24::FORMAT;
    let every: Vec<[u64; 2]> = (0..1u64 << 24).map(|a| [a, 0]).collect();
    check::<fp24::Recip>("fp24 recip", fp24::Recip::max_stages(), &every, |a, _| {
        f.recip(a)
    });
    let f = fp32::FORMAT;
    let fractions: Vec<[u64; 2]> = [127u64, 1, 253, 0x1fe]
        .iter()
        .flat_map(|&e| (0..1u64 << 23).map(move |m| [(e << 23) | m, 0]))
        .collect();
    check::<fp32::Recip>(
        "fp32 recip",
        fp32::Recip::max_stages(),
        &fractions,
        |a, _| f.recip(a),
    );
}

/// The subtractor's leading-zero anticipation and its one-place correction on every pair of
/// fp16 fractions at exponent distances 0, 1 and 2 (in both orders): every cancellation a
/// difference can have (at distance 2 at most one leading zero remains) and every place of
/// the leading one, at max stages and unpipelined.
#[test]
fn sub_of_every_close_fp16_pair_matches_the_model() {
    let f = fp16::FORMAT;
    let at = |exp: u64, frac: u64| (exp << 10) | frac;
    let pairs: Vec<[u64; 2]> = [(15u64, 15u64), (15, 14), (14, 15), (15, 13), (13, 15)]
        .iter()
        .flat_map(|&(ea, eb)| {
            (0..1u64 << 10)
                .flat_map(move |ma| (0..1u64 << 10).map(move |mb| [at(ea, ma), at(eb, mb)]))
        })
        .collect();
    for stages in [0, fp16::Sub::max_stages()] {
        check::<fp16::Sub>("fp16 sub", stages, &pairs, |a, b| f.sub(a, b));
    }
}

/// Every fp16 zero and subnormal (both signs, flushed to zero by the SPEC) with operands of
/// the smallest exponents (where a subnormal's fraction would change the result if it were
/// not treated as zero), the specials and the largest finite, in both orders, added and
/// subtracted: the adder aligns a zero operand out instead of masking its significand.
#[test]
fn add_and_sub_with_every_fp16_subnormal_match_the_model() {
    let f = fp16::FORMAT;
    let subnormals: Vec<u64> = (0..2u64)
        .flat_map(|sign| (0..1u64 << 10).map(move |frac| (sign << 15) | frac))
        .collect();
    let others: Vec<u64> = [0u64, 1, 2, 30, 31]
        .iter()
        .flat_map(|&exp| {
            (0..1u64 << 10)
                .step_by(4)
                .map(move |frac| (exp << 10) | frac)
        })
        .flat_map(|x| [x, x | 1 << 15])
        .collect();
    let pairs: Vec<[u64; 2]> = subnormals
        .iter()
        .flat_map(|&s| others.iter().flat_map(move |&o| [[s, o], [o, s]]))
        .collect();
    let stages = fp16::Add::max_stages();
    check::<fp16::Add>("fp16 add", stages, &pairs, |a, b| f.add(a, b));
    check::<fp16::Sub>("fp16 sub", stages, &pairs, |a, b| f.sub(a, b));
}

/// `cargo test --release -p sim --test integration operators_verilator:: -- --ignored`
#[test]
#[ignore]
fn all_operators_match_the_model_on_1m_vectors() {
    check_format!(fp32, 1 << 20);
    check_format!(fp16, 1 << 20);
    check_format!(fx32_16_rnd_sat, 1 << 20);
}
