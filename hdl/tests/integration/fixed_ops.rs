//! The fixed-point operators in rust-hdl's simulator, bit for bit against `hw_model`, for
//! every catalogue fixed format (all six widths, Trn/Wrap and Rnd/Sat each) at 0, a middle
//! and the maximum number of pipeline stages.
//! More vectors: `cargo test --release -p hdl --test integration fixed_ops:: -- --ignored`.
//! Verilator lint of every operator (fixed formats included, through `HwFormat::all()`):
//! `every_operator_passes_verilator_lint` in `float_ops.rs`.

use hdl::formats;
use hdl::operator::{simulate_operator, Op, Operator, OperatorError};
use hdl::synth::{synthesize, SynthOptions};
use hdl::verilog::TOP;
use hw_model::{Format, HwFormat};
use rand::{rngs::StdRng, Rng, SeedableRng};

/// (int, frac) of a fixed format.
fn layout(format: Format) -> (u32, u32) {
    let Format::Fixed { int, frac, .. } = format else {
        panic!("fixed formats only")
    };
    (int, frac)
}

/// The W-bit pattern of the integer `v` (units of 2^-F), wrapped.
fn pattern(format: Format, v: i64) -> u64 {
    (v as u64) & (u64::MAX >> (64 - format.width()))
}

/// Edge-case operands: 0, ±1 LSB, ±2 LSB, max, min and their neighbours, ±1.0, ±0.5 and
/// its neighbours (products that are rounding ties), ±1.5, values whose products or sums
/// overflow, and the reciprocal tie 2^(2F+1) when it is in range.
fn edge_values(format: Format) -> Vec<u64> {
    let (_, frac) = layout(format);
    let w = format.width();
    let max = (1i64 << (w - 1)) - 1;
    let one = 1i64 << frac;
    let half = one / 2;
    let root = 1i64 << ((w - 1 + frac) / 2); // root² ≈ 2·max: products just past the range
    let mut v = vec![
        0,
        1,
        2,
        3,
        max,
        max - 1,
        max / 2 + 1,
        one,
        one + 1,
        one - 1,
        half,
        half + 1,
        half - 1,
        3 * half,
        5,
        root,
        root - 1,
        root + 1,
        1 << (w - 2),
    ];
    if 2 * frac + 1 < w - 1 {
        v.push(1 << (2 * frac + 1));
    }
    let mut all: Vec<u64> = v
        .iter()
        .flat_map(|&x| [pattern(format, x), pattern(format, -x)])
        .collect();
    all.push(pattern(format, -max - 1)); // min
    all.sort_unstable();
    all.dedup();
    all
}

/// Edge × edge pairs, then random pairs: random bits, small magnitudes (large reciprocals),
/// values near the range limits, and x with −x.
fn vectors(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let (_, frac) = layout(format);
    let w = format.width();
    let edges = edge_values(format);
    let mut v: Vec<(u64, u64)> = edges
        .iter()
        .flat_map(|&a| edges.iter().map(move |&b| (a, b)))
        .collect();
    let mut rng = StdRng::seed_from_u64(seed);
    let any = |rng: &mut StdRng| pattern(format, rng.gen::<i64>());
    let small = |rng: &mut StdRng| pattern(format, rng.gen_range(-(4i64 << frac)..(4i64 << frac)));
    let near_limit =
        |rng: &mut StdRng| pattern(format, (1i64 << (w - 1)) - rng.gen_range(0..(1i64 << frac)));
    for i in 0..random {
        let pair = match i % 4 {
            0 => (any(&mut rng), any(&mut rng)),
            1 => (small(&mut rng), any(&mut rng)),
            2 => (near_limit(&mut rng), small(&mut rng)),
            _ => {
                let a = any(&mut rng);
                (a, pattern(format, -format_value(format, a)))
            }
        };
        v.push(pair);
    }
    v
}

