//! `rtfpga verilog`: the accelerator's Verilog (`rtfpga_top.v`), C header and driver and
//! `config.json` for one configuration, or every committed file set (`--defaults`); with
//! `--unit traversal` the traversal unit under AXI4-Lite control (`traversal_unit.v`), its C
//! header and driver and `config.json`.

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use std::path::PathBuf;

use crate::engine::{AdvanceArg, Datapath, HwConfig, UnitArgs, UnitKind};
use crate::options::{Given, Target};
use crate::report;
use hdl::generate::{
    default_configs, default_unit_config, generate, unit_dir_name, unit_files, write_files,
};
use hdl::top::TopConfig;
use hdl::traversal::unit::UnitConfig;

#[derive(ClapArgs)]
pub struct Args {
    /// The hardware: the Möller-Trumbore accelerator, or the traversal unit.
    #[arg(long, value_enum, default_value_t = UnitKind::Mt)]
    unit: UnitKind,
    #[command(flatten)]
    datapath: Datapath,
    #[command(flatten)]
    unit_args: UnitArgs,
    #[command(flatten)]
    advance: AdvanceArg,
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Write every committed file set, one folder each (what generated-verilog/ holds): the
    /// accelerator's default configurations and the traversal unit's C files and config.json.
    #[arg(long)]
    defaults: bool,
}

pub fn run(a: Args, given: &Given) -> Result<()> {
    let target = match (a.defaults, a.unit) {
        (true, UnitKind::Mt) => Target::Defaults,
        (true, UnitKind::Traversal) => anyhow::bail!("--defaults writes every committed file set, the traversal unit's among them: it takes no --unit traversal"),
        (false, UnitKind::Mt) => Target::Accelerator,
        (false, UnitKind::Traversal) => Target::Unit,
    };
    given.check(target)?;
    if a.unit == UnitKind::Traversal {
        let hw = HwConfig {
            datapath: a.datapath.clone(),
            unit: a.unit_args.clone(),
            dual_filter: None,
        };
        let config = hw.unit_config(a.advance.advance.unwrap_or_default())?;
        report::dir_out(&a.out)?;
        return traversal_unit(&config, &a.out, true);
    }
    let jobs: Vec<(TopConfig, PathBuf)> = if a.defaults {
        default_configs()
            .into_iter()
            .map(|c| {
                let dir = a.out.join(c.dir_name());
                (c, dir)
            })
            .collect()
    } else {
        vec![(a.datapath.top_config()?, a.out.clone())]
    };
    report::dir_out(&a.out)?;
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
    if a.defaults {
        // The unit's Verilog is not committed (~6 MB): its C files and config.json are.
        let config = default_unit_config();
        traversal_unit(&config, &a.out.join(unit_dir_name(&config)), false)?;
    }
    Ok(())
}

/// The traversal unit under AXI4-Lite control: its Verilog if `verilog` (top module `top`,
/// rust-hdl's port names, docs/traversal-unit.md), the C header and driver of its register
/// map, and a config.json (configuration, scene memory capacity, timing, register words,
/// ports).
fn traversal_unit(config: &UnitConfig, out: &std::path::Path, verilog: bool) -> Result<()> {
    write_files(&unit_files(config, verilog)?, out)?;
    let (nodes, triangles) = config.memory.capacity();
    println!(
        "traversal unit {} depth {} lanes {}: {} slots, stack {}, scene memory {} nodes and {} triangles -> {}",
        config.format,
        config.depth,
        config.lanes,
        config.slots,
        config.stack_depth,
        nodes,
        triangles,
        out.display()
    );
    Ok(())
}
