//! The estimated critical path of a saved netlist (`hdl::synth::SynthOptions::netlist`, or
//! yosys `write_json` after `synth_xilinx -flatten`): re-estimates a design without
//! synthesising it again, e.g. after the routing model is recalibrated. Prints
//! `fmax_mhz_estimate` and `critical_path` as `rtfpga synth --json` does, then the path as
//! its Markdown table. Usage: `timing_report NETLIST.json TOP`.

use anyhow::{Context, Result};
use hdl::timing::{analyze, ROUTING};

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let (Some(netlist), Some(top)) = (args.next(), args.next()) else {
        anyhow::bail!("usage: timing_report NETLIST.json TOP");
    };
    let json = std::fs::read_to_string(&netlist).with_context(|| format!("reading {netlist}"))?;
    let path = analyze(&json, &top, &ROUTING)?;
    let v = serde_json::json!({
        "fmax_mhz_estimate": path.as_ref().map(|p| p.fmax_mhz()),
        "critical_path": path,
    });
    println!("{}", serde_json::to_string_pretty(&v)?);
    if let Some(path) = path {
        print!("\n{}", path.steps_markdown());
    }
    Ok(())
}
