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
