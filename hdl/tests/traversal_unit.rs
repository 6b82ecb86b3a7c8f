//! The assembled traversal unit in rust-hdl's simulator against `hw_model::traversal`'s
//! model: a random mesh loaded through the scene stream, random rays (closest-hit and any-hit,
//! with t_min and an excluded triangle) streamed in, every answer and the counters equal to
//! the model's. The Verilated unit runs the larger tests (sim/tests/traversal_unit_verilator.rs).

use hdl::traversal::scene_memory_driver::{check_before_load, status_result, LoadStatus};
use hdl::traversal::unit::{
    unit_verilog, with_big_stack, TraversalUnit4x5, UnitConfig, UnitConfigError,
};
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::traversal::packet::{hit_from_words, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::{TraversalModel, UnitCounters, UnitRay};
use hw_model::{Format, HwFormat};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::bvh::Bvh;
use sw_renderer::hit::Hit;
use sw_renderer::math::V3;
use sw_renderer::scene_image::SceneImage;
use sw_renderer::world::WorldTriangle;

const DEPTH: usize = 1;

fn config() -> UnitConfig {
    let mut c = UnitConfig::new(HwFormat::FP32, DEPTH, 1);
    c.memory.node_bits = 4;
    c.memory.triangle_bits = 5;
    c
}

struct Bench {
    uut: Box<TraversalUnit4x5>,
    cycles: u64,
}

impl Bench {
    fn new() -> Self {
        let mut uut = Box::new(TraversalUnit4x5::new(DEPTH, 32));
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

    fn load(&mut self, words: &[u32]) -> LoadStatus {
        self.uut.scene_start.next = true;
        self.cycle();
        self.uut.scene_start.next = false;
        for (i, &w) in words.iter().enumerate() {
            self.uut.scene_tdata.next = u64::from(w).into();
            self.uut.scene_tvalid.next = true;
            self.uut.scene_tlast.next = i + 1 == words.len();
            self.settle();
            assert!(self.uut.scene_tready.val(), "scene word {i} not taken");
            self.cycle();
        }
        self.uut.scene_tvalid.next = false;
        self.cycle();
        self.settle();
        let u = &self.uut;
        LoadStatus {
            loading: false,
            loaded: u.scene_loaded.val(),
            error_code: u.scene_error_code.val().to_u64(),
            error_word: u.scene_error_word.val().to_u64() as u32,
            error_value: u.scene_error_value.val().to_u64() as u32,
            nodes: words[2],
            triangles: words[3],
        }
    }

    /// Streams `rays` in, with the hit stream's `tready` low with chance `stall`, and
    /// returns the answers by id and the counters.
    fn run(
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
            self.uut.ray_tdata.next = data;
            self.uut.ray_tvalid.next = next < rays.len();
            self.uut.hit_tready.next = !rng.gen_bool(stall);
            self.settle();
            let took_ray = self.uut.ray_tvalid.val() && self.uut.ray_tready.val();
            let took_hit = self.uut.hit_tvalid.val() && self.uut.hit_tready.val();
            if took_hit {
                let packet = self.uut.hit_tdata.val();
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
        assert!(!u.overflow.val(), "stack overflow reported");
        let counters = UnitCounters {
            rays: c(u.count_rays.val()),
            node_visits: c(u.count_node_visits.val()),
            box_tests: c(u.count_box_tests.val()),
            mt_tests: c(u.count_mt_tests.val()),
        };
        (answers.into_iter().map(Option::unwrap).collect(), counters)
    }
}

fn mesh(seed: u64, count: usize) -> (Vec<WorldTriangle>, Vec<bool>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut v = || {
        V3::new(
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
        )
    };
    let tris: Vec<WorldTriangle> = (0..count)
        .map(|k| WorldTriangle {
            verts: [v(), v(), v()],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: (k / 3) as u32,
        })
        .collect();
    let casts = tris.iter().map(|t| t.object % 2 == 0).collect();
    (tris, casts)
}

fn rays(seed: u64, count: usize, triangles: u32) -> Vec<UnitRay> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..count)
        .map(|id| {
            let orig = [0; 3].map(|_| rng.gen_range(-9.0f32..9.0));
            let target = [0; 3].map(|_| rng.gen_range(-3.0f32..3.0));
            UnitRay {
                orig,
                dir: std::array::from_fn(|k| target[k] - orig[k]),
                t_max: if rng.gen_bool(0.3) {
                    rng.gen_range(0.0..1.5)
                } else {
                    f32::MAX
                },
                t_min: if rng.gen_bool(0.2) {
                    rng.gen_range(0.0..0.5)
                } else {
                    0.0
                },
                exclude: rng.gen_bool(0.2).then(|| rng.gen_range(0..triangles)),
                any_hit: rng.gen_bool(0.4),
                id: id as u32,
            }
        })
        .collect()
}

#[test]
fn the_unit_answers_and_counts_as_the_model() {
    with_big_stack(answers_and_counts);
}

fn answers_and_counts() {
    let (tris, casts) = mesh(11, 24);
    let words = SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts).to_words();
    let config = config();
    let image = check_before_load(&words, config.memory).unwrap();
    let mut bench = Bench::new();
    let status = bench.load(&words);
    status_result(&status, &words, config.memory).unwrap();
    let rays = rays(3, 40, tris.len() as u32);
    let model = TraversalModel::new(Format::Float { exp: 8, man: 23 }, 32, image);
    let mut want_counters = UnitCounters::default();
    let want: Vec<Option<Hit>> = rays
        .iter()
        .map(|r| model.trace(r, &mut want_counters).unwrap())
        .collect();
    let mut rng = StdRng::seed_from_u64(1);
    let (got, counters) = bench.run(&rays, &mut rng, 0.3);
    let bits =
        |h: &Option<Hit>| h.map(|h| (h.triangle, h.t.to_bits(), h.u.to_bits(), h.v.to_bits()));
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(bits(g), bits(w), "ray {k}: {:?}", rays[k]);
    }
    assert!(
        want.iter().filter(|h| h.is_some()).count() >= 5,
        "too few hits to show anything"
    );
    assert_eq!(counters, want_counters);
    eprintln!("{} rays in {} cycles", rays.len(), bench.cycles);
}

#[test]
fn unsupported_configurations_are_errors() {
    let ok = config();
    assert_eq!(
        unit_verilog(&UnitConfig {
            format: HwFormat::named("fp16"),
            ..ok
        })
        .unwrap_err(),
        UnitConfigError::Format(HwFormat::named("fp16"))
    );
    assert_eq!(
        unit_verilog(&UnitConfig { lanes: 2, ..ok }).unwrap_err(),
        UnitConfigError::Lanes(2)
    );
    assert_eq!(
        unit_verilog(&UnitConfig {
            stack_depth: 33,
            ..ok
        })
        .unwrap_err(),
        UnitConfigError::StackDepth(33)
    );
    let mut odd = ok;
    odd.memory.node_bits = 7;
    assert!(unit_verilog(&odd)
        .unwrap_err()
        .to_string()
        .contains("7 node"));
}

#[test]
fn the_units_verilog_passes_verilator_lint() {
    let verilog = unit_verilog(&config()).unwrap();
    verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS).unwrap();
}
