//! The Verilated dual-precision pair (`sim::dual_pair`: bfp18 or Plücker filter slots
//! sharing an fp32 lane) answers bit for bit as the model's `DualIntersector`, and renders the thesis' 7
//! scenes (found by `sw_renderer::thesis_scenes`; skipped with a `SKIPPED` line on stderr
//! when absent) exactly as fp32 does. The model builds (~2 min each) are cached on disk.

use hdl::dual::pair::SlotFilter;
use hw_model::dual::{DualIntersector, Filter, FormatPair};
use hw_model::{MtQuery, MtResult};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sim::dual_pair::{pair_verilog, PairConfig, PairError, PairIntersector};
use std::path::PathBuf;
use sw_renderer::compare::compare;
use sw_renderer::intersect::{F32Intersector, Intersector};
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;

/// Two slots of either filter before an fp32 lane at depth 1.
const PAIRS: [PairConfig; 2] = [
    PairConfig {
        slots: 2,
        depth: 1,
        filter: SlotFilter::Bfp,
    },
    PairConfig {
        slots: 2,
        depth: 1,
        filter: SlotFilter::Plucker,
    },
];

fn model(pair: &PairConfig) -> DualIntersector {
    let formats = FormatPair::parse("bfp18/fp32").unwrap();
    DualIntersector::with_filter(Filter::new(formats, pair.filter.model_kind()))
}

fn point(rng: &mut StdRng, size: f32) -> [f32; 3] {
    std::array::from_fn(|_| rng.gen_range(-size..size))
}

/// Rays aimed at, near and past triangles of sizes 2^-8 to 2^8, some edge-on, some with a
/// lower bound near the hit, some with non-finite coordinates.
fn queries(n: usize, seed: u64) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let size = 2f32.powi(rng.gen_range(-8..=8));
            let v0 = point(&mut rng, size);
            let edge = |rng: &mut StdRng| std::array::from_fn(|k| v0[k] + point(rng, size)[k]);
            let (v1, v2) = (edge(&mut rng), edge(&mut rng));
            let (a, b) = (rng.gen_range(-0.3..1.3), rng.gen_range(-0.3..1.3));
            let orig = point(&mut rng, 4.0 * size);
            let t_min = [0.0, 0.0, rng.gen_range(0.0..2.0), 1.0][rng.gen_range(0..4)];
            let mut q = MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min);
            match rng.gen_range(0..10) {
                0 => q.dir = std::array::from_fn(|k| v1[k] - v2[k]),
                1 => q.orig[rng.gen_range(0..3)] = f32::NAN,
                2 => q.dir = q.dir.map(|d| -d),
                _ => {}
            }
            q
        })
        .collect()
}

#[test]
fn random_queries_equal_the_model() {
    for pair in &PAIRS {
        random_queries(pair);
    }
}

fn random_queries(pair: &PairConfig) {
    let hw = PairIntersector::new(pair).unwrap();
    let qs = queries(100_000, 7);
    let mut got = vec![MtResult::default(); qs.len()];
    // Batches of several sizes, the last one short.
    for (q, r) in qs.chunks(30_001).zip(got.chunks_mut(30_001)) {
        hw.intersect_batch(q, r).unwrap();
    }
    let model = model(pair);
    let mut want = vec![MtResult::default(); qs.len()];
    model.intersect_batch(&qs, &mut want).unwrap();
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(
            g.same_bits(w),
            "query {i}: {g:?} != model {w:?} for {:?}",
            qs[i]
        );
    }
    let (s, m) = (hw.stats(), model.stats());
    assert_eq!(s.tests, m.tests);
    assert_eq!(s.forwarded, m.forwarded(), "forwarded: hardware and model");
    println!(
        "{}: {} tests, {:.1} % forwarded, {:.3} tests/cycle, {} stall cycles",
        hw.name(),
        s.tests,
        100.0 * s.forwarded_share(),
        s.tests_per_cycle(),
        s.stall_cycles
    );
}

/// The thesis' scenes through the pair: the images are fp32's pixel for pixel, every test
/// the renderer made reached the hardware, and its forwarded count is the model's.
#[test]
fn thesis_scenes_render_as_fp32() {
    let Some(root) = thesis_scenes::for_test("dual_pair_verilator::thesis_scenes_render_as_fp32")
    else {
        return;
    };
    let dirs: Vec<PathBuf> = thesis_scenes::SCENE_DIRS
        .iter()
        .map(|name| root.join(name))
        .collect();
    for pair in &PAIRS {
        render_scenes(pair, &dirs);
    }
}

fn render_scenes(pair: &PairConfig, dirs: &[PathBuf]) {
    let hw = PairIntersector::new(pair).unwrap();
    let opts = RenderOptions {
        width: Some(64),
        height: Some(36),
        ..RenderOptions::default()
    };
    for dir in dirs {
        let scene = Scene::load(dir.to_str().unwrap()).unwrap();
        let (before, model) = (hw.stats(), model(pair));
        let hw_image = render(&scene, &hw, &opts).unwrap().image;
        let modelled = render(&scene, &model, &opts).unwrap();
        let sw = render(&scene, &F32Intersector, &opts).unwrap();
        let diff = compare(&hw_image, &sw.image).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{}: {diff:?}", dir.display());
        assert_eq!(
            compare(&modelled.image, &sw.image)
                .unwrap()
                .differing_pixels,
            0
        );
        let s = hw.stats();
        let m = model.stats();
        assert_eq!(s.tests - before.tests, sw.stats.trace.cast.mt_tests);
        assert_eq!(s.tests - before.tests, m.tests, "{}", dir.display());
        assert_eq!(s.forwarded - before.forwarded, m.forwarded());
        println!(
            "{pair}, {}: {:.1} % forwarded",
            scene.name,
            100.0 * m.forwarded_share()
        );
    }
}

/// A pair of 0 or 6 slots is not built: a clear error, not a panic.
#[test]
fn unbuilt_slot_counts_are_errors() {
    for slots in [0, 6] {
        let err = pair_verilog(&PairConfig { slots, ..PAIRS[0] }).unwrap_err();
        assert!(matches!(err, PairError::Slots(n) if n == slots));
        assert!(err.to_string().contains("1 to 5 filter slots"), "{err}");
    }
}
