//! The `rtfpga` binary itself, run as a user runs it: the contracts of the README's
//! command-line table (the last line `psnr_db=...`, the sizes of written images, the format
//! catalogue, the committed Verilog) and the exit codes and messages of bad input: 0 on
//! success, 1 on an error the program reports (`error: ...` on stderr, naming the bad value
//! and what was expected), 2 on a command-line usage error.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Duration;

use assert_cmd::Command;
use hw_model::precision::{auto_scale_exp, spawn_policy, SceneRange};
use hw_model::ModelIntersector;
use hw_model::{Advance, Edges};
use image::{Rgb, RgbImage};
use predicates::prelude::*;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::RayEngine;
use sw_renderer::render::{render, save_png, RenderOptions};
use sw_renderer::scene::Scene;

const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// The binary, with a timeout: a command that should refuse its input at once must not be
/// allowed to render for hours instead.
fn rtfpga() -> Command {
    let mut cmd = Command::cargo_bin("rtfpga").expect("the rtfpga binary");
    cmd.timeout(Duration::from_secs(120));
    cmd
}

/// Runs `rtfpga args`, asserts exit code 0, returns stdout.
fn ok(args: &[&str]) -> String {
    let out = rtfpga().args(args).assert().success().get_output().clone();
    String::from_utf8(out.stdout).expect("stdout is UTF-8")
}

/// Runs `rtfpga args`, asserts exit `code` and a message on stderr starting `error:` and
/// containing each of `needles`; returns stderr.
fn fails(args: &[&str], code: i32, needles: &[&str]) -> String {
    let out = rtfpga().args(args).assert().code(code).get_output().clone();
    let stderr = String::from_utf8(out.stderr).expect("stderr is UTF-8");
    assert!(
        stderr.starts_with("error:"),
        "`rtfpga {}`: stderr does not start with `error:`:\n{stderr}",
        args.join(" ")
    );
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "`rtfpga {}`: stderr does not mention `{needle}`:\n{stderr}",
            args.join(" ")
        );
    }
    if code == 1 {
        // A reported error is one message, not a panic or a half-written result, and it
        // says each thing once (not a cause repeated by the message that wraps it).
        assert!(!stderr.contains("panicked"), "{stderr}");
        let parts: Vec<&str> = stderr.trim_end().split(": ").collect();
        for (i, part) in parts.iter().enumerate() {
            assert!(
                !parts[i + 1..].contains(part),
                "`rtfpga {}`: `{part}` said twice:\n{stderr}",
                args.join(" ")
            );
        }
        assert!(
            out.stdout.is_empty(),
            "`rtfpga {}` printed results before failing:\n{}",
            args.join(" "),
            String::from_utf8_lossy(&out.stdout)
        );
    }
    stderr
}

fn last_line(stdout: &str) -> &str {
    stdout.lines().last().unwrap_or("")
}

/// The value of the last line `psnr_db=<number|inf>`.
fn psnr_of(stdout: &str) -> f64 {
    let line = last_line(stdout);
    let value = line
        .strip_prefix("psnr_db=")
        .unwrap_or_else(|| panic!("last line is not psnr_db=...: {line:?}\n{stdout}"));
    if value == "inf" {
        f64::INFINITY
    } else {
        let x: f64 = value
            .parse()
            .unwrap_or_else(|_| panic!("psnr_db value {value:?} is not a number"));
        assert!(
            x.is_finite(),
            "a finite PSNR is printed as a number: {line}"
        );
        x
    }
}

fn s(p: &Path) -> &str {
    p.to_str().expect("temporary paths are UTF-8")
}

fn read_png(p: &Path) -> RgbImage {
    image::open(p)
        .unwrap_or_else(|e| panic!("{} is not a readable image: {e}", p.display()))
        .to_rgb8()
}

/// A test pattern: smooth gradients, so that changed pixels change the MSE by known amounts.
fn pattern(w: u32, h: u32) -> RgbImage {
    RgbImage::from_fn(w, h, |x, y| {
        Rgb([(x * 7) as u8, (y * 11) as u8, ((x + y) * 3) as u8])
    })
}

/// PSNR computed here from the pixels, independently of the library: MSE over every R, G and
/// B sample, peak 255.
fn psnr_independent(a: &RgbImage, b: &RgbImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let mut sum = 0.0f64;
    let mut n = 0.0f64;
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = f64::from(p[c]) - f64::from(q[c]);
            sum += d * d;
            n += 1.0;
        }
    }
    let mse = sum / n;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        20.0 * 255.0f64.log10() - 10.0 * mse.log10()
    }
}

/// The library's render of a built-in scene at a size, through `isect`.
fn library_render(scene: &str, w: u32, h: u32, isect: &dyn RayEngine) -> RgbImage {
    let scene = Scene::load(scene).expect("built-in scene");
    let opts = RenderOptions {
        width: Some(w),
        height: Some(h),
        progress: false,
        ..Default::default()
    };
    render(&scene, isect, &opts).expect("render").image
}

// ---- compare ------------------------------------------------------------------------------

#[test]
fn compare_identical_images_prints_psnr_inf_last() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b, d) = (
        dir.path().join("a.png"),
        dir.path().join("b.png"),
        dir.path().join("d.png"),
    );
    let img = pattern(23, 11);
    save_png(&img, &a).unwrap();
    save_png(&img, &b).unwrap();
    let out = ok(&["compare", s(&a), s(&b), "--diff", s(&d)]);
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    assert_eq!(psnr_of(&out), f64::INFINITY);
    assert_eq!(read_png(&d).dimensions(), (23, 11), "--diff has A's size");
    // The same file twice, and without --diff, too.
    let out = ok(&["compare", s(&a), s(&a)]);
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
}

#[test]
fn compare_different_images_prints_the_psnr_of_their_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b, d) = (
        dir.path().join("a.png"),
        dir.path().join("b.png"),
        dir.path().join("diff.png"),
    );
    let ia = pattern(40, 30);
    let mut ib = ia.clone();
    // A few strongly and many slightly changed samples, in every channel.
    ib.put_pixel(0, 0, Rgb([255, 255, 255]));
    ib.put_pixel(39, 29, Rgb([0, 0, 0]));
    for x in 0..40 {
        let p = ib.get_pixel_mut(x, 7);
        p[x as usize % 3] = p[x as usize % 3].wrapping_add(3);
    }
    save_png(&ia, &a).unwrap();
    save_png(&ib, &b).unwrap();
    let expected = psnr_independent(&ia, &ib);
    assert!(expected.is_finite() && expected > 10.0);

    let out = ok(&["compare", s(&a), s(&b), "--diff", s(&d)]);
    let got = psnr_of(&out);
    assert!(
        (got - expected).abs() < 1e-3,
        "rtfpga compare says psnr_db={got}, the pixels give {expected:.6}\n{out}"
    );
    // Symmetric.
    let out = ok(&["compare", s(&b), s(&a)]);
    assert!((psnr_of(&out) - expected).abs() < 1e-3, "{out}");

    let diff = read_png(&d);
    assert_eq!(
        diff.dimensions(),
        ia.dimensions(),
        "--diff has the images' size"
    );
    assert_ne!(
        diff.get_pixel(0, 0),
        diff.get_pixel(20, 20),
        "the heat-map marks the changed pixel"
    );
}

