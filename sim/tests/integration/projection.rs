//! The ZedBoard projection model: its calibration against the thesis' measured times, the
//! workload counts, monotonicity of the cost model, and rejection of bad designs.
//!
//! The calibration renders Simple plane, Simple plane 2 (1080p, 720p) and Utah teapot
//! (1080p, 720p) once; the slow scenes' checks are printed by
//! `rtfpga project --calibration` (docs/projection.md).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use proptest::prelude::*;
use sim::projection::{
    calibrate, project, Board, Calibration, Design, Frontend, Role, Setup, Traversal, UnitWork,
    Workload, Workloads,
};
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;

/// The thesis scenes, or None after a `SKIPPED projection::<test>` line.
fn thesis_dir(test: &str) -> Option<PathBuf> {
    thesis_scenes::for_test(&format!("projection::{test}"))
}

fn calibration(root: &Path) -> &'static Calibration {
    static CAL: OnceLock<Calibration> = OnceLock::new();
    CAL.get_or_init(|| {
        let mut workloads = Workloads::new(root);
        calibrate(&mut workloads, |m| {
            [
                "Simple_plane_scene",
                "Simple_plane2_scene",
                "Utah_teapot_scene",
            ]
            .contains(&m.scene)
        })
        .expect("calibration on the thesis scenes")
    })
}

fn row<'a>(c: &'a Calibration, label: &str) -> &'a sim::projection::CalibrationRow {
    c.rows
        .iter()
        .find(|r| r.measurement.label == label)
        .unwrap_or_else(|| panic!("no row {label}"))
}

#[test]
fn fit_reproduces_its_four_measurements_and_checks_hold_within_25_percent() {
    let Some(root) =
        thesis_dir("fit_reproduces_its_four_measurements_and_checks_hold_within_25_percent")
    else {
        return;
    };
    let c = calibration(&root);
    let fits: Vec<_> = c
        .rows
        .iter()
        .filter(|r| r.measurement.role == Role::Fit)
        .collect();
    assert_eq!(fits.len(), 4, "4 constants from 4 measurements");
    for r in &fits {
        assert!(
            r.error_pct().abs() < 1e-3,
            "{:?}: {:.4}%",
            r.measurement,
            r.error_pct()
        );
    }
    let checks: Vec<_> = c
        .rows
        .iter()
        .filter(|r| r.measurement.role == Role::Check)
        .collect();
    assert!(checks.len() >= 15, "held-out checks: {}", checks.len());
    // Runs 3 and 4 are the thesis' own contradiction (see the next test): left out here.
    for r in checks
        .iter()
        .filter(|r| !["Run 3", "Run 4"].contains(&r.measurement.label))
    {
        assert!(
            r.error_pct().abs() <= 25.0,
            "{} ({}, {} {}x{}): measured {} s, modelled {:.3} s ({:+.1}%)",
            r.measurement.label,
            r.measurement.source,
            r.measurement.scene,
            r.measurement.width,
            r.measurement.height,
            r.measurement.seconds,
            r.modelled_s,
            r.error_pct()
        );
    }
    // The named targets of the issue, closer than the ±25% bound.
    for (label, height, bound) in [("HW baseline", 720, 2.0), ("Run 2", 1080, 2.0)] {
        let r = c
            .rows
            .iter()
            .find(|r| r.measurement.label == label && r.measurement.height == height)
            .expect("row");
        assert!(
            r.error_pct().abs() < bound,
            "{label} {height}p: {:+.2}%",
            r.error_pct()
        );
    }
}

