//! Which option applies to which engine, unit or design: one table ([`RULES`]) from which the
//! subcommands' checks ([`Given::check`]) and the "applies to" part of their help
//! ([`annotate`]) both come. An option given where it does not act is an error naming where
//! it does; an option that acts with some values only names the values.

use anyhow::{bail, Result};
use clap::parser::ValueSource;
use clap::{ArgMatches, Command};

/// What a command line configures: the engine, unit or design the option acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The reference Möller-Trumbore in native f32.
    F32,
    /// The bit-accurate model of the datapath's arithmetic, one format.
    Model,
    /// The bit-accurate model of a dual-precision pair (FILTER/FALLBACK).
    ModelPair,
    /// The Verilated Möller-Trumbore accelerator.
    Accelerator,
    /// The Verilated dual-precision pair (the one built in rust-hdl).
    HwPair,
    /// The traversal unit's bit-accurate model, timed by its schedule model.
    UnitModel,
    /// The traversal unit's RTL.
    Unit,
    /// The frame unit's bit-accurate model: ray generation, shading and pixel sums around
    /// the traversal unit's model (untimed).
    FrameModel,
    /// One operator of a lane (`synth --op`).
    Operator,
    /// Every committed configuration (`verilog --defaults`).
    Defaults,
    /// The projection's designs.
    ThesisDesign,
    StreamDesign,
    TraversalDesign,
    FrameDesign,
}

use Target::*;

/// The values of an option a target takes.
#[derive(Clone, Copy, Debug)]
pub enum Values {
    Any,
    Only(&'static [&'static str]),
}

/// Where the option with clap id `arg` acts.
pub struct Rule {
    pub arg: &'static str,
    pub applies: &'static [(Target, Values)],
}

