//! `rtfpga synth`: yosys Xilinx 7-series resources and logic depth of the whole accelerator,
//! of one operator or of the traversal unit (`--unit traversal`), whether it fits an XC7Z020
//! (for the accelerator also how many lanes would, for a dual-precision pair how many filter
//! slots), and its estimated Fmax and critical path on the XC7Z020-1 (docs/timing.md).

use anyhow::{bail, Result};
use clap::Args as ClapArgs;

use crate::engine::{AdvanceArg, HwConfig, UnitKind};
use crate::options::{Given, Target};
use crate::report;
use hdl::dual::pair::{forward_latency, miss_latency};
use hdl::operator::Op;
use hdl::synth::{synthesize, SynthOptions, SynthReport};
use hdl::top::fit::{fit_from, synthesize_top, LaneFit, Usage, XC7Z020};
use hdl::top::TopConfig;
use hdl::traversal::config::unit_verilog;
use sim::dual_pair::{pair_verilog, PairConfig};

#[derive(ClapArgs)]
pub struct Args {
    /// The hardware: the Möller-Trumbore accelerator, or the traversal unit.
    #[arg(long, value_enum, default_value_t = UnitKind::Mt)]
    unit: UnitKind,
    #[command(flatten)]
    hw: HwConfig,
    #[command(flatten)]
    advance: AdvanceArg,
    /// Synthesise one operator of `--format` instead of the accelerator (add, sub, mul,
    /// recip, lt, from_f32, to_f32; sqrt in a float format).
    #[arg(long)]
    op: Option<String>,
    /// Pipeline stages of `--op`: 0 to the operator's maximum in the format.
    #[arg(long, default_value_t = 0)]
    stages: usize,
    /// Skip the lanes=1 vs lanes=2 runs that estimate how many lanes fit.
    #[arg(long)]
    no_fit: bool,
    /// Machine-readable output.
    #[arg(long)]
    json: bool,
}

/// yosys on `verilog` (top module `top`), behind a spinner naming `what`.
fn yosys(what: &str, verilog: &str, top: &str, options: &SynthOptions) -> Result<SynthReport> {
    let (report, _) = report::spinner(&format!("yosys synth_xilinx: {what}"), || {
        synthesize(verilog, top, options)
    });
    Ok(report?)
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    let target = match (&a.op, a.unit) {
        (Some(_), UnitKind::Traversal) => bail!("--op synthesises one operator of the accelerator's lane; it does not combine with --unit traversal"),
        (Some(_), UnitKind::Mt) => Target::Operator,
        (None, unit) => unit.target(&a.hw.datapath.format),
    };
    given.check(target)?;
    let options = SynthOptions::default();
    if a.unit == UnitKind::Traversal {
        let config = a.hw.unit_config(a.advance.advance.unwrap_or_default())?;
        let verilog = unit_verilog(&config)?;
        let (nodes, triangles) = config.memory.capacity();
        let label = format!(
            "traversal unit {} d{} l{} memory {nodes},{triangles}",
            config.format, config.depth, config.lanes,
        );
        let report = yosys(&label, &verilog, "top", &options)?;
        return print(&label, &report, None, None, a.json);
    }
    if let Some(op) = &a.op {
        let op: Op = op.parse()?;
        let format = a.hw.datapath.single_format()?;
        let rtl = hdl::formats::rtl(format.try_into()?, op, a.stages)?;
        let label = format!("{} {} stages={}", format, op, a.stages);
        let report = yosys(&label, &rtl.verilog, hdl::verilog::TOP, &options)?;
        return print(&label, &report, Some(rtl.latency), None, a.json);
    }
    if target == Target::HwPair {
        return synth_pair(&a, &a.hw.pair_config()?, &options);
    }
    let config = a.hw.datapath.top_config()?;
    let synth = |lanes: usize| -> Result<SynthReport> {
        let config = TopConfig {
            lanes,
            ..config.clone()
        };
        let what = format!("{} ({lanes} lanes)", config.dir_name());
        let (report, _) = report::spinner(&format!("yosys synth_xilinx: {what}"), || {
            synthesize_top(&config, &options)
        });
        Ok(report?)
    };
    let report = synth(config.lanes)?;
    let fit = lane_fit(&a, config.lanes, &report, synth)?;
    print(
        &config.dir_name(),
        &report,
        Some(config.lane_latency()?),
        fit,
        a.json,
    )
}

