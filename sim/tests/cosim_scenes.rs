//! fp32 hardware renders of the thesis' 7 scenes (../shared/scenes/thesis/, skipped with a
//! notice when absent) through the Verilated accelerator in stream mode equal the software
//! renders pixel for pixel (PSNR inf). 48×27 keeps the run short; the model build (fp32,
//! depth 1, one lane, ~1 min) is cached on disk.

use hdl::top::TopConfig;
use sim::hw_intersector::{HwIntersector, Mode};
use std::path::{Path, PathBuf};
use sw_renderer::compare::compare;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

fn thesis_scene_dirs() -> Option<Vec<PathBuf>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/scenes/thesis");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("objects.txt").is_file())
        .collect();
    dirs.sort();
    Some(dirs)
}

#[test]
fn fp32_hardware_renders_equal_the_software_renders() {
    let Some(dirs) = thesis_scene_dirs() else {
        eprintln!(
            "NOTICE: ../shared/scenes/thesis is absent; the thesis scene co-simulation is skipped"
        );
        return;
    };
    assert_eq!(dirs.len(), 7, "{dirs:?}");
    let hw = HwIntersector::new(&TopConfig::new("fp32", 1, 1), Mode::Stream).unwrap();
    let opts = RenderOptions {
        width: Some(48),
        height: Some(27),
        ..RenderOptions::default()
    };
    for dir in &dirs {
        let scene = Scene::load(dir.to_str().unwrap()).unwrap();
        let before = hw.stats().tests;
        let hw_image = render(&scene, &hw, &opts).unwrap().image;
        assert!(hw.take_error().is_none());
        let sw = render(&scene, &F32Intersector, &opts).unwrap();
        let diff = compare(&hw_image, &sw.image).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{}: {diff:?}", dir.display());
        assert!(diff.psnr_db.is_infinite());
        assert_eq!(
            hw.stats().tests - before,
            sw.stats.trace.mt_queries,
            "{}",
            dir.display()
        );
    }
    let s = hw.stats();
    println!(
        "7 scenes at 48x27: {} tests, {} cycles, utilisation {:.3}, {:.0} tests/s per core",
        s.tests,
        s.cycles,
        s.lane_utilisation(),
        s.tests_per_sec()
    );
}