/// The table. Options not listed act wherever their subcommand has them.
pub const RULES: &[Rule] = &[
    Rule {
        arg: "format",
        applies: &[
            (Model, Values::Any),
            (ModelPair, Values::Any),
            (Accelerator, Values::Any),
            (HwPair, Values::Any),
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (FrameModel, Values::Any),
            (Operator, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Only(&["fp32"])),
        ],
    },
    Rule {
        arg: "depth",
        applies: &[
            (Accelerator, Values::Any),
            (HwPair, Values::Any),
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Any),
        ],
    },
    Rule {
        arg: "lanes",
        applies: &[
            (Accelerator, Values::Any),
            (HwPair, Values::Any),
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (ThesisDesign, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Any),
        ],
    },
    Rule {
        arg: "slots",
        applies: &[
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Any),
        ],
    },
    Rule {
        arg: "scene_memory",
        applies: &[
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (FrameModel, Values::Any),
            (TraversalDesign, Values::Any),
        ],
    },
    Rule {
        arg: "nodes",
        applies: &[
            (UnitModel, Values::Any),
            (Unit, Values::Only(&["bvh2-fp32", "bvh4-q8", "bvh8-q8"])),
            (FrameModel, Values::Any),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Any),
        ],
    },
    Rule {
        arg: "box_ports",
        applies: &[
            (UnitModel, Values::Any),
            (Unit, Values::Only(&["1"])),
            (TraversalDesign, Values::Any),
            (FrameDesign, Values::Any),
        ],
    },
    Rule {
        arg: "no_chunks",
        applies: &[
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            (FrameModel, Values::Any),
            (TraversalDesign, Values::Any),
        ],
    },
    Rule {
        arg: "dual_filter",
        applies: &[(ModelPair, Values::Any), (HwPair, Values::Any)],
    },
    Rule {
        arg: "scale",
        applies: &[
            (Model, Values::Any),
            (UnitModel, Values::Any),
            (FrameModel, Values::Any),
        ],
    },
    Rule {
        arg: "spawn",
        applies: &[
            (F32, Values::Any),
            (Model, Values::Any),
            (ModelPair, Values::Any),
            (Accelerator, Values::Any),
            (HwPair, Values::Any),
            (UnitModel, Values::Any),
            (Unit, Values::Any),
            // The frame unit spawns as the thesis does: the bias, every hit counting.
            (FrameModel, Values::Only(&["thesis"])),
        ],
    },
    Rule {
        arg: "edges",
        applies: &[(Model, Values::Any)],
    },
    Rule {
        arg: "advance",
        applies: &[
            (Model, Values::Only(&["none", "triangle-box"])),
            (UnitModel, Values::Only(&["none", "leaf-box"])),
            (Unit, Values::Only(&["none", "leaf-box"])),
            (FrameModel, Values::Only(&["none", "leaf-box"])),
        ],
    },
    Rule {
        arg: "mode",
        applies: &[(Accelerator, Values::Any)],
    },
    Rule {
        arg: "vcd",
        applies: &[(Accelerator, Values::Any)],
    },
    Rule {
        arg: "stages",
        applies: &[(Operator, Values::Any)],
    },
    Rule {
        arg: "no_fit",
        applies: &[(Accelerator, Values::Any), (HwPair, Values::Any)],
    },
    Rule {
        arg: "cycles_per_test",
        applies: &[(ThesisDesign, Values::Any), (StreamDesign, Values::Any)],
    },
    Rule {
        arg: "traversal",
        applies: &[(ThesisDesign, Values::Any), (StreamDesign, Values::Any)],
    },
    Rule {
        arg: "hp_ports",
        applies: &[(StreamDesign, Values::Any), (TraversalDesign, Values::Any)],
    },
    Rule {
        arg: "dma_efficiency",
        applies: &[(StreamDesign, Values::Any), (TraversalDesign, Values::Any)],
    },
    Rule {
        arg: "pack_cycles",
        applies: &[(StreamDesign, Values::Any), (TraversalDesign, Values::Any)],
    },
    Rule {
        arg: "tile_size",
        applies: &[(TraversalDesign, Values::Any)],
    },
    Rule {
        arg: "shader_cores",
        applies: &[(FrameDesign, Values::Any)],
    },
    Rule {
        arg: "shader_threads",
        applies: &[(FrameDesign, Values::Any)],
    },
    Rule {
        arg: "ray_store",
        applies: &[(FrameDesign, Values::Any)],
    },
    Rule {
        arg: "spawn_reserve",
        applies: &[(FrameDesign, Values::Any)],
    },
    // The frame design needs no board constants.
    Rule {
        arg: "calibration",
        applies: &[
            (ThesisDesign, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
        ],
    },
    Rule {
        arg: "recalibrate",
        applies: &[
            (ThesisDesign, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
        ],
    },
    Rule {
        arg: "thesis_scenes",
        applies: &[
            (ThesisDesign, Values::Any),
            (StreamDesign, Values::Any),
            (TraversalDesign, Values::Any),
        ],
    },
];

/// A subcommand's targets, each with how its command line chooses it.
pub type Targets = &'static [(Target, &'static str)];

/// The targets of each subcommand (its path of names).
pub const SUBCOMMANDS: &[(&[&str], Targets)] = &[
    (&["render"], RENDER),
    (&["bench"], BENCH),
    (
        &["cosim"],
        &[
            (Accelerator, "--unit mt"),
            (HwPair, "--unit mt --format bfp18/fp32"),
            (Unit, "--unit traversal"),
        ],
    ),
    (
        &["verilog"],
        &[
            (Accelerator, "--unit mt"),
            (Unit, "--unit traversal"),
            (Defaults, "--defaults"),
        ],
    ),
    (
        &["synth"],
        &[
            (Accelerator, "--unit mt"),
            (HwPair, "--unit mt --format bfp18/fp32"),
            (Unit, "--unit traversal"),
            (Operator, "--op"),
        ],
    ),
    (
        &["trace", "replay"],
        &[(Model, "--engine model"), (Accelerator, "--engine hw|both")],
    ),
    (
        &["project"],
        &[
            (ThesisDesign, "--design thesis"),
            (StreamDesign, "--design stream"),
            (TraversalDesign, "--design traversal"),
            (FrameDesign, "--design frame"),
        ],
    ),
];