#[test]
fn runs_3_and_6_contradict_each_other_in_the_thesis_data() {
    let Some(root) = thesis_dir("runs_3_and_6_contradict_each_other_in_the_thesis_data") else {
        return;
    };
    // Same fabric clock, nearly the same HLS latency, 50% apart: no model of clock and
    // latency can match both; the model sides with Runs 5, 6 and 7.
    let c = calibration(&root);
    let (r3, r6) = (row(c, "Run 3"), row(c, "Run 6"));
    let (
        Setup::Accelerator {
            fpl_mhz: f3,
            latency: l3,
            ..
        },
        Setup::Accelerator {
            fpl_mhz: f6,
            latency: l6,
            ..
        },
    ) = (r3.measurement.setup, r6.measurement.setup)
    else {
        panic!("Runs 3 and 6 are accelerator runs");
    };
    assert_eq!(f3, f6);
    assert!((l3.1 - l6.1).abs() / l3.1 < 0.05);
    assert!(r3.measurement.seconds / r6.measurement.seconds > 1.4);
    assert!((r3.modelled_s / r6.modelled_s - 1.0).abs() < 0.05);
    assert!(r6.error_pct().abs() < 5.0);
}

#[test]
fn fitted_constants_are_physically_plausible() {
    let Some(root) = thesis_dir("fitted_constants_are_physically_plausible") else {
        return;
    };
    let b = calibration(&root).board;
    for mhz in [100.0, 214.0] {
        let ns = b.access_ns(mhz);
        assert!(
            (10.0..=500.0).contains(&ns),
            "AXI-Lite access at {mhz} MHz: {ns} ns"
        );
    }
    assert!(b.access_fixed_ns >= 0.0, "{b:?}");
    assert!((1.0..=100.0).contains(&b.access_pl_cycles), "{b:?}");
    // A software MT test (a division and ~30 other flops on VFP) is tens to hundreds of cycles.
    let test_cycles = b.arm_test_ns * 0.667;
    assert!((20.0..=500.0).contains(&test_cycles), "{b:?}");
    assert!((50.0..=5000.0).contains(&b.arm_ray_ns), "{b:?}");
}

#[test]
fn thesis_design_matches_the_hand_written_equation() {
    // One unit, latency longer than half an access: 20 accesses, the latency, half a poll.
    let Some(root) = thesis_dir("thesis_design_matches_the_hand_written_equation") else {
        return;
    };
    let c = calibration(&root);
    let b = c.board;
    let mut workloads = Workloads::new(&root);
    let w = workloads
        .get("Simple_plane_scene", 1920, 1080)
        .unwrap()
        .clone();
    let d = Design {
        frontend: Frontend::Thesis {
            units: 1,
            cycles_per_test: 71.0,
        },
        traversal: Traversal::BruteForce,
        fpl_mhz: 100.0,
    };
    let p = project(&w, &d, &b).unwrap();
    let access = (b.access_fixed_ns + b.access_pl_cycles * 10.0) * 1e-9;
    let expected = w.rays() as f64 * b.arm_ray_ns * 1e-9
        + w.brute_force_tests() as f64 * (20.5 * access + 710e-9);
    assert!(
        (p.total_s() / expected - 1.0).abs() < 1e-12,
        "{} vs {expected}",
        p.total_s()
    );
    assert_eq!(p.tests, 4_250_044);
}

#[test]
fn brute_force_count_is_rays_by_kind_times_the_triangles_they_test() {
    let w = Workload {
        scene: "synthetic".into(),
        width: 2,
        height: 2,
        primary_rays: 4,
        reflection_rays: 3,
        refraction_rays: 2,
        shadow_rays: 5,
        triangles: 10,
        shadow_casting_triangles: 7,
        bvh_tests: 11,
        batches: 1,
        unit: None,
    };
    assert_eq!(w.brute_force_tests(), (4 + 3 + 2) * 10 + 5 * 7);
    assert_eq!(w.tests(Traversal::Bvh), 11);
}

