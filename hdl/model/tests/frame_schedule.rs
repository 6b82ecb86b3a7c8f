//! The frame schedule model (`hw_model::frame::schedule`): frames whose time can be worked
//! out by hand, the traversal part against the wavefront schedule, every ray shaded once
//! (against the frame engine's counts), more shader cores or ray-store entries never slower,
//! and the errors for impossible units.

use std::path::Path;

use hw_model::frame::raygen::INTERVAL;
use hw_model::frame::schedule::{schedule_frame, FrameSchedule, FrameUnit, ScheduleError, Stage};
use hw_model::frame::shader::ProgramKind;
use hw_model::frame::{Frame, FrameLimits, FrameRay, RayKind, WAVEFRONT};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::schedule::UnitTiming;
use hw_model::traversal::{TraversalEngine, TraversalModel, DEFAULT_STACK_DEPTH};
use hw_model::Format;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

/// A unit like the planned binary one (32 slots, one lane, one box port).
const TIMING: UnitTiming = UnitTiming {
    slots: 32,
    lanes: 1,
    box_ports: 1,
    setup_latency: 20,
    box_latency: 12,
    mt_latency: 40,
    far_latency: 8,
    pop_latency: 3,
};

const UNIT: FrameUnit = FrameUnit {
    traversal: TIMING,
    ray_store: 256,
    spawn_reserve: 64,
    shader_cores: 1,
    threads: 16,
    pixel_slots: 1024,
    raygen_latency: 30,
    raygen_interval: INTERVAL,
    accumulate_latency: 4,
};

fn engine(timing: Option<UnitTiming>) -> TraversalEngine {
    TraversalEngine {
        timing,
        ..TraversalEngine::resident(Format::FP32)
    }
}

fn test_scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/frame_scenes")
        .join(format!("{name}.toml"));
    Scene::load(path.to_str().unwrap()).unwrap()
}

/// `scene` at `width`×`height` on `unit`.
fn timed(
    scene: &Scene,
    width: u32,
    height: u32,
    unit: &FrameUnit,
) -> Result<FrameSchedule, ScheduleError> {
    let prepared = PreparedScene::new(scene).unwrap();
    let traversal = engine(None);
    let frame = Frame::new(
        scene,
        &prepared,
        &traversal,
        width,
        height,
        &FrameLimits::HW,
    )
    .unwrap();
    let model = TraversalModel::new(
        Format::FP32,
        DEFAULT_STACK_DEPTH,
        SceneImage::new(&prepared),
    );
    schedule_frame(frame.constants(), frame.program(), &model, unit, &|_| {})
}

#[test]
fn a_frame_of_misses_is_bound_by_the_shader_issue_or_two_cycles_a_pixel() {
    // No triangles: every walk is empty (the ray's setup, then its answer), every ray runs
    // the 4-instruction miss program and spawns nothing.
    let mut scene = test_scene("diffuse_distant");
    scene.objects.clear();
    let (w, h) = (40, 30);
    let pixels = u64::from(w * h);
    // Latency from a pixel to its finished pixel: ray generation, setup and the answer, the
    // thread's start and its 4 issues T apart, the settle record and the accumulator.
    let latency = |u: &FrameUnit| {
        u.raygen_latency
            + u.traversal.setup_latency
            + 2
            + 4 * u.threads as u64
            + 2
            + u.accumulate_latency
    };
    for (cores, threads) in [(1, 16), (1, 4), (2, 16), (4, 8), (8, 8)] {
        let u = FrameUnit {
            shader_cores: cores,
            threads,
            ..UNIT
        };
        let s = timed(&scene, w, h, &u).unwrap();
        assert_eq!(s.rays, [pixels, 0, 0, 0]);
        assert_eq!(
            s.threads[ProgramKind::Miss.index()].instructions,
            4 * pixels
        );
        assert_eq!(s.traversal.box_busy + s.traversal.mt_busy, 0);
        // A core issues one instruction a cycle; ray generation takes a pixel every
        // `raygen::INTERVAL` cycles, the traversal unit's output one a cycle, the
        // accumulator one record a cycle (an open and a settle per pixel).
        let issue = 4 * pixels / cores as u64;
        let bound = issue.max(2 * pixels).max(u.raygen_interval * pixels);
        assert!(
            s.cycles >= bound && s.cycles <= bound + latency(&u),
            "{cores} cores of {threads} threads: {} cycles, bound {bound} + {}",
            s.cycles,
            latency(&u)
        );
        let busiest = if issue > 2 * pixels {
            Stage::ShaderIssue
        } else {
            Stage::Accumulator
        };
        assert_eq!(s.busiest(), busiest, "{cores} cores: {s:?}");
    }
}

