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

/// A rust-hdl bench of the unit type `$unit` (the same ports in every format).
macro_rules! bench {
    ($unit:ty) => {
        use super::*;

        pub struct Bench {
            uut: Box<$unit>,
            cycles: u64,
        }

        impl Bench {
            pub fn new(lanes: usize, advance: Advance) -> Self {
                let mut uut = Box::new(<$unit>::new(DEPTH, 32, lanes, advance));
                uut.connect_all();
                let mut b = Bench { uut, cycles: 0 };
                b.uut.reset_n.next = false;
                for _ in 0..3 {
                    b.cycle();
                }
                b.uut.reset_n.next = true;
                b
            }

            fn cycle(&mut self) {
                self.uut.clock.next = Clock { clk: false };
                assert!(simulate(self.uut.as_mut(), 1000));
                self.uut.clock.next = Clock { clk: true };
                assert!(simulate(self.uut.as_mut(), 1000));
                self.cycles += 1;
            }

            /// Outputs as the next rising edge will see them.
            fn settle(&mut self) {
                self.uut.clock.next = Clock { clk: false };
                assert!(simulate(self.uut.as_mut(), 1000));
            }

            pub fn load(&mut self, words: &[u32]) -> LoadStatus {
                self.uut.control.scene_start.next = true;
                self.cycle();
                self.uut.control.scene_start.next = false;
                for (i, &w) in words.iter().enumerate() {
                    self.uut.scene.tdata.next = u64::from(w).into();
                    self.uut.scene.tvalid.next = true;
                    self.uut.scene.tlast.next = i + 1 == words.len();
                    self.settle();
                    assert!(self.uut.scene.tready.val(), "scene word {i} not taken");
                    self.cycle();
                }
                self.uut.scene.tvalid.next = false;
                self.cycle();
                self.settle();
                let u = &self.uut;
                LoadStatus {
                    loading: false,
                    loaded: u.control.scene_loaded.val(),
                    error_code: u.control.scene_error_code.val().to_u64(),
                    error_word: u.control.scene_error_word.val().to_u64() as u32,
                    error_value: u.control.scene_error_value.val().to_u64() as u32,
                    nodes: words[2],
                    triangles: words[3],
                }
            }

            /// Streams `rays` in, with the hit stream's `tready` low with chance `stall`, and
            /// returns the answers by id and the counters.
            pub fn run(
                &mut self,
                rays: &[UnitRay],
                rng: &mut StdRng,
                stall: f64,
            ) -> (Vec<Option<Hit>>, UnitCounters) {
                let mut answers: Vec<Option<Option<Hit>>> = vec![None; rays.len()];
                let mut next = 0;
                let mut done = 0;
                let mut quiet = 0;
                while done < rays.len() {
                    let mut data = Bits::<{ 32 * RAY_WORDS }>::default();
                    if next < rays.len() {
                        for (k, w) in rays[next].to_words().iter().enumerate() {
                            data = data
                                | (bit_cast::<{ 32 * RAY_WORDS }, 32>(u64::from(*w).into())
                                    << (32 * k) as u64);
                        }
                    }
                    self.uut.ray.tdata.next = data;
                    self.uut.ray.tvalid.next = next < rays.len();
                    self.uut.hit.tready.next = !rng.gen_bool(stall);
                    self.settle();
                    let took_ray = self.uut.ray.tvalid.val() && self.uut.ray.tready.val();
                    let took_hit = self.uut.hit.tvalid.val() && self.uut.hit.tready.val();
                    if took_hit {
                        let packet = self.uut.hit.tdata.val();
                        let words: [u32; HIT_WORDS] =
                            std::array::from_fn(|k| packet.get_bits::<32>(32 * k).to_u64() as u32);
                        let (id, hit) = hit_from_words(&words);
                        let slot = &mut answers[id as usize];
                        assert!(slot.is_none(), "ray {id} answered twice");
                        *slot = Some(hit);
                        done += 1;
                    }
                    self.cycle();
                    if took_ray {
                        next += 1;
                    }
                    quiet = if took_ray || took_hit { 0 } else { quiet + 1 };
                    assert!(
                        quiet < 2000,
                        "the unit hangs: {done} of {} answered",
                        rays.len()
                    );
                }
                self.settle();
                let u = &self.uut;
                let c = |x: Bits<32>| x.to_u64();
                assert!(!u.control.overflow.val(), "stack overflow reported");
                let counters = UnitCounters {
                    rays: c(u.counters.rays.val()),
                    node_visits: c(u.counters.node_visits.val()),
                    box_tests: c(u.counters.box_tests.val()),
                    mt_tests: c(u.counters.mt_tests.val()),
                };
                (answers.into_iter().map(Option::unwrap).collect(), counters)
            }
        }
    };
}

mod fp32_unit {
    bench!(hdl::traversal::unit_top::fp32::Unit4x5);
}

mod fp16_unit {
    bench!(hdl::traversal::unit_top::fp16::Unit4x5);
}

mod e5m14_unit {
    bench!(hdl::traversal::unit_top::e5m14::Unit4x5);
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
    for nodes in [NodeFormat::Bvh2Q8, NodeFormat::Bvh4Q8, NodeFormat::Bvh8Q8] {
        let e = unit_verilog(&UnitConfig { nodes, ..ok }).unwrap_err();
        assert_eq!(e, UnitConfigError::Nodes(nodes));
        assert!(e.to_string().contains(nodes.name()), "{e}");
    }
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
