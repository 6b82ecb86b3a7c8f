//! The wide box stage (`hdl::traversal::wide`) in rust-hdl's simulator, bit for bit against
//! `hw_model::traversal::wide::box_test::wide_box_test`, one node test a cycle with bubbles,
//! for every node width at depth 1 and at the maximum: every output cycle is the model's
//! answer to the input `latency(depth)` cycles earlier, and not to the one a cycle before or
//! after it. Then its Verilog through Verilator's lint, its DSP plane through yosys, and
//! (ignored, slow: one synthesis a test) its yosys resources:
//! `cargo test --release -p hdl --test integration -- --ignored --nocapture wide_box_stage::resources_8_children_depth_5`.

use hdl::synth::{synthesize, SynthOptions};
use hdl::traversal::wide::ones::Ones;
use hdl::traversal::wide::pad_in_t::{simulate_pad_in_t, PadInT, PadInput};
use hdl::traversal::wide::plane::Plane;
use hdl::traversal::wide::{
    latency, max_depth, schedule, simulate_wide_box_stage, wide_box_stage_verilog, WideInput,
    WideOutput,
};
use hw_model::traversal::box_test::ray_setup;
use hw_model::traversal::wide::box_test::WideRay;
use hw_model::traversal::wide::cases::random_test;
use hw_model::traversal::wide::WIDTHS;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

/// Idle cycles before the tests.
const LEAD: usize = 3;

/// Three idle cycles, then `n` node tests of up to `width` children with `valid` low every
/// seventh cycle and a counting tag.
fn inputs(width: usize, n: usize, seed: u64) -> Vec<WideInput> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..LEAD)
        .map(|_| WideInput::idle())
        .chain((0..n).map(|i| {
            let t = random_test(&mut rng, width);
            WideInput {
                valid: i % 7 != 6,
                tag: (i as u16).wrapping_mul(0x9E37) ^ 0x5A5A,
                ray: t.ray,
                node: t.node,
                at: t.at,
            }
        }))
        .collect()
}

/// The output cycles that are not the model's answer to the input `read` cycles earlier
/// (valid, tag, and for a valid test the entered children), with the first one described.
fn mismatches(out: &[WideOutput], inputs: &[WideInput], read: usize) -> (usize, String) {
    let mut count = 0;
    let mut first = String::new();
    for (cycle, o) in out.iter().enumerate() {
        let x = cycle
            .checked_sub(read)
            .and_then(|c| inputs.get(c))
            .cloned()
            .unwrap_or_else(WideInput::idle);
        let want = if x.valid {
            WideOutput {
                valid: true,
                tag: x.tag,
                entered: WideOutput::of_model(&x),
            }
        } else {
            WideOutput::default()
        };
        let got = if o.valid {
            o.clone()
        } else {
            WideOutput::default()
        };
        if got != want {
            if count == 0 {
                first = format!("cycle {cycle}: {x:?}\n stage {got:?}\n model {want:?}");
            }
            count += 1;
        }
    }
    (count, first)
}

/// Streams `n` tests through the stage of `width` children at `depth` and checks every
/// output cycle; also that the stream had children entered, several in one test, and none.
fn check(width: usize, depth: usize, n: usize, seed: u64) {
    let lat = latency(depth);
    let x = inputs(width, n, seed);
    let out = simulate_wide_box_stage(width, depth, &x, lat + 2);
    let (bad, first) = mismatches(&out, &x, lat);
    assert_eq!(
        bad, 0,
        "width {width} depth {depth} (latency {lat}): {first}"
    );
    for wrong in [lat - 1, lat + 1] {
        assert!(
            mismatches(&out, &x, wrong).0 > n / 4,
            "width {width} depth {depth}: read at {wrong} instead of {lat} passes"
        );
    }
    let answers: Vec<usize> = out
        .iter()
        .filter(|o| o.valid)
        .map(|o| o.entered.len())
        .collect();
    let none = answers.iter().filter(|&&k| k == 0).count();
    let several = answers.iter().filter(|&&k| k >= 2).count();
    eprintln!(
        "width {width} depth {depth} (latency {lat}): {} tests, {none} enter nothing, {several} enter several",
        answers.len()
    );
    assert!(
        none > n / 20 && several > n / 20,
        "{none} none, {several} several of {n}"
    );
}

#[test]
fn wide_stage_matches_the_model_at_depth_1() {
    for (k, &width) in WIDTHS.iter().enumerate() {
        check(width, 1, 1000, 10 + k as u64);
    }
}

#[test]
fn wide_stage_matches_the_model_at_max_depth() {
    for (k, &width) in WIDTHS.iter().enumerate() {
        check(width, max_depth(), 1000, 20 + k as u64);
    }
}

#[test]
fn wide_stage_latency_is_its_blocks_registers() {
    let l: Vec<usize> = (0..=max_depth() + 1).map(latency).collect();
    println!(
        "wide box stage latency at depth 0..={}: {l:?}",
        max_depth() + 1
    );
    assert_eq!(l[0], 0, "a combinational stage");
    assert!(l.windows(2).take(max_depth()).all(|w| w[0] < w[1]), "{l:?}");
    assert_eq!(l[max_depth() + 1], l[max_depth()], "depth beyond max_depth");
    let s = schedule(max_depth());
    assert_eq!(
        s.sub
            + s.mul
            + s.grid
            + s.scaled
            + s.axis
            + s.plane
            + s.code
            + s.fold
            + s.order.max(s.entry)
            + s.select,
        s.latency
    );
}

