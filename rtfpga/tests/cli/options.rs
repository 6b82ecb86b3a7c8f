//! Every option acts or is an error; one name per concept; the help says where each option
//! acts, and what it says is what the checks do (both come from one table).

use crate::common::*;

/// A value each option takes somewhere (for the refusals: the value is not what is refused).
fn sample(option: &str) -> Option<&'static [&'static str]> {
    Some(match option {
        "--format" => &["fp16"],
        "--depth" => &["2"],
        "--lanes" => &["2"],
        "--slots" => &["16"],
        // Values every target of the option builds, so that only where it acts is tested.
        "--nodes" => &["bvh2-fp32"],
        "--box-ports" => &["1"],
        "--scene-memory" => &["2048,4096"],
        "--no-chunks" | "--no-fit" => &[],
        "--dual-filter" => &["bfp"],
        "--scale" => &["none"],
        "--edges" => &["exact"],
        "--advance" => &["none"],
        "--spawn" => &["thesis"],
        "--mode" => &["stream"],
        "--vcd" => &["x.vcd"],
        "--stages" => &["1"],
        "--cycles-per-test" => &["2"],
        "--traversal" => &["bvh"],
        "--hp-ports" => &["2"],
        "--dma-efficiency" => &["0.5"],
        "--pack-cycles" => &["10"],
        "--tile-size" => &["8"],
        "--shader-cores" => &["2"],
        "--shader-threads" => &["8"],
        "--ray-store" => &["256"],
        "--spawn-reserve" => &["64"],
        "--calibration" | "--recalibrate" => &[],
        "--thesis-scenes" => &["no_such_dir"],
        _ => return None,
    })
}

/// The options of `help` (one subcommand's `--help`) with an "[applies to: …]" note, and the
/// note's text.
fn notes(help: &str) -> Vec<(String, String)> {
    // An option's block: its header line (`      --name <VALUE>`), then its indented help.
    let mut blocks: Vec<(String, String)> = Vec::new();
    for line in help.lines() {
        let t = line.trim_start();
        let indent = line.len() - t.len();
        if (1..10).contains(&indent) && t.starts_with('-') {
            let long = t
                .split_whitespace()
                .find(|w| w.starts_with("--"))
                .unwrap_or(t)
                .trim_end_matches(',');
            blocks.push((long.to_string(), String::new()));
        } else if let Some((_, text)) = blocks.last_mut() {
            text.push(' ');
            text.push_str(t);
        }
    }
    blocks
        .into_iter()
        .filter_map(|(option, text)| {
            let note = text
                .split("[applies to: ")
                .nth(1)?
                .split(']')
                .next()?
                .to_string();
            Some((option, note))
        })
        .collect()
}

