//! No panic on any input: every subcommand's numeric options at 0, 1, their maximum and
//! beyond either run or are refused with a message (exit 1 or 2), never a panic (exit 101)
//! or a hang. The valid extremes run where that is cheap (the bit-accurate engines, Verilog
//! of the accelerator); for the Verilated and synthesised ones this checks the refusals,
//! which come before any build.

use crate::common::*;

/// How a run must end.
#[derive(Clone, Copy, Debug)]
enum End {
    Ok,
    /// Refused by the program (1) or by the command line (2).
    Refused(i32),
}
use End::*;

fn check(run: Run, end: End, what: &str) {
    match end {
        Ok => {
            run.ok();
        }
        Refused(code) => {
            let stderr = run.fails(code, &[]);
            assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        }
    }
}

#[test]
fn image_sizes_and_render_options_at_their_limits() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let fp32_max = hdl::mt::max_depth(hw_model::HwFormat::FP32).to_string();
    let beyond = (hdl::mt::max_depth(hw_model::HwFormat::FP32) + 1).to_string();
    let r = |args: &[&str]| {
        rtfpga(&["render", "--scene", "simple_plane", "--quiet"])
            .out(&png)
            .args(args)
    };
    let cases: Vec<(Vec<&str>, End)> = vec![
        (vec!["--width", "0"], Refused(2)),
        (vec!["--width", "1", "--height", "1"], Ok),
        (vec!["--width", "16384", "--height", "1"], Ok),
        (vec!["--width", "16385"], Refused(2)),
        (vec!["--height", "4294967296"], Refused(2)),
        (vec!["--width=-1"], Refused(2)),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--depth",
                "0",
            ],
            Ok,
        ),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--depth",
                &fp32_max,
            ],
            Ok,
        ),
        (
            vec!["--engine", "traversal", "--depth", &beyond],
            Refused(1),
        ),
        (
            vec!["--engine", "traversal", "--depth", "18446744073709551616"],
            Refused(2),
        ),
        (vec!["--engine", "traversal", "--lanes", "0"], Refused(1)),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--lanes",
                "3",
            ],
            Ok,
        ),
        (vec!["--engine", "traversal", "--lanes", "4"], Refused(1)),
        (vec!["--engine", "traversal", "--slots", "0"], Refused(2)),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--slots",
                "1",
            ],
            Ok,
        ),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--slots",
                "1024",
            ],
            Ok,
        ),
        (vec!["--engine", "traversal", "--slots", "1025"], Refused(2)),
        (
            vec!["--engine", "traversal", "--lanes", "3", "--slots", "2"],
            Refused(1),
        ),
        (
            vec!["--engine", "traversal", "--scene-memory", "0,0"],
            Refused(2),
        ),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--scene-memory",
                "0,2",
            ],
            Ok,
        ),
        (
            vec!["--engine", "traversal", "--scene-memory", "0,1"],
            Refused(1),
        ),
        (
            vec![
                "--engine",
                "traversal",
                "--width",
                "4",
                "--height",
                "4",
                "--scene-memory",
                "4294967295,4294967295",
            ],
            Ok,
        ),
        (
            vec!["--engine", "traversal", "--scene-memory", "4294967296,1"],
            Refused(2),
        ),
        // The frame unit's image limits (hw_model::frame::FrameLimits::HW).
        (
            vec!["--engine", "frame", "--width", "1", "--height", "1"],
            Ok,
        ),
        (
            vec!["--engine", "frame", "--width", "1920", "--height", "1"],
            Ok,
        ),
        (
            vec!["--engine", "frame", "--width", "1921", "--height", "1"],
            Refused(1),
        ),
        (
            vec!["--engine", "frame", "--width", "1", "--height", "1081"],
            Refused(1),
        ),
        (vec!["--engine", "hw", "--lanes", "0"], Refused(1)),
        (vec!["--engine", "hw", "--lanes", "9"], Refused(1)),
        (vec!["--engine", "hw", "--depth", &beyond], Refused(1)),
        (
            vec!["--engine", "hw", "--format", "bfp18/fp32", "--lanes", "0"],
            Refused(1),
        ),
        (
            vec!["--engine", "hw", "--format", "bfp18/fp32", "--lanes", "6"],
            Refused(1),
        ),
        (
            vec![
                "--engine",
                "hw",
                "--format",
                "bfp18/fp32",
                "--depth",
                &beyond,
            ],
            Refused(1),
        ),
    ];
    for (args, end) in cases {
        check(r(&args), end, &args.join(" "));
    }
}

