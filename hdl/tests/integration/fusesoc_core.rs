//! The FuseSoC core file `rtfpga.core` at the repository root: it lists exactly the files of
//! every generated-verilog/<config>/ folder, its lint target uses the project's Verilator
//! waivers, and (when `fusesoc` is installed) `fusesoc run --target lint rtfpga` passes.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The core's name (`fusesoc run ... rtfpga` matches it by its name part).
const CORE_NAME: &str = "rtfpga:accel:rtfpga:0.1.0";
const GENERATED: &str = "generated-verilog";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The default configuration's folder (the first `make verilog` writes).
fn default_config() -> String {
    hdl::generate::default_configs()[0].dir_name()
}

fn core_text() -> String {
    let path = repo().join("rtfpga.core");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The YAML lines of the core without comments and trailing blanks.
fn lines(core: &str) -> Vec<&str> {
    core.lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .map(str::trim_end)
        .filter(|l| !l.is_empty())
        .collect()
}

/// The value of a list item `- value` or `- value: {attributes}`.
fn list_item(line: &str) -> Option<&str> {
    let item = line.trim_start().strip_prefix("- ")?.trim();
    Some(item.split_once(": ").map_or(item, |(path, _)| path).trim())
}

/// Every file of generated-verilog/ the core names, by configuration folder.
fn listed_files(core: &str) -> BTreeMap<String, BTreeSet<String>> {
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for item in lines(core).into_iter().filter_map(list_item) {
        if let Some(rest) = item.strip_prefix(&format!("{GENERATED}/")) {
            let (dir, file) = rest
                .split_once('/')
                .unwrap_or_else(|| panic!("`{item}`: expected {GENERATED}/<config>/<file>"));
            assert!(!file.contains('/'), "`{item}`: nested path");
            let fresh = out.entry(dir.to_string()).or_default().insert(file.into());
            assert!(fresh, "`{item}` is listed twice");
        }
    }
    out
}

/// Every file of every configuration folder under generated-verilog/.
fn present_files() -> BTreeMap<String, BTreeSet<String>> {
    let root = repo().join(GENERATED);
    let entries = |dir: &Path| {
        std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap())
            .collect::<Vec<_>>()
    };
    entries(&root)
        .into_iter()
        .filter(|e| e.path().is_dir())
        .map(|d| {
            let files = entries(&d.path())
                .into_iter()
                .map(|f| f.file_name().to_string_lossy().into_owned())
                .collect();
            (d.file_name().to_string_lossy().into_owned(), files)
        })
        .collect()
}

#[test]
fn core_lists_exactly_the_generated_files() {
    let core = core_text();
    assert!(
        core.starts_with("CAPI=2:\n"),
        "a CAPI2 core starts with `CAPI=2:`"
    );
    assert!(
        lines(&core).contains(&format!("name: {CORE_NAME}").as_str()),
        "core name is {CORE_NAME}"
    );
    let present = present_files();
    assert!(
        present.contains_key(&default_config()),
        "the default configuration"
    );
    // Its `default` target and its lint target use the default configuration.
    for target in ["default", "lint"] {
        let filesets = lines(&core)
            .iter()
            .skip_while(|l| !l.trim().starts_with(&format!("{target}:")))
            .find_map(|l| l.trim().strip_prefix("filesets: ").map(str::to_string));
        assert_eq!(
            filesets,
            Some(format!("[rtl_{0}, sw_{0}]", default_config())),
            "the {target} target's filesets"
        );
    }
    assert_eq!(
        listed_files(&core),
        present,
        "rtfpga.core's files differ from generated-verilog/ (folders and their files): \
         update its filesets"
    );
    // The files outside generated-verilog/ it names exist too.
    for item in lines(&core).into_iter().filter_map(list_item) {
        if item.contains('/') && !item.starts_with(GENERATED) {
            assert!(
                repo().join(item).is_file(),
                "rtfpga.core lists {item}: missing"
            );
        }
    }
}

#[test]
fn lint_target_uses_the_project_waivers() {
    let core = core_text();
    let lines = lines(&core);
    let start = lines
        .iter()
        .position(|l| l.trim() == "verilator_options:")
        .expect("the lint target has verilator_options");
    let indent = |l: &str| l.len() - l.trim_start().len();
    let options: Vec<&str> = lines[start + 1..]
        .iter()
        .take_while(|l| indent(l) > indent(lines[start]) && l.trim_start().starts_with("- "))
        .filter_map(|l| list_item(l))
        .collect();
    let expected: Vec<&str> = std::iter::once("-Wall")
        .chain(hdl::verilog::VERILATOR_WAIVERS.iter().copied())
        .chain(hdl::verilog::TOP_VERILATOR_WAIVERS.iter().copied())
        .collect();
    assert_eq!(options, expected);
    // Every folder with Verilog (the unit's holds only its C files and config.json).
    for (config, files) in present_files() {
        if config != default_config() && files.iter().any(|f| f.ends_with(".v")) {
            let target = format!("lint_{config}:");
            assert!(
                lines.iter().any(|l| l.trim() == target),
                "no {target} target"
            );
        }
    }
}

fn fusesoc_available() -> bool {
    Command::new("fusesoc")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn fusesoc_lint_target_passes() {
    if !fusesoc_available() {
        // The harness captures print!/eprint!, not writes to the real stderr.
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED fusesoc_core::fusesoc_lint_target_passes: fusesoc not on PATH, `fusesoc run --target lint rtfpga` not run \
             (enable: pip install fusesoc, or scripts/setup.sh)"
        );
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let out = Command::new("fusesoc")
        .arg("--cores-root")
        .arg(repo())
        .arg("run")
        .arg("--build-root")
        .arg(work.path().join("build"))
        .args(["--target", "lint", "rtfpga"])
        .current_dir(work.path())
        .output()
        .expect("running fusesoc");
    let text = |b: &[u8]| {
        let s = String::from_utf8_lossy(b).into_owned();
        let lines: Vec<&str> = s.lines().collect();
        lines[lines.len().saturating_sub(60)..].join("\n")
    };
    assert!(
        out.status.success(),
        "fusesoc run --target lint rtfpga failed:\n{}\n{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    let vc = work
        .path()
        .join("build/rtfpga_accel_rtfpga_0.1.0/lint/rtfpga_accel_rtfpga_0.1.0.vc");
    let vc = std::fs::read_to_string(&vc).unwrap_or_else(|e| panic!("{}: {e}", vc.display()));
    assert!(
        vc.contains("--lint-only") && vc.contains("--top-module rtfpga_top"),
        "{vc}"
    );
}