/// For each subcommand with targets, every option whose help says where it acts is refused
/// with exit 1 on every other target, naming where it acts, before any work; and passes the
/// check on a target it names. (Each command line also holds something that fails after the
/// check, before any work: a missing scene or trace, an output folder inside a file, a depth
/// not built, an unknown operator.)
#[test]
fn an_option_given_where_it_does_not_act_is_refused_naming_where_it_does() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let file = at(&dir, "file");
    std::fs::write(&file, "").unwrap();
    let folder = file.join("v");
    // Each subcommand: its base command line and its targets as the help spells them.
    let subcommands: [(&[&str], &[&str]); 6] = [
        (
            &["render", "--scene", "no_such_scene", "--out", s(&png)],
            &[
                "--engine f32",
                "--engine model",
                "--engine model --format FILTER/FALLBACK",
                "--engine hw",
                "--engine hw --format bfp18/fp32",
                "--engine traversal",
                "--engine frame",
            ],
        ),
        (
            &["cosim", "--scene", "no_such_scene", "--out", s(&png)],
            &[
                "--unit mt",
                "--unit mt --format bfp18/fp32",
                "--unit traversal",
            ],
        ),
        (
            &["verilog", "--out", s(&folder)],
            &["--unit mt", "--unit traversal", "--defaults"],
        ),
        (
            &["synth"],
            &[
                "--unit mt",
                "--unit mt --format bfp18/fp32",
                "--unit traversal",
                "--op",
            ],
        ),
        (
            &["trace", "replay", "none.trace"],
            &["--engine model", "--engine hw|both"],
        ),
        (
            &["project", "--scene", "no_such_scene"],
            &[
                "--design thesis",
                "--design stream",
                "--design traversal",
                "--design frame",
            ],
        ),
    ];
    let mut refused = 0;
    for (base, targets) in subcommands {
        let help_args: Vec<&str> = base
            .iter()
            .take_while(|a| !a.starts_with('-') && !a.ends_with(".trace"))
            .copied()
            .chain(["--help"])
            .collect();
        let help = rtfpga(&help_args).ok();
        let notes = notes(&help);
        assert!(
            !notes.is_empty(),
            "no option of {base:?} says where it acts:\n{help}"
        );
        for (option, note) in notes {
            let values = sample(&option).unwrap_or_else(|| panic!("no sample value of {option}"));
            for target in targets {
                let spelled = target
                    .replace("FILTER/FALLBACK", "bfp14/fp32")
                    .replace("hw|both", "hw")
                    .replace("--op", "--op bogus");
                let spelled: Vec<&str> = spelled.split(' ').collect();
                if spelled.contains(&option.as_str()) {
                    continue;
                }
                let mut run = rtfpga(base).args(&spelled);
                if base[0] == "synth" && !target.starts_with("--op") {
                    // A configuration not built: refused after the options' check.
                    let stopper = if option == "--depth" {
                        "--lanes"
                    } else {
                        "--depth"
                    };
                    run = run.args(&[stopper, "99"]);
                }
                let run = run.args(&[&option]).args(values);
                let acts = note
                    .split(", ")
                    .any(|t| t == *target || t.starts_with(&format!("{target} (")));
                if acts {
                    let out = run.command().output().unwrap();
                    let stderr = String::from_utf8_lossy(&out.stderr);
                    assert!(
                        out.status.code() == Some(1) && !stderr.contains("does not act on"),
                        "{option} on {target} ({note}): {stderr}"
                    );
                } else {
                    run.fails(
                        1,
                        &[&format!(
                            "{option} does not act on {target}: it applies to {note}"
                        )],
                    );
                    refused += 1;
                }
            }
        }
    }
    assert!(refused > 40, "only {refused} refusals checked");
    assert!(
        !png.exists() && !folder.exists(),
        "no work before a refusal"
    );
}

/// The cases of issue 42, each an option that was silently ignored.
#[test]
fn options_that_were_ignored_are_refused() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let r = || render("simple_plane", 8, 8, &png);
    r().args(&["--engine", "f32", "--format", "fp16"])
        .fails(1, &["--format does not act on --engine f32"]);
    r().args(&[
        "--engine",
        "model",
        "--format",
        "fp16",
        "--dual-filter",
        "plucker-signs",
    ])
    .fails(1, &["--dual-filter does not act on --engine model:"]);
    r().args(&["--engine", "hw", "--slots", "4"]).fails(
        1,
        &["--slots does not act on --engine hw: it applies to --engine traversal"],
    );
    r().args(&["--engine", "model", "--depth", "99"])
        .fails(1, &["--depth does not act on --engine model"]);
    // The frame model has no cycles and spawns as the thesis does.
    r().args(&["--engine", "frame", "--lanes", "2"])
        .fails(1, &["--lanes does not act on --engine frame"]);
    r().args(&["--engine", "frame", "--spawn", "format-aware"])
        .fails(1, &["--spawn format-aware: --engine frame takes thesis"]);
    rtfpga(&["bench", "simple_plane", "--engine", "frame"])
        .fails(1, &["--engine frame renders whole frames", "rtfpga render"]);
    // The schedule model's unit is the RTL's in depth and lanes (its slots may vary).
    r().args(&["--engine", "traversal", "--depth", "99"])
        .fails(1, &["depth = 99", "depth 0 to"]);
    r().args(&["--engine", "traversal", "--lanes", "64"])
        .fails(1, &["64 Möller-Trumbore lanes", "1 to 3"]);
    r().args(&["--engine", "traversal", "--lanes", "0"])
        .fails(1, &["0 Möller-Trumbore lanes"]);
    rtfpga(&["verilog", "--defaults", "--format", "fp16"])
        .out(&at(&dir, "v"))
        .fails(1, &["--format does not act on --defaults"]);
    rtfpga(&[
        "project",
        "--scene",
        "simple_plane",
        "--design",
        "thesis",
        "--format",
        "fp16",
    ])
    .fails(1, &["--format does not act on --design thesis"]);
    rtfpga(&["project", "--calibration", "--width", "8"]).fails(2, &["--scene"]);
    rtfpga(&["project", "--scene", "simple_plane", "--quick"]).fails(2, &["--calibration"]);
    assert!(!png.exists());
}

