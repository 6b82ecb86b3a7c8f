//! The assembled traversal unit in rust-hdl's simulator against `hw_model::traversal`'s
//! model: a random mesh loaded through the scene stream, random rays (closest-hit and any-hit,
//! with t_min and an excluded triangle) streamed in, every answer and the counters equal to
//! the model's. The Verilated unit runs the larger tests (sim/tests/integration/traversal_unit_verilator.rs).

use hdl::top::with_build_stack;
use hdl::traversal::config::{unit_verilog, UnitConfig, UnitConfigError, MAX_LANES};
use hdl::traversal::scene_memory::zynq_address_bits;
use hdl::traversal::scene_memory_driver::{check_before_load, status_result, LoadStatus};
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::traversal::packet::{hit_from_words, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::wide::NodeFormat;
use hw_model::traversal::{TraversalModel, UnitCounters, UnitRay};
use hw_model::{Advance, Format, HwFormat};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use rust_hdl::prelude::*;
use sw_renderer::bvh::Bvh;
use sw_renderer::hit::Hit;

use crate::common::{mesh, rays};

const DEPTH: usize = 1;

fn config() -> UnitConfig {
    config_with(1)
}

fn config_with(lanes: usize) -> UnitConfig {
    let mut c = UnitConfig::new(HwFormat::FP32, DEPTH, lanes);
    c.memory.node_bits = 4;
    c.memory.triangle_bits = 5;
    c
}

mod fp32_unit {
    unit_bench!(hdl::traversal::unit_top::fp32::Unit4x5, |lanes, advance| {
        <hdl::traversal::unit_top::fp32::Unit4x5>::new(DEPTH, 32, lanes, advance)
    });
}

mod fp16_unit {
    unit_bench!(hdl::traversal::unit_top::fp16::Unit4x5, |lanes, advance| {
        <hdl::traversal::unit_top::fp16::Unit4x5>::new(DEPTH, 32, lanes, advance)
    });
}

mod e5m14_unit {
    unit_bench!(
        hdl::traversal::unit_top::e5m14::Unit4x5,
        |lanes, advance| {
            <hdl::traversal::unit_top::e5m14::Unit4x5>::new(DEPTH, 32, lanes, advance)
        }
    );
}

/// The fp32 unit with `lanes` lanes: answers and counters equal the model's, with
/// back-pressure on the hits.
fn fp32_unit_answers_and_counts_as_the_model(lanes: usize) {
    with_build_stack(move || {
        let (load, run) = (fp32_unit::Bench::load, fp32_unit::Bench::run);
        let bench = fp32_unit::Bench::new(lanes, Advance::None);
        answers_and_counts(Format::FP32, lanes, Advance::None, bench, load, run)
    });
}

#[test]
fn the_fp32_unit_answers_and_counts_as_the_model() {
    fp32_unit_answers_and_counts_as_the_model(1);
}

/// Two lanes: the slots split between two leaf ports, triangle reads and hit updates.
#[test]
fn the_two_lane_fp32_unit_answers_and_counts_as_the_model() {
    fp32_unit_answers_and_counts_as_the_model(2);
}

/// Three lanes (a second triangle memory copy; 32 slots do not divide by 3). Verilated by
/// default in sim/tests/integration/traversal_unit_verilator.rs; here `-- --ignored`.
#[test]
#[ignore]
fn the_three_lane_fp32_unit_answers_and_counts_as_the_model() {
    fp32_unit_answers_and_counts_as_the_model(3);
}

/// fp16 through the unit: the lane's format changes the answers, the unit still equals the
/// model in that format (unscaled).
#[test]
fn the_fp16_unit_answers_and_counts_as_the_model() {
    with_build_stack(|| {
        let (load, run) = (fp16_unit::Bench::load, fp16_unit::Bench::run);
        let bench = fp16_unit::Bench::new(1, Advance::None);
        answers_and_counts(FP16, 1, Advance::None, bench, load, run)
    });
}

/// The leaf advance in fp16 (`--advance leaf-box`): each leaf's queries moved to the leaf's
/// entry distance from the box test, the lane's t moved back; answers and counters equal
/// the model's `advanced(LeafBox)`, and differ from the unadvanced lane's somewhere.
#[test]
fn the_fp16_unit_with_the_leaf_advance_answers_and_counts_as_the_model() {
    with_build_stack(|| {
        let (load, run) = (fp16_unit::Bench::load, fp16_unit::Bench::run);
        let bench = fp16_unit::Bench::new(1, Advance::LeafBox);
        answers_and_counts(FP16, 1, Advance::LeafBox, bench, load, run)
    });
}

/// e5m14 with the leaf advance: the 20-bit catalogue format this advance takes past 40 dB on
/// the thesis scenes (docs/precision.md), the unit its yosys figures are for.
#[test]
fn the_e5m14_unit_with_the_leaf_advance_answers_and_counts_as_the_model() {
    with_build_stack(|| {
        let (load, run) = (e5m14_unit::Bench::load, e5m14_unit::Bench::run);
        let bench = e5m14_unit::Bench::new(1, Advance::LeafBox);
        let format = HwFormat::named("e5m14").format();
        answers_and_counts(format, 1, Advance::LeafBox, bench, load, run)
    });
}

const FP16: Format = Format::Float { exp: 5, man: 10 };

type Answers = (Vec<Option<Hit>>, UnitCounters);

fn answers_and_counts<B>(
    format: Format,
    lanes: usize,
    advance: Advance,
    mut bench: B,
    load: fn(&mut B, &[u32]) -> LoadStatus,
    run: fn(&mut B, &[UnitRay], &mut StdRng, f64) -> Answers,
) {
    let (tris, casts) = mesh(11, 24);
    let words = SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts).to_words();
    let config = config_with(lanes);
    let image = check_before_load(&words, config.memory).unwrap();
    let status = load(&mut bench, &words);
    status_result(&status, &words, config.memory).unwrap();
    let rays = rays(3, 40, tris.len() as u32);
    let model = TraversalModel::new(format, 32, image).advanced(advance);
    let mut want_counters = UnitCounters::default();
    let want: Vec<Option<Hit>> = (rays.iter())
        .map(|r| model.trace(r, &mut want_counters).unwrap())
        .collect();
    let mut rng = StdRng::seed_from_u64(1);
    let (got, counters) = run(&mut bench, &rays, &mut rng, 0.3);
    let bits =
        |h: &Option<Hit>| h.map(|h| (h.triangle, h.t.to_bits(), h.u.to_bits(), h.v.to_bits()));
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(bits(g), bits(w), "ray {k}: {:?}", rays[k]);
    }
    let hits = want.iter().filter(|h| h.is_some()).count();
    assert!(hits >= 5, "{hits} hits are too few to show anything");
    assert_eq!(counters, want_counters);
    // The format and the advance each change some answer, so the test shows them.
    let differs_from = |other: TraversalModel| {
        (rays.iter().zip(&want))
            .any(|(r, w)| bits(&other.trace(r, &mut UnitCounters::default()).unwrap()) != bits(w))
    };
    if format != Format::FP32 {
        let fp32 = TraversalModel::new(Format::FP32, 32, model.image().clone());
        assert!(
            differs_from(fp32),
            "{format} answered every ray as fp32: the lane's format is not shown"
        );
    }
    if advance != Advance::None {
        let plain = TraversalModel::new(format, 32, model.image().clone());
        assert!(
            differs_from(plain),
            "{format} answered every ray as without the advance: it is not shown"
        );
    }
}

