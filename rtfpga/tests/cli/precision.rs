//! `--spawn`, `--scale`, `--edges`, `--advance`: reduced precision that renders
//! (docs/precision.md); each reaches the engine, its default is the documented one.

use hw_model::precision::{auto_scale_exp, spawn_policy, SceneRange};
use hw_model::{Advance, Edges, ModelIntersector};
use sw_renderer::render::RenderOptions;
use sw_renderer::scene::Scene;

use crate::common::*;

#[test]
fn a_narrow_model_render_is_format_aware_by_default_and_scales_on_request() {
    let dir = tmp();
    let png = at(&dir, "plane16.png");
    let base =
        render("simple_plane", 32, 18, &png).args(&["--engine", "model", "--format", "fp16"]);
    let out = base.clone().ok();
    for (key, want) in [
        ("spawn", "format-aware"),
        ("scale_exp", "0"),
        ("edges", "exact"),
        ("advance", "triangle-box"),
    ] {
        assert_eq!(value(&out, key).as_deref(), Some(want), "{out}");
    }
    let out = base.args(&["--scale", "auto"]).ok();
    let fp16 = hw_model::lookup("fp16").unwrap();
    let scene = Scene::load("simple_plane").unwrap();
    let scale_exp = auto_scale_exp(&fp16, &SceneRange::of(&scene).unwrap());
    assert_eq!(
        value(&out, "scale_exp"),
        Some(scale_exp.to_string()),
        "{out}"
    );
    let engine = ModelIntersector {
        scale_exp,
        advance: Advance::TriangleBox,
        ..ModelIntersector::new(fp16)
    };
    let opts = RenderOptions {
        spawn: spawn_policy(&fp16, scale_exp),
        ..Default::default()
    };
    assert_eq!(
        read_png(&png),
        library_render_with("simple_plane", 32, 18, &engine, opts)
    );
}

#[test]
fn fp32_and_the_f32_engine_stay_the_thesis_renderer() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    for engine in ["model", "f32"] {
        let out = render("simple_plane", 8, 8, &png)
            .args(&["--engine", engine])
            .ok();
        assert_eq!(value(&out, "spawn").as_deref(), Some("thesis"), "{out}");
        assert_eq!(value(&out, "advance").as_deref(), Some("none"), "{out}");
    }
}

#[test]
fn edges_and_advance_reach_the_model_lane() {
    let dir = tmp();
    let png = at(&dir, "teapot.png");
    let out = render("utah_teapot", 32, 18, &png)
        .args(&["--engine", "model", "--format", "e5m14"])
        .args(&["--edges", "conservative", "--advance", "none"])
        .ok();
    assert_eq!(
        value(&out, "edges").as_deref(),
        Some("conservative"),
        "{out}"
    );
    let e5m14 = hw_model::lookup("e5m14").unwrap();
    let engine = ModelIntersector {
        edges: Edges::Conservative,
        ..ModelIntersector::new(e5m14)
    };
    let opts = RenderOptions {
        spawn: spawn_policy(&e5m14, 0),
        ..Default::default()
    };
    assert_eq!(
        read_png(&png),
        library_render_with("utah_teapot", 32, 18, &engine, opts)
    );
}

#[test]
fn unknown_spawn_scale_edges_and_advance_values_are_usage_errors_listing_the_choices() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    for (option, bad, choices) in [
        ("--spawn", "bogus", &["thesis", "format-aware"][..]),
        ("--scale", "double", &["auto", "none"]),
        ("--edges", "loose", &["exact", "conservative"]),
        ("--advance", "far", &["none", "triangle-box", "leaf-box"]),
    ] {
        let mut needles = vec![bad];
        needles.extend(choices);
        render("simple_plane", 8, 8, &png)
            .args(&["--engine", "model", option, bad])
            .fails(2, &needles);
    }
    assert!(!png.exists());
}
