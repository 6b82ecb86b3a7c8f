//! The frame engine (`hdl::frame::engine`) through Verilator (`sim::frame_unit`), its
//! traversal unit played by the frame model's: image and counters bit for bit
//! `hw_model::frame::Frame::render`'s, under random answer delays and orders and random
//! back-pressure on the ray and pixel streams; the engine's cycles beside the frame schedule
//! model's (`hw_model::frame::schedule`) for the same frame.

use hdl::frame::{schedule_unit, shader::core};
use hdl::traversal::config::UnitConfig;
use hw_model::frame::schedule::schedule_frame;
use hw_model::frame::{Frame, FrameLimits, WAVEFRONT};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::{TraversalEngine, TraversalModel};
use hw_model::{Format, HwFormat};
use sim::frame_unit::{engine_model, run_frame, EngineConfig, FrameCounts, FrameRun, Traffic};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;
use sw_renderer::trace::PreparedScene;

/// The engine's operators at depth 5 (the shader core's 8 threads), 4,096 triangles.
const DEPTH: usize = 5;
const CONFIG: EngineConfig = EngineConfig {
    depth: DEPTH,
    triangle_bits: 12,
};

/// Answers after 0 to 60 cycles in a random order, stalls on the ray and pixel streams.
const TRAFFIC: Traffic = Traffic {
    ray_stall: 0.2,
    max_delay: 60,
    pixel_stall: 0.3,
    seed: 40,
};

/// Every ray answered the cycle after it is taken, no stalls: the engine's own pace.
const FULL_SPEED: Traffic = Traffic {
    ray_stall: 0.0,
    max_delay: 0,
    pixel_stall: 0.0,
    seed: 0,
};

fn frame_test_scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../hdl/model/tests/frame_scenes")
        .join(format!("{name}.toml"));
    Scene::load(path.to_str().unwrap()).unwrap()
}

/// `scene` at `w`×`h` through the engine (a store of `store` entries), against the model;
/// a line with the cycles, the schedule model's beside them.
fn check(scene: &Scene, w: u32, h: u32, store: Option<usize>, traffic: Traffic) -> FrameRun {
    let prepared = PreparedScene::new(scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = Frame::new(scene, &prepared, &unit, w, h, &FrameLimits::HW).unwrap();
    let want = frame.render(32, WAVEFRONT, &|| {}).unwrap();
    let model = engine_model(&CONFIG).unwrap();
    let run = run_frame(&model, &frame, store, traffic)
        .unwrap_or_else(|e| panic!("{} {w}×{h}: {e}", scene.name));
    let pixels = u64::from(w * h);
    assert_eq!(
        run.counts,
        FrameCounts::of_model(&want.stats, pixels),
        "{} {w}×{h}: the engine's counters, then the model's",
        scene.name
    );
    let differing: Vec<(u32, u32)> = (want.image.enumerate_pixels())
        .filter(|(x, y, p)| run.image.get_pixel(*x, *y) != *p)
        .map(|(x, y, _)| (x, y))
        .take(8)
        .collect();
    assert!(
        differing.is_empty(),
        "{} {w}×{h}: pixels differ from the model's, first {differing:?}",
        scene.name
    );
    let traversal = TraversalModel::new(unit.format, unit.stack_depth, SceneImage::new(&prepared))
        .with_nodes(unit.nodes)
        .unwrap();
    let schedule = schedule_unit(
        UnitConfig::new(HwFormat::FP32, DEPTH, 1).timing(),
        DEPTH,
        store.unwrap_or(512),
        128.min(store.unwrap_or(512) - 1),
        1,
        core::threads(DEPTH),
    );
    let modelled = schedule_frame(
        frame.constants(),
        frame.program(),
        &traversal,
        &schedule,
        &|_| {},
    );
    println!(
        "{} {w}x{h} traffic={} store={} cycles={} schedule_model={} escape_starts={} peak_in_unit={} rays={}",
        scene.name,
        if traffic == FULL_SPEED { "full" } else { "random" },
        store.unwrap_or(512),
        run.cycles,
        modelled.map_or_else(|e| format!("({e})"), |s| s.cycles.to_string()),
        run.escape_starts,
        run.peak_in_unit,
        run.counts.rays.iter().sum::<u64>()
    );
    run
}

/// The 5 frame test scenes and the built-in scenes the 4,096-triangle memory holds (the
/// teapot and All materials do not: load errors naming the sizes).
#[test]
fn test_and_builtin_scenes_equal_the_frame_model() {
    for name in [
        "diffuse_distant",
        "diffuse_point",
        "mirror",
        "glass",
        "phong",
    ] {
        check(&frame_test_scene(name), 16, 9, None, TRAFFIC);
        check(&frame_test_scene(name), 16, 9, None, FULL_SPEED);
    }
    for name in sw_renderer::scene::builtin::names() {
        let scene = Scene::load(name).unwrap();
        let prepared = PreparedScene::new(&scene).unwrap();
        let unit = TraversalEngine::resident(Format::FP32);
        let frame = Frame::new(&scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
        if frame.constants().triangles.len() > 1 << CONFIG.triangle_bits {
            continue;
        }
        check(&scene, 16, 9, None, TRAFFIC);
    }
}

/// The thesis scenes whose triangles the 4,096-entry memory holds.
#[test]
fn small_thesis_scenes_equal_the_frame_model() {
    let Some(root) = thesis_scenes::for_test("frame_engine_verilator::small_thesis_scenes") else {
        return;
    };
    for name in [
        "Simple_plane_scene",
        "Simple_plane2_scene",
        "Glasses_scene",
        "Glasses_point_scene",
    ] {
        let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
        check(&scene, 16, 9, None, TRAFFIC);
        check(&scene, 16, 9, None, FULL_SPEED);
    }
}

/// The least store the escape argument allows (C·D + M + 1 entries) on the glass scene
/// (glass under max depth 5 and a diffuse floor): the escape starts threads below the
/// reserve, and the frame is still the model's.
#[test]
fn the_least_store_escapes_and_equals_the_frame_model() {
    let scene = frame_test_scene("glass");
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = Frame::new(&scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let least = sim::frame_unit::engine_frame(&CONFIG, &frame, Some(512))
        .unwrap()
        .escape_reserve
        + 1;
    let run = check(&scene, 16, 9, Some(least), TRAFFIC);
    assert!(run.escape_starts > 0, "the escape never started a thread");
    let e = sim::frame_unit::engine_frame(&CONFIG, &frame, Some(least - 1)).unwrap_err();
    assert!(e.to_string().contains(&format!("needs {least}")), "{e}");
}
