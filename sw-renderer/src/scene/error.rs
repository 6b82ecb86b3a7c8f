//! Errors of scene loading: every one names the file, the place in it and what was expected.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum SceneError {
    #[error(
        "{spec}: no such scene directory, .toml file or built-in scene (built-ins: {builtins})"
    )]
    NotFound { spec: String, builtins: String },
    #[error("{}: cannot read: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A problem at a place in a file: `line` is 1-based, `token` what was found there.
    #[error("{}:{line}: {what} (found `{token}`)", path.display())]
    Syntax {
        path: PathBuf,
        line: usize,
        token: String,
        what: String,
    },
    /// A problem with the file as a whole (missing entries, inconsistent counts, …).
    #[error("{}: {what}", path.display())]
    Invalid { path: PathBuf, what: String },
}