#[test]
fn unsupported_configurations_are_errors() {
    let ok = config();
    for lanes in [0, MAX_LANES + 1] {
        let e = unit_verilog(&UnitConfig { lanes, ..ok }).unwrap_err();
        assert_eq!(e, UnitConfigError::Lanes(lanes));
        assert!(
            e.to_string()
                .contains(&format!("{lanes} Möller-Trumbore lanes"))
                && e.to_string().contains(&format!("1 to {MAX_LANES}")),
            "{e}"
        );
    }
    assert_eq!(
        unit_verilog(&UnitConfig {
            stack_depth: 33,
            ..ok
        })
        .unwrap_err(),
        UnitConfigError::StackDepth(33)
    );
    let e = unit_verilog(&ok.with_nodes(NodeFormat::Bvh2Q8)).unwrap_err();
    assert_eq!(e, UnitConfigError::Nodes(NodeFormat::Bvh2Q8));
    assert!(e.to_string().contains("not bvh2-q8"), "{e}");
    // Wide nodes need the wide unit's 64 slots, the binary ones 32.
    let e = unit_verilog(&UnitConfig {
        nodes: NodeFormat::Bvh8Q8,
        ..ok
    })
    .unwrap_err();
    assert_eq!(
        e,
        UnitConfigError::Slots {
            nodes: NodeFormat::Bvh8Q8,
            slots: 32
        }
    );
    assert!(
        e.to_string()
            .contains("bvh8-q8 nodes has 64 ray slots, not 32"),
        "{e}"
    );
    let e = unit_verilog(&UnitConfig { slots: 64, ..ok }).unwrap_err();
    assert!(
        e.to_string()
            .contains("bvh2-fp32 nodes has 32 ray slots, not 64"),
        "{e}"
    );
    // 4-wide nodes are built with the small test memory only.
    let e = unit_verilog(&config().with_nodes(NodeFormat::Bvh4Q8)).unwrap_err();
    assert!(
        e.to_string()
            .contains("11 node and 13 triangle address bits")
            && e.to_string().contains("for bvh4-q8 nodes (sizes: 4/5)"),
        "{e}"
    );
    let triangle_box = UnitConfig {
        advance: Advance::TriangleBox,
        ..ok
    };
    let e = unit_verilog(&triangle_box).unwrap_err();
    assert_eq!(e, UnitConfigError::Advance(Advance::TriangleBox));
    assert!(e.to_string().contains("not triangle-box"), "{e}");
    let mut odd = ok;
    odd.memory.node_bits = 7;
    assert!(unit_verilog(&odd)
        .unwrap_err()
        .to_string()
        .contains("7 node"));
}

