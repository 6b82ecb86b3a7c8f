//! `rtfpga render`: the image a render writes is the library's for the same engine.

use hw_model::frame::{Frame, FrameLimits, WAVEFRONT};
use hw_model::traversal::{NodeFormat, SceneMemory, TraversalEngine, DEFAULT_STACK_DEPTH};
use hw_model::{Advance, Format, ModelIntersector};
use image::RgbImage;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::common::*;

#[test]
fn f32_writes_the_size_asked_and_the_librarys_image() {
    let dir = tmp();
    let png = at(&dir, "plane.png");
    let out = render("simple_plane", 32, 18, &png).ok();
    assert_eq!(value(&out, "size").as_deref(), Some("32x18"), "{out}");
    let img = read_png(&png);
    assert_eq!(img.dimensions(), (32, 18));
    assert_eq!(
        img,
        library_render("simple_plane", 32, 18, &F32Intersector),
        "the CLI's f32 render differs from sw_renderer::render"
    );
}

#[test]
fn simple_plane_at_the_golden_size_is_the_golden_image_in_f32_and_the_fp32_model() {
    // golden/ holds 640x360 f32 renders; simple_plane has 2 triangles, so this is quick.
    let golden = read_png(&std::path::Path::new(REPO).join("golden/simple_plane.png"));
    assert_eq!(golden.dimensions(), (640, 360), "see golden/manifest.toml");
    let dir = tmp();
    let png = at(&dir, "plane.png");
    // No size given: the scene's own (640x360).
    rtfpga(&["render", "--scene", "simple_plane", "--quiet"])
        .out(&png)
        .ok();
    assert!(
        read_png(&png) == golden,
        "f32 differs from golden/simple_plane.png"
    );
    // The fp32 model with its defaults (thesis policy: exact edges, the query's origin).
    let out = rtfpga(&[
        "render",
        "--scene",
        "simple_plane",
        "--engine",
        "model",
        "--quiet",
    ])
    .out(&png)
    .ok();
    assert_eq!(value(&out, "edges").as_deref(), Some("exact"), "{out}");
    assert_eq!(value(&out, "advance").as_deref(), Some("none"), "{out}");
    assert!(
        read_png(&png) == golden,
        "the fp32 model differs from the golden image"
    );
}

#[test]
fn the_fp16_model_writes_the_models_image_not_f32s() {
    let dir = tmp();
    let png = at(&dir, "plane16.png");
    let out = render("simple_plane", 32, 18, &png)
        .args(&["--engine", "model", "--format", "fp16", "--spawn", "thesis"])
        .args(&["--scale", "none", "--advance", "none"])
        .ok();
    assert_eq!(
        value(&out, "engine").as_deref(),
        Some("model fp16"),
        "{out}"
    );
    let img = read_png(&png);
    let fp16 = ModelIntersector::new(hw_model::lookup("fp16").unwrap());
    assert_eq!(img, library_render("simple_plane", 32, 18, &fp16));
    assert_ne!(
        img,
        library_render("simple_plane", 32, 18, &F32Intersector),
        "--engine model --format fp16 rendered exactly the f32 image"
    );
}

/// The frame model's image of `scene` (hw_model::frame), its rays answered by the traversal
/// unit's model in `format`.
fn library_frame(scene: &str, w: u32, h: u32, format: Format) -> RgbImage {
    let scene = Scene::load(scene).expect("scene");
    let prepared = PreparedScene::new(&scene).expect("prepared");
    let unit = TraversalEngine {
        format,
        stack_depth: DEFAULT_STACK_DEPTH,
        scale_exp: 0,
        advance: Advance::None,
        timing: None,
        memory: SceneMemory::Unbounded,
        nodes: NodeFormat::Bvh2Fp32,
    };
    let frame = Frame::new(&scene, &prepared, &unit, w, h, &FrameLimits::HW).expect("loaded");
    frame.render(16, WAVEFRONT, &|| {}).expect("rendered").image
}

/// `--engine frame` writes the frame model's image, its rays answered in `--format`; on
/// simple_plane (one contribution a pixel) that is the software's image. Its `frame` line
/// counts the rays by kind.
#[test]
fn the_frame_engine_writes_the_frame_models_image_and_counts_rays_by_kind() {
    let dir = tmp();
    let png = at(&dir, "frame.png");
    let out = render("simple_plane", 64, 36, &png)
        .args(&["--engine", "frame"])
        .ok();
    assert_eq!(value(&out, "engine").as_deref(), Some("frame"), "{out}");
    assert_eq!(
        value(&out, "traversal").as_deref(),
        Some("traversal model fp32"),
        "{out}"
    );
    assert_eq!(value(&out, "spawn").as_deref(), Some("thesis"), "{out}");
    let frame = labelled(&out, "frame");
    for (kind, count) in [
        ("primary_rays", "2304"),
        ("reflection_rays", "0"),
        ("refraction_rays", "0"),
    ] {
        assert_eq!(value(frame, kind).as_deref(), Some(count), "{out}");
    }
    assert_eq!(
        read_png(&png),
        library_render("simple_plane", 64, 36, &F32Intersector)
    );

    let out = render("glass_pen", 40, 24, &png)
        .args(&["--engine", "frame", "--format", "e8m14"])
        .ok();
    let frame = labelled(&out, "frame");
    for kind in ["reflection_rays", "refraction_rays", "shadow_rays"] {
        let n: u64 = value(frame, kind).unwrap().parse().unwrap();
        assert!(n > 0, "no {kind}: {out}");
    }
    let image = read_png(&png);
    assert_eq!(
        image,
        library_frame("glass_pen", 40, 24, hw_model::lookup("e8m14").unwrap())
    );
    assert_ne!(
        image,
        library_frame("glass_pen", 40, 24, Format::FP32),
        "--format did not reach the traversal unit"
    );
}