#[test]
fn ray_counts_agree_with_the_image() {
    // Simple plane: one diffuse plane, one distant light, so every primary ray that hits the
    // plane casts exactly one shadow ray and every pixel that misses shows the background.
    let Some(root) = thesis_dir("ray_counts_agree_with_the_image") else {
        return;
    };
    let scene = Scene::load(root.join("Simple_plane_scene").to_str().unwrap()).unwrap();
    let (w, h) = (320, 180);
    let workload = Workload::measure(&scene, w, h).unwrap();
    let image = render(
        &scene,
        &F32Intersector,
        &RenderOptions {
            width: Some(w),
            height: Some(h),
            ..Default::default()
        },
    )
    .unwrap()
    .image;
    let bg = sw_renderer::shade::to_rgb8(sw_renderer::math::V3::from(scene.options.background));
    let covered = image.pixels().filter(|p| p.0 != bg).count() as u64;
    assert_eq!(workload.primary_rays, u64::from(w * h));
    assert_eq!(workload.shadow_rays, covered);
    assert_eq!(workload.reflection_rays + workload.refraction_rays, 0);
    assert_eq!(workload.brute_force_tests(), 2 * workload.rays());
    assert!(workload.bvh_tests <= workload.brute_force_tests());
}

#[test]
fn glass_objects_are_skipped_by_shadow_rays_only() {
    let Some(root) = thesis_dir("glass_objects_are_skipped_by_shadow_rays_only") else {
        return;
    };
    let scene = Scene::load(root.join("Glasses_scene").to_str().unwrap()).unwrap();
    let w = Workload::measure(&scene, 64, 36).unwrap();
    assert_eq!((w.triangles, w.shadow_casting_triangles), (720, 400));
    assert!(w.refraction_rays > 0 && w.shadow_rays > 0);
    assert!(w.bvh_tests < w.brute_force_tests());
}

fn board() -> impl Strategy<Value = Board> {
    (50.0..2000.0f64, 20.0..500.0f64, 0.0..300.0f64, 1.0..50.0f64).prop_map(|(r, t, f, c)| Board {
        arm_ray_ns: r,
        arm_test_ns: t,
        access_fixed_ns: f,
        access_pl_cycles: c,
    })
}

fn workload() -> impl Strategy<Value = Workload> {
    (
        1u64..5_000_000,
        0u64..3_000_000,
        1u64..20_000,
        1u64..50_000_000,
        1u64..5000,
    )
        .prop_map(
            |(primary, shadow, triangles, bvh_tests, batches)| Workload {
                scene: "random".into(),
                width: 1,
                height: 1,
                primary_rays: primary,
                reflection_rays: primary / 3,
                refraction_rays: primary / 5,
                shadow_rays: shadow,
                triangles,
                shadow_casting_triangles: triangles / 2,
                bvh_tests,
                batches,
                unit: None,
            },
        )
}

