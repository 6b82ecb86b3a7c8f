//! Errors of the simulation crate.

use std::path::PathBuf;

/// Everything that can go wrong while building, loading or driving a simulated model.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A tool the builder needs is not on PATH.
    #[error("{tool} not found on PATH: install it with `apt-get install {package}` (or run `make setup`)")]
    ToolNotFound { tool: String, package: String },

    /// A tool ran but failed; `output` holds the first lines of what it printed.
    #[error("{tool} failed ({what}):\n{output}")]
    ToolFailed {
        tool: String,
        what: String,
        output: String,
    },

    /// The Verilog's port declarations could not be understood.
    #[error("Verilog ports of module `{module}`, line {line}: {message}")]
    Ports {
        module: String,
        line: usize,
        message: String,
    },

    /// The model's port list does not fit what the caller asked for.
    #[error("model interface: {0}")]
    Interface(String),

    /// A file or directory operation failed.
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },

    /// The built shared object could not be loaded or lacks a symbol.
    #[error("loading {path}: {source}")]
    Load {
        path: PathBuf,
        source: libloading::Error,
    },
}

impl SimError {
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        SimError::Io {
            path: path.into(),
            source,
        }
    }
}