const RENDER: Targets = &[
    (F32, "--engine f32"),
    (Model, "--engine model"),
    (ModelPair, "--engine model --format FILTER/FALLBACK"),
    (Accelerator, "--engine hw"),
    (HwPair, "--engine hw --format bfp18/fp32"),
    (UnitModel, "--engine traversal"),
    (FrameModel, "--engine frame"),
];

/// `bench` times the renderer's ray engines: `render`'s but the frame model (its last), which
/// renders whole frames.
const BENCH: Targets = match RENDER.split_last() {
    Some((_, ray_engines)) => ray_engines,
    None => &[],
};

fn rule(arg: &str) -> Option<&'static Rule> {
    RULES.iter().find(|r| r.arg == arg)
}

fn targets_of(path: &[&str]) -> Option<Targets> {
    SUBCOMMANDS
        .iter()
        .find(|(p, _)| *p == path)
        .map(|(_, t)| *t)
}

/// "--engine model (none, triangle-box), --engine traversal": where `rule` acts among
/// `targets`, with the values it takes there.
fn applies_text(rule: &Rule, targets: &[(Target, &str)]) -> String {
    // A target spelled with the option itself (`--engine hw --format bfp18/fp32` for
    // `--format`) goes without saying.
    let flag = format!("--{} ", rule.arg.replace('_', "-"));
    let mut parts: Vec<String> = Vec::new();
    for (target, spelling) in targets {
        if format!("{spelling} ").contains(&flag) {
            continue;
        }
        if let Some((_, values)) = rule.applies.iter().find(|(t, _)| t == target) {
            parts.push(match values {
                Values::Any => spelling.to_string(),
                Values::Only(v) => format!("{spelling} ({})", v.join(", ")),
            });
        }
    }
    parts.join(", ")
}

/// `cmd` with the help of every option that acts on some of its subcommand's targets only
/// ending in "[applies to: …]", from [`RULES`].
pub fn annotate(mut cmd: Command) -> Command {
    for (path, targets) in SUBCOMMANDS {
        cmd = annotate_at(cmd, path, targets);
    }
    cmd
}

fn annotate_at(cmd: Command, path: &[&str], targets: &[(Target, &str)]) -> Command {
    let Some((first, rest)) = path.split_first() else {
        return cmd;
    };
    if !rest.is_empty() {
        return cmd.mut_subcommand(*first, |sub| annotate_at(sub, rest, targets));
    }
    cmd.mut_subcommand(*first, |mut sub| {
        let ids: Vec<String> = sub
            .get_arguments()
            .map(|a| a.get_id().to_string())
            .collect();
        for id in ids {
            let Some(rule) = rule(&id) else { continue };
            let everywhere = targets.iter().all(|(t, _)| {
                rule.applies
                    .iter()
                    .any(|(at, v)| at == t && matches!(v, Values::Any))
            });
            if everywhere {
                continue;
            }
            let note = format!("[applies to: {}]", applies_text(rule, targets));
            // Where every target here takes some values only, the note lists them: the
            // parser's list of every value would say more than acts.
            let only = targets.iter().all(|(t, _)| {
                rule.applies
                    .iter()
                    .all(|(at, v)| at != t || matches!(v, Values::Only(_)))
            });
            sub = sub.mut_arg(id, |a| {
                let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
                a.help(format!("{help} {note}")).hide_possible_values(only)
            });
        }
        sub
    })
}

/// The options given on the command line of the subcommand that runs.
#[derive(Clone, Debug, Default)]
pub struct Given {
    path: Vec<String>,
    /// Clap id, `--long` name, and the value as typed (flags: "true").
    args: Vec<(String, String, String)>,
}