/// `--format bfp18/fp32`: the dual-precision pair, and how many filter slots would fit
/// beside its one fp32 lane (from the 1- and 2-slot designs).
fn synth_pair(a: &Args, pair: &PairConfig, options: &SynthOptions) -> Result<()> {
    let synth = |slots: usize| -> Result<SynthReport> {
        let config = PairConfig { slots, ..*pair };
        let verilog = pair_verilog(&config)?;
        yosys(&config.to_string(), &verilog, hdl::verilog::TOP, options)
    };
    let report = synth(pair.slots)?;
    let fit = lane_fit(a, pair.slots, &report, synth)?;
    if !a.json {
        println!(
            "latency: {} cycles to a certain miss, {} to a forwarded query's answer (queue empty, fp32 lane free); the lanes below are filter slots, the fixed part is the fp32 lane",
            miss_latency(pair.filter),
            forward_latency(pair.filter, pair.depth)
        );
    }
    print(&pair.to_string(), &report, None, fit, a.json)
}

/// The lanes (or slots) that fit, from the 1- and 2-lane designs (`synth(lanes)`), reusing
/// `report` of the `lanes` asked for when it is one of them; `None` with `--no-fit`.
fn lane_fit(
    a: &Args,
    lanes: usize,
    report: &SynthReport,
    synth: impl Fn(usize) -> Result<SynthReport>,
) -> Result<Option<LaneFit>> {
    if a.no_fit {
        return Ok(None);
    }
    let at = |n: usize| -> Result<Usage> {
        if n == lanes {
            return Ok(Usage::of(report));
        }
        Ok(Usage::of(&synth(n)?))
    };
    Ok(Some(fit_from(at(1)?, at(2)?, &XC7Z020)))
}

fn print(
    label: &str,
    report: &SynthReport,
    latency: Option<usize>,
    fit: Option<LaneFit>,
    json: bool,
) -> Result<()> {
    // The design as synthesised, against the device: near the limit this, not the 1-/2-lane
    // estimate (which carries two syntheses' noise), decides.
    let usage = Usage::of(report);
    let fits = XC7Z020.holds(usage);
    if json {
        let v = serde_json::json!({"design": label, "latency": latency, "report": report,
            "usage": usage, "fits": fits, "fit": fit,
            "fmax_mhz_estimate": report.fmax_mhz_estimate(),
            "critical_path": report.critical_path});
        println!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    println!("{}", SynthReport::markdown_header());
    println!("{}", report.markdown_row(label));
    if let Some(latency) = latency {
        println!("\nlatency: {latency} cycles");
    }
    let d = XC7Z020;
    let pct = |used: u64, of: u64| 100.0 * used as f64 / of as f64;
    println!(
        "this design on an {}: {} ({} of {} LUT incl. SRL ({:.1} %), {} of {} FF, {} of {} DSP48E1, {} of {} RAMB18)",
        d.name,
        if fits { "fits" } else { "does not fit" },
        usage.lut, d.lut, pct(usage.lut, d.lut), usage.ff, d.ff, usage.dsp48e1, d.dsp48e1, usage.bram18, d.bram18
    );
    if let Some(f) = fit {
        println!(
            "per lane: {} LUT, {} FF, {} DSP48E1, {} RAMB18; fixed part: {} LUT, {} FF, {} DSP48E1, {} RAMB18",
            f.per_lane.lut, f.per_lane.ff, f.per_lane.dsp48e1, f.per_lane.bram18, f.fixed.lut, f.fixed.ff, f.fixed.dsp48e1, f.fixed.bram18
        );
        println!(
            "lanes that fit an {} (estimated from the 1- and 2-lane designs): {} (limited by {})",
            f.device, f.lanes, f.limit
        );
    }
    let Some(path) = &report.critical_path else {
        println!("\nno register-to-register path: no Fmax estimate");
        return Ok(());
    };
    let ns = |ps: u64| ps as f64 / 1000.0;
    println!();
    report::Line::new()
        .fixed("fmax_mhz_estimate", path.fmax_mhz(), 0)
        .fixed("delay_ns", ns(path.delay_ps), 2)
        .fixed("cell_ns", ns(path.cell_ps), 2)
        .fixed("routing_ns", ns(path.routing_ps), 2)
        .kv("levels", path.levels)
        .print();
    report::Line::labelled("critical_path")
        .kv("from", &path.start)
        .kv("to", &path.end)
        .print();
    println!("\nAn estimate for the XC7Z020-1 from yosys' cell delays and a calibrated routing model, not placed and routed (docs/timing.md: its error band). The path:\n");
    print!("{}", path.steps_markdown());
    Ok(())
}
