//! The contract every fuzz target checks: a parser returns `Ok` with a consistent value, or an
//! error that names the file and a line that exists in the text, with a non-empty message.
//! It never panics (libFuzzer reports a panic as a crash), never hangs (`-timeout`) and never
//! allocates absurdly (`-rss_limit_mb`, `-malloc_limit_mb`).

use std::path::Path;

use sw_renderer::scene::{Mesh, SceneError};

/// Fuzz inputs are bytes; the loaders read files with `read_to_string`, so non-UTF-8 files
/// never reach the parsers. Lossy decoding lets every input reach them.
pub fn text(data: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(data)
}

/// Lines a 1-based line number may name: the text's lines, or 1 for an empty text.
fn line_count(text: &str) -> usize {
    text.matches('\n').count() + 1
}

/// An error of the thesis token parsers (`.sod`, `.ood`, `.geo`, `objects.txt`): it names
/// `path`, a line of the text, and the token it found there is on that line (or is the end
/// of the file).
pub fn check_thesis_error(text: &str, path: &Path, err: &SceneError) {
    let message = err.to_string();
    assert!(
        message.starts_with(&path.display().to_string()),
        "error does not name the file: {message}"
    );
    match err {
        SceneError::Syntax {
            line, token, what, ..
        } => {
            assert!(
                *line >= 1 && *line <= line_count(text),
                "line {line} outside the text: {message}"
            );
            assert!(!what.is_empty(), "empty message: {message}");
            if token != "end of file" {
                let source_line = text.split('\n').nth(line - 1).unwrap_or("");
                assert!(
                    source_line.contains(token.as_str()),
                    "token `{token}` is not on line {line}: {message}"
                );
            }
        }
        SceneError::Invalid { what, .. } => assert!(!what.is_empty(), "empty message"),
        other => panic!("a parser of text returned a non-parse error: {other}"),
    }
}

/// An error of the TOML scene loader: names the file; a line, when given, is in the text.
/// `.geo` references may fail to read (`Io`, or a `.geo` parse error naming that file).
pub fn check_toml_error(text: &str, path: &Path, err: &SceneError) {
    let message = err.to_string();
    assert!(!message.is_empty());
    match err {
        SceneError::Syntax {
            path: p,
            line,
            what,
            ..
        } => {
            assert!(!what.is_empty(), "empty message: {message}");
            if p == path {
                assert!(
                    *line >= 1 && *line <= line_count(text),
                    "line {line} outside the text: {message}"
                );
            }
        }
        SceneError::Invalid { what, .. } => assert!(!what.is_empty(), "empty message"),
        SceneError::Io { .. } => {}
        SceneError::NotFound { .. } => panic!("load_str looked a scene up by name: {message}"),
    }
}

/// A mesh the renderer can use: every index names a position, one normal and one texture
/// coordinate triple per triangle, every number finite.
pub fn check_mesh(mesh: &Mesh) {
    assert_eq!(mesh.normals.len(), mesh.triangles.len());
    assert_eq!(mesh.uvs.len(), mesh.triangles.len());
    let n = mesh.positions.len();
    for t in &mesh.triangles {
        assert!(
            t.iter().all(|&i| (i as usize) < n),
            "index out of range: {t:?} of {n} positions"
        );
    }
    assert!(
        mesh.positions.iter().all(|p| p.is_finite()),
        "non-finite position"
    );
    assert!(
        mesh.normals.iter().flatten().all(|v| v.is_finite()),
        "non-finite normal"
    );
    assert!(
        mesh.uvs.iter().flatten().all(|v| v.is_finite()),
        "non-finite uv"
    );
}