#[test]
fn hardware_commands_refuse_out_of_range_numbers_before_building() {
    let dir = tmp();
    let png = at(&dir, "x.png");
    let folder = at(&dir, "v");
    let beyond = (hdl::mt::max_depth(hw_model::HwFormat::FP32) + 1).to_string();
    let cases: Vec<(Run, End)> = vec![
        (rtfpga(&["verilog", "--lanes", "1"]).out(&folder), Ok),
        (rtfpga(&["verilog", "--lanes", "8"]).out(&folder), Ok),
        (
            rtfpga(&["verilog", "--lanes", "9"]).out(&folder),
            Refused(1),
        ),
        (rtfpga(&["verilog", "--depth", "0"]).out(&folder), Ok),
        (
            rtfpga(&["verilog", "--depth", &beyond]).out(&folder),
            Refused(1),
        ),
        (
            rtfpga(&["verilog", "--lanes", "-1"]).out(&folder),
            Refused(2),
        ),
        (
            rtfpga(&["verilog", "--unit", "traversal", "--lanes", "0"]).out(&folder),
            Refused(1),
        ),
        (
            rtfpga(&["verilog", "--unit", "traversal", "--slots", "0"]).out(&folder),
            Refused(2),
        ),
        (
            rtfpga(&["verilog", "--unit", "traversal", "--scene-memory", "0,0"]).out(&folder),
            Refused(2),
        ),
        (rtfpga(&["synth", "--lanes", "0"]), Refused(1)),
        (
            rtfpga(&["synth", "--op", "add", "--stages", "100000"]),
            Refused(1),
        ),
        (
            rtfpga(&["synth", "--op", "add", "--stages", "-1"]),
            Refused(2),
        ),
        (
            rtfpga(&["synth", "--unit", "traversal", "--depth", &beyond]),
            Refused(1),
        ),
        (
            cosim("simple_plane", 4, 4, &png).args(&["--lanes", "0"]),
            Refused(1),
        ),
        (
            cosim("simple_plane", 4, 4, &png).args(&["--depth", &beyond]),
            Refused(1),
        ),
        (
            cosim("simple_plane", 4, 4, &png).args(&["--vcd", "x.vcd", "--vcd-cycles", "0"]),
            Refused(2),
        ),
        (
            cosim("simple_plane", 4, 4, &png).args(&["--vcd", "x.vcd", "--vcd-from", "-1"]),
            Refused(2),
        ),
        (
            cosim("simple_plane", 4, 4, &png).args(&["--unit", "traversal", "--slots", "1025"]),
            Refused(2),
        ),
        (cosim("simple_plane", 0, 4, &png), Refused(2)),
        (
            rtfpga(&["trace", "replay", "x.trace", "--lanes", "0"]),
            Refused(1),
        ),
        (
            rtfpga(&["trace", "replay", "x.trace", "--depth", &beyond]),
            Refused(1),
        ),
        (
            rtfpga(&["trace", "record", "--scene", "simple_plane", "--width", "0"])
                .out(&at(&dir, "t")),
            Refused(2),
        ),
        (
            rtfpga(&[
                "scene-image",
                "--scene",
                "simple_plane",
                "--scene-memory",
                "0,0",
            ]),
            Refused(2),
        ),
        (
            rtfpga(&[
                "scene-image",
                "--scene",
                "simple_plane",
                "--scene-memory",
                "0,2",
            ]),
            Ok,
        ),
        (
            rtfpga(&[
                "scene-image",
                "--scene",
                "simple_plane",
                "--scene-memory",
                "0,1",
            ]),
            Refused(1),
        ),
        (
            rtfpga(&["sweep", "--config", "none.toml", "--jobs", "0"]).out(&folder),
            Refused(2),
        ),
        (
            rtfpga(&["sweep", "--config", "none.toml", "--jobs", "257"]).out(&folder),
            Refused(2),
        ),
    ];
    for (run, end) in cases {
        let what = format!("{run:?}");
        check(run, end, &what);
    }
    assert!(!png.exists());
}

#[test]
fn bench_and_project_numbers_at_their_limits() {
    let beyond = (hdl::mt::max_depth(hw_model::HwFormat::FP32) + 1).to_string();
    let bench = |args: &[&str]| rtfpga(&["bench", "simple_plane", "--sizes", "4x4"]).args(args);
    let project = |args: &[&str]| rtfpga(&["project", "--scene", "simple_plane"]).args(args);
    let cases: Vec<(Run, End)> = vec![
        (bench(&["--repeat", "0"]), Refused(2)),
        (bench(&["--repeat", "1"]), Ok),
        (bench(&["--repeat", "1001"]), Refused(2)),
        (
            rtfpga(&["bench", "simple_plane", "--sizes", "0x4"]),
            Refused(1),
        ),
        (
            rtfpga(&["bench", "simple_plane", "--sizes", "16385x1"]),
            Refused(1),
        ),
        (
            bench(&["--engine", "traversal", "--lanes", "4"]),
            Refused(1),
        ),
        (
            bench(&["--engine", "traversal", "--scene-memory", "0,0"]),
            Refused(2),
        ),
        (project(&["--depth", &beyond]), Refused(1)),
        (project(&["--lanes", "0"]), Refused(1)),
        (
            project(&["--design", "traversal", "--lanes", "4"]),
            Refused(1),
        ),
        (
            project(&["--design", "traversal", "--slots", "0"]),
            Refused(2),
        ),
        (
            project(&["--design", "traversal", "--tile-size", "0"]),
            Refused(2),
        ),
        (
            project(&["--design", "traversal", "--tile-size", "4097"]),
            Refused(2),
        ),
        (project(&["--fpl-mhz", "0"]), Refused(1)),
        (project(&["--fpl-mhz", "nan"]), Refused(1)),
        (project(&["--fpl-mhz", "inf"]), Refused(1)),
        (project(&["--fpl-mhz=-100"]), Refused(1)),
        (project(&["--hp-ports", "0"]), Refused(1)),
        (project(&["--hp-ports", "5"]), Refused(1)),
        (project(&["--dma-efficiency", "0"]), Refused(1)),
        (project(&["--dma-efficiency", "1.5"]), Refused(1)),
        (project(&["--pack-cycles=-1"]), Refused(1)),
        (project(&["--cycles-per-test", "0"]), Refused(1)),
        (project(&["--width", "16385"]), Refused(2)),
    ];
    for (run, end) in cases {
        let what = format!("{run:?}");
        check(run, end, &what);
    }
}