#[test]
fn compare_refuses_images_of_different_sizes_and_unreadable_files() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    save_png(&pattern(8, 4), &a).unwrap();
    save_png(&pattern(4, 8), &b).unwrap();
    fails(&["compare", s(&a), s(&b)], 1, &["8×4", "4×8"]);

    let missing = dir.path().join("missing.png");
    fails(&["compare", s(&a), s(&missing)], 1, &["missing.png"]);
    let text = dir.path().join("notes.png");
    std::fs::write(&text, "not an image").unwrap();
    fails(&["compare", s(&text), s(&a)], 1, &["notes.png"]);
}

// ---- render ------------------------------------------------------------------------------

#[test]
fn render_f32_writes_the_size_asked_and_the_librarys_image() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("plane.png");
    let out = ok(&[
        "render",
        "--scene",
        "simple_plane",
        "--width",
        "32",
        "--height",
        "18",
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    assert!(out.contains("size=32x18"), "{out}");
    let img = read_png(&out_png);
    assert_eq!(img.dimensions(), (32, 18));
    assert_eq!(
        img,
        library_render("simple_plane", 32, 18, &F32Intersector),
        "the CLI's f32 render differs from sw_renderer::render"
    );
}

#[test]
fn render_of_simple_plane_at_the_golden_size_equals_the_golden_image() {
    // golden/ holds 640x360 f32 renders; simple_plane has 2 triangles, so this is quick.
    let golden = Path::new(REPO).join("golden/simple_plane.png");
    let golden = read_png(&golden);
    assert_eq!(golden.dimensions(), (640, 360), "see golden/manifest.toml");
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("plane.png");
    // No size given: the scene's own (640x360).
    ok(&[
        "render",
        "--scene",
        "simple_plane",
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    assert!(
        read_png(&out_png) == golden,
        "rtfpga render --scene simple_plane differs from golden/simple_plane.png"
    );
    // The fp32 model with its defaults (thesis policy: exact edges, the query's origin).
    let out = ok(&[
        "render",
        "--scene",
        "simple_plane",
        "--engine",
        "model",
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    assert!(out.contains("edges=exact advance=none "), "{out}");
    assert!(
        read_png(&out_png) == golden,
        "rtfpga render --engine model --scene simple_plane differs from golden/simple_plane.png"
    );
}

#[test]
fn render_model_fp16_writes_the_models_image() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("plane16.png");
    let out = ok(&[
        "render",
        "--scene",
        "simple_plane",
        "--width",
        "32",
        "--height",
        "18",
        "--engine",
        "model",
        "--format",
        "fp16",
        "--spawn",
        "thesis",
        "--scale",
        "none",
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    assert!(out.contains("engine=model"), "{out}");
    let img = read_png(&out_png);
    assert_eq!(img.dimensions(), (32, 18));
    let fp16 = ModelIntersector::new(hw_model::lookup("fp16").unwrap());
    assert_eq!(
        img,
        library_render("simple_plane", 32, 18, &fp16),
        "the CLI's fp16 model render differs from the library's"
    );
    // fp16 really is used: at this size its render differs from f32's in a few pixels.
    assert_ne!(
        img,
        library_render("simple_plane", 32, 18, &F32Intersector),
        "--engine model --format fp16 rendered exactly the f32 image"
    );
}

/// A format pair renders the fallback's image with each filter and reports the share of
/// tests it forwarded.
#[test]
fn render_model_with_a_format_pair_writes_the_fallbacks_image() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("dual.png");
    let fp32 = ModelIntersector::new(hw_model::lookup("fp32").unwrap());
    let want = library_render("utah_teapot", 32, 18, &fp32);
    for (pair, args, filter) in [
        ("fp16/fp32", &[][..], "linear"),
        ("fp16/fp32", &["--dual-filter", "quotient"][..], "quotient"),
        (
            "fp16/fp32",
            &["--dual-filter", "linear-exact"][..],
            "linear-exact",
        ),
        ("bfp18/fp32", &[][..], "bfp"),
        ("bfp18/fp32", &["--dual-filter", "plucker"][..], "plucker"),
        (
            "bfp18/fp32",
            &["--dual-filter", "plucker-signs"][..],
            "plucker-signs",
        ),
    ] {
        let mut cmd = vec![
            "render",
            "--scene",
            "utah_teapot",
            "--width",
            "32",
            "--height",
            "18",
            "--engine",
            "model",
            "--format",
            pair,
            "--out",
            s(&out_png),
            "--quiet",
        ];
        cmd.extend(args);
        let out = ok(&cmd);
        assert!(
            out.contains(&format!("engine=model {pair} spawn=thesis")),
            "{out}"
        );
        let line = out
            .lines()
            .find(|l| l.starts_with("dual_precision "))
            .unwrap_or_else(|| panic!("no dual_precision line:\n{out}"));
        assert!(line.contains(&format!(" filter={filter} ")), "{line}");
        let field = |key: &str| -> f64 {
            let v = line.split(' ').find_map(|w| w.strip_prefix(key)).unwrap();
            v.parse().unwrap()
        };
        let (tests, forwarded) = (field("tests="), field("forwarded="));
        assert!(tests > 0.0 && forwarded < tests, "{line}");
        assert!(
            (field("forwarded_share=") - forwarded / tests).abs() < 1e-4,
            "{line}"
        );
        assert_eq!(
            read_png(&out_png),
            want,
            "the {pair} render with the {filter} filter differs from the fp32 model's"
        );
    }
}

/// Bad pairs are usage errors naming what is wrong; a pair where only one format can be
/// used is an error saying dual precision is model-only.
#[test]
fn format_pairs_are_checked_and_model_only() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let render = |format: &'static str, engine: &'static str| {
        [
            "render",
            "--scene",
            "simple_plane",
            "--width",
            "8",
            "--height",
            "8",
            "--engine",
            engine,
            "--format",
            format,
            "--out",
            s(&out_png),
        ]
        .map(str::to_string)
    };
    for (format, needle) in [
        ("fp32/fp16", "not narrower"),
        ("fp16/xyz", "xyz"),
        ("fp16/fp16", "same format"),
        ("fp16/", "FILTER/FALLBACK"),
        ("a/b/c", "FILTER/FALLBACK"),
        ("fx32_16/fp32", "float formats only"),
        ("bfp7/fp32", "8 to 24 bits"),
        ("bfp18/fp16", "holds fp32"),
    ] {
        let args = render(format, "model");
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, 2, &[format, needle]);
    }
    // A filter kind that does not fit the pair's filter, and a scaled bfp filter.
    for (extra, needle) in [
        (["--dual-filter", "linear"], "needs a float filter"),
        (["--scale", "auto"], "not scaled"),
    ] {
        let args = render("bfp18/fp32", "model");
        let mut args: Vec<&str> = args.iter().map(String::as_str).collect();
        args.extend(extra);
        fails(&args, 1, &["bfp18/fp32", needle]);
    }
    let model_only = "model-only";
    for engine in ["hw", "traversal"] {
        let args = render("fp16/fp32", engine);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, 1, &["fp16/fp32", model_only]);
    }
    let out_dir = s(dir.path());
    fails(
        &["verilog", "--format", "fp16/fp32", "--out", out_dir],
        1,
        &[model_only],
    );
    fails(&["synth", "--format", "fp16/fp32"], 1, &[model_only]);
    fails(
        &[
            "cosim",
            "--scene",
            "simple_plane",
            "--format",
            "fp16/fp32",
            "--out",
            s(&out_png),
        ],
        1,
        &[model_only],
    );
    assert!(!out_png.exists());
}

/// The pair built in hardware, bfp18/fp32, co-simulates: the image is fp32's (PSNR inf
/// against the software render) and the forwarded share is printed. The configurations it
/// is not built in are errors naming what is.
#[test]
fn the_hardware_pair_cosimulates_as_fp32() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("pair.png");
    let cosim = |extra: &[&str]| -> Vec<String> {
        let base = [
            "cosim",
            "--scene",
            "simple_plane",
            "--width",
            "12",
            "--height",
            "8",
            "--format",
            "bfp18/fp32",
            "--out",
            s(&out_png),
            "--quiet",
        ];
        base.iter().chain(extra).map(|a| a.to_string()).collect()
    };
    for (extra, needles) in [
        (
            &["--lanes", "6"][..],
            &["--lanes 6", "1 to 5 filter slots"][..],
        ),
        (&["--lanes", "2", "--mode", "register"], &["at its ports"]),
        (
            &["--lanes", "2", "--dual-filter", "quotient"],
            &["the hardware pairs are bfp18/fp32", "model-only"],
        ),
    ] {
        let args = cosim(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, 1, needles);
    }
    assert!(!out_png.exists());
    // Two slots at depth 1: the model sim's tests build (cached on disk).
    let args = cosim(&["--lanes", "2", "--depth", "1"]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = ok(&args);
    assert!(out.contains("engine=\"hw bfp18/fp32 pair s2 d1\""), "{out}");
    assert!(out.contains(" forwarded_share=0."), "{out}");
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    assert_eq!(read_png(&out_png).dimensions(), (12, 8));
}

/// `--advance leaf-box` reaches the traversal unit's model: the CLI's image is the library's
/// engine with the leaf advance, and the render line says it.
#[test]
fn render_traversal_with_the_leaf_advance_is_the_librarys() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("leaf.png");
    let out = ok(&[
        "render",
        "--scene",
        "glass_pen",
        "--width",
        "32",
        "--height",
        "18",
        "--engine",
        "traversal",
        "--format",
        "e5m14",
        "--advance",
        "leaf-box",
        "--scene-capacity",
        "100000,100000",
        "--quiet",
        "--out",
        s(&out_png),
    ]);
    assert!(
        out.contains("spawn=format-aware scale_exp=0 edges=exact advance=leaf-box "),
        "{out}"
    );
    let e5m14: hw_model::Format = "e5m14".parse().unwrap();
    let engine = hw_model::traversal::TraversalEngine {
        format: e5m14,
        stack_depth: hw_model::traversal::DEFAULT_STACK_DEPTH,
        scale_exp: 0,
        advance: Advance::LeafBox,
        timing: None,
        memory: hw_model::traversal::SceneMemory::Unbounded,
        nodes: hw_model::traversal::NodeFormat::Bvh2Fp32,
    };
    let opts = RenderOptions {
        width: Some(32),
        height: Some(18),
        spawn: spawn_policy(&e5m14, 0),
        ..Default::default()
    };
    let scene = Scene::load("glass_pen").unwrap();
    assert_eq!(
        read_png(&out_png),
        render(&scene, &engine, &opts).unwrap().image
    );
}

/// Without --spawn a narrow model render is format-aware; `--scale auto` scales it; the
/// render line says both.
#[test]
fn render_model_fp16_is_format_aware_by_default_and_scales_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("plane16.png");
    let args = [
        "render",
        "--scene",
        "simple_plane",
        "--width",
        "32",
        "--height",
        "18",
        "--engine",
        "model",
        "--format",
        "fp16",
        "--quiet",
        "--out",
    ];
    let out = ok(&[&args[..], &[s(&out_png)]].concat());
    assert!(
        out.contains("spawn=format-aware scale_exp=0 edges=exact advance=triangle-box "),
        "{out}"
    );
    let out = ok(&[&args[..1], &["--scale", "auto"], &args[1..], &[s(&out_png)]].concat());
    let fp16 = hw_model::lookup("fp16").unwrap();
    let scene = Scene::load("simple_plane").unwrap();
    let scale_exp = auto_scale_exp(&fp16, &SceneRange::of(&scene).unwrap());
    assert!(
        out.contains(&format!("spawn=format-aware scale_exp={scale_exp} ")),
        "{out}"
    );
    let opts = RenderOptions {
        width: Some(32),
        height: Some(18),
        spawn: spawn_policy(&fp16, scale_exp),
        ..Default::default()
    };
    let engine = ModelIntersector {
        scale_exp,
        advance: Advance::TriangleBox,
        ..ModelIntersector::new(fp16)
    };
    assert_eq!(
        read_png(&out_png),
        render(&scene, &engine, &opts).unwrap().image
    );
    // fp32 and the f32 engine stay the thesis' renderer.
    let out = ok(&[
        "render",
        "--scene",
        "simple_plane",
        "--width",
        "8",
        "--height",
        "8",
        "--engine",
        "model",
        "--quiet",
        "--out",
        s(&out_png),
    ]);
    assert!(
        out.contains("spawn=thesis scale_exp=0 edges=exact advance=none "),
        "{out}"
    );
}

