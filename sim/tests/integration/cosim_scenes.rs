//! fp32 hardware renders of the thesis' 7 scenes (found by `sw_renderer::thesis_scenes`;
//! skipped with a `SKIPPED` line on stderr when absent) through the Verilated accelerator in
//! stream mode equal the software renders pixel for pixel (PSNR inf). 48×27 keeps the run
//! short; the model build (fp32, depth 1, one lane, ~1 min) is cached on disk.

use hdl::top::TopConfig;
use hw_model::HwFormat;
use sim::hw_intersector::{HwIntersector, Mode};
use std::path::PathBuf;
use sw_renderer::compare::compare;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;

#[test]
fn fp32_hardware_renders_equal_the_software_renders() {
    let Some(root) =
        thesis_scenes::for_test("cosim_scenes::fp32_hardware_renders_equal_the_software_renders")
    else {
        return;
    };
    let dirs: Vec<PathBuf> = thesis_scenes::SCENE_DIRS
        .iter()
        .map(|name| root.join(name))
        .collect();
    let hw =
        HwIntersector::new(&TopConfig::new(HwFormat::named("fp32"), 1, 1), Mode::Stream).unwrap();
    let opts = RenderOptions {
        width: Some(48),
        height: Some(27),
        ..RenderOptions::default()
    };
    for dir in &dirs {
        let scene = Scene::load(dir.to_str().unwrap()).unwrap();
        let before = hw.stats().tests;
        let hw_image = render(&scene, &hw, &opts).unwrap().image;
        let sw = render(&scene, &F32Intersector, &opts).unwrap();
        let diff = compare(&hw_image, &sw.image).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{}: {diff:?}", dir.display());
        assert!(diff.psnr_db.is_infinite());
        assert_eq!(
            hw.stats().tests - before,
            sw.stats.trace.cast.mt_tests,
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