fn frontend(units: u32, stream: bool, cycles: f64, latency: u32) -> Frontend {
    if stream {
        Frontend::Stream {
            lanes: units,
            cycles_per_test: cycles.min(4.0),
            pipeline_latency: latency,
            hp_ports: 1 + units % 4,
            dma_efficiency: 0.8,
            pack_arm_cycles: 40.0,
        }
    } else {
        Frontend::Thesis {
            units,
            cycles_per_test: cycles,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn more_lanes_or_a_faster_fabric_is_never_slower(
        b in board(),
        w in workload(),
        stream in any::<bool>(),
        units in 1u32..16,
        cycles in 1.0..300.0f64,
        latency in 1u32..200,
        mhz in 10.0..400.0f64,
        faster in 1.0..4.0f64,
        bvh in any::<bool>(),
    ) {
        let traversal = if bvh { Traversal::Bvh } else { Traversal::BruteForce };
        let base = Design { frontend: frontend(units, stream, cycles, latency), traversal, fpl_mhz: mhz };
        let t = project(&w, &base, &b).unwrap().total_s();
        // Same HP ports, one more lane or unit.
        let more = match base.frontend {
            Frontend::Stream { lanes, .. } => {
                let Frontend::Stream { cycles_per_test, pipeline_latency, hp_ports, dma_efficiency, pack_arm_cycles, .. } = base.frontend else { unreachable!() };
                Frontend::Stream { lanes: lanes + 1, cycles_per_test, pipeline_latency, hp_ports, dma_efficiency, pack_arm_cycles }
            }
            Frontend::Thesis { units, cycles_per_test } => Frontend::Thesis { units: units + 1, cycles_per_test },
            Frontend::Traversal { .. } => unreachable!("frontend() makes no traversal design"),
        };
        let t_more = project(&w, &Design { frontend: more, ..base }, &b).unwrap().total_s();
        prop_assert!(t_more <= t * (1.0 + 1e-12), "{t_more} > {t}");
        let t_fast = project(&w, &Design { fpl_mhz: mhz * faster, ..base }, &b).unwrap().total_s();
        prop_assert!(t_fast <= t * (1.0 + 1e-12), "{t_fast} > {t}");
        let p = project(&w, &base, &b).unwrap();
        prop_assert!(p.arm_s >= 0.0 && p.bus_s >= 0.0 && p.accel_s >= 0.0);
    }
}

#[test]
fn bad_designs_are_rejected_with_a_clear_error() {
    let b = Board {
        arm_ray_ns: 500.0,
        arm_test_ns: 125.0,
        access_fixed_ns: 80.0,
        access_pl_cycles: 15.0,
    };
    let w = Workload {
        scene: "s".into(),
        width: 1,
        height: 1,
        primary_rays: 1,
        reflection_rays: 0,
        refraction_rays: 0,
        shadow_rays: 0,
        triangles: 1,
        shadow_casting_triangles: 1,
        bvh_tests: 1,
        batches: 1,
        unit: None,
    };
    let stream = |lanes, hp_ports, dma_efficiency| Frontend::Stream {
        lanes,
        cycles_per_test: 1.0,
        pipeline_latency: 10,
        hp_ports,
        dma_efficiency,
        pack_arm_cycles: 40.0,
    };
    let traversal = |hp_ports, dma_efficiency| Frontend::Traversal {
        hp_ports,
        dma_efficiency,
        pack_arm_cycles: 40.0,
    };
    let cases = [
        (stream(0, 1, 0.8), 100.0, "0 lanes"),
        (stream(1, 1, 0.8), 0.0, "0 MHz"),
        (stream(1, 1, 0.8), -5.0, "-5 MHz"),
        (stream(1, 1, 0.8), f64::NAN, "NaN MHz"),
        (stream(1, 5, 0.8), 100.0, "5 HP ports"),
        (stream(1, 1, 0.0), 100.0, "DMA efficiency 0"),
        (stream(1, 1, 1.5), 100.0, "DMA efficiency 1.5"),
        (
            Frontend::Thesis {
                units: 0,
                cycles_per_test: 71.0,
            },
            100.0,
            "0 accelerators",
        ),
        (
            Frontend::Thesis {
                units: 1,
                cycles_per_test: 0.0,
            },
            100.0,
            "cycles per test 0",
        ),
        (traversal(5, 0.8), 100.0, "5 HP ports"),
        (traversal(1, 0.0), 100.0, "DMA efficiency 0"),
        // A valid traversal design, but the workload has no measurement of the unit.
        (traversal(1, 0.8), 100.0, "needs the unit's work"),
    ];
    for (frontend, fpl_mhz, expected) in cases {
        let d = Design {
            frontend,
            traversal: Traversal::Bvh,
            fpl_mhz,
        };
        let err = project(&w, &d, &b).expect_err(expected).to_string();
        assert!(err.contains(expected), "`{err}` should name `{expected}`");
    }
}

#[test]
fn missing_thesis_scene_names_the_directory() {
    let mut workloads = Workloads::new(Path::new("/nonexistent/thesis"));
    let err = workloads
        .get("Simple_plane_scene", 64, 36)
        .expect_err("no such directory")
        .to_string();
    assert!(
        err.contains("/nonexistent/thesis/Simple_plane_scene"),
        "{err}"
    );
}

#[test]
fn the_traversal_design_streams_rays_and_answers_beside_the_units_cycles() {
    let b = Board {
        arm_ray_ns: 500.0,
        arm_test_ns: 125.0,
        access_fixed_ns: 80.0,
        access_pl_cycles: 15.0,
    };
    let unit = |cycles| UnitWork {
        box_tests: 10_000,
        node_visits: 11_000,
        mt_tests: 2_000,
        cycles,
        wavefronts: 10,
        passes: 10,
        ray_passes: 2_000,
        image_bytes: 64_000,
        chunk_loads: 0,
        loaded_bytes: 64_000,
    };
    let w = |cycles| Workload {
        scene: "s".into(),
        width: 10,
        height: 100,
        primary_rays: 1_000,
        reflection_rays: 0,
        refraction_rays: 0,
        shadow_rays: 1_000,
        triangles: 100,
        shadow_casting_triangles: 100,
        bvh_tests: 3_000,
        batches: 10,
        unit: Some(unit(cycles)),
    };
    let d = Design {
        frontend: Frontend::Traversal {
            hp_ports: 1,
            dma_efficiency: 0.5,
            pack_arm_cycles: 66.7,
        },
        traversal: Traversal::Bvh,
        fpl_mhz: 100.0,
    };
    // 4 bytes (a packet word) a cycle: 2,000 rays in take 2,000·RAY_WORDS cycles (22,000),
    // their answers 2,000·HIT_WORDS (12,000); the image 16,000 more. Below 22,000 unit cycles
    // the input stream sets the pace, above it the unit.
    let cycle = 1e-8;
    let rays_in = (2_000 * hw_model::traversal::RAY_WORDS) as f64;
    const { assert!(hw_model::traversal::HIT_WORDS < hw_model::traversal::RAY_WORDS) };
    for (cycles, pace) in [(1_000, rays_in), (50_000, 50_000.0)] {
        let p = project(&w(cycles), &d, &b).unwrap();
        assert_eq!(p.tests, 2_000);
        assert!(
            (p.accel_s - (pace + 16_000.0) * cycle).abs() < 1e-12,
            "{p:?}"
        );
        let arm = 2_000.0 * (500e-9 + 66.7 / 667e6);
        assert!((p.arm_s - arm).abs() < 1e-12, "{p:?}");
    }
    // The ARM with the BVH walk pays the MT tests and the box tests.
    let walk = b.arm_bvh_walk_s(&w(1)).unwrap();
    assert!((walk - (2_000.0 * 500e-9 + 3_000.0 * 125e-9 + 10_000.0 * 125e-9)).abs() < 1e-12);

    // In 3 chunks: 30 passes streaming 5,000 rays (5,000·RAY_WORDS cycles in), 30 chunk
    // loads of 200,000 bytes in all (50,000 cycles), each pass and load started over
    // AXI4-Lite.
    let mut chunked = w(1_000);
    chunked.unit = Some(UnitWork {
        passes: 30,
        ray_passes: 5_000,
        chunk_loads: 30,
        loaded_bytes: 200_000,
        ..unit(1_000)
    });
    let p = project(&chunked, &d, &b).unwrap();
    let passes_in = (5_000 * hw_model::traversal::RAY_WORDS) as f64;
    assert!(
        (p.accel_s - (passes_in + 50_000.0) * cycle).abs() < 1e-12,
        "{p:?}"
    );
    let arm = 2_000.0 * 500e-9 + 5_000.0 * 66.7 / 667e6;
    assert!((p.arm_s - arm).abs() < 1e-12, "{p:?}");
    let access = b.access_ns(100.0) * 1e-9;
    assert!(
        (p.bus_s - (30.0 * 8.0 + 30.0 * 4.0) * access).abs() < 1e-12,
        "{p:?}"
    );
}