/// `--edges` and `--advance` reach the model lane: the CLI's image is the library's with the
/// same options.
#[test]
fn render_model_takes_the_lane_options() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("teapot.png");
    let out = ok(&[
        "render",
        "--scene",
        "utah_teapot",
        "--width",
        "32",
        "--height",
        "18",
        "--engine",
        "model",
        "--format",
        "e5m14",
        "--edges",
        "conservative",
        "--advance",
        "none",
        "--quiet",
        "--out",
        s(&out_png),
    ]);
    assert!(out.contains("edges=conservative advance=none "), "{out}");
    let e5m14 = hw_model::lookup("e5m14").unwrap();
    let scene = Scene::load("utah_teapot").unwrap();
    let opts = RenderOptions {
        width: Some(32),
        height: Some(18),
        spawn: spawn_policy(&e5m14, 0),
        ..Default::default()
    };
    let engine = ModelIntersector {
        edges: Edges::Conservative,
        ..ModelIntersector::new(e5m14)
    };
    assert_eq!(
        read_png(&out_png),
        render(&scene, &engine, &opts).unwrap().image
    );
}

#[test]
fn bad_spawn_and_scale_arguments_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let base = [
        "render",
        "--scene",
        "simple_plane",
        "--width",
        "8",
        "--height",
        "8",
    ];
    fails(
        &[&base[..], &["--spawn", "bogus", "--out", s(&out_png)]].concat(),
        2,
        &["bogus", "thesis", "format-aware"],
    );
    fails(
        &[&base[..], &["--scale", "double", "--out", s(&out_png)]].concat(),
        2,
        &["double", "auto", "none"],
    );
    fails(
        &[&base[..], &["--scale", "auto", "--out", s(&out_png)]].concat(),
        1,
        &["--scale auto needs the model or traversal engine"],
    );
    fails(
        &[&base[..], &["--edges", "loose", "--out", s(&out_png)]].concat(),
        2,
        &["loose", "exact", "conservative"],
    );
    fails(
        &[&base[..], &["--advance", "far", "--out", s(&out_png)]].concat(),
        2,
        &["far", "none", "triangle-box", "leaf-box"],
    );
    // The lane options are the model's, leaf-box the traversal unit's: other engines and
    // pairs refuse them.
    for (engine, format, option, says) in [
        (
            "hw",
            "fp16",
            ["--edges", "conservative"],
            "model-only so far",
        ),
        (
            "traversal",
            "fp16",
            ["--advance", "triangle-box"],
            "model-only so far",
        ),
        (
            "traversal",
            "fp16",
            ["--edges", "conservative"],
            "model-only so far",
        ),
        (
            "f32",
            "fp32",
            ["--edges", "conservative"],
            "model-only so far",
        ),
        (
            "model",
            "fp16/fp32",
            ["--advance", "triangle-box"],
            "model-only so far",
        ),
        (
            "hw",
            "fp16",
            ["--advance", "leaf-box"],
            "the traversal unit's",
        ),
        (
            "model",
            "fp16/fp32",
            ["--advance", "leaf-box"],
            "the traversal unit's",
        ),
        (
            "model",
            "fp16",
            ["--advance", "leaf-box"],
            "needs the traversal engine",
        ),
    ] {
        let args = ["--engine", engine, "--format", format, option[0], option[1]];
        fails(
            &[&base[..], &args[..], &["--out", s(&out_png)]].concat(),
            1,
            &[says],
        );
    }
    assert!(!out_png.exists());
}

