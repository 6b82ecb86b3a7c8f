//! The float square root (`hdl::float::FloatSqrt`) in rust-hdl's simulator, bit for bit
//! against `hw_model`'s `FloatFormat::sqrt`, at 0, 1 and the maximum number of pipeline
//! stages: the edge values, random operands at both exponent parities (odd and even exponent
//! fields take different radicand alignments), every fp16 and bf16 pattern at max stages.

use hdl::formats::{self, bf16, e5m14, fp16, fp24, fp32};
use hdl::operator::{simulate_operator, Op, Operator, OperatorError};
use hdl::synth::{synthesize, SynthOptions};
use hdl::verilog::TOP;
use hw_model::{Format, HwFormat};
use rand::{rngs::StdRng, Rng, SeedableRng};

use crate::float_ops::edge_values;

/// The edge values, then `random` operands of either sign whose exponent fields alternate
/// between odd and even (the smallest and largest normal binades among them).
fn operands(format: Format, random: usize, seed: u64) -> Vec<(u64, u64)> {
    let Format::Float { exp, man } = format else {
        panic!("float formats only")
    };
    let top = (1u64 << exp) - 2;
    let mut rng = StdRng::seed_from_u64(seed);
    let randoms = (0..random).map(move |i| {
        let field = match i % 8 {
            0 => 1 + (i as u64 / 8) % 2,
            1 => top - (i as u64 / 8) % 2,
            _ => rng.gen_range(1..=top),
        };
        // Odd, then even, then odd… exponent fields.
        let field = if (field % 2 == 1) == (i % 2 == 0) {
            field
        } else if field > 1 {
            field - 1
        } else {
            field + 1
        };
        let sign = if i % 7 == 0 { 1u64 << (exp + man) } else { 0 };
        sign | field << man | (rng.gen::<u64>() & ((1 << man) - 1))
    });
    edge_values(format)
        .into_iter()
        .chain(randoms)
        .map(|a| (a, 0))
        .collect()
}

fn check<T: Operator>(what: &str, format: Format, vectors: &[(u64, u64)], stage_list: &[usize]) {
    for &stages in stage_list {
        let out = simulate_operator::<T>(stages, vectors);
        for (&(a, _), &y) in vectors.iter().zip(&out) {
            let want = format.sqrt(a).expect("a float format");
            assert_eq!(
                y, want,
                "{what} stages={stages}: sqrt({a:#x}) gave {y:#x}, model {want:#x}"
            );
        }
    }
}

macro_rules! sqrt_tests {
    ($($fmt:ident: $random:literal),*) => {
        /// Every catalogue float format at 0, 1 and max stages.
        #[test]
        fn sqrt_matches_the_model_in_every_float_format() {
            $(
                let f = $fmt::FORMAT;
                let v = operands(f, $random, 40);
                let stages = [0, 1, $fmt::max_stages(Op::Sqrt)];
                check::<$fmt::Sqrt>(concat!(stringify!($fmt), " sqrt"), f, &v, &stages);
            )*
        }
    };
}

sqrt_tests!(fp32: 2000, fp24: 500, bf16: 300, fp16: 300, e5m14: 300);

/// Every half-precision pattern (every fraction at every exponent, both signs, the
/// specials) at max stages: the rows' widths are exercised at every radicand.
#[test]
fn sqrt_of_every_half_precision_input_matches_the_model() {
    let all: Vec<(u64, u64)> = (0..1u64 << 16).map(|a| (a, 0)).collect();
    check::<bf16::Sqrt>(
        "bf16 sqrt",
        bf16::FORMAT,
        &all,
        &[bf16::max_stages(Op::Sqrt)],
    );
    check::<fp16::Sqrt>(
        "fp16 sqrt",
        fp16::FORMAT,
        &all,
        &[fp16::max_stages(Op::Sqrt)],
    );
}

/// The square root's Verilog passes Verilator's lint in every float format at 0 and max
/// stages; a fixed-point format has none, and says so.
#[test]
fn sqrt_rtl_lints_and_fixed_point_formats_refuse_it() {
    for format in HwFormat::all() {
        let max = formats::max_stages(format, Op::Sqrt);
        if !matches!(format.format(), Format::Float { .. }) {
            assert_eq!(max, 0);
            assert!(matches!(
                formats::rtl(format, Op::Sqrt, 0),
                Err(OperatorError::NotInFormat { .. })
            ));
            continue;
        }
        for stages in [0, max] {
            let rtl = formats::rtl(format, Op::Sqrt, stages).unwrap();
            assert_eq!(rtl.latency, stages);
            if let Err(e) = hdl::verilog::verilator_lint(&rtl.verilog) {
                panic!("{format} sqrt stages={stages}: verilator lint failed:\n{e}");
            }
        }
        assert!(matches!(
            formats::rtl(format, Op::Sqrt, max + 1),
            Err(OperatorError::TooManyStages { .. })
        ));
    }
    assert_eq!("sqrt".parse::<Op>(), Ok(Op::Sqrt));
    assert_eq!(fp32::max_stages(Op::Sqrt), 23 + 6);
}

/// yosys `synth_xilinx` of the fp32 square root at a spread of stages from 0 to the maximum
/// (slow, a few minutes): `cargo test --release -p hdl --test integration -- --ignored
/// --nocapture float_sqrt::sqrt_synthesis_table`. One operator alone: `rtfpga synth --format
/// fp32 --op sqrt --stages N`.
#[test]
#[ignore]
fn sqrt_synthesis_table() {
    let max = fp32::max_stages(Op::Sqrt);
    println!("| stages | LUT | FF | DSP48E1 | CARRY4 | logic depth |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for stages in [0, 1, 2, 3, 5, 7, 10, 15, max] {
        let rtl = fp32::rtl(Op::Sqrt, stages).unwrap();
        let r =
            synthesize(&rtl.verilog, TOP, &SynthOptions::default()).expect("yosys synth_xilinx");
        println!(
            "| {stages} | {} | {} | {} | {} | {} |",
            r.lut, r.ff, r.dsp48e1, r.carry4, r.logic_depth
        );
    }
}
