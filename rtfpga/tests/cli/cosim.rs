//! `rtfpga cosim` through Verilator (each test prints SKIPPED without it): the image is the
//! software's or the bit-accurate model's, the build says whether the cache had the model,
//! and an interrupted build leaves nothing in the cache.

use sw_renderer::intersect::F32Intersector;

use crate::common::*;

#[test]
fn the_accelerator_renders_the_software_image() {
    if !needs(
        "verilator",
        "cosim::the_accelerator_renders_the_software_image",
    ) {
        return;
    }
    let dir = tmp();
    let png = at(&dir, "hw.png");
    let out = cosim("simple_plane", 16, 9, &png)
        .args(&["--format", "fp32", "--depth", "1", "--lanes", "1"])
        .ok();
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    let verilated = labelled(&out, "verilated");
    assert_eq!(
        value(verilated, "engine").as_deref(),
        Some("hw fp32 d1 l1 stream")
    );
    assert!(
        matches!(value(verilated, "cache").as_deref(), Some("hit" | "miss")),
        "{verilated}"
    );
    assert_eq!(value(&out, "out").as_deref(), Some(s(&png)), "{out}");
    assert_eq!(
        read_png(&png),
        library_render("simple_plane", 16, 9, &F32Intersector)
    );
}

/// `cosim --spawn` spawns as `render` does, with its default (format-aware for fp16): the
/// image is `render --engine model` with the same format and spawn (the model equals the
/// hardware bit for bit), and the policies differ here, so the option reaches the render.
/// fp16 at depth 1 with one lane is the build cosim_equivalence.rs's fp16 test makes: the
/// shared model cache adds no Verilator build.
#[test]
fn the_accelerator_spawns_as_render_does() {
    if !needs("verilator", "cosim::the_accelerator_spawns_as_render_does") {
        return;
    }
    let dir = tmp();
    let hw = ["--format", "fp16", "--depth", "1", "--lanes", "1"];
    let model = |spawn: &str| {
        let png = at(&dir, &format!("model-{spawn}.png"));
        render("simple_plane", 16, 9, &png)
            .args(&["--engine", "model", "--format", "fp16", "--advance", "none"])
            .args(&["--spawn", spawn])
            .ok();
        read_png(&png)
    };
    let (format_aware, thesis) = (model("format-aware"), model("thesis"));
    assert_ne!(format_aware, thesis, "the policies render alike here");
    for (spawn, name, want) in [
        (&[][..], "format-aware", &format_aware),
        (&["--spawn", "format-aware"], "format-aware", &format_aware),
        (&["--spawn", "thesis"], "thesis", &thesis),
    ] {
        let png = at(&dir, &format!("cosim{}.png", spawn.join("")));
        let out = cosim("simple_plane", 16, 9, &png)
            .args(&hw)
            .args(spawn)
            .ok();
        assert_eq!(value(&out, "spawn").as_deref(), Some(name), "{out}");
        assert!(
            &read_png(&png) == want,
            "{spawn:?}: not the model's image\n{out}"
        );
    }
}

/// The pair built in hardware, bfp18/fp32, co-simulates: the image is fp32's (PSNR inf
/// against the software render) and the forwarded share is printed.
#[test]
fn the_hardware_pair_renders_as_fp32() {
    if !needs("verilator", "cosim::the_hardware_pair_renders_as_fp32") {
        return;
    }
    let dir = tmp();
    let png = at(&dir, "pair.png");
    let out = cosim("simple_plane", 12, 8, &png)
        .args(&["--format", "bfp18/fp32", "--lanes", "2", "--depth", "1"])
        .ok();
    assert_eq!(
        value(&out, "engine").as_deref(),
        Some("hw bfp18/fp32 pair s2 d1"),
        "{out}"
    );
    assert!(
        value(&out, "forwarded_share").unwrap().starts_with("0."),
        "{out}"
    );
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    assert_eq!(read_png(&png).dimensions(), (12, 8));
}

/// `cosim --unit traversal` renders through the Verilated unit: its counters per ray, the
/// simulation speed, and the image identical to the software's.
#[test]
fn the_traversal_unit_renders_the_software_image() {
    if !needs(
        "verilator",
        "cosim::the_traversal_unit_renders_the_software_image",
    ) {
        return;
    }
    let dir = tmp();
    let png = at(&dir, "unit.png");
    let out = cosim("simple_plane", 16, 9, &png)
        .args(&["--unit", "traversal"])
        .ok();
    for key in [
        "rays",
        "cycles",
        "cycles_per_ray",
        "box_tests_per_ray",
        "mt_tests_per_ray",
        "box_utilisation",
        "lane_utilisation",
        "sim_cycles_per_s",
        "rays_per_s",
    ] {
        assert!(value(&out, key).is_some(), "no {key} in:\n{out}");
    }
    assert_eq!(
        value(labelled(&out, "verilated"), "engine").as_deref(),
        Some("hw traversal fp32 d1 l1")
    );
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    assert_eq!(
        read_png(&png),
        library_render("simple_plane", 16, 9, &F32Intersector)
    );
}

/// A build into an empty cache reports on stderr while it runs (`building …`, a line when
/// stderr is not a terminal) and `cache=miss`; interrupted (Ctrl-C) it exits 130 and leaves
/// no temporary folder in the cache.
#[cfg(unix)]
#[test]
fn an_interrupted_build_leaves_nothing_in_the_cache() {
    if !needs(
        "verilator",
        "cosim::an_interrupted_build_leaves_nothing_in_the_cache",
    ) {
        return;
    }
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let cache = tmp();
    let dir = tmp();
    let png = at(&dir, "x.png");
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("rtfpga"))
        .args([
            "cosim",
            "--scene",
            "simple_plane",
            "--width",
            "4",
            "--height",
            "4",
        ])
        .args(["--out", s(&png), "--quiet"])
        .env("RTFPGA_CACHE", cache.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Interrupt once the build has its temporary folder (the runtime's, then the model's).
    let started = Instant::now();
    let building = || {
        std::fs::read_dir(cache.path())
            .map(|d| {
                d.flatten()
                    .any(|e| e.file_name().to_string_lossy().starts_with(".tmp-"))
            })
            .unwrap_or(false)
    };
    while !building() {
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no build started"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // SAFETY: signalling the child process this test started, by its id.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("building the Verilated model"), "{stderr}");
    let left: Vec<String> = std::fs::read_dir(cache.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tmp-"))
        .collect();
    assert!(left.is_empty(), "left in the cache: {left:?}");
    assert!(!png.exists());
}
