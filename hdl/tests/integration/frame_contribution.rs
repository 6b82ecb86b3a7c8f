//! The frame unit's contribution conversion (`hdl::frame::contribution`) in rust-hdl's
//! simulator, bit for bit against `hw_model::frame::accumulate::Contribution::of`, at depth
//! 0, 1 and the depth where both operators have all their registers: zeros, subnormals, NaNs
//! (canonical or not), infinities, every colour whose 255·c lands on or next to an integer k
//! in 0..=256, values at and around the saturation at ±2048 steps and around a unit of
//! 2^-16, then random words; one colour a cycle, each answer exactly `latency(depth)` cycles
//! after its input and nothing valid in between. Inputs are raw fp32 words (subnormals and
//! NaN payloads as they come); the model reads them with `Fp32::new`. Verilator's lint.

use crate::common::{fp32_edge_words, print_critical_path};
use hdl::frame::contribution::{
    contribution_verilog, full_depth, latency, simulate_contribution, CONTRIBUTION_BITS,
};
use hw_model::fp32::Vec3;
use hw_model::frame::accumulate::{Contribution, CONTRIBUTION, FRACTION_BITS};
use rand::{rngs::StdRng, Rng, SeedableRng};

fn model(c: [u32; 3]) -> Contribution {
    Contribution::of(Vec3::of(c.map(f32::from_bits)))
}

/// The edge words, one channel's worth each.
fn edge_words() -> Vec<u32> {
    let mut words = fp32_edge_words();
    let around = |words: &mut Vec<u32>, c: f32| {
        words.extend([c.next_down(), c, c.next_up()].map(f32::to_bits));
    };
    // 255·c on and next to every integer k of an 8-bit channel and one past it.
    for k in 0..=256u32 {
        around(&mut words, k as f32 / 255.0);
    }
    // The saturation: v at ±2048 steps (the format's range) and just inside it, and beyond.
    let range = (1u32 << (CONTRIBUTION.width() - 1 - FRACTION_BITS)) as f32;
    for v in [
        range,
        -range,
        range - 1.0,
        -range + 1.0,
        2.0 * range,
        -2.0 * range,
    ] {
        around(&mut words, v / 255.0);
    }
    around(&mut words, 1e30);
    around(&mut words, -1e30);
    // v around one and a few units of 2^-16, positive and negative (truncation toward −∞).
    for n in [1.0, 1.5, 2.0, 3.0] {
        let unit = n * 2f32.powi(-(FRACTION_BITS as i32));
        around(&mut words, unit / 255.0);
        around(&mut words, -unit / 255.0);
    }
    words
}

/// Colours of the edge words, each word once in every channel, then `random` random ones:
/// raw words (any exponent), colours in [0, 1.1) and values in (−9, 9).
fn colours(random: usize, seed: u64) -> Vec<[u32; 3]> {
    let words = edge_words();
    let n = words.len();
    let edges = (0..n).map(|i| [words[i], words[(i + 1) % n], words[(i + 2) % n]]);
    let mut rng = StdRng::seed_from_u64(seed);
    let randoms: Vec<[u32; 3]> = (0..random)
        .map(|i| {
            std::array::from_fn(|_| match i % 3 {
                0 => rng.gen(),
                1 => rng.gen_range(0.0f32..1.1).to_bits(),
                _ => rng.gen_range(-9.0f32..9.0).to_bits(),
            })
        })
        .collect();
    edges.chain(randoms).collect()
}

/// Runs `colours` through the block at `depth`, one a cycle; gaps (no valid input) after
/// every `gap`-th colour if given. Every contribution is the model's, shown exactly
/// `latency(depth)` cycles after its colour, and no cycle shows one without a colour then.
fn check(depth: usize, colours: &[[u32; 3]], gap: Option<usize>) {
    let mut inputs = Vec::new();
    for (n, &c) in colours.iter().enumerate() {
        inputs.push(Some(c));
        if gap.is_some_and(|g| n % g == g - 1) {
            inputs.push(None);
        }
    }
    let l = latency(depth);
    let out = simulate_contribution(depth, &inputs, l);
    assert_eq!(out.len(), inputs.len() + l);
    for (c, shown) in out.iter().enumerate() {
        let want = c.checked_sub(l).and_then(|i| inputs[i]).map(model);
        assert_eq!(
            *shown,
            want,
            "depth {depth}, cycle {c}: input {:?}",
            c.checked_sub(l)
                .and_then(|i| inputs[i])
                .map(|w| w.map(f32::from_bits))
        );
    }
}

#[test]
fn contribution_matches_the_model_one_colour_a_cycle() {
    let colours = colours(1_000, 40);
    // The edge colours reach both ends of the format, 0 and every integer step to 256.
    let values: Vec<i32> = colours.iter().flat_map(|&c| model(c).0).collect();
    let most = (1i32 << (CONTRIBUTION_BITS - 1)) - 1;
    for v in [-most - 1, most, 0, -1, 1] {
        assert!(values.contains(&v), "no channel at {v}");
    }
    for k in 0..=256 {
        assert!(
            values.contains(&(k << FRACTION_BITS)),
            "no channel at {k} steps"
        );
    }
    for depth in [0, 1, full_depth()] {
        check(depth, &colours, None);
    }
    check(1, &colours[..200], Some(7));
    // The latency is the operators': a multiply and a conversion.
    assert_eq!(latency(0), 0);
    assert_eq!(latency(1), 2);
    assert_eq!(latency(full_depth() + 3), latency(full_depth()));
}

#[test]
fn contribution_verilog_passes_verilator_lint() {
    for depth in [0, full_depth()] {
        if let Err(e) = hdl::verilog::verilator_lint(&contribution_verilog(depth)) {
            panic!("contribution depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// 30,000 random colours at every depth up to the full one, with and without gaps:
/// `cargo test --release -p hdl --test integration -- --ignored
/// frame_contribution::contribution_random_words`.
#[test]
#[ignore]
fn contribution_random_words() {
    for depth in 0..=full_depth() {
        let colours = colours(30_000, 100 + depth as u64);
        check(depth, &colours, None);
        check(depth, &colours[..5_000], Some(3));
    }
}

/// yosys `synth_xilinx` of the conversion at the full depth (slow):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// frame_contribution::contribution_synthesis`.
#[test]
#[ignore]
fn contribution_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    let depth = full_depth();
    let r = synthesize(
        &contribution_verilog(depth),
        "top",
        &SynthOptions::default(),
    )
    .expect("yosys synth_xilinx");
    println!(
        "| depth | latency | LUT | FF | SRL | DSP48E1 | CARRY4 | logic depth | Fmax estimate |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {depth} | {} | {} | {} | {} | {} | {} | {} | {} |",
        latency(depth),
        r.lut,
        r.ff,
        r.srl,
        r.dsp48e1,
        r.carry4,
        r.logic_depth,
        r.fmax_mhz_estimate()
            .map_or("–".into(), |f| format!("{f:.0} MHz"))
    );
    print_critical_path(&r);
}
