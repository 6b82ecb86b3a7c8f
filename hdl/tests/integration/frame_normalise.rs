//! The frame unit's normalisation (`hdl::frame::normalise`) in rust-hdl's simulator, bit for
//! bit against `hw_model::fp32::Vec3::normalized`, one vector a cycle, each answered exactly
//! `latency(depth)` cycles later; at depth 0, 1 and the depth where every operator has all
//! its registers. Inputs are fp32 words as the hardware's operators give them (subnormals
//! flushed, NaN canonical: `Fp32::new`), as every vector the frame unit normalises is.

use hdl::formats::fp32;
use hdl::frame::normalise::{latency, normalise_verilog, simulate_normalise};
use hdl::operator::Op;
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
fn normalise_matches_the_model_one_vector_a_cycle() {
    let v = vectors(300);
    let max = [Op::Add, Op::Mul, Op::Recip, Op::Lt, Op::Sqrt]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0);
    for depth in [0, 1, max] {
        let l = latency(depth);
        let out = simulate_normalise(depth, &v, l);
        for (c, &x) in v.iter().enumerate() {
            assert_eq!(
                out[c + l],
                model(x),
                "depth {depth}: normalise({:?}) at cycle {}",
                x.map(f32::from_bits),
                c + l
            );
        }
    }
    // The latency is the operators': two multiplies, two adds, sqrt and recip.
    assert_eq!(latency(0), 0);
    assert_eq!(latency(1), 6);
}

#[test]
fn normalise_verilog_passes_verilator_lint() {
    for depth in [0, 3] {
        if let Err(e) = hdl::verilog::verilator_lint(&normalise_verilog(depth)) {
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