#[test]
fn wide_stage_verilog_passes_verilator_lint() {
    for &width in &WIDTHS {
        for depth in [0, 1, max_depth()] {
            let v = wide_box_stage_verilog(width, depth);
            let last = 3 * width - 1;
            for port in [
                "valid_in".to_string(),
                "width_exp".into(),
                format!("hi${last}"),
                format!("entry_link${}", width - 1),
                "entered".into(),
            ] {
                assert!(
                    v.contains(&port),
                    "width {width} depth {depth}: no port {port}"
                );
            }
            if let Err(e) = hdl::verilog::verilator_lint(&v) {
                panic!("width {width} depth {depth}: verilator lint failed:\n{e}");
            }
        }
    }
}

/// The carry-save count of the ranks: every byte.
#[test]
fn ones_counts_every_byte() {
    let mut uut = Ones::default();
    uut.connect_all();
    for x in 0..=255u32 {
        uut.x.next = u64::from(x).into();
        assert!(simulate(&mut uut, 100));
        assert_eq!(
            uut.count.val().to_u64(),
            u64::from(x.count_ones()),
            "{x:08b}"
        );
    }
}

/// A plane is one DSP48E1 and nothing else: the multiply, the post-adder on the C port and
/// both register cuts inside it (yosys `synth_xilinx`).
#[test]
fn a_plane_is_one_dsp48e1() {
    let mut plane = Plane::new(Plane::max_stages());
    plane.connect_all();
    let verilog = generate_verilog(&plane);
    let report = match synthesize(&verilog, "top", &SynthOptions::default()) {
        Err(hdl::synth::SynthError::YosysNotFound) => {
            println!("SKIPPED a_plane_is_one_dsp48e1: yosys is not installed");
            return;
        }
        r => r.unwrap(),
    };
    assert_eq!(report.dsp48e1, 1, "{report:?}");
    // The infinity flag (an OR of the code, two flags) and its two flip-flops are all that is
    // left.
    assert!(
        report.lut <= 3 && report.carry4 == 0 && report.ff <= 2,
        "{report:?}"
    );
}

/// yosys xc7 resources and register-to-register logic depth of the stage of `width`
/// children at `depth`, as a Markdown row (docs/wide-nodes.md "The box stage in RTL").
fn resources(width: usize, depth: usize) {
    let design = format!(
        "wide box stage, {width} children, depth {depth} (latency {})",
        latency(depth)
    );
    let verilog = wide_box_stage_verilog(width, depth);
    println!(
        "{}",
        hdl::synth::markdown_table(&[(design, verilog)]).unwrap()
    );
}

/// One synthesis each (minutes apart; run one at a time):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture wide_box_stage::resources_8_children_depth_5`
#[test]
#[ignore]
fn resources_8_children_depth_5() {
    resources(8, 5);
}

#[test]
#[ignore]
fn resources_4_children_depth_5() {
    resources(4, 5);
}

#[test]
#[ignore]
fn resources_8_children_depth_2() {
    resources(8, 2);
}

#[test]
#[ignore]
fn resources_4_children_depth_2() {
    resources(4, 2);
}

/// The wide ray's `pad_t` from the ray setup's words, bit for bit `WideRay::from_setup`, one
/// ray a cycle with bubbles, at depth 0, 1 and the maximum: rays of random origins (far and
/// near the origin) and directions with zero, tiny and huge components (the setup's
/// `±HUGE_SLOPE` reciprocals), negative ones (`|inv_dir|`).
#[test]
fn pad_in_t_is_the_wide_ray_setups() {
    let mut rng = StdRng::seed_from_u64(41);
    let component = |rng: &mut StdRng| -> f32 {
        match rng.gen_range(0..6) {
            0 => 0.0,
            1 => -0.0,
            2 => rng.gen_range(-1e-30..1e-30),
            3 => rng.gen_range(-1e30..1e30),
            _ => rng.gen_range(-10.0..10.0),
        }
    };
    let rays: Vec<WideRay> = (0..400)
        .map(|_| {
            let orig = [0; 3].map(|_| component(&mut rng));
            let dir = [0; 3].map(|_| component(&mut rng));
            WideRay::from_setup(orig, &ray_setup(orig, dir, rng.gen_range(0.0..1e6)))
        })
        .collect();
    let inputs: Vec<PadInput> = (rays.iter().enumerate())
        .map(|(i, r)| PadInput {
            valid: i % 5 != 4,
            pad: r.pad.to_bits(),
            inv_dir: r.inv_dir.map(f32::to_bits),
        })
        .collect();
    for depth in [0, 1, max_depth()] {
        let latency = PadInT::latency(depth);
        let out = simulate_pad_in_t(depth, &inputs, latency + 1);
        for (i, (x, r)) in inputs.iter().zip(&rays).enumerate() {
            let y = out[i + latency];
            assert_eq!(y.valid, x.valid, "depth {depth} ray {i}");
            assert_eq!(
                y.pad_t,
                r.pad_t.map(f32::to_bits),
                "depth {depth} ray {i}: {r:?}"
            );
        }
    }
    let mut block = PadInT::new(max_depth());
    block.connect_all();
    hdl::verilog::verilator_lint(&generate_verilog(&block))
        .unwrap_or_else(|e| panic!("pad in t: {e}"));
}
