//! `rtfpga project`: the projected frame time, its board constants fitted once on the thesis
//! scenes and stored (needs the thesis scenes: SKIPPED without them).

use crate::common::*;

/// A projection of Simple plane at 32×18.
fn small_projection() -> Run {
    rtfpga(&[
        "project",
        "--scene",
        "simple_plane",
        "--width",
        "32",
        "--height",
        "18",
    ])
}

fn thesis(test: &str) -> bool {
    sw_renderer::thesis_scenes::for_test(&format!("cli::project::{test}")).is_some()
}

/// The first projection fits and stores the constants, saying so on stderr; the next ones
/// use the stored fit (same numbers), `--recalibrate` fits again, and a fit stored by another
/// program is not used.
#[test]
fn the_fit_is_made_once_stored_and_reused() {
    if !thesis("the_fit_is_made_once_stored_and_reused") {
        return;
    }
    let cache = tmp();
    let project = || small_projection().env("RTFPGA_CACHE", cache.path().to_str().unwrap());
    let run = |run: Run| {
        let out = run.command().assert().success().get_output().clone();
        let (stdout, stderr) = (
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        );
        check_lines(&stdout).unwrap();
        (stdout, stderr)
    };
    let (first, said) = run(project());
    assert!(
        said.contains("calibration: fitted on the thesis scenes"),
        "{said}"
    );
    let store = cache.path().join("projection-fit.json");
    assert!(store.is_file(), "{said}");
    let (again, said) = run(project());
    assert!(said.contains("calibration: the fit stored at"), "{said}");
    assert_eq!(again, first, "the stored fit projects the same");
    let (_, said) = run(project().args(&["--recalibrate"]));
    assert!(said.contains("calibration: fitted"), "{said}");
    let text = std::fs::read_to_string(&store).unwrap();
    let program = serde_json::from_str::<serde_json::Value>(&text).unwrap()["program"]
        .as_str()
        .unwrap()
        .to_string();
    std::fs::write(&store, text.replace(&program, "another program")).unwrap();
    let (_, said) = run(project());
    assert!(
        said.contains("calibration: fitted"),
        "another program's fit: {said}"
    );
}

/// The projection prints `key=value` lines (scene, design, rays, the result) and a Markdown
/// table of the terms; the traversal design adds its unit's schedule and memory lines.
#[test]
fn the_projection_is_a_table_and_key_value_lines() {
    if !thesis("the_projection_is_a_table_and_key_value_lines") {
        return;
    }
    let out = small_projection().ok();
    assert!(out.contains("| term | seconds |"), "{out}");
    for (key, want) in [
        ("design", "stream"),
        ("traversal", "bvh"),
        ("size", "32x18"),
    ] {
        assert_eq!(value(&out, key).as_deref(), Some(want), "{out}");
    }
    for key in ["rays", "tests", "total_s", "speedup_vs_arm"] {
        assert!(value(&out, key).is_some(), "no {key}: {out}");
    }
    assert!(
        !out.contains('{') && !out.contains("Stream"),
        "a debug dump: {out}"
    );
    let out = small_projection()
        .args(&["--design", "traversal", "--depth", "5"])
        .ok();
    assert!(
        value(labelled(&out, "unit_schedule"), "cycles_per_ray").is_some(),
        "{out}"
    );
    assert!(
        value(labelled(&out, "unit_memory"), "wavefronts").is_some(),
        "{out}"
    );
}

#[test]
fn the_traversal_design_takes_its_cycles_from_the_schedule_model() {
    rtfpga(&[
        "project",
        "--scene",
        "simple_plane",
        "--design",
        "traversal",
    ])
    .args(&["--cycles-per-test", "3"])
    .fails(1, &["--cycles-per-test does not act on --design traversal"]);
}

/// `--design frame`: the frame schedule model's cycles, no board constants; more shader
/// cores never slower; options of the other designs and impossible units refused.
#[test]
fn the_frame_design_times_a_frame_on_the_planned_frame_unit() {
    let frame = |extra: &[&str]| small_projection().args(&["--design", "frame"]).args(extra);
    let cycles = |cores: &str| {
        let out = frame(&["--shader-cores", cores]).ok();
        check_lines(&out).unwrap();
        let line = labelled(&out, "frame_schedule");
        let fps: f64 = value(line, "fps_at_100mhz").unwrap().parse().unwrap();
        let cycles: f64 = value(line, "frame_cycles").unwrap().parse().unwrap();
        assert!((fps - 1e8 / cycles).abs() < 0.01 * fps, "{out}");
        assert_eq!(value(&out, "primary_rays").as_deref(), Some("576"), "{out}");
        cycles
    };
    assert!(cycles("2") <= cycles("1"));
    frame(&["--hp-ports", "2"]).fails(1, &["--hp-ports does not act on --design frame"]);
    frame(&["--format", "fp16"]).fails(1, &["--format fp16: --design frame takes fp32"]);
    frame(&["--ray-store", "8", "--spawn-reserve", "8"]).fails(
        1,
        &["a ray store of 8 entries with a spawn reserve of 8: it needs at least 9"],
    );
}