/// `--scene-memory` is the one spelling in every subcommand; the old `--unit-memory` and
/// `--scene-capacity` still work, hidden from the help, and mean the same.
#[test]
fn the_scene_memory_has_one_name_and_the_old_ones_are_hidden_aliases() {
    for sub in [
        "render",
        "bench",
        "cosim",
        "verilog",
        "synth",
        "project",
        "scene-image",
    ] {
        let help = rtfpga(&[sub, "--help"]).ok();
        assert!(
            help.contains("--scene-memory <NODES,TRIANGLES>"),
            "{sub}:\n{help}"
        );
        assert!(
            !help.contains("--unit-memory") && !help.contains("--scene-capacity"),
            "{sub}"
        );
    }
    let image =
        |option: &str| rtfpga(&["scene-image", "--scene", "utah_teapot", option, "1000,2000"]).ok();
    let want = image("--scene-memory");
    assert_eq!(image("--unit-memory"), want);
    assert_eq!(image("--scene-capacity"), want);
}

/// The help says what the project is and what each engine, unit and filter is, true today.
#[test]
fn the_help_is_true() {
    let top = rtfpga(&["--help"]).ok();
    assert!(top.contains("ray-tracing core"), "{top}");
    assert!(top.contains("scene in block RAM"), "{top}");
    assert!(
        !top.contains("ray-triangle intersection accelerator toolkit"),
        "{top}"
    );
    let cosim = rtfpga(&["cosim", "--help"]).ok();
    assert!(
        !cosim.contains("model only"),
        "plucker-signs is built:\n{cosim}"
    );
    // Both filters are built: the hardware pair takes every value of --dual-filter.
    assert!(
        cosim.contains("[default: bfp] [applies to: --unit mt --format bfp18/fp32]")
            && cosim.contains("- plucker-signs:"),
        "{cosim}"
    );
    let render = rtfpga(&["render", "--help"]).ok();
    assert!(
        !render.contains("`--unit traversal`"),
        "render has no --unit:\n{render}"
    );
    assert!(
        render.contains("[applies to: --engine model (none, triangle-box), --engine traversal (none, leaf-box), --engine frame (none, leaf-box)]"),
        "{render}"
    );
    // Every option and positional argument has a description.
    for sub in [
        "render",
        "compare",
        "cosim",
        "verilog",
        "synth",
        "project",
        "bench",
        "scene-image",
        "formats",
        "golden",
    ] {
        let help = rtfpga(&[sub, "--help"]).ok();
        let lines: Vec<&str> = help.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            let is_item = (t.starts_with("--") || t.starts_with('<') || t.starts_with("-h"))
                && line.starts_with("  ");
            if is_item {
                let described = t.contains("  ")
                    || lines
                        .get(i + 1)
                        .is_some_and(|n| n.starts_with("          ") && !n.trim().is_empty());
                assert!(
                    described,
                    "`rtfpga {sub} --help`: `{t}` has no description:\n{help}"
                );
            }
        }
    }
}