#[test]
fn the_units_verilog_passes_verilator_lint() {
    // A Verilator process a unit, one a core: the widest alone is most of the test's time.
    [
        (HwFormat::FP32, 1),
        (HwFormat::named("fx32_16"), 1),
        // Every lane-dependent part is in the widest unit (2 lanes are Verilated in sim).
        (HwFormat::FP32, MAX_LANES),
    ]
    .into_par_iter()
    .for_each(|(format, lanes)| {
        let verilog = unit_verilog(&UnitConfig {
            format,
            ..config_with(lanes)
        })
        .unwrap();
        verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS)
            .unwrap_or_else(|e| panic!("{format}, {lanes} lanes: {e}"));
    });
}

/// yosys resources of the unit (fp32, depth 5, `lanes` lanes) with the scene memory of
/// `(node_bits, triangle_bits)` address bits.
fn unit_resources(lanes: usize, memories: &[(usize, usize)]) {
    let designs: Vec<(String, String)> = memories
        .iter()
        .map(|&(node_bits, triangle_bits)| {
            let mut c = UnitConfig::new(HwFormat::FP32, 5, lanes);
            c.memory.node_bits = node_bits;
            c.memory.triangle_bits = triangle_bits;
            (
                format!("unit fp32 d5, {lanes} lanes, {node_bits}/{triangle_bits} memory"),
                unit_verilog(&c).unwrap(),
            )
        })
        .collect();
    println!("{}", hdl::synth::markdown_table(&designs).unwrap());
}

/// The scene memory beside one lane on the XC7Z020 (each design takes 35–60 min here):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// traversal_unit::unit_resources_zynq`.
#[test]
#[ignore]
fn unit_resources_zynq() {
    unit_resources(1, &[zynq_address_bits(1)]);
}

/// Two lanes beside their memory: `… --ignored --nocapture unit_resources_zynq_2_lanes`.
#[test]
#[ignore]
fn unit_resources_zynq_2_lanes() {
    unit_resources(2, &[zynq_address_bits(2)]);
}

/// Three lanes beside their memory: `… --ignored --nocapture unit_resources_zynq_3_lanes`.
#[test]
#[ignore]
fn unit_resources_zynq_3_lanes() {
    unit_resources(3, &[zynq_address_bits(3)]);
}

/// A small scene memory, to tell the logic from the block RAM: `… unit_resources_small`.
#[test]
#[ignore]
fn unit_resources_small() {
    unit_resources(1, &[(9, 10)]);
}
