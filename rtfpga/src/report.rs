//! What the subcommands print and write, the same way everywhere: `key=value` lines that
//! split alike ([`Line`]), output paths checked before any work ([`image_out`],
//! [`file_out`]), and a spinner on stderr for slow external tools ([`spinner`]).

use std::fmt::{self, Display, Write as _};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// One output line: an optional label word, then `key=value` fields separated by spaces. A
/// value that is empty or holds a space, a double quote, a backslash or an `=` is written in
/// double quotes with `"` and `\` escaped by a backslash, so every line splits as a shell
/// splits words (Python's `shlex.split`).
#[derive(Clone, Debug, Default)]
pub struct Line(String);

impl Line {
    /// A line of fields only.
    pub fn new() -> Line {
        Line::default()
    }

    /// A line starting with the word `label` (e.g. `unit_memory`).
    pub fn labelled(label: &str) -> Line {
        Line(label.to_string())
    }

    /// Adds `key=value`.
    pub fn kv(mut self, key: &str, value: impl Display) -> Line {
        if !self.0.is_empty() {
            self.0.push(' ');
        }
        let value = value.to_string();
        let plain = !value.is_empty()
            && !value
                .chars()
                .any(|c| c.is_whitespace() || matches!(c, '"' | '\\' | '=' | '\''));
        if plain {
            let _ = write!(self.0, "{key}={value}");
        } else {
            let escaped = value.replace('\\', "\\\\").replace('"', "\\\"");
            let _ = write!(self.0, "{key}=\"{escaped}\"");
        }
        self
    }

    /// Adds `key=x` with `digits` decimals.
    pub fn fixed(self, key: &str, x: f64, digits: usize) -> Line {
        self.kv(key, format_args!("{x:.digits$}"))
    }

    /// Adds `key=<path>` as an absolute path.
    pub fn path(self, key: &str, path: &Path) -> Line {
        self.kv(key, absolute(path).display())
    }

    pub fn print(&self) {
        println!("{self}");
    }
}

impl Display for Line {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// `p` made absolute against the working directory (not resolving links), for output lines.
pub fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// A PSNR as printed: `inf` for identical images, else 4 decimals.
pub fn psnr(db: f64) -> String {
    if db.is_infinite() {
        "inf".to_string()
    } else {
        format!("{db:.4}")
    }
}

/// An image a command will write to `path` (given as `option`): it must end in `.png` (the
/// images are PNG; another extension would silently hold PNG data), and its folder is
/// created now, before any rendering or simulation.
pub fn image_out(option: &str, path: &Path) -> Result<()> {
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        bail!(
            "{option} {}: images are written as PNG; give a path ending in .png",
            path.display()
        );
    }
    file_out(path)
}

/// A file a command will write to `path`: its folder is created now (before any work), and
/// `path` must not be a folder.
pub fn file_out(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!("{}: is a folder, not a file to write", path.display());
    }
    dir_out(path.parent().unwrap_or(Path::new("")))
}

/// A folder a command will write into: created now, with its parents.
pub fn dir_out(dir: &Path) -> Result<()> {
    if dir.as_os_str().is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("creating the folder {}", dir.display()))
}

/// Runs `work` behind a spinner on stderr that says `what` and the time spent (nothing when
/// stderr is not a terminal: the caller prints the result), and returns what it returned
/// and how long it took.
pub fn spinner<T>(what: &str, work: impl FnOnce() -> T) -> (T, Duration) {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} [{elapsed}]") {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    bar.enable_steady_tick(Duration::from_millis(120));
    let start = Instant::now();
    let out = work();
    bar.finish_and_clear();
    (out, start.elapsed())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_with_spaces_quotes_or_equals_are_quoted() {
        let line = Line::labelled("verilated")
            .kv("engine", "hw fp32 d1 l1 stream")
            .kv("cache", "hit")
            .kv("empty", "")
            .kv("odd", r#"a "b" \c=d"#)
            .fixed("build_s", 1.23456, 2);
        assert_eq!(
            line.to_string(),
            r#"verilated engine="hw fp32 d1 l1 stream" cache=hit empty="" odd="a \"b\" \\c=d" build_s=1.23"#
        );
        assert_eq!(Line::new().kv("a", 1).kv("b", "x").to_string(), "a=1 b=x");
    }

    #[test]
    fn only_png_images_and_folders_are_made_before_work() {
        let dir = tempfile::tempdir().unwrap();
        let jpg = dir.path().join("new/x.jpg");
        let e = image_out("--out", &jpg).unwrap_err().to_string();
        assert!(e.contains("x.jpg") && e.contains(".png"), "{e}");
        assert!(
            !dir.path().join("new").exists(),
            "nothing made for a refused path"
        );
        image_out("--out", &dir.path().join("new/deeper/x.PNG")).unwrap();
        assert!(dir.path().join("new/deeper").is_dir());
        let e = file_out(dir.path()).unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
    }
}
