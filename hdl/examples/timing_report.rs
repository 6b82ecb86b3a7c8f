//! The estimated critical path of a saved netlist (`hdl::synth::SynthOptions::netlist`, or
//! yosys `write_json` after `synth_xilinx -flatten`), as `rtfpga synth` prints it: re-estimates
//! a design without synthesising it again, e.g. after the routing model is recalibrated.
//! Usage: `timing_report NETLIST.json TOP`.

use anyhow::{Context, Result};
use hdl::timing::{analyze, ROUTING};

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let (Some(netlist), Some(top)) = (args.next(), args.next()) else {
        anyhow::bail!("usage: timing_report NETLIST.json TOP");
    };
    let json = std::fs::read_to_string(&netlist).with_context(|| format!("reading {netlist}"))?;
    match analyze(&json, &top, &ROUTING)? {
        Some(path) => print!("{path}"),
        None => println!("fmax_mhz_estimate: none (no register-to-register path)"),
    }
    Ok(())
}