#[test]
fn a_core_with_fewer_threads_ready_than_its_latency_leaves_issue_slots_idle() {
    let mut scene = test_scene("diffuse_distant");
    scene.objects.clear();
    let (w, h) = (32, 16);
    let pixels = u64::from(w * h);
    // Two pixel slots: at most two pixels, so two miss threads, at once; each takes 3·16 + 2
    // cycles of the core.
    let u = FrameUnit {
        pixel_slots: 2,
        ..UNIT
    };
    let two = timed(&scene, w, h, &u).unwrap();
    assert!(two.cycles >= pixels / 2 * (3 * 16 + 2), "{two:?}");
    assert!(
        two.utilisation(Stage::ShaderIssue) <= 2.0 * 4.0 / 50.0,
        "{two:?}"
    );
    let all = timed(&scene, w, h, &UNIT).unwrap();
    assert!(all.utilisation(Stage::ShaderIssue) > 0.9, "{all:?}");
}

#[test]
fn the_traversal_part_alone_is_the_wavefront_schedule() {
    // A diffuse scene without lights: hits spawn nothing, so the traversal unit sees the
    // primary rays in pixel order, one a cycle from cycle 0 (ray generation at a ray a
    // cycle), as the wavefront schedule does when they all wait at its input.
    let mut scene = test_scene("diffuse_distant");
    scene.lights.clear();
    let (w, h) = (24, 16);
    let u = FrameUnit {
        raygen_latency: 0,
        raygen_interval: 1,
        ray_store: 1024,
        spawn_reserve: 0,
        shader_cores: 8,
        ..UNIT
    };
    let s = timed(&scene, w, h, &u).unwrap();
    let prepared = PreparedScene::new(&scene).unwrap();
    let traversal = engine(Some(TIMING));
    let frame = Frame::new(&scene, &prepared, &traversal, w, h, &FrameLimits::HW).unwrap();
    let batch: Vec<FrameRay> = (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| FrameRay::primary(frame.constants(), i, j))
        .collect();
    let wavefront = frame.cast(&batch, &mut Vec::new()).unwrap();
    assert!(wavefront.box_tests > 0 && wavefront.mt_tests > 0);
    assert_eq!(s.traversal.cycles, wavefront.cycles);
    assert_eq!(s.rays, [u64::from(w * h), 0, 0, 0]);
}

#[test]
fn every_ray_is_traced_and_shaded_exactly_once() {
    for name in ["glass", "phong", "diffuse_point"] {
        let scene = test_scene(name);
        let (w, h) = (32, 18);
        let s = timed(&scene, w, h, &UNIT).unwrap();
        let prepared = PreparedScene::new(&scene).unwrap();
        let traversal = engine(None);
        let frame = Frame::new(&scene, &prepared, &traversal, w, h, &FrameLimits::HW).unwrap();
        let stats = frame.render(32, WAVEFRONT, &|| {}).unwrap().stats;
        for (k, kind) in RayKind::ALL.into_iter().enumerate() {
            assert_eq!(s.rays[k], stats.of_kind(kind), "{name}: {kind:?}");
        }
        assert_eq!(s.threads, stats.threads, "{name}");
        let cast = stats.rays() - stats.shadow_rays;
        assert_eq!(s.threads.iter().map(|l| l.threads).sum::<u64>(), cast);
        // One open per pixel, one settle per ray.
        assert_eq!(s.records, s.pixels + stats.rays(), "{name}");
        assert!(s.peak_in_flight <= UNIT.ray_store);
    }
}