// ---- formats, verilog ------------------------------------------------------------------

#[test]
fn render_traversal_equals_the_software_image_and_reports_the_units_schedule() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let stdout = ok(&[
        "render",
        "--scene",
        "glass_pen",
        "--width",
        "40",
        "--height",
        "24",
        "--engine",
        "traversal",
        "--slots",
        "16",
        "--out",
        s(&out),
        "--quiet",
    ]);
    assert_eq!(
        read_png(&out),
        library_render("glass_pen", 40, 24, &F32Intersector),
        "an fp32 traversal render is the software image"
    );
    let schedule = last_line(&stdout);
    assert!(
        schedule.starts_with("unit_schedule slots=16 lanes=1 "),
        "{stdout}"
    );
    for key in [
        "cycles_per_ray=",
        "box_tests_per_ray=",
        "mt_tests_per_ray=",
        "box_utilisation=",
        "lane_utilisation=",
    ] {
        assert!(schedule.contains(key), "no {key}: {stdout}");
    }
    // A format without hardware renders through the model but has no lane to time.
    let stdout = ok(&[
        "render",
        "--scene",
        "glass_pen",
        "--width",
        "8",
        "--height",
        "6",
        "--engine",
        "traversal",
        "--format",
        "e8m14",
        "--out",
        s(&out),
        "--quiet",
    ]);
    assert!(!stdout.contains("unit_schedule"), "{stdout}");
    fails(
        &[
            "render",
            "--scene",
            "glass_pen",
            "--engine",
            "traversal",
            "--slots",
            "0",
            "--out",
            s(&out),
        ],
        2,
        &["--slots"],
    );
}

/// A traversal unit with a scene memory smaller than the scene renders in chunked passes
/// (the same image), refuses it with --no-chunks naming both sizes, and a malformed capacity
/// is a usage error.
#[test]
fn render_traversal_with_a_small_scene_memory_chunks_or_names_the_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let base = [
        "render",
        "--scene",
        "utah_teapot",
        "--width",
        "24",
        "--height",
        "16",
        "--engine",
        "traversal",
        "--out",
        s(&out),
        "--quiet",
    ];
    let args = |extra: &[&'static str]| [&base[..], extra].concat();
    let stdout = ok(&args(&["--scene-capacity", "1000,2000"]));
    assert_eq!(
        read_png(&out),
        library_render("utah_teapot", 24, 16, &F32Intersector)
    );
    let memory = stdout
        .lines()
        .find(|l| l.starts_with("unit_memory "))
        .unwrap_or_else(|| panic!("no unit_memory line: {stdout}"));
    let loads: u64 = memory
        .split_whitespace()
        .find_map(|kv| kv.strip_prefix("chunk_loads="))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no chunk_loads: {memory}"));
    assert!(loads >= 4, "a teapot in 1,000-node chunks: {memory}");
    let chunks = ok(&[
        "scene-image",
        "--scene",
        "utah_teapot",
        "--scene-capacity",
        "1000,2000",
    ]);
    assert!(
        chunks.lines().filter(|l| l.starts_with("chunk=")).count() >= 4,
        "{chunks}"
    );
    fails(
        &args(&["--scene-capacity", "2048,4096", "--no-chunks"]),
        1,
        &["nodes and 6,322 triangles; this unit holds 2,048 nodes and 4,096 triangles"],
    );
    fails(
        &args(&["--scene-capacity", "100,1"]),
        1,
        &["holds 100 nodes and 1 triangles; its BVH has a leaf of"],
    );
    fails(
        &args(&["--scene-capacity", "2048"]),
        2,
        &["NODES,TRIANGLES"],
    );
    fails(
        &args(&["--scene-capacity", "2048,-1"]),
        2,
        &["--scene-capacity"],
    );
}

