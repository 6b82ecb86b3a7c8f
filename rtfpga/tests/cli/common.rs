//! What the CLI tests share: the binary run as a user runs it ([`Run`], with a timeout and
//! the checks every run makes), argument builders, the one guard for an external tool
//! ([`needs`]) and the one parser of output lines ([`fields`]).

use std::path::{Path, PathBuf};
use std::time::Duration;

use image::RgbImage;
use sw_renderer::rays::RayEngine;
use sw_renderer::render::{render as library, RenderOptions};
use sw_renderer::scene::Scene;

pub const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// A command line of `rtfpga`.
#[derive(Clone, Debug)]
pub struct Run {
    args: Vec<String>,
    envs: Vec<(String, String)>,
    timeout: Duration,
}

/// `rtfpga args…`: a command that should answer at once gets 120 s (it must not render for
/// hours instead of refusing its input).
pub fn rtfpga(args: &[&str]) -> Run {
    Run {
        args: args.iter().map(|a| a.to_string()).collect(),
        envs: Vec::new(),
        timeout: Duration::from_secs(120),
    }
}

/// `rtfpga render --scene SCENE --width W --height H --out OUT --quiet`.
pub fn render(scene: &str, w: u32, h: u32, out: &Path) -> Run {
    rtfpga(&["render", "--scene", scene, "--quiet"])
        .size(w, h)
        .out(out)
}

/// `rtfpga cosim --scene SCENE --width W --height H --out OUT --quiet`, allowed a cold
/// Verilator build.
pub fn cosim(scene: &str, w: u32, h: u32, out: &Path) -> Run {
    rtfpga(&["cosim", "--scene", scene, "--quiet"])
        .size(w, h)
        .out(out)
        .cold_build()
}

impl Run {
    pub fn args(mut self, args: &[&str]) -> Run {
        self.args.extend(args.iter().map(|a| a.to_string()));
        self
    }

    pub fn size(self, w: u32, h: u32) -> Run {
        self.args(&["--width", &w.to_string(), "--height", &h.to_string()])
    }

    pub fn out(self, path: &Path) -> Run {
        self.args(&["--out", s(path)])
    }

    pub fn env(mut self, key: &str, value: &str) -> Run {
        self.envs.push((key.into(), value.into()));
        self
    }

    /// A cold model cache builds the Verilated model first: minutes, not seconds.
    pub fn cold_build(mut self) -> Run {
        self.timeout = Duration::from_secs(1800);
        self
    }

    pub fn command(&self) -> assert_cmd::Command {
        let mut cmd = assert_cmd::Command::cargo_bin("rtfpga").expect("the rtfpga binary");
        cmd.args(&self.args).timeout(self.timeout);
        for (k, v) in &self.envs {
            cmd.env(k, v);
        }
        cmd
    }

    fn shown(&self) -> String {
        format!("rtfpga {}", self.args.join(" "))
    }

    /// Runs it, asserts exit code 0 and that every output line parses ([`check_lines`]);
    /// returns stdout.
    pub fn ok(&self) -> String {
        let out = self.command().assert().success().get_output().clone();
        let stdout = String::from_utf8(out.stdout).expect("stdout is UTF-8");
        check_lines(&stdout).unwrap_or_else(|e| panic!("`{}`: {e}\n{stdout}", self.shown()));
        stdout
    }

    /// Runs it, asserts exit `code` and a message on stderr starting `error:` containing each
    /// of `needles`; returns stderr. An error the program reports (code 1) is one message
    /// saying each thing once, after no result on stdout, and never a panic.
    pub fn fails(&self, code: i32, needles: &[&str]) -> String {
        let out = self.command().assert().code(code).get_output().clone();
        let stderr = String::from_utf8(out.stderr).expect("stderr is UTF-8");
        let shown = self.shown();
        assert!(
            stderr.starts_with("error:"),
            "`{shown}`: stderr does not start with `error:`:\n{stderr}"
        );
        for needle in needles {
            assert!(
                stderr.contains(needle),
                "`{shown}`: stderr does not mention `{needle}`:\n{stderr}"
            );
        }
        if code == 1 {
            assert!(!stderr.contains("panicked"), "{stderr}");
            let parts: Vec<&str> = stderr.trim_end().split(": ").collect();
            for (i, part) in parts.iter().enumerate() {
                assert!(
                    !parts[i + 1..].contains(part),
                    "`{shown}`: `{part}` said twice:\n{stderr}"
                );
            }
            assert!(
                out.stdout.is_empty(),
                "`{shown}` printed results before failing:\n{}",
                String::from_utf8_lossy(&out.stdout)
            );
        }
        stderr
    }
}

/// The guard of a test that needs an external tool: true when `tool` is on PATH, else false
/// after printing `SKIPPED <test>: …` (the project's convention for a test that cannot run
/// here; CI installs the tools).
pub fn needs(tool: &str, test: &str) -> bool {
    let found = std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|p| p.join(tool).is_file()));
    if !found {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED {test}: no {tool} on PATH (`make setup` installs it)"
        );
    }
    found
}

pub fn s(p: &Path) -> &str {
    p.to_str().expect("temporary paths are UTF-8")
}