#[test]
fn more_shader_cores_or_ray_store_entries_are_never_slower() {
    for name in ["glass", "phong", "mirror"] {
        let scene = test_scene(name);
        let (w, h) = (32, 18);
        let run = |u: FrameUnit| {
            let s = timed(&scene, w, h, &u).unwrap();
            eprintln!(
                "{name} K={} R={}: {} cycles, {}",
                u.shader_cores,
                u.ray_store,
                s.cycles,
                Stage::ALL
                    .map(|st| format!("{}={:.2}", st.name(), s.utilisation(st)))
                    .join(" ")
            );
            s.cycles
        };
        let by_cores: Vec<u64> = (1..=3)
            .map(|k| {
                run(FrameUnit {
                    shader_cores: k,
                    ..UNIT
                })
            })
            .collect();
        let by_store: Vec<u64> = [80, 128, 256, 1024]
            .into_iter()
            .map(|r| {
                run(FrameUnit {
                    ray_store: r,
                    ..UNIT
                })
            })
            .collect();
        assert!(
            by_cores.windows(2).all(|p| p[1] <= p[0]),
            "{name}: {by_cores:?}"
        );
        // Rays are served first come first served, so a larger store may reorder the last
        // pixels' trees: within 1 % (a greedy schedule has no stricter guarantee).
        assert!(
            by_store.windows(2).all(|p| p[1] * 100 <= p[0] * 101),
            "{name}: {by_store:?}"
        );
    }
}

#[test]
fn impossible_units_are_errors_naming_the_sizes() {
    let scene = test_scene("phong");
    let msg = |u: FrameUnit| timed(&scene, 8, 8, &u).unwrap_err().to_string();
    assert_eq!(
        msg(FrameUnit {
            shader_cores: 0,
            ..UNIT
        }),
        "0 shader cores: the frame unit needs at least one"
    );
    assert_eq!(
        msg(FrameUnit { threads: 0, ..UNIT }),
        "shader cores of 0 threads: a core needs at least one"
    );
    assert_eq!(
        msg(FrameUnit {
            pixel_slots: 0,
            ..UNIT
        }),
        "0 pixel slots: the accumulator needs at least one"
    );
    assert_eq!(
        msg(FrameUnit {
            raygen_interval: 0,
            ..UNIT
        }),
        "ray generation every 0 cycles: it needs at least one"
    );
    assert!(msg(FrameUnit {
        traversal: UnitTiming { slots: 0, ..TIMING },
        ..UNIT
    })
    .starts_with("the traversal unit: a unit of 0 ray slots"));
    assert_eq!(
        msg(FrameUnit {
            ray_store: 64,
            ..UNIT
        }),
        "a ray store of 64 entries with a spawn reserve of 64: it needs at least 65"
    );
    // Phong under two lights pushes up to 2 shadow rays; glass 2 reflection or refraction
    // rays, 5 deep.
    assert_eq!(
        msg(FrameUnit {
            spawn_reserve: 1,
            ..UNIT
        }),
        "a spawn reserve of 1 entries: this scene's threads push up to 2 rays, 0 of them reflection or refraction rays, 4 deep, so it needs at least 2 (0·4 + 2)"
    );
    let glass = timed(
        &test_scene("glass"),
        8,
        8,
        &FrameUnit {
            spawn_reserve: 11,
            ..UNIT
        },
    );
    assert_eq!(
        glass.unwrap_err().to_string(),
        "a spawn reserve of 11 entries: this scene's threads push up to 2 rays, 2 of them reflection or refraction rays, 5 deep, so it needs at least 12 (2·5 + 2)"
    );
}

#[test]
fn the_smallest_ray_store_renders_trees_deeper_than_it_is_wide() {
    // The least reserve and store for the glass scene (depth 5, 2 cast pushes): every
    // pixel finishes, every ray shaded once.
    let scene = test_scene("glass");
    let least = FrameUnit {
        ray_store: 13,
        spawn_reserve: 12,
        ..UNIT
    };
    let s = timed(&scene, 32, 18, &least).unwrap();
    let roomy = timed(&scene, 32, 18, &UNIT).unwrap();
    assert_eq!(s.rays, roomy.rays);
    assert!(s.peak_in_flight <= 13 && s.cycles > roomy.cycles, "{s:?}");
}
