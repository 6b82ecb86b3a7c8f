//! Usage errors (exit 2), help and version, missing scenes and formats, a closed stdout.

use predicates::prelude::*;

use crate::common::*;

#[test]
fn usage_errors_exit_2() {
    rtfpga(&["frobnicate"]).fails(2, &["frobnicate"]);
    rtfpga(&["render", "--scene", "simple_plane"]).fails(2, &["--out"]);
    rtfpga(&["render", "--out", "x.png"]).fails(2, &["--scene"]);
    rtfpga(&["compare", "a.png"]).fails(2, &[]);
    rtfpga(&[
        "render",
        "--scene",
        "simple_plane",
        "--engine",
        "gpu",
        "--out",
        "x.png",
    ])
    .fails(2, &["gpu", "f32", "model", "hw", "traversal"]);
}

#[test]
fn help_and_version_are_not_errors() {
    rtfpga(&["--help"])
        .command()
        .assert()
        .success()
        .stdout(predicate::str::contains("render").and(predicate::str::contains("compare")));
    rtfpga(&["render", "--help"])
        .command()
        .assert()
        .success()
        .stdout(predicate::str::contains("--engine"));
    rtfpga(&["--version"])
        .command()
        .assert()
        .success()
        .stdout(predicate::str::starts_with("rtfpga "));
}

#[test]
fn missing_scene_paths_and_names_are_reported() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let missing = at(&dir, "nowhere.toml");
    rtfpga(&["render", "--scene", s(&missing)])
        .out(&png)
        .fails(1, &["nowhere.toml", "cannot read"]);
    rtfpga(&["render", "--scene", "simple_plain"])
        .out(&png)
        .fails(1, &["simple_plain", "built-in", "simple_plane"]);
    assert!(!png.exists(), "no image for a failed render");
}

#[test]
fn an_unknown_format_names_it_and_points_to_rtfpga_formats() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    rtfpga(&[
        "render",
        "--scene",
        "simple_plane",
        "--engine",
        "model",
        "--format",
        "fp99",
    ])
    .out(&png)
    .fails(2, &["fp99", "rtfpga formats"]);
    rtfpga(&["verilog", "--format", "fp99"])
        .out(dir.path())
        .fails(2, &["fp99", "rtfpga formats"]);
    assert!(!png.exists());
}

#[test]
fn bench_refuses_bad_sizes_before_rendering() {
    for (sizes, needles) in [
        ("32x0", vec!["`32x0`", "1 to 16384"]),
        ("100000x100000", vec!["`100000x100000`", "1 to 16384"]),
        ("32-18", vec!["`32-18`", "WxH"]),
        ("32xtall", vec!["`32xtall`", "height"]),
    ] {
        rtfpga(&["bench", "simple_plane", "--repeat", "1", "--sizes", sizes]).fails(1, &needles);
    }
    let out = rtfpga(&["bench", "simple_plane", "--repeat", "1", "--sizes", "16x9"]).ok();
    assert!(out.contains("| simple_plane | 2 | 16×9 |"), "{out}");
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
