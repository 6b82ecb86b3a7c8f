//! `rtfpga`: render scenes in software, through the bit-accurate models or the Verilated
//! hardware, compare images, list number formats, generate and measure the hardware. The CLI
//! contract is the repository's `docs/cli.md`; each subcommand lives in its own module, which
//! option acts where in `options`.

mod cmd_bench;
mod cmd_compare;
mod cmd_cosim;
mod cmd_formats;
mod cmd_golden;
mod cmd_project;
mod cmd_render;
mod cmd_scene_image;
mod cmd_sweep;
mod cmd_synth;
mod cmd_trace;
mod cmd_verilog;
mod engine;
mod options;
mod report;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

use options::Given;

#[derive(Parser)]
#[command(
    name = "rtfpga",
    version,
    about = "An FPGA ray-tracing core designed and verified in Rust: the scene in block RAM, BVH \
             traversal and ray-triangle intersection in hardware (rust-hdl, a bit-accurate \
             model, Verilator co-simulation, yosys resources; Zynq XC7Z020). It began as the \
             Möller-Trumbore accelerator of a 2021 MSc thesis, which it also builds."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene (thesis scene directory, .toml scene, or built-in name) to PNG with an
    /// engine: software f32, the bit-accurate model, the Verilated accelerator, or the
    /// traversal unit's model.
    Render(cmd_render::Args),
    /// Compare two images: PSNR (last line `psnr_db=...`) and an optional error heat-map.
    Compare(cmd_compare::Args),
    /// List the number-format catalogue.
    Formats(cmd_formats::Args),
    /// Time renders of scenes at several sizes (Markdown table).
    Bench(cmd_bench::Args),
    /// Regenerate the golden images of the built-in scenes.
    Golden(cmd_golden::Args),
    /// Projected ZedBoard frame time of an accelerator design; --calibration: the model vs the thesis.
    Project(cmd_project::Args),
    /// Render through the Verilated accelerator or traversal unit; cycles, utilisation,
    /// simulation speed, PSNR vs software.
    Cosim(cmd_cosim::Args),
    /// Record a render's ray-triangle queries to a trace file, or replay one into the
    /// bit-accurate model and/or the Verilated accelerator.
    Trace(cmd_trace::Args),
    /// Generate the Verilog, C header/driver and config.json of the accelerator or the
    /// traversal unit.
    Verilog(cmd_verilog::Args),
    /// yosys resources and logic depth of the accelerator, a pair, the traversal unit or one
    /// operator; lanes that fit.
    Synth(cmd_synth::Args),
    /// A scene as the traversal unit's memory holds it: sizes, and the image's words.
    SceneImage(cmd_scene_image::Args),
    /// Design-space sweep (formats x depths x lanes): manifest, every job here, merge.
    Sweep(cmd_sweep::Args),
    /// Run one job of a sweep's manifest (prepare, quality/FORMAT, point/ID).
    SweepJob(cmd_sweep::JobArgs),
    /// Merge a sweep's job results into results.csv/json/md and the plots.
    SweepMerge(cmd_sweep::MergeArgs),
}

fn main() -> std::process::ExitCode {
    // Rust ignores SIGPIPE, so a closed stdout (`rtfpga scene-image … | head`) would make
    // println! panic; the default action ends the program quietly instead.
    #[cfg(unix)]
    // SAFETY: at start-up, before any other thread exists, restoring the default action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // An interrupted Verilator build leaves no half-built model in the cache.
    let _ = ctrlc::set_handler(|| {
        sim::verilator::remove_unfinished_builds();
        std::process::exit(130);
    });
    sim::verilator::show_build_progress(true);
    let cmd = options::annotate(Cli::command());
    let matches = cmd.clone().get_matches();
    let given = Given::of(&cmd, &matches);
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = match cli.command {
        Command::Render(a) => cmd_render::run(a, &given),
        Command::Compare(a) => cmd_compare::run(a),
        Command::Formats(a) => cmd_formats::run(a),
        Command::Golden(a) => cmd_golden::run(a),
        Command::Verilog(a) => cmd_verilog::run(a, &given),
        Command::Synth(a) => cmd_synth::run(a, &given),
        Command::Bench(a) => cmd_bench::run(a, &given),
        Command::Project(a) => cmd_project::run(a, &given),
        Command::Cosim(a) => cmd_cosim::run(a, &given),
        Command::Trace(a) => cmd_trace::run(a, &given),
        Command::SceneImage(a) => cmd_scene_image::run(a),
        Command::Sweep(a) => cmd_sweep::run(a),
        Command::SweepJob(a) => cmd_sweep::run_job(a),
        Command::SweepMerge(a) => cmd_sweep::run_merge(a),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", error_text(&e));
            std::process::ExitCode::FAILURE
        }
    }
}

/// The error and its causes, joined by `: `, leaving out a cause whose text the message
/// already holds (error types that print their source in their own message, as most of
/// the workspace's do, would otherwise say it twice).
fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain().map(|c| c.to_string()) {
        if !text.contains(&cause) {
            if !text.is_empty() {
                text.push_str(": ");
            }
            text.push_str(&cause);
        }
    }
    text
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_cause_already_in_the_message_is_said_once() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "no such file");
        let e = anyhow::Error::new(sw_renderer::scene::SceneError::Io {
            path: "s.toml".into(),
            source: io,
        })
        .context("loading the scene");
        assert_eq!(
            super::error_text(&e),
            "loading the scene: s.toml: cannot read: no such file"
        );
        let e = anyhow::anyhow!("inner").context("outer");
        assert_eq!(super::error_text(&e), "outer: inner");
    }
}