/// Splits `line` as a POSIX shell splits words with double quotes (the quoting of
/// `rtfpga`'s output lines): `None` when a quote is left open.
pub fn split(line: &str) -> Option<Vec<String>> {
    let (mut words, mut word, mut quoted, mut in_word) = (Vec::new(), String::new(), false, false);
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                quoted = !quoted;
                in_word = true;
            }
            '\\' if quoted => word.push(chars.next()?),
            c if c.is_whitespace() && !quoted => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            c => {
                word.push(c);
                in_word = true;
            }
        }
    }
    if quoted {
        return None;
    }
    if in_word {
        words.push(word);
    }
    Some(words)
}

/// A parsed `key=value` line: its label word (if it has one) and its fields in order.
pub type Fields = (Option<String>, Vec<(String, String)>);

/// A `key=value` line: its label word (if it has one) and its fields; an error unless every
/// word after the label is `key=value` with a lowercase key.
pub fn fields(line: &str) -> Result<Fields, String> {
    let words = split(line).ok_or_else(|| format!("unbalanced quote in {line:?}"))?;
    let mut label = None;
    let mut out = Vec::new();
    for (i, word) in words.iter().enumerate() {
        match word.split_once('=') {
            Some((k, v))
                if !k.is_empty()
                    && k.chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_') =>
            {
                out.push((k.to_string(), v.to_string()))
            }
            None if i == 0 && word.chars().all(|c| c.is_ascii_lowercase() || c == '_') => {
                label = Some(word.clone())
            }
            _ => return Err(format!("{word:?} is not key=value in {line:?}")),
        }
    }
    Ok((label, out))
}

/// Every `key=value` line of `stdout` (one whose first word, or second after a label word,
/// is `key=…`) parses whole: prose, tables and JSON are left alone.
pub fn check_lines(stdout: &str) -> Result<(), String> {
    let is_key = |w: &str| {
        w.split_once('=').is_some_and(|(k, _)| {
            !k.is_empty()
                && k.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        })
    };
    for line in stdout.lines() {
        let mut words = line.split(' ');
        let first = words.next().unwrap_or("");
        let label = first.chars().all(|c| c.is_ascii_lowercase() || c == '_');
        if is_key(first) || (label && words.next().is_some_and(is_key)) {
            fields(line)?;
        }
    }
    Ok(())
}

/// The value of `key` in the first line of `stdout` that has it.
pub fn value(stdout: &str, key: &str) -> Option<String> {
    stdout.lines().find_map(|line| {
        let (_, kv) = fields(line).ok()?;
        kv.into_iter().find(|(k, _)| k == key).map(|(_, v)| v)
    })
}

/// The line of `stdout` labelled `label` (e.g. `unit_memory`).
pub fn labelled<'a>(stdout: &'a str, label: &str) -> &'a str {
    stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(label))
        .unwrap_or_else(|| panic!("no {label} line in:\n{stdout}"))
}

pub fn last_line(stdout: &str) -> &str {
    stdout.lines().last().unwrap_or("")
}

/// The value of the last line `psnr_db=<number|inf>`.
pub fn psnr_of(stdout: &str) -> f64 {
    let line = last_line(stdout);
    let value = line
        .strip_prefix("psnr_db=")
        .unwrap_or_else(|| panic!("last line is not psnr_db=...: {line:?}\n{stdout}"));
    if value == "inf" {
        return f64::INFINITY;
    }
    let x: f64 = value
        .parse()
        .unwrap_or_else(|_| panic!("psnr_db value {value:?} is not a number"));
    assert!(
        x.is_finite(),
        "a finite PSNR is printed as a number: {line}"
    );
    x
}

pub fn read_png(p: &Path) -> RgbImage {
    image::open(p)
        .unwrap_or_else(|e| panic!("{} is not a readable image: {e}", p.display()))
        .to_rgb8()
}

/// The library's render of a scene at a size, through `engine` with `opts`' other settings.
pub fn library_render_with(
    scene: &str,
    w: u32,
    h: u32,
    engine: &dyn RayEngine,
    opts: RenderOptions,
) -> RgbImage {
    let scene = Scene::load(scene).expect("scene");
    let opts = RenderOptions {
        width: Some(w),
        height: Some(h),
        progress: false,
        ..opts
    };
    library(&scene, engine, &opts).expect("render").image
}

/// The library's render of a scene at a size, through `engine`, the thesis' spawn.
pub fn library_render(scene: &str, w: u32, h: u32, engine: &dyn RayEngine) -> RgbImage {
    library_render_with(scene, w, h, engine, RenderOptions::default())
}

/// A fresh temporary folder.
pub fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary folder")
}

/// `dir/name` as a path.
pub fn at(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    dir.path().join(name)
}

#[test]
fn the_line_parser_splits_as_a_shell_does() {
    assert_eq!(
        fields(r#"verilated engine="hw fp32 d1 l1 stream" cache=hit x="a \"b\"""#).unwrap(),
        (
            Some("verilated".into()),
            vec![
                ("engine".into(), "hw fp32 d1 l1 stream".into()),
                ("cache".into(), "hit".into()),
                ("x".into(), "a \"b\"".into())
            ]
        )
    );
    assert!(fields("engine=model fp16").is_err(), "an unquoted space");
    assert!(fields(r#"a="open"#).is_err());
    assert!(check_lines("| a | b=c |\nprose, a = b\n  \"json\": \"x=y\"\nk=v").is_ok());
    assert!(check_lines("engine=model fp16").is_err());
    assert!(check_lines("label k=v x").is_err());
}
