//! The frame unit's normalisation (`hdl::frame::normalise`) in rust-hdl's simulator, bit for
//! bit against `hw_model::fp32::Vec3::normalized`, one vector every two cycles (the words in
//! the cycles between, random, ignored), each answered exactly `latency(depth)` cycles
//! later; at depth 0, 1 and the depth where every operator has all its registers. Inputs are fp32 words as the hardware's operators give them (subnormals
//! flushed, NaN canonical: `Fp32::new`), as every vector the frame unit normalises is.

use hdl::formats::fp32;
use hdl::frame::normalise::{latency, normalise_verilog, simulate_normalise};
use hdl::operator::Op;
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::fp32::{Fp32, Vec3};
use rand::{rngs::StdRng, Rng, SeedableRng};

/// Zero, NaN, infinite, subnormal (flushed), huge (n overflows) and tiny (n underflows to 0)
/// vectors, then random ones over a wide range of magnitudes.
fn vectors(random: usize) -> Vec<[u32; 3]> {
    let special: [[f32; 3]; 14] = [
        [0.0, 0.0, 0.0],
        [-0.0, 0.0, -0.0],
        [3.0, 4.0, 0.0],
        [0.0, 0.0, -1.0],
        [f32::NAN, 1.0, 2.0],
        [f32::INFINITY, 1.0, 0.0],
        [1.0, f32::NEG_INFINITY, f32::INFINITY],
        [1e-40, -1e-45, 0.0],
        [1e-40, 1.0, 0.0],
        [3e38, 3e38, 1.0],
        [2e19, -1e19, 5e18],
        [1e-20, 1e-20, -1e-20],
        [1.5e-19, 0.0, 0.0],
        [f32::MAX, 0.0, 0.0],
    ];
    let mut rng = StdRng::seed_from_u64(40);
    let randoms = (0..random).map(|i| {
        let scale = match i % 4 {
            0 => 1.0,
            1 => 2f32.powi(rng.gen_range(-60..60)),
            2 => 2f32.powi(rng.gen_range(-70..-55)),
            _ => 2f32.powi(rng.gen_range(55..66)),
        };
        std::array::from_fn(|_| rng.gen_range(-1.0f32..1.0) * scale)
    });
    special
        .into_iter()
        .chain(randoms)
        .map(|v| v.map(|x| Fp32::new(x).bits()))
        .collect()
}

fn model(v: [u32; 3]) -> [u32; 3] {
    let n = Vec3::new(
        Fp32::from_bits(v[0]),
        Fp32::from_bits(v[1]),
        Fp32::from_bits(v[2]),
    )
    .normalized();
    [n.x.bits(), n.y.bits(), n.z.bits()]
}

#[test]
fn normalise_matches_the_model_a_vector_every_two_cycles() {
    let v = vectors(300);
    let mut rng = StdRng::seed_from_u64(41);
    // Vector k in cycle 2k; random words in the cycles between.
    let inputs: Vec<[u32; 3]> = (v.iter())
        .flat_map(|&x| [x, std::array::from_fn(|_| rng.gen())])
        .collect();
    let max = [Op::Add, Op::Mul, Op::Recip, Op::Lt, Op::Sqrt]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0);
    for depth in [0, 1, 2, max] {
        let l = latency(depth);
        let out = simulate_normalise(depth, &inputs, l + 1);
        for (k, &x) in v.iter().enumerate() {
            assert_eq!(
                out[2 * k + l],
                model(x),
                "depth {depth}: normalise({:?}) at cycle {}",
                x.map(f32::from_bits),
                2 * k + l
            );
        }
    }
    // The operators' latencies (two multiplies, two adds, sqrt and recip), each operator's
    // second use a register later where the cycles since its first are even.
    assert_eq!(latency(0), 1);
    assert_eq!(latency(1), 6);
}

#[test]
fn normalise_verilog_passes_verilator_lint() {
    // UNOPTFLAT waived as for the shader core (`UNIT_VERILATOR_WAIVERS`): a shared adder's
    // or multiplier's output comes back to its input through a register (the second use),
    // which Verilator sees as a loop between always blocks.
    for depth in [0, 3] {
        if let Err(e) = verilator_lint_waiving(&normalise_verilog(depth), UNIT_VERILATOR_WAIVERS) {
            panic!("normalise depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// yosys `synth_xilinx` of the normalisation at depths 1, 4 and the maximum (slow):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// frame_normalise::normalise_synthesis`.
#[test]
#[ignore]
fn normalise_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| depth | latency | LUT | FF | DSP48E1 | CARRY4 | logic depth |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for depth in [1, 4, fp32::max_stages(Op::Sqrt)] {
        let r = synthesize(&normalise_verilog(depth), "top", &SynthOptions::default())
            .expect("yosys synth_xilinx");
        println!(
            "| {depth} | {} | {} | {} | {} | {} | {} |",
            latency(depth),
            r.lut,
            r.ff,
            r.dsp48e1,
            r.carry4,
            r.logic_depth
        );
    }
}
