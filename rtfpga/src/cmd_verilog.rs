//! `rtfpga verilog`: the accelerator's Verilog (`rtfpga_top.v`), C header and driver and
//! `config.json` for one configuration, or every committed default configuration.

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use std::path::PathBuf;

use crate::engine::HwConfig;
use hdl::generate::{default_configs, generate};
use hdl::top::TopConfig;

#[derive(ClapArgs)]
pub struct Args {
    #[command(flatten)]
    hw: HwConfig,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Write every default configuration, one folder each (what generated-verilog/ holds).
    #[arg(long)]
    defaults: bool,
}

pub fn run(a: Args) -> Result<()> {
    let jobs: Vec<(TopConfig, PathBuf)> = if a.defaults {
        default_configs()
            .into_iter()
            .map(|c| {
                let dir = a.out.join(c.dir_name());
                (c, dir)
            })
            .collect()
    } else {
        vec![(a.hw.top_config()?, a.out.clone())]
    };
    for (config, dir) in jobs {
        let generated =
            generate(&config).with_context(|| format!("configuration {}", config.dir_name()))?;
        generated.write_to(&dir)?;
        let s = &generated.summary;
        println!(
            "{}: {} lanes, lane latency {} cycles, stream latency {} cycles -> {}",
            config.dir_name(),
            s.lanes,
            s.lane_latency,
            s.stream_latency,
            dir.display()
        );
    }
    Ok(())
}
