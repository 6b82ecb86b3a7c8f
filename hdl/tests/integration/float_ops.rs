//! The float operators in rust-hdl's simulator, bit for bit against `hw_model`, for every
//! catalogue float format at 0, a middle and the maximum number of pipeline stages.
//! More vectors: `cargo test --release -p hdl --test integration float_ops:: -- --ignored`.

use hdl::formats::{self, bf16, e5m14, fp16, fp24, fp32};
use hdl::operator::{simulate_operator, Op, Operator, OperatorError};
use hdl::synth::{synthesize, SynthOptions};
use hdl::verilog::TOP;
use hw_model::{Format, HwFormat};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rayon::prelude::*;

/// Edge-case operands of a float format: zeros, subnormals, min/max normal, Inf, NaN,
/// one and its neighbours, values whose sums/products land on rounding halfway points.
pub(crate) fn edge_values(format: Format) -> Vec<u64> {
    let Format::Float { exp, man } = format else {
        panic!("float formats only")
    };
    let sign = 1u64 << (exp + man);
    let bias = (1u64 << (exp - 1)) - 1;
    let inf = ((1u64 << exp) - 1) << man;
    let one = bias << man;
    let mags = [
        0,
        1,              // smallest subnormal
        (1 << man) - 1, // largest subnormal
        1 << man,       // smallest normal
        (1 << man) | 1,
        inf - 1,          // largest finite
        inf - (1 << man), // largest binade, fraction 0
        inf,
        inf | 1,                // a NaN that is not canonical
        inf | (1 << (man - 1)), // canonical NaN
        one,
        one + 1,
        one - 1,
        one | (1 << (man - 1)),         // 1.5
        one + (1 << man),               // 2
        one | ((1 << man) - 1),         // 2 - ulp
        (bias + man as u64 + 1) << man, // 2^(M+1): adding 1 is a tie
        (bias + man as u64 + 2) << man | 1,
        ((bias / 2) << man) | 3,
        ((bias + bias / 2) << man) | 5,
    ];
    mags.iter().flat_map(|&m| [m, m | sign]).collect()
}

/// Edge × edge pairs, then random pairs: random bits, close magnitudes (cancellation),
/// exponents near overflow and underflow, and x with −x.
fn vectors(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let width = format.width();
    let mask = (1u64 << width) - 1;
    let Format::Float { man, .. } = format else {
        unreachable!()
    };
    let edges = edge_values(format);
    let mut v: Vec<(u64, u64)> = edges
        .iter()
        .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
        .collect();
    let mut rng = StdRng::seed_from_u64(seed);
    for i in 0..random {
        let a = rng.gen::<u64>() & mask;
        let b = match i % 5 {
            0 => rng.gen::<u64>() & mask,
            1 => {
                (a ^ (rng.gen::<u64>() & ((1 << man) - 1)) ^ (rng.gen_range(0..2) << (width - 1)))
                    & mask
            }
            2 => (a ^ (1 << (width - 1))) & mask,
            3 => {
                (a.wrapping_add(rng.gen_range(0..4u64) << man)
                    ^ (rng.gen_range(0..2) << (width - 1)))
                    & mask
            }
            _ => {
                // Exponent sum close to the bias: products near the overflow and underflow limits.
                let e = (a >> man) & ((1 << (width - 1 - man)) - 1);
                let bias = (1u64 << (width - 2 - man)) - 1;
                let eb = (3 * bias).saturating_sub(e).min(2 * bias) ^ rng.gen_range(0..3);
                ((eb << man) | (rng.gen::<u64>() & ((1 << man) - 1))) & mask
            }
        };
        v.push((a, b));
    }
    v
}

/// Single operands for the unary operators: the edge values and both operands of the random pairs.
fn singles(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let edges = edge_values(format);
    let pairs = vectors(format, random, seed);
    let randoms = pairs[edges.len() * edges.len()..]
        .iter()
        .flat_map(|&(a, b)| [a, b]);
    edges
        .iter()
        .copied()
        .chain(randoms)
        .map(|a| (a, 0))
        .collect()
}