#[test]
fn scene_image_writes_the_words_it_reports() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("teapot.rtsi");
    let stdout = ok(&["scene-image", "--scene", "utah_teapot", "--out", s(&out)]);
    let bytes = std::fs::read(&out).unwrap();
    assert!(
        stdout.contains(&format!("bytes={}", bytes.len())) && stdout.contains("triangles=6322"),
        "{stdout}"
    );
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes(w.try_into().unwrap()))
        .collect();
    let image = hw_model::traversal::scene_image::SceneImage::from_words(&words).unwrap();
    assert_eq!(image.triangles.len(), 6322);
}

#[test]
fn project_traversal_takes_its_cycles_from_the_schedule_model() {
    fails(
        &[
            "project",
            "--scene",
            "simple_plane",
            "--design",
            "traversal",
            "--cycles-per-test",
            "3",
        ],
        1,
        &["--cycles-per-test", "schedule model"],
    );
}

#[test]
fn formats_lists_every_catalogue_format() {
    let out = ok(&["formats"]);
    let rows: Vec<&str> = out
        .lines()
        .filter_map(|l| l.strip_prefix("| "))
        .filter_map(|l| l.split(" |").next())
        .filter(|name| *name != "name" && !name.starts_with('-'))
        .collect();
    let names: Vec<&str> = hw_model::catalogue().iter().map(|f| f.name).collect();
    assert!(names.len() >= 4, "fp32, fp24, bf16, fp16 at least");
    assert_eq!(
        rows, names,
        "rtfpga formats, table rows vs hw_model::catalogue()\n{out}"
    );

    let json: serde_json::Value = serde_json::from_str(&ok(&["formats", "--json"])).unwrap();
    let json_names: Vec<&str> = json
        .as_array()
        .expect("a JSON array")
        .iter()
        .map(|f| f["name"].as_str().expect("a name"))
        .collect();
    assert_eq!(json_names, names, "rtfpga formats --json");
}

#[test]
fn verilog_fp32_d1_l1_equals_the_committed_copy() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("v");
    ok(&[
        "verilog",
        "--format",
        "fp32",
        "--depth",
        "1",
        "--lanes",
        "1",
        "--out",
        s(&out_dir),
    ]);
    let committed = Path::new(REPO).join("generated-verilog/fp32_d1_l1");
    let listing = |d: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let names = listing(&out_dir);
    for needed in ["rtfpga_top.v", "xrtfpga.h"] {
        assert!(
            names.iter().any(|n| n == needed),
            "no {needed} in {names:?}"
        );
    }
    assert_eq!(names, listing(&committed), "files written vs committed");
    for name in &names {
        let (got, want) = (
            std::fs::read(out_dir.join(name)).unwrap(),
            std::fs::read(committed.join(name)).unwrap(),
        );
        assert!(
            got == want,
            "{name} differs from generated-verilog/fp32_d1_l1/{name} (stale: `make verilog`)"
        );
    }
}

// ---- exit codes and messages -----------------------------------------------------------

#[test]
fn usage_errors_exit_2() {
    fails(&["frobnicate"], 2, &["frobnicate"]);
    fails(&["render", "--scene", "simple_plane"], 2, &["--out"]);
    fails(&["render", "--out", "x.png"], 2, &["--scene"]);
    fails(&["compare", "a.png"], 2, &[]);
    fails(
        &[
            "render",
            "--scene",
            "simple_plane",
            "--engine",
            "gpu",
            "--out",
            "x.png",
        ],
        2,
        &["gpu", "f32", "model", "hw"],
    );
    // Help and version are not errors.
    rtfpga()
        .arg("--help")
        .assert()
        .success()
        .stdout(predicate::str::contains("render").and(predicate::str::contains("compare")));
    rtfpga()
        .args(["render", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("--engine"));
}

#[test]
fn missing_scene_paths_and_names_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let missing = dir.path().join("nowhere.toml");
    fails(
        &["render", "--scene", s(&missing), "--out", s(&out_png)],
        1,
        &["nowhere.toml", "cannot read"],
    );
    fails(
        &["render", "--scene", "simple_plain", "--out", s(&out_png)],
        1,
        &["simple_plain", "built-in", "simple_plane"],
    );
    assert!(!out_png.exists(), "no image for a failed render");
}

#[test]
fn unknown_format_names_it_and_points_to_rtfpga_formats() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let render = [
        "render",
        "--scene",
        "simple_plane",
        "--engine",
        "model",
        "--format",
        "fp99",
        "--out",
        s(&out_png),
    ];
    let verilog = ["verilog", "--format", "fp99", "--out", s(dir.path())];
    for args in [&render[..], &verilog[..]] {
        let out = rtfpga().args(args).assert().failure().get_output().clone();
        let code = out.status.code().unwrap();
        assert!(code == 1 || code == 2, "exit code {code}");
        fails(args, code, &["fp99", "rtfpga formats"]);
    }
    assert!(!out_png.exists());
}

#[test]
fn depth_beyond_the_formats_maximum_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("v");
    fails(
        &[
            "verilog",
            "--format",
            "fp32",
            "--depth",
            "99",
            "--out",
            s(&out_dir),
        ],
        1,
        &["depth = 99", "fp32", "depth 0 to"],
    );
    assert!(
        !out_dir.join("rtfpga_top.v").exists(),
        "no Verilog for a refused configuration"
    );
}

#[test]
fn zero_lanes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("v");
    fails(
        &["verilog", "--lanes", "0", "--out", s(&out_dir)],
        1,
        &["lanes = 0", "at least one lane"],
    );
    fails(
        &["verilog", "--lanes", "1000", "--out", s(&out_dir)],
        1,
        &["lanes = 1000", "at most"],
    );
    assert!(!out_dir.join("rtfpga_top.v").exists());
    let out_png = dir.path().join("x.png");
    fails(
        &[
            "render",
            "--scene",
            "simple_plane",
            "--engine",
            "hw",
            "--lanes",
            "0",
            "--out",
            s(&out_png),
        ],
        1,
        &["lanes = 0", "at least one lane"],
    );
}

