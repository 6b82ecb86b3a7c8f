//! The traversal unit walking wide nodes (`--nodes bvh4-q8`, `bvh8-q8`) in rust-hdl's
//! simulator against `hw_model::traversal`'s model walking the same version-3 image: random
//! meshes loaded through the scene stream, random rays (closest-hit and any-hit, with t_min
//! and an excluded triangle) streamed in with back-pressure on the hits, every answer and the
//! counters equal to the model's.

use hdl::top::with_build_stack;
use hdl::traversal::config::{unit_verilog, UnitConfig};
use hdl::traversal::scene_memory_driver::{
    check_before_load_wide, status_result_in, LoadStatus, MemoryConfig, NodeLayout,
};
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::traversal::packet::{hit_from_words, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::wide::image::WideImage;
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
const STACK_DEPTH: usize = 32;
const MEMORY: MemoryConfig = MemoryConfig {
    node_bits: 4,
    triangle_bits: 5,
};

mod fp32_4_wide {
    unit_bench!(
        hdl::traversal::unit_top::fp32::WideUnit4w4x5,
        |lanes, advance| {
            <hdl::traversal::unit_top::fp32::WideUnit4w4x5>::new(
                4,
                DEPTH,
                STACK_DEPTH,
                lanes,
                advance,
            )
        }
    );
}

mod fp32_8_wide {
    unit_bench!(
        hdl::traversal::unit_top::fp32::WideUnit8w4x5,
        |lanes, advance| {
            <hdl::traversal::unit_top::fp32::WideUnit8w4x5>::new(
                8,
                DEPTH,
                STACK_DEPTH,
                lanes,
                advance,
            )
        }
    );
}

type Answers = (Vec<Option<Hit>>, UnitCounters);

/// Meshes of `seeds` as `width`-wide images, each loaded into a fresh unit from `bench` and
/// traced by 40 random rays: answers and counters equal the model's. One mesh a width keeps
/// each test's simulation within `make test`'s budget; the Verilated tests take many more.
fn answers_and_counts<B>(
    width: usize,
    seeds: &[u64],
    bench: impl Fn() -> B,
    load: fn(&mut B, &[u32]) -> LoadStatus,
    run: fn(&mut B, &[UnitRay], &mut StdRng, f64) -> Answers,
) {
    let mut pushes_several = false;
    for &seed in seeds {
        let (tris, casts) = mesh(seed, 24);
        let binary = SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts);
        let words = WideImage::of(&binary, width).unwrap().to_words();
        let image = check_before_load_wide(&words, MEMORY, width).unwrap();
        pushes_several |= image.tree.nodes.iter().any(|n| n.children.len() > 2);
        let mut unit = bench();
        let status = load(&mut unit, &words);
        status_result_in(&status, &words, MEMORY, NodeLayout::Wide(width)).unwrap();
        let rays = rays(seed + 100, 40, tris.len() as u32);
        let model = TraversalModel::new(Format::FP32, STACK_DEPTH, image);
        let mut want_counters = UnitCounters::default();
        let want: Vec<Option<Hit>> = (rays.iter())
            .map(|r| model.trace(r, &mut want_counters).unwrap())
            .collect();
        let mut rng = StdRng::seed_from_u64(seed);
        let (got, counters) = run(&mut unit, &rays, &mut rng, 0.3);
        let bits =
            |h: &Option<Hit>| h.map(|h| (h.triangle, h.t.to_bits(), h.u.to_bits(), h.v.to_bits()));
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            assert_eq!(bits(g), bits(w), "mesh {seed}, ray {k}: {:?}", rays[k]);
        }
        let hits = want.iter().filter(|h| h.is_some()).count();
        assert!(
            hits >= 5,
            "mesh {seed}: {hits} hits are too few to show anything"
        );
        assert_eq!(counters, want_counters, "mesh {seed}");
    }
    assert!(
        pushes_several,
        "no node with more than 2 children: the banked pushes are not shown"
    );
}

#[test]
fn the_4_wide_unit_answers_and_counts_as_the_model() {
    with_build_stack(|| {
        answers_and_counts(
            4,
            &[11],
            || fp32_4_wide::Bench::new(1, Advance::None),
            fp32_4_wide::Bench::load,
            fp32_4_wide::Bench::run,
        )
    });
}

#[test]
fn the_8_wide_unit_answers_and_counts_as_the_model() {
    with_build_stack(|| {
        answers_and_counts(
            8,
            &[13],
            || fp32_8_wide::Bench::new(1, Advance::None),
            fp32_8_wide::Bench::load,
            fp32_8_wide::Bench::run,
        )
    });
}

/// The wide units' Verilog (fp32, 4- and 8-wide with the small memory, 8-wide with the
/// XC7Z020's) passes Verilator's lint.
#[test]
fn the_wide_units_verilog_passes_verilator_lint() {
    let small = |nodes| {
        let mut c = UnitConfig::new(HwFormat::FP32, DEPTH, 1).with_nodes(nodes);
        c.memory = MEMORY;
        c
    };
    [
        small(NodeFormat::Bvh4Q8),
        small(NodeFormat::Bvh8Q8),
        UnitConfig::new(HwFormat::FP32, 5, 1).with_nodes(NodeFormat::Bvh8Q8),
    ]
    .into_par_iter()
    .for_each(|config| {
        let verilog = unit_verilog(&config).unwrap();
        verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS)
            .unwrap_or_else(|e| panic!("{}: {e}", config.nodes.name()));
    });
}
