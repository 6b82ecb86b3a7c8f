//! The generated accelerator Verilog: Verilator `-Wall` lint (documented waivers), Icarus
//! compile, yosys Xilinx synthesis, and the committed copies under generated-verilog/ being
//! current.

use hdl::generate::VERILOG_FILE;
use hdl::top::{top_verilog, TopConfig};
use hw_model::HwFormat;
use std::path::PathBuf;
use std::process::Command;

/// At depth 0 the lane is one combinational cloud spread over many always blocks, which
/// Verilator reports as circular (UNOPTFLAT) although no signal depends on itself.
const DEPTH0_WAIVERS: &[&str] = &["-Wno-UNOPTFLAT"];

fn temp_verilog(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(VERILOG_FILE);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn run(cmd: &mut Command, what: &str) {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run: {e} (make setup installs the tools)"));
    assert!(
        out.status.success(),
        "{what} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .take(60)
            .collect::<Vec<_>>()
            .join("\n"),
        String::from_utf8_lossy(&out.stderr)
            .lines()
            .take(60)
            .collect::<Vec<_>>()
            .join("\n")
    );
}

fn lint(config: &TopConfig, extra_waivers: &[&str]) {
    let (_dir, path) = temp_verilog(&top_verilog(config).unwrap());
    run(
        Command::new("verilator")
            .args(["--lint-only", "-Wall", "--top-module", "rtfpga_top"])
            .args(hdl::verilog::VERILATOR_WAIVERS)
            .args(hdl::verilog::TOP_VERILATOR_WAIVERS)
            .args(extra_waivers)
            .arg(&path),
        &format!("verilator lint of {}", config.dir_name()),
    );
    let out = path.with_extension("vvp");
    run(
        Command::new("iverilog")
            .args(["-g2012", "-s", "rtfpga_top", "-o"])
            .arg(&out)
            .arg(&path),
        &format!("iverilog of {}", config.dir_name()),
    );
}

#[test]
fn fp32_one_lane_passes_verilator_and_icarus() {
    lint(&TopConfig::new(HwFormat::named("fp32"), 1, 1), &[]);
}

/// At depth 5 the lane's word delay lines are block RAM rings (`hdl::mt::delay::RamDelay`).
#[test]
fn fp32_depth5_lane_with_ram_delay_lines_passes_verilator_and_icarus() {
    let config = TopConfig::new(HwFormat::named("fp32"), 5, 1);
    assert!(top_verilog(&config).unwrap().contains("ram_style"));
    lint(&config, &[]);
}

#[test]
fn fp16_two_lanes_passes_verilator_and_icarus() {
    lint(&TopConfig::new(HwFormat::named("fp16"), 1, 2), &[]);
}

#[test]
fn bf16_depth_zero_passes_verilator_and_icarus() {
    lint(
        &TopConfig::new(HwFormat::named("bf16"), 0, 1),
        DEPTH0_WAIVERS,
    );
}

/// The stream front end alone (2 lanes) through yosys: its result FIFO maps to block RAM,
/// 4 RAMB18 a lane (97-bit results in 3, the 32-bit control word in 1).
#[test]
fn stream_front_end_fifo_maps_to_block_ram() {
    use hdl::top::stream::StreamFrontEnd;
    use rust_hdl::prelude::*;
    let verilog = hdl::top::with_build_stack(|| {
        let mut front = StreamFrontEnd::new(2, 11);
        front.connect_all();
        generate_verilog(&front)
    });
    let r = hdl::synth::synthesize(&verilog, "top", &hdl::synth::SynthOptions::default()).unwrap();
    let usage = hdl::top::fit::Usage::of(&r);
    assert_eq!(usage.bram18, 8, "{:?}", r.cells);
    assert_eq!(r.dsp48e1, 0);
}

/// The whole accelerator through yosys' synth_xilinx (minutes on 2 cores):
/// `cargo test --release -p hdl --test integration top_verilog:: -- --ignored`.
#[test]
#[ignore]
fn fp32_accelerator_synthesises_for_xc7() {
    let r = hdl::top::fit::synthesize_top(
        &TopConfig::new(HwFormat::named("fp32"), 1, 1),
        &hdl::synth::SynthOptions::default(),
    )
    .unwrap();
    println!(
        "{}\n{}",
        hdl::synth::SynthReport::markdown_header(),
        r.markdown_row("fp32_d1_l1")
    );
    assert!(r.dsp48e1 > 0 && r.lut > 0 && r.ff > 0, "{:?}", r.cells);
    assert_eq!(hdl::top::fit::Usage::of(&r).bram18, 4, "{:?}", r.cells);
}