/// fp32 inputs for the conversion to `format`: fp32's own vectors, and the format's values
/// widened to fp32 with random dropped bits, exact halfway points and halfway ± 1 ulp.
fn fp32_inputs(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let Format::Float { man, .. } = format else {
        unreachable!()
    };
    let dropped = 23 - man;
    let mut rng = StdRng::seed_from_u64(seed);
    let mut v = singles(fp32::FORMAT, random / 2, seed);
    for (a, _) in singles(format, random / 2, seed + 1) {
        let wide = format.to_f32(a).to_bits() as u64;
        if dropped == 0 || f32::from_bits(wide as u32).is_nan() {
            continue;
        }
        let half = 1u64 << (dropped - 1);
        v.push((wide | (rng.gen::<u64>() & ((1 << dropped) - 1)), 0));
        v.push((wide | half, 0));
        v.push((wide | half | 1, 0));
        v.push(((wide | half) - 1, 0));
    }
    v
}

fn check<T: Operator>(what: &str, vectors: &[(u64, u64)], model: impl Fn(u64, u64) -> u64) {
    let max = T::max_stages();
    let mut stage_list = vec![0, max / 2, max];
    stage_list.dedup();
    for stages in stage_list {
        let out = simulate_operator::<T>(stages, vectors);
        for (&(a, b), &y) in vectors.iter().zip(&out) {
            let want = model(a, b);
            assert_eq!(
                y, want,
                "{what} stages={stages}: a={a:#x} b={b:#x} gave {y:#x}, model {want:#x}"
            );
        }
    }
}

macro_rules! float_tests {
    ($($fmt:ident),*) => {
        fn check_all_formats(random: usize, seed: u64) {
            $(
                let f = $fmt::FORMAT;
                let v = vectors(f, random, seed);
                check::<$fmt::Mul>(concat!(stringify!($fmt), " mul"), &v, |a, b| f.mul(a, b));
                check::<$fmt::Add>(concat!(stringify!($fmt), " add"), &v, |a, b| f.add(a, b));
                check::<$fmt::Sub>(concat!(stringify!($fmt), " sub"), &v, |a, b| f.sub(a, b));
                check::<$fmt::Lt>(concat!(stringify!($fmt), " lt"), &v, |a, b| f.lt(a, b) as u64);
                let u = singles(f, random, seed);
                check::<$fmt::Recip>(concat!(stringify!($fmt), " recip"), &u, |a, _| f.recip(a));
                check::<$fmt::ToF32>(concat!(stringify!($fmt), " to_f32"), &u, |a, _| f.to_f32(a).to_bits() as u64);
                let w = fp32_inputs(f, random, seed);
                check::<$fmt::FromF32>(concat!(stringify!($fmt), " from_f32"), &w, |a, _| f.from_f32(f32::from_bits(a as u32)));
            )*
        }

        #[test]
        fn catalogue_modules_match_the_model_catalogue() {
            $(
                assert_eq!(hw_model::catalogue::lookup($fmt::NAME).unwrap(), $fmt::FORMAT);
                assert_eq!($fmt::WIDTH as u32, $fmt::FORMAT.width());
            )*
        }
    };
}

float_tests!(fp32, fp24, bf16, fp16, e5m14);

#[test]
fn float_operators_match_the_model() {
    check_all_formats(300, 1);
}

#[test]
#[ignore]
fn float_operators_match_the_model_many_vectors() {
    check_all_formats(20_000, 2);
}

/// The table reciprocal's approximation must hold on every segment: every bf16 and fp16 bit
/// pattern (each fraction at every exponent, both signs, the specials), at 0 and max stages.
#[test]
fn recip_of_every_half_precision_input_matches_the_model() {
    let all = |width: usize| (0..1u64 << width).map(|a| (a, 0)).collect::<Vec<_>>();
    let f = bf16::FORMAT;
    for stages in [0, bf16::max_stages(Op::Recip)] {
        let v = all(16);
        for (&(a, _), y) in v.iter().zip(simulate_operator::<bf16::Recip>(stages, &v)) {
            assert_eq!(y, f.recip(a), "bf16 recip stages={stages}: a={a:#x}");
        }
    }
    let f = fp16::FORMAT;
    let v = all(16);
    for (&(a, _), y) in v.iter().zip(simulate_operator::<fp16::Recip>(
        fp16::max_stages(Op::Recip),
        &v,
    )) {
        assert_eq!(y, f.recip(a), "fp16 recip: a={a:#x}");
    }
}

