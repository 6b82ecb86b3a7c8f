//! `rtfpga render`: the image a render writes is the library's for the same engine.

use hw_model::ModelIntersector;
use sw_renderer::intersect::F32Intersector;

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