#[test]
fn zero_and_absurd_image_sizes_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let base = [
        "render",
        "--scene",
        "simple_plane",
        "--out",
        s(&out_png),
        "--quiet",
    ];
    for (flag, value) in [
        ("--width", "0"),
        ("--height", "0"),
        ("--width", "100000"),
        ("--height", "4294967295"),
        ("--width=-3", "-3"),
        ("--width", "wide"),
    ] {
        let args: Vec<&str> = if flag.contains('=') {
            base.iter().copied().chain([flag]).collect()
        } else {
            base.iter().copied().chain([flag, value]).collect()
        };
        let flag = flag.split('=').next().unwrap();
        // clap refuses it (exit 2) before anything is rendered; the timeout of `rtfpga()`
        // catches an absurd size being rendered instead.
        fails(&args, 2, &[value, flag]);
    }
    let args: Vec<&str> = base.iter().copied().chain(["--width", "0"]).collect();
    fails(&args, 2, &["1..=16384"]);
    assert!(!out_png.exists());
    // A scene file asking for 0 pixels is refused at its line.
    let toml = dir.path().join("empty.toml");
    std::fs::write(
        &toml,
        simple_plane_toml().replace("width = 640", "width = 0"),
    )
    .unwrap();
    fails(
        &["render", "--scene", s(&toml), "--out", s(&out_png)],
        1,
        &["empty.toml:7", "at least 1 pixel", "`0`"],
    );
}

#[test]
fn bench_refuses_bad_sizes_before_rendering() {
    for (sizes, needles) in [
        ("32x0", vec!["`32x0`", "1 to 16384"]),
        ("100000x100000", vec!["`100000x100000`", "1 to 16384"]),
        ("32-18", vec!["`32-18`", "WxH"]),
        ("32xtall", vec!["`32xtall`", "height"]),
    ] {
        fails(
            &["bench", "simple_plane", "--repeat", "1", "--sizes", sizes],
            1,
            &needles,
        );
    }
    let out = ok(&["bench", "simple_plane", "--repeat", "1", "--sizes", "16x9"]);
    assert!(out.contains("| simple_plane | 2 | 16×9 |"), "{out}");
}

// ---- malformed scene files ------------------------------------------------------------

fn simple_plane_toml() -> String {
    std::fs::read_to_string(Path::new(REPO).join("scenes/simple_plane.toml")).unwrap()
}