/// e5m14's table has its own segment count (M = 14 is none of the widths the table's error
/// bound was measured at): every fraction, both signs, at the smallest, the unit's and the
/// largest normal exponent, at max stages. The reciprocal's significand depends on the
/// fraction only, so the other exponents differ in the packing the edge values test.
#[test]
fn recip_of_every_e5m14_fraction_matches_the_model() {
    let f = e5m14::FORMAT;
    let Format::Float { exp, man } = f else {
        unreachable!()
    };
    let top = (1u64 << exp) - 2;
    let v: Vec<(u64, u64)> = [1, top / 2, top]
        .into_iter()
        .flat_map(|e| [0, 1u64 << (exp + man)].map(|sign| sign | e << man))
        .flat_map(|base| (0..1u64 << man).map(move |frac| (base | frac, 0)))
        .collect();
    for (&(a, _), y) in v.iter().zip(simulate_operator::<e5m14::Recip>(
        e5m14::max_stages(Op::Recip),
        &v,
    )) {
        assert_eq!(y, f.recip(a), "e5m14 recip: a={a:#x}");
    }
}

#[test]
fn every_operator_passes_verilator_lint() {
    let designs: Vec<(HwFormat, Op, usize)> = HwFormat::all()
        .flat_map(|format| {
            Op::ALL.into_iter().flat_map(move |op| {
                [0, formats::max_stages(format, op)].map(|stages| (format, op, stages))
            })
        })
        .collect();
    // A Verilator process a design, one a core.
    designs.into_par_iter().for_each(|(format, op, stages)| {
        let rtl = formats::rtl(format, op, stages).unwrap();
        assert_eq!(rtl.latency, stages);
        if let Err(e) = hdl::verilog::verilator_lint(&rtl.verilog) {
            panic!("{format} {op} stages={stages}: verilator lint failed:\n{e}");
        }
    });
}

#[test]
fn stages_beyond_the_maximum_are_an_error() {
    let fp16 = HwFormat::named("fp16");
    let max = formats::max_stages(fp16, Op::Mul);
    assert!(matches!(
        formats::rtl(fp16, Op::Mul, max + 1),
        Err(OperatorError::TooManyStages { .. })
    ));
    assert_eq!("recip".parse::<Op>(), Ok(Op::Recip));
    assert!("div".parse::<Op>().is_err());
}

/// yosys `synth_xilinx` of the fp32 multiplier: the 24×24 significand product must map onto
/// DSP slices (≤ 3 DSP48E1) and the design must synthesise at 0 and max stages.
#[test]
fn fp32_mul_synthesises_onto_dsp_slices() {
    for stages in [0, fp32::max_stages(Op::Mul)] {
        let rtl = fp32::rtl(Op::Mul, stages).unwrap();
        let report =
            synthesize(&rtl.verilog, TOP, &SynthOptions::default()).expect("yosys synth_xilinx");
        eprintln!(
            "fp32 mul stages={stages}: {} LUT {} FF {} DSP48E1 {} CARRY4",
            report.lut, report.ff, report.dsp48e1, report.carry4
        );
        assert!(
            report.dsp48e1 >= 1 && report.dsp48e1 <= 3,
            "fp32 mul uses {} DSP48E1",
            report.dsp48e1
        );
        assert!(
            report.lut < 1000,
            "fp32 mul uses {} LUTs: the multiplier went into fabric",
            report.lut
        );
    }
}

/// Synthesis report of every operator in every format at 0 and max stages (slow: ~10 min):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture float_ops::synthesis_table`.
#[test]
#[ignore]
fn synthesis_table() {
    println!("| format | op | stages | LUT | FF | DSP48E1 | CARRY4 | depth |");
    for format in HwFormat::all() {
        for op in Op::ALL {
            let max = formats::max_stages(format, op);
            for stages in [0, max] {
                let rtl = formats::rtl(format, op, stages).unwrap();
                let r = synthesize(&rtl.verilog, TOP, &SynthOptions::default())
                    .expect("yosys synth_xilinx");
                println!(
                    "| {format} | {op} | {stages} | {} | {} | {} | {} | {} |",
                    r.lut, r.ff, r.dsp48e1, r.carry4, r.logic_depth
                );
                if op == Op::Mul && format == HwFormat::FP32 {
                    assert!(r.dsp48e1 <= 3);
                }
            }
        }
    }
}
