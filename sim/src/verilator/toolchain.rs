//! Finding and running the external tools: `verilator` and the C++ compiler.

use crate::SimError;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The C++ compilers a model is built with when none is named, the first found on the search
/// path: clang++'s code of a Verilated model runs about a quarter faster than g++'s (the
/// traversal unit on Utah teapot, BENCHMARKS "Traversal unit, co-simulated"); g++ is what
/// Verilator's own makefiles use.
pub const CXX_PREFERENCE: [&str; 2] = ["clang++", "g++"];

/// How many lines of a failing tool's output go into an error.
const ERROR_LINES: usize = 30;

/// The located tools and what the build needs to know about them.
#[derive(Clone, Debug)]
pub struct Toolchain {
    pub verilator: PathBuf,
    pub cxx: PathBuf,
    /// `$VERILATOR_ROOT/include`.
    pub include: PathBuf,
    /// First lines of `verilator --version` and `c++ --version`, for the cache key.
    pub versions: String,
}

/// Looks `name` up in the directories of `path_var` (a PATH-style list).
pub fn find_on_path(name: &str, path_var: Option<&OsString>) -> Option<PathBuf> {
    let candidate = Path::new(name);
    if candidate.components().count() > 1 {
        return candidate.is_file().then(|| candidate.to_path_buf());
    }
    std::env::split_paths(path_var?)
        .map(|dir| dir.join(name))
        .find(|p| is_executable(p))
}

#[cfg(unix)]
fn is_executable(p: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt;
    p.metadata()
        .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
}

#[cfg(not(unix))]
fn is_executable(p: &Path) -> bool {
    p.is_file()
}

fn locate(name: &str, package: &str, path_var: Option<&OsString>) -> Result<PathBuf, SimError> {
    find_on_path(name, path_var).ok_or_else(|| SimError::ToolNotFound {
        tool: name.to_string(),
        package: package.to_string(),
    })
}

/// The first `ERROR_LINES` lines of a process's stderr and stdout, error lines first (so that
/// a long list of warnings cannot hide the error).
fn first_lines(out: &std::process::Output) -> String {
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout)
    );
    let mut lines: Vec<&str> = text.lines().collect();
    lines.sort_by_key(|l| !l.to_ascii_lowercase().contains("error"));
    let mut shown = lines[..lines.len().min(ERROR_LINES)].join("\n");
    if lines.len() > ERROR_LINES {
        shown.push_str(&format!("\n… ({} more lines)", lines.len() - ERROR_LINES));
    }
    shown
}

/// Runs `cmd` with no standard input; a non-zero exit becomes `SimError::ToolFailed`.
pub fn run(mut cmd: Command, tool: &str, what: &str) -> Result<std::process::Output, SimError> {
    let out = cmd
        .stdin(Stdio::null())
        .output()
        .map_err(|e| SimError::ToolFailed {
            tool: tool.into(),
            what: what.into(),
            output: e.to_string(),
        })?;
    if out.status.success() {
        Ok(out)
    } else {
        Err(SimError::ToolFailed {
            tool: tool.into(),
            what: format!("{what}, {}", out.status),
            output: first_lines(&out),
        })
    }
}

fn first_line_of(path: &Path, tool: &str, args: &[&str]) -> Result<String, SimError> {
    let mut cmd = Command::new(path);
    cmd.args(args);
    let out = run(cmd, tool, &args.join(" "))?;
    Ok(String::from_utf8_lossy(&out.stdout)
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .to_string())
}

impl Toolchain {
    /// Finds `verilator` and `cxx` (`None`: the first of [`CXX_PREFERENCE`]) on `path_var` and
    /// asks Verilator where its runtime is.
    pub fn locate(
        verilator: &str,
        cxx: Option<&str>,
        path_var: Option<&OsString>,
    ) -> Result<Self, SimError> {
        let verilator = locate(verilator, "verilator", path_var)?;
        let cxx = match cxx {
            Some(name) => locate(name, "g++", path_var)?,
            None => match CXX_PREFERENCE
                .iter()
                .find_map(|n| find_on_path(n, path_var))
            {
                Some(found) => found,
                None => locate(CXX_PREFERENCE[1], "g++", path_var)?,
            },
        };
        let root = first_line_of(&verilator, "verilator", &["--getenv", "VERILATOR_ROOT"])?;
        let include = PathBuf::from(root).join("include");
        if !include.join("verilated.cpp").is_file() {
            return Err(SimError::ToolFailed {
                tool: "verilator".into(),
                what: "locating its runtime".into(),
                output: format!("{} has no verilated.cpp", include.display()),
            });
        }
        let versions = format!(
            "{}\n{}",
            first_line_of(&verilator, "verilator", &["--version"])?,
            first_line_of(&cxx, "c++ compiler", &["--version"])?
        );
        Ok(Toolchain {
            verilator,
            cxx,
            include,
            versions,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_tool_gives_install_hint() {
        let empty = OsString::from("/nonexistent-dir-for-rtfpga-test");
        let err = Toolchain::locate("verilator", None, Some(&empty))
            .unwrap_err()
            .to_string();
        assert_eq!(err, "verilator not found on PATH: install it with `apt-get install verilator` (or run `make setup`)");
    }

    /// A directory of stand-in tools (shell scripts printing a version line; Verilator's
    /// root with a runtime beside them) holding `compilers`.
    #[cfg(unix)]
    fn stand_in_tools(compilers: &[&str]) -> tempfile::TempDir {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("include")).unwrap();
        std::fs::write(dir.path().join("include/verilated.cpp"), "").unwrap();
        let root = dir.path().display();
        let verilator =
            format!("#!/bin/sh\n[ \"$1\" = --getenv ] && echo {root} || echo Verilator 5\n");
        let tools = [("verilator", verilator)].into_iter().chain(
            compilers
                .iter()
                .map(|c| (*c, format!("#!/bin/sh\necho {c} 1\n"))),
        );
        for (name, script) in tools {
            let path = dir.path().join(name);
            std::fs::write(&path, script).unwrap();
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
        }
        dir
    }

    #[cfg(unix)]
    #[test]
    fn the_compiler_is_clang_when_there_else_gcc() {
        for (present, chosen) in [
            (&["g++", "clang++"][..], "clang++"),
            (&["g++"][..], "g++"),
            (&["clang++"][..], "clang++"),
        ] {
            let dir = stand_in_tools(present);
            let path = OsString::from(dir.path());
            let tools = Toolchain::locate("verilator", None, Some(&path)).unwrap();
            assert_eq!(tools.cxx, dir.path().join(chosen), "{present:?}");
            assert!(
                tools.versions.ends_with(&format!("{chosen} 1")),
                "{}",
                tools.versions
            );
        }
        let dir = stand_in_tools(&[]);
        let err = Toolchain::locate("verilator", None, Some(&OsString::from(dir.path())))
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("g++ not found on PATH"), "{err}");
    }

    #[test]
    fn finds_sh_on_the_real_path() {
        let path = std::env::var_os("PATH");
        assert!(find_on_path("sh", path.as_ref()).is_some());
        assert!(find_on_path("no-such-tool-rtfpga", path.as_ref()).is_none());
    }

    #[test]
    fn failing_tool_output_is_shown() {
        let mut cmd = Command::new("sh");
        cmd.args(["-c", "echo first; echo '%Error: oops' >&2; exit 3"]);
        let err = run(cmd, "sh", "a test").unwrap_err().to_string();
        assert!(err.contains("a test") && err.contains("first"), "{err}");
        assert!(
            err.find("%Error: oops") < err.find("first"),
            "error lines come first: {err}"
        );
    }
}