impl Given {
    /// The leaf subcommand of `matches` (parsed by `cmd`) and the options typed for it.
    pub fn of(cmd: &Command, matches: &ArgMatches) -> Given {
        let mut given = Given::default();
        let (mut cmd, mut m) = (cmd, matches);
        while let Some((name, sub)) = m.subcommand() {
            let Some(sub_cmd) = cmd.find_subcommand(name) else {
                break;
            };
            given.path.push(name.to_string());
            (cmd, m) = (sub_cmd, sub);
        }
        for arg in cmd.get_arguments() {
            let id = arg.get_id().as_str();
            if m.value_source(id) != Some(ValueSource::CommandLine) {
                continue;
            }
            let value = m
                .get_raw(id)
                .map(|v| {
                    let v: Vec<String> = v.map(|s| s.to_string_lossy().into_owned()).collect();
                    v.join(",")
                })
                .unwrap_or_default();
            let long = arg
                .get_long()
                .map_or_else(|| id.to_string(), |l| format!("--{l}"));
            given.args.push((id.to_string(), long, value));
        }
        given
    }

    /// An error for the first typed option that does not act on `target`, or acts with other
    /// values, naming where it acts.
    pub fn check(&self, target: Target) -> Result<()> {
        let path: Vec<&str> = self.path.iter().map(String::as_str).collect();
        let Some(targets) = targets_of(&path) else {
            return Ok(());
        };
        let chosen = targets
            .iter()
            .find(|(t, _)| *t == target)
            .map_or("this target", |(_, s)| s);
        for (id, long, value) in &self.args {
            let Some(rule) = rule(id) else { continue };
            match rule.applies.iter().find(|(t, _)| *t == target) {
                None => bail!(
                    "{long} does not act on {chosen}: it applies to {}",
                    applies_text(rule, targets)
                ),
                Some((_, Values::Only(values))) if !values.contains(&value.as_str()) => {
                    bail!("{long} {value}: {chosen} takes {}", values.join(" or "))
                }
                Some(_) => {}
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// Every rule names an option some subcommand has, and every subcommand option with a rule
    /// acts on at least one of that subcommand's targets (else its help would say nowhere).
    #[test]
    fn the_table_names_real_options_and_each_acts_somewhere() {
        let cli = crate::Cli::command();
        let mut seen: Vec<&str> = Vec::new();
        for (path, targets) in SUBCOMMANDS {
            let mut cmd = &cli;
            for name in *path {
                cmd = cmd
                    .find_subcommand(name)
                    .expect("a subcommand of the table");
            }
            for arg in cmd.get_arguments() {
                let id = arg.get_id().as_str();
                if let Some(rule) = rule(id) {
                    seen.push(rule.arg);
                    assert!(
                        !applies_text(rule, targets).is_empty(),
                        "{path:?} has --{id}, which acts on none of its targets"
                    );
                }
            }
        }
        for rule in RULES {
            assert!(seen.contains(&rule.arg), "no subcommand has {}", rule.arg);
        }
    }

    #[test]
    fn help_and_checks_say_where_an_option_acts() {
        let cmd = annotate(crate::Cli::command());
        let render = cmd.find_subcommand("render").unwrap();
        let slots = render
            .get_arguments()
            .find(|a| a.get_id() == "slots")
            .unwrap();
        assert!(
            slots
                .get_help()
                .unwrap()
                .to_string()
                .ends_with("[applies to: --engine traversal]"),
            "{:?}",
            slots.get_help()
        );
        let m = cmd
            .clone()
            .try_get_matches_from(["rtfpga", "render", "--scene", "s", "--out", "o.png"])
            .unwrap();
        let given = Given::of(&cmd, &m);
        assert!(given.check(Accelerator).is_ok(), "defaults are not typed");
        let m = cmd
            .clone()
            .try_get_matches_from([
                "rtfpga", "render", "--scene", "s", "--out", "o.png", "--slots", "4",
            ])
            .unwrap();
        let e = Given::of(&cmd, &m).check(Accelerator).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--slots does not act on --engine hw: it applies to --engine traversal"
        );
        let m = cmd
            .clone()
            .try_get_matches_from([
                "rtfpga",
                "render",
                "--scene",
                "s",
                "--out",
                "o.png",
                "--advance",
                "leaf-box",
            ])
            .unwrap();
        let e = Given::of(&cmd, &m).check(Model).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--advance leaf-box: --engine model takes none or triangle-box"
        );
    }
}
