//! `rtfpga synth`: yosys Xilinx 7-series resources and logic depth of the whole accelerator
//! or of one operator, and how many lanes of the configuration fit an XC7Z020.

use anyhow::Result;
use clap::Args as ClapArgs;

use crate::engine::HwConfig;
use hdl::operator::Op;
use hdl::synth::{synthesize, SynthOptions, SynthReport};
use hdl::top::fit::{fit_from, synthesize_top, LaneFit, Usage, XC7Z020};
use hdl::top::TopConfig;

#[derive(ClapArgs)]
pub struct Args {
    #[command(flatten)]
    hw: HwConfig,
    /// Synthesise one operator of `--format` instead of the accelerator (add, sub, mul,
    /// recip, lt, from_f32, to_f32).
    #[arg(long)]
    op: Option<String>,
    /// Pipeline stages of `--op`.
    #[arg(long, default_value_t = 0)]
    stages: usize,
    /// Skip the lanes=1 vs lanes=2 runs that estimate how many lanes fit.
    #[arg(long)]
    no_fit: bool,
    /// Machine-readable output.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let options = SynthOptions::default();
    if let Some(op) = &a.op {
        let op: Op = op.parse()?;
        let rtl = hdl::formats::rtl(&a.hw.format, op, a.stages)?;
        let report = synthesize(&rtl.verilog, hdl::verilog::TOP, &options)?;
        let label = format!("{} {} stages={}", a.hw.format, op, a.stages);
        return print(&label, &report, rtl.latency, None, a.json);
    }
    let config = TopConfig::new(&a.hw.format, a.hw.depth, a.hw.lanes);
    config.validate()?;
    let report = synthesize_top(&config, &options)?;
    let fit = if a.no_fit {
        None
    } else {
        // The fit needs the 1- and 2-lane designs; reuse the report when it is one of them.
        let at = |lanes: usize| -> Result<Usage> {
            if lanes == config.lanes {
                return Ok(Usage::of(&report));
            }
            Ok(Usage::of(&synthesize_top(
                &TopConfig {
                    lanes,
                    ..config.clone()
                },
                &options,
            )?))
        };
        Some(fit_from(at(1)?, at(2)?, &XC7Z020))
    };
    print(
        &config.dir_name(),
        &report,
        config.lane_latency()?,
        fit,
        a.json,
    )
}

fn print(
    label: &str,
    report: &SynthReport,
    latency: usize,
    fit: Option<LaneFit>,
    json: bool,
) -> Result<()> {
    if json {
        let v =
            serde_json::json!({"design": label, "latency": latency, "report": report, "fit": fit});
        println!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    println!("{}", SynthReport::markdown_header());
    println!("{}", report.markdown_row(label));
    println!("\nlatency: {latency} cycles");
    if let Some(f) = fit {
        println!(
            "per lane: {} LUT, {} FF, {} DSP48E1, {} RAMB18; fixed part: {} LUT, {} FF, {} DSP48E1, {} RAMB18",
            f.per_lane.lut, f.per_lane.ff, f.per_lane.dsp48e1, f.per_lane.bram18, f.fixed.lut, f.fixed.ff, f.fixed.dsp48e1, f.fixed.bram18
        );
        println!(
            "lanes that fit an {}: {} (limited by {})",
            f.device, f.lanes, f.limit
        );
    }
    Ok(())
}