/// Writes `text` with the line starting `old` replaced by `new` to `dir/name`; returns the
/// path and the 1-based number of that line.
fn with_line(dir: &Path, name: &str, text: &str, old: &str, new: &str) -> (PathBuf, usize) {
    let mut number = None;
    let lines: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if number.is_none() && l.trim_start().starts_with(old) {
                number = Some(i + 1);
                new.to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    let number = number.unwrap_or_else(|| panic!("no line starting {old:?}"));
    let path = dir.join(name);
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    (path, number)
}

#[test]
fn malformed_toml_scenes_name_the_file_the_line_and_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("x.png");
    let base = simple_plane_toml();
    // The unbroken copy renders: the failures below are the edits'.
    let good = dir.path().join("good.toml");
    std::fs::write(&good, &base).unwrap();
    ok(&[
        "render",
        "--scene",
        s(&good),
        "--width",
        "8",
        "--height",
        "4",
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    std::fs::remove_file(&out_png).unwrap();

    let cases = [
        (
            "fov.toml",
            "fov =",
            "fov = 200",
            vec!["`200`", "fov", "between 0 and 180"],
        ),
        (
            "key.toml",
            "color =",
            "colour = [0.6, 0.6, 1]",
            vec!["unknown field `colour`", "`color`"],
        ),
        (
            "kind.toml",
            "kind = \"distant\"",
            "kind = \"spot\"",
            vec!["spot", "distant", "point"],
        ),
        ("nan.toml", "intensity =", "intensity = nan", vec!["finite"]),
    ];
    for (name, old, new, needles) in cases {
        let (path, line) = with_line(dir.path(), name, &base, old, new);
        let at = format!("{name}:{line}");
        let mut all = vec![at.as_str()];
        all.extend(needles);
        fails(
            &[
                "render",
                "--scene",
                s(&path),
                "--width",
                "8",
                "--height",
                "4",
                "--out",
                s(&out_png),
            ],
            1,
            &all,
        );
    }
    // A TOML syntax error: the file and a line number at or just after the broken line.
    let (path, line) = with_line(
        dir.path(),
        "syntax.toml",
        &base,
        "height =",
        "height = [360",
    );
    let stderr = fails(
        &["render", "--scene", s(&path), "--out", s(&out_png)],
        1,
        &["syntax.toml:"],
    );
    assert!(
        stderr.contains(&format!("syntax.toml:{line}:"))
            || stderr.contains(&format!("syntax.toml:{}:", line + 1)),
        "{stderr}"
    );
    assert!(!out_png.exists());
}

const SOD: &str = "\
// width height fov
32 18 40
0.2 0.3 0.4
1 0 0 0
0 1 0 0
0 0 1 0
0 5 20 1
0.0001 4
1
0 1 1 1 1
1 0 0 0
0 0 -1 0
0 1 0 0
0 0 0 1
";

const OOD: &str = "\
1 0 0 0
0 1 0 0
0 0 1 0
0 0 0 1
0 1 0.18 0.18 0.18 0.8 0.2 10
";

const GEO: &str = "\
1
4
0 1 2 3
-10 0 10  10 0 10  10 0 -10  -10 0 -10
0 1 0  0 1 0  0 1 0  0 1 0
0 0  1 0  1 1  0 1
";

/// A thesis scene directory with `files` replaced/added, under `parent/name`.
fn thesis_dir(parent: &Path, name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = parent.join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let mut all = vec![
        ("scene.sod", SOD),
        ("objects.txt", "# geometry object\nplane.geo plane.ood\n"),
        ("plane.ood", OOD),
        ("plane.geo", GEO),
    ];
    for (file, text) in files {
        match all.iter_mut().find(|(f, _)| f == file) {
            Some(entry) => entry.1 = text,
            None => all.push((file, text)),
        }
    }
    for (file, text) in all {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

#[test]
fn malformed_thesis_scene_directories_name_the_file_the_line_and_the_token() {
    let tmp = tempfile::tempdir().unwrap();
    let out_png = tmp.path().join("x.png");

    // The well-formed directory renders at its .sod's size.
    let good = thesis_dir(tmp.path(), "good", &[]);
    ok(&[
        "render",
        "--scene",
        s(&good),
        "--out",
        s(&out_png),
        "--quiet",
    ]);
    let img = read_png(&out_png);
    assert_eq!(img.dimensions(), (32, 18), "the .sod's width and height");
    let background = Rgb([51, 77, 102]);
    assert!(
        img.pixels()
            .any(|p| p.0.iter().zip(background.0).any(|(a, b)| a.abs_diff(b) > 2)),
        "the plane is in view"
    );
    std::fs::remove_file(&out_png).unwrap();

    let geo_bad_normal = GEO.replace("0 1 0  0 1 0  0 1 0  0 1 0", "0 1 0  0 one 0  0 1 0  0 1 0");
    let geo_short = GEO.replace("0 0  1 0  1 1  0 1", "0 0  1 0  1 1");
    let ood_bad_kind = OOD.replace("0 1 0.18", "7 1 0.18");
    let sod_bad_fov = SOD.replace("32 18 40", "32 18 200");
    let sod_zero_width = SOD.replace("32 18 40", "0 18 40");
    let cases: Vec<(&str, (&str, &str), Vec<&str>)> = vec![
        (
            "normal",
            ("plane.geo", &geo_bad_normal),
            vec!["plane.geo:5", "`one`", "normal 2 of 4"],
        ),
        (
            "short",
            ("plane.geo", &geo_short),
            vec!["plane.geo:6", "end of file", "texture coordinate 4 of 4"],
        ),
        (
            "material",
            ("plane.ood", &ood_bad_kind),
            vec!["plane.ood:5", "`7`", "material type"],
        ),
        (
            "fov",
            ("scene.sod", &sod_bad_fov),
            vec!["scene.sod:2", "`200`", "fov"],
        ),
        (
            "width",
            ("scene.sod", &sod_zero_width),
            vec!["scene.sod:2", "`0`", "image width"],
        ),
        (
            "list",
            (
                "objects.txt",
                "# geometry object\nplane.geo plane.ood extra\n",
            ),
            vec!["objects.txt:2", "plane.geo plane.ood extra", "2 file names"],
        ),
        (
            "missing_geo",
            ("objects.txt", "plane.geo plane.ood\nnone.geo plane.ood\n"),
            vec!["none.geo", "cannot read"],
        ),
        (
            "empty_list",
            ("objects.txt", "# nothing\n"),
            vec!["objects.txt", "no objects"],
        ),
    ];
    for (name, file, needles) in cases {
        let dir = thesis_dir(tmp.path(), name, &[file]);
        fails(
            &["render", "--scene", s(&dir), "--out", s(&out_png)],
            1,
            &needles,
        );
    }
    // A directory without its .sod.
    let dir = thesis_dir(tmp.path(), "no_sod", &[]);
    std::fs::remove_file(dir.join("scene.sod")).unwrap();
    fails(
        &["render", "--scene", s(&dir), "--out", s(&out_png)],
        1,
        &["no_sod", ".sod"],
    );
    assert!(!out_png.exists());
}

// ---- co-simulation ---------------------------------------------------------------------

#[test]
fn cosim_of_a_small_simple_plane_matches_software() {
    if which("verilator").is_none() {
        writeln!(
            std::io::stderr(),
            "cosim_of_a_small_simple_plane_matches_software: skipped, no verilator on PATH"
        )
        .unwrap();
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("hw.png");
    let mut cmd = rtfpga();
    // A cold model cache builds the Verilated model first.
    cmd.timeout(Duration::from_secs(900));
    let out = cmd
        .args([
            "cosim",
            "--scene",
            "simple_plane",
            "--width",
            "16",
            "--height",
            "9",
            "--format",
            "fp32",
            "--depth",
            "1",
            "--lanes",
            "1",
            "--out",
            s(&out_png),
            "--quiet",
        ])
        .assert()
        .success()
        .get_output()
        .clone();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(last_line(&stdout), "psnr_db=inf", "{stdout}");
    let img = read_png(&out_png);
    assert_eq!(img.dimensions(), (16, 9));
    assert_eq!(img, library_render("simple_plane", 16, 9, &F32Intersector));
}

/// `cosim --spawn` spawns as `render` does, with its default (format-aware for fp16): the
/// image is `render --engine model` with the same format and spawn (the model equals the
/// hardware bit for bit), and the policies differ here, so the option reaches the render.
/// fp16 at depth 1 with one lane is the build cosim_equivalence.rs's fp16 test makes: the
/// shared model cache adds no Verilator build.
#[test]
fn cosim_spawns_as_render_does() {
    if which("verilator").is_none() {
        writeln!(
            std::io::stderr(),
            "cosim_spawns_as_render_does: skipped, no verilator on PATH"
        )
        .unwrap();
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let size = ["--scene", "simple_plane", "--width", "16", "--height", "9"];
    let hw = [
        "--format", "fp16", "--depth", "1", "--lanes", "1", "--quiet",
    ];
    let cosim = |spawn: &[&str]| {
        let out_png = dir.path().join(format!("cosim{}.png", spawn.join("")));
        let mut cmd = rtfpga();
        // A cold model cache builds the Verilated model first.
        cmd.timeout(Duration::from_secs(900));
        let out = cmd
            .arg("cosim")
            .args(size)
            .args(hw)
            .args(spawn)
            .args(["--out", s(&out_png)])
            .assert()
            .success()
            .get_output()
            .clone();
        (String::from_utf8(out.stdout).unwrap(), read_png(&out_png))
    };
    let model = |spawn: &str| {
        let out_png = dir.path().join(format!("model-{spawn}.png"));
        let mut args = vec!["render", "--engine", "model", "--advance", "none"];
        args.extend(size.iter().chain(&hw));
        args.extend(["--spawn", spawn, "--out", s(&out_png)]);
        ok(&args);
        read_png(&out_png)
    };
    let format_aware = model("format-aware");
    let thesis = model("thesis");
    assert_ne!(format_aware, thesis, "the policies render alike here");
    for (spawn, name, want) in [
        (&[][..], "format-aware", &format_aware),
        (&["--spawn", "format-aware"], "format-aware", &format_aware),
        (&["--spawn", "thesis"], "thesis", &thesis),
    ] {
        let (stdout, image) = cosim(spawn);
        assert!(stdout.contains(&format!(" spawn={name} ")), "{stdout}");
        assert!(&image == want, "{spawn:?}: not the model's image\n{stdout}");
    }
}

/// `--spawn` takes a policy's name; anything else is a usage error listing them.
#[test]
fn cosim_spawn_takes_a_policy_name() {
    rtfpga()
        .args(["cosim", "--scene", "simple_plane", "--spawn", "bias"])
        .args(["--out", "never.png"])
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("--spawn")
                .and(predicate::str::contains("thesis"))
                .and(predicate::str::contains("format-aware")),
        );
}

/// `--unit traversal`: the configurations the unit's RTL does not build, and options of the
/// accelerator only, are errors naming what is wrong, before any model is built; a bad
/// `--unit` is a usage error.
#[test]
fn traversal_unit_options_refuse_what_the_rtl_does_not_build() {
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("unit.png");
    let out_dir = dir.path().join("v");
    let cosim = |extra: &[&str]| -> Vec<String> {
        let mut args: Vec<String> = ["cosim", "--unit", "traversal", "--scene", "simple_plane"]
            .map(String::from)
            .to_vec();
        args.extend(extra.iter().map(|x| x.to_string()));
        args.extend(["--out".to_string(), s(&out_png).to_string()]);
        args
    };
    for (extra, needles) in [
        (
            &["--lanes", "4"][..],
            &["4 Möller-Trumbore lanes", "built with 1 to 3"][..],
        ),
        (&["--slots", "16"], &["32 ray slots, not 16"]),
        (
            &["--unit-memory", "100,100"],
            &["7 node and 7 triangle address bits"],
        ),
        (&["--format", "fp16/fp32"], &["model-only"]),
        (&["--mode", "register"], &["options of --unit mt"]),
    ] {
        let args = cosim(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, 1, needles);
    }
    assert!(!out_png.exists());
    fails(
        &[
            "verilog",
            "--unit",
            "traversal",
            "--defaults",
            "--out",
            s(&out_dir),
        ],
        1,
        &["--defaults"],
    );
    fails(
        &[
            "verilog",
            "--unit",
            "traversal",
            "--lanes",
            "4",
            "--out",
            s(&out_dir),
        ],
        1,
        &["4 Möller-Trumbore lanes"],
    );
    assert!(!out_dir.exists());
    fails(
        &["synth", "--unit", "traversal", "--op", "add"],
        1,
        &["--op", "--unit traversal"],
    );
    fails(
        &["synth", "--unit", "traversal", "--lanes", "4"],
        1,
        &["4 Möller-Trumbore lanes", "1 to 3"],
    );
    rtfpga()
        .args([
            "cosim",
            "--unit",
            "bvh",
            "--scene",
            "simple_plane",
            "--out",
            s(&out_png),
        ])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--unit"));
}

/// `verilog --unit traversal` writes the unit's AXI4-Lite top, its C files and a config.json
/// whose ports are the Verilog's, the streams as wide as the packets.
#[test]
fn verilog_of_the_traversal_unit_writes_its_verilog_and_config() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("unit");
    let stdout = ok(&[
        "verilog",
        "--unit",
        "traversal",
        "--depth",
        "2",
        "--out",
        s(&out_dir),
    ]);
    assert!(stdout.contains("4096 nodes and 8192 triangles"), "{stdout}");
    let verilog = std::fs::read_to_string(out_dir.join("traversal_unit.v")).unwrap();
    assert!(verilog.contains("module top"));
    let config: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("config.json")).unwrap())
            .unwrap();
    assert_eq!(config["format"], "fp32");
    assert_eq!(config["depth"], 2);
    assert_eq!(config["memory"]["triangles"], 8192);
    let width = |name: &str| {
        config["ports"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("no port {name} in {config}"))["width"]
            .as_u64()
            .unwrap()
    };
    use hw_model::traversal::packet::{HIT_WORDS, RAY_WORDS};
    assert_eq!(width("ray_tdata"), 32 * RAY_WORDS as u64);
    assert_eq!(width("hit_tdata"), 32 * HIT_WORDS as u64);
    assert_eq!(width("axi$awaddr"), hdl::regmap::ADDR_BITS as u64);
    for name in [
        hdl::cgen::UNIT_HEADER_FILE,
        hdl::cgen::UNIT_DRIVER_HEADER_FILE,
        hdl::cgen::UNIT_DRIVER_SOURCE_FILE,
    ] {
        assert!(out_dir.join(name).is_file(), "no {name}");
    }
}

/// `--advance leaf-box` builds the traversal unit with the leaf advance around its lane
/// (`none`, the default, has none of it); the accelerator and triangle-box are refused.
#[test]
fn verilog_of_the_traversal_unit_with_the_leaf_advance() {
    let dir = tempfile::tempdir().unwrap();
    let unit = |advance: &str| {
        let out_dir = dir.path().join(advance);
        ok(&[
            "verilog",
            "--unit",
            "traversal",
            "--unit-memory",
            "16,32",
            "--advance",
            advance,
            "--out",
            s(&out_dir),
        ]);
        std::fs::read_to_string(out_dir.join("traversal_unit.v")).unwrap()
    };
    assert!(unit("leaf-box").contains("around$0$lane_query"));
    assert!(!unit("none").contains("around"));
    let out = s(dir.path());
    fails(
        &["verilog", "--advance", "leaf-box", "--out", out],
        1,
        &["--advance leaf-box", "--unit traversal"],
    );
    fails(
        &[
            "verilog",
            "--unit",
            "traversal",
            "--advance",
            "triangle-box",
            "--out",
            out,
        ],
        1,
        &["not triangle-box"],
    );
}

/// `cosim --unit traversal` renders through the Verilated unit: its counters per ray, the
/// simulation speed, and the image identical to the software's.
#[test]
fn cosim_of_the_traversal_unit_matches_software() {
    if which("verilator").is_none() {
        writeln!(
            std::io::stderr(),
            "cosim_of_the_traversal_unit_matches_software: skipped, no verilator on PATH"
        )
        .unwrap();
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out_png = dir.path().join("unit.png");
    let mut cmd = rtfpga();
    // A cold model cache builds the Verilated unit first.
    cmd.timeout(Duration::from_secs(1800));
    let out = cmd
        .args([
            "cosim",
            "--unit",
            "traversal",
            "--scene",
            "simple_plane",
            "--width",
            "16",
            "--height",
            "9",
            "--out",
            s(&out_png),
            "--quiet",
        ])
        .assert()
        .success()
        .get_output()
        .clone();
    let stdout = String::from_utf8(out.stdout).unwrap();
    for key in [
        "rays=",
        "cycles=",
        "cycles_per_ray=",
        "box_tests_per_ray=",
        "mt_tests_per_ray=",
        "box_utilisation=",
        "lane_utilisation=",
        "sim_cycles_per_s=",
        "rays_per_s=",
    ] {
        assert!(stdout.contains(key), "no {key} in:\n{stdout}");
    }
    assert_eq!(last_line(&stdout), "psnr_db=inf", "{stdout}");
    assert_eq!(
        read_png(&out_png),
        library_render("simple_plane", 16, 9, &F32Intersector)
    );
}

fn which(tool: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|p| p.join(tool))
            .find(|p| p.is_file())
    })
}

/// Output into a pipe whose reader has gone (`rtfpga … | head`) ends the program by SIGPIPE,
/// as other Unix tools end, not by println! panicking (exit 101).
#[cfg(unix)]
#[test]
fn a_closed_stdout_ends_quietly() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rtfpga"))
        .args(["scene-image", "--scene", "all_materials"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Closed before the scene is loaded and its line printed.
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(13), "{:?}: {stderr}", out.status);
}
