//! Inputs found by the fuzz targets of `fuzz/` (`make fuzz`) that broke a parser's contract:
//! `Ok`, or an error naming the file, the line and what was expected; never a panic, a hang or
//! an absurd allocation. Each test fails without its fix.

use std::path::Path;

use sw_renderer::scene::toml_scene::load_str;
use sw_renderer::scene::SceneError;

/// `make fuzz`, target toml_scene: a carriage return not followed by a line feed gave a
/// syntax error with an empty message (the toml crate has none for it).
#[test]
fn toml_scene_stray_carriage_return_is_named() {
    let path = Path::new("dir/stray_cr.toml");
    for (text, line) in [("\r", 1), ("\ra = 1", 1), ("[options]\n\rwidth = 1\n", 2)] {
        let err = load_str(text, path).expect_err("a stray \\r is not TOML");
        let shown = err.to_string();
        match err {
            SceneError::Syntax { line: l, what, .. } => {
                assert_eq!(l, line, "{text:?}: {shown}");
                assert!(what.contains("carriage return"), "{text:?}: {shown}");
            }
            other => panic!("{text:?}: expected a syntax error, got {other}"),
        }
        assert!(
            shown.starts_with(&format!("dir/stray_cr.toml:{line}: ")),
            "{shown}"
        );
    }
}

/// Found while writing the toml_scene fuzz target: `geo = "..."` naming a FIFO (or a device
/// such as `/dev/zero`) made the loader block forever in `open` (or read without end). Only
/// regular files are read now.
#[cfg(unix)]
#[test]
fn toml_scene_geo_naming_a_pipe_is_refused() {
    use std::sync::mpsc;
    use std::time::Duration;

    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("mesh.geo");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("SKIPPED: mkfifo is not available");
        return;
    }
    let text = format!(
        "[options]\nwidth = 4\nheight = 4\nfov = 40\nlook_at = {{ from = [0, 0, 5], to = [0, 0, 0] }}\n\n\
         [[objects]]\nname = \"pipe\"\nmaterial = {{ kind = \"diffuse\" }}\ngeo = {:?}\n",
        fifo.display().to_string()
    );
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let result = load_str(&text, Path::new("dir/pipe.toml")).map(|_| ());
        send.send(result.map_err(|e| e.to_string())).ok();
    });
    let result = receive
        .recv_timeout(Duration::from_secs(20))
        .expect("loading a scene whose geo names a FIFO blocked for 20 s");
    let err = result.expect_err("a FIFO is not a mesh file");
    assert!(err.contains("not a regular file"), "{err}");
    assert!(err.starts_with("dir/pipe.toml:10: "), "{err}");
}

/// The scene file itself named as a FIFO blocked in `open` too (the same fix covers it).
#[cfg(unix)]
#[test]
fn a_toml_scene_that_is_a_pipe_is_refused() {
    use std::sync::mpsc;
    use std::time::Duration;

    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("scene.toml");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo (coreutils) failed");
    let spec = fifo.display().to_string();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let result = sw_renderer::scene::Scene::load(&spec).map(|_| ());
        send.send(result.map_err(|e| e.to_string())).ok();
    });
    let err = receive
        .recv_timeout(Duration::from_secs(20))
        .expect("loading a FIFO as a scene blocked for 20 s")
        .expect_err("a FIFO is not a scene file");
    assert!(err.contains("not a regular file"), "{err}");
    assert!(err.contains("scene.toml"), "{err}");
}