/// The signed integer (units of 2^-F) of a W-bit pattern.
fn format_value(format: Format, bits: u64) -> i64 {
    let unused = 64 - format.width();
    ((bits << unused) as i64) >> unused
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

/// fp32 inputs for the conversion to `format`: NaNs, ±Inf, zeros, subnormals, huge and tiny
/// numbers, values just in and out of the range, every edge value and random values plus
/// a quarter, half (a tie) and three quarters of an LSB, and random fp32 bits over the
/// exponents around the format's range.
fn fp32_inputs(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let (int, frac) = layout(format);
    let lsb = (-(frac as f64)).exp2();
    let limit = ((int - 1) as f64).exp2();
    let mut x: Vec<f32> = vec![
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0x7f80_0001),
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        f32::from_bits(1),
        f32::from_bits(0x807f_ffff),
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        1e30,
        -1e30,
        1e-30,
        -1e-30,
        limit as f32,
        -limit as f32,
        (limit - lsb) as f32,
        (-limit - lsb) as f32,
        (limit * 64.0) as f32,
        (-limit * 64.0 - lsb) as f32,
        (limit * 2f64.powi(40)) as f32,
        (lsb / 2.0) as f32,
        (-lsb / 2.0) as f32,
        (lsb / 4.0) as f32,
        (-lsb * 0.75) as f32,
    ];
    let mut rng = StdRng::seed_from_u64(seed);
    for (a, _) in singles(format, random / 4, seed) {
        let v = format.to_f64(a);
        for offset in [0.0, 0.25, 0.5, 0.75, -0.5] {
            x.push((v + offset * lsb) as f32);
        }
    }
    for _ in 0..random {
        let exponent = rng.gen_range(127 - frac as i32 - 30..=127 + int as i32 + 30) as u32;
        x.push(f32::from_bits(
            (rng.gen::<u32>() & 0x807f_ffff) | (exponent << 23),
        ));
    }
    x.into_iter().map(|f| (f.to_bits() as u64, 0)).collect()
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

macro_rules! fixed_tests {
    ($($fmt:ident),*) => {
        $(
            mod $fmt {
                use super::*;
                use hdl::formats::$fmt as format;

                pub fn check_operators(random: usize, seed: u64) {
                    let f = format::FORMAT;
                    let name = format::NAME;
                    let v = vectors(f, random, seed);
                    check::<format::Add>(&format!("{name} add"), &v, |a, b| f.add(a, b));
                    check::<format::Sub>(&format!("{name} sub"), &v, |a, b| f.sub(a, b));
                    check::<format::Mul>(&format!("{name} mul"), &v, |a, b| f.mul(a, b));
                    check::<format::Lt>(&format!("{name} lt"), &v, |a, b| f.lt(a, b) as u64);
                    let u = singles(f, random, seed);
                    check::<format::Recip>(&format!("{name} recip"), &u, |a, _| f.recip(a));
                    check::<format::ToF32>(&format!("{name} to_f32"), &u, |a, _| f.to_f32(a).to_bits() as u64);
                    let x = fp32_inputs(f, random, seed);
                    check::<format::FromF32>(&format!("{name} from_f32"), &x, |a, _| {
                        f.from_f32(f32::from_bits(a as u32))
                    });
                }

                #[test]
                fn operators_match_the_model() {
                    check_operators(120, 1);
                }

                #[test]
                fn module_matches_the_model_catalogue() {
                    assert_eq!(hw_model::catalogue::lookup(format::NAME).unwrap(), format::FORMAT);
                    assert_eq!(format::WIDTH as u32, format::FORMAT.width());
                }
            }
        )*

        /// 20 000 random vectors a format:
        /// `cargo test --release -p hdl --test integration -- --ignored fixed_ops::many_vectors`.
        #[test]
        #[ignore]
        fn fixed_operators_match_the_model_many_vectors() {
            $( $fmt::check_operators(20_000, 2); )*
        }
    };
}

fixed_tests!(
    fx16_10,
    fx16_10_rnd_sat,
    fx16_13,
    fx16_13_rnd_sat,
    fx21_12,
    fx21_12_rnd_sat,
    fx25_10,
    fx25_10_rnd_sat,
    fx32_16,
    fx32_16_rnd_sat,
    fx32_20,
    fx32_20_rnd_sat
);

/// Every fixed format of the catalogue has operators of its widths.
#[test]
fn every_catalogue_fixed_format_has_operators() {
    for h in HwFormat::all() {
        let entry = h.entry();
        if let Format::Fixed { frac, .. } = entry.format {
            let max = formats::max_stages(h, Op::Recip);
            assert_eq!(
                max,
                2 * frac as usize + 3,
                "{}: recip has a cut per division row and 3 more",
                entry.name
            );
            let rtl = formats::rtl(h, Op::FromF32, 1).unwrap();
            assert_eq!(
                (rtl.a_width, rtl.b_width, rtl.y_width, rtl.latency),
                (32, 0, entry.format.width() as usize, 1)
            );
            let rtl = formats::rtl(h, Op::Lt, 0).unwrap();
            assert_eq!(
                (rtl.a_width, rtl.b_width, rtl.y_width),
                (
                    entry.format.width() as usize,
                    entry.format.width() as usize,
                    1
                )
            );
            let too_many = formats::rtl(h, Op::Mul, formats::max_stages(h, Op::Mul) + 1);
            assert!(matches!(too_many, Err(OperatorError::TooManyStages { .. })));
        }
    }
}

/// yosys `synth_xilinx` of the <32,16> multiplier: the 32×32 product must go onto DSP slices.
#[test]
fn fx32_16_mul_synthesises_onto_dsp_slices() {
    for stages in [0, formats::fx32_16::max_stages(Op::Mul)] {
        let rtl = formats::fx32_16::rtl(Op::Mul, stages).unwrap();
        let r =
            synthesize(&rtl.verilog, TOP, &SynthOptions::default()).expect("yosys synth_xilinx");
        eprintln!(
            "fx32_16 mul stages={stages}: {} LUT {} FF {} DSP48E1 {} CARRY4",
            r.lut, r.ff, r.dsp48e1, r.carry4
        );
        assert!(
            (1..=4).contains(&r.dsp48e1),
            "fx32_16 mul uses {} DSP48E1",
            r.dsp48e1
        );
        assert!(
            r.lut < 400,
            "fx32_16 mul uses {} LUTs: the multiplier went into fabric",
            r.lut
        );
    }
}

/// Synthesis report of every operator of <32,16> and <16,10> (both modes) at 0 and max stages:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture fixed_ops::synthesis_table`.
#[test]
#[ignore]
fn synthesis_table() {
    println!("| format | op | stages | LUT | FF | DSP48E1 | CARRY4 | depth |");
    for name in ["fx32_16", "fx32_16_rnd_sat", "fx16_10", "fx16_10_rnd_sat"] {
        let format = HwFormat::named(name);
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
            }
        }
    }
}
