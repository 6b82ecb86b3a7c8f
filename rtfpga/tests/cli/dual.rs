//! Dual-precision pairs `--format bfpW/FALLBACK`: the model engine renders the fallback's
//! image with either filter; the hardware builds one pair; every other use names what is
//! built.

use hw_model::ModelIntersector;

use crate::common::*;

#[test]
fn a_model_pair_renders_the_fallbacks_image_and_reports_what_it_forwarded() {
    let dir = tmp();
    let png = at(&dir, "dual.png");
    let fp32 = ModelIntersector::new(hw_model::lookup("fp32").unwrap());
    let want = library_render("utah_teapot", 32, 18, &fp32);
    for (pair, args, filter) in [
        ("bfp18/fp32", &[][..], "bfp"),
        (
            "bfp18/fp32",
            &["--dual-filter", "plucker-signs"],
            "plucker-signs",
        ),
        ("bfp14/fp32", &[], "bfp"),
    ] {
        let out = render("utah_teapot", 32, 18, &png)
            .args(&["--engine", "model", "--format", pair])
            .args(args)
            .ok();
        assert_eq!(
            value(&out, "engine"),
            Some(format!("model {pair}")),
            "{out}"
        );
        assert_eq!(value(&out, "spawn").as_deref(), Some("thesis"), "{out}");
        let line = labelled(&out, "dual_precision");
        let field = |key: &str| -> f64 { value(line, key).unwrap().parse().unwrap() };
        assert_eq!(value(line, "filter").as_deref(), Some(filter), "{line}");
        let (tests, forwarded) = (field("tests"), field("forwarded"));
        assert!(tests > 0.0 && forwarded < tests, "{line}");
        assert!(
            (field("forwarded_share") - forwarded / tests).abs() < 1e-4,
            "{line}"
        );
        assert_eq!(
            read_png(&png),
            want,
            "{pair} with {filter} is not fp32's image"
        );
    }
}

#[test]
fn a_malformed_pair_is_a_usage_error_naming_what_is_wrong() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    for (format, needle) in [
        ("fp16/fp32", "not block floating point"),
        ("bfp18/xyz", "xyz"),
        ("fp16/", "FILTER/FALLBACK"),
        ("a/b/c", "FILTER/FALLBACK"),
        ("fx32_16/fp32", "not block floating point"),
        ("bfp7/fp32", "8 to 24 bits"),
        ("bfp18/fp16", "holds fp32"),
    ] {
        render("simple_plane", 8, 8, &png)
            .args(&["--engine", "model", "--format", format])
            .fails(2, &[format, needle]);
    }
    assert!(!png.exists());
}

#[test]
fn a_filter_that_is_not_built_and_a_scaled_pair_are_errors() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let pair = || {
        render("simple_plane", 8, 8, &png).args(&["--engine", "model", "--format", "bfp18/fp32"])
    };
    pair()
        .args(&["--dual-filter", "linear"])
        .fails(2, &["linear", "bfp", "plucker-signs"]);
    pair().args(&["--scale", "auto"]).fails(
        1,
        &["--scale does not act on --engine model --format FILTER/FALLBACK"],
    );
    assert!(!png.exists());
}

#[test]
fn pairs_other_than_the_built_one_are_model_only_everywhere() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    for engine in ["hw", "traversal"] {
        render("simple_plane", 8, 8, &png)
            .args(&["--engine", engine, "--format", "bfp14/fp32"])
            .fails(1, &["bfp14/fp32", "model-only"]);
    }
    rtfpga(&["verilog", "--format", "bfp14/fp32", "--out", s(dir.path())])
        .fails(1, &["model-only"]);
    rtfpga(&["synth", "--format", "bfp14/fp32"]).fails(1, &["model-only"]);
    rtfpga(&["cosim", "--scene", "simple_plane", "--format", "bfp14/fp32"])
        .out(&png)
        .fails(1, &["the hardware pair is bfp18/fp32", "model-only"]);
    assert!(!png.exists());
}

/// The configurations of the hardware pair it is not built in, before any model is built.
#[test]
fn the_hardware_pair_refuses_what_it_is_not_built_with() {
    let dir = tmp();
    let png = at(&dir, "pair.png");
    let pair = || cosim("simple_plane", 12, 8, &png).args(&["--format", "bfp18/fp32"]);
    pair()
        .args(&["--lanes", "6"])
        .fails(1, &["--lanes 6", "1 to 5 filter slots"]);
    pair()
        .args(&["--lanes", "2", "--mode", "register"])
        .fails(1, &["--mode does not act on --unit mt --format bfp18/fp32"]);
    pair()
        .args(&["--depth", "99"])
        .fails(1, &["depth = 99", "depth 0 to"]);
    assert!(!png.exists());
}
