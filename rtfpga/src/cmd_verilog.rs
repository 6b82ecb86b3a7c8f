//! `rtfpga verilog`: the accelerator's Verilog (`rtfpga_top.v`), C header and driver and
//! `config.json` for one configuration, or every committed file set (`--defaults`); with
//! `--unit traversal` the traversal unit under AXI4-Lite control (`traversal_unit.v`), its C
//! header and driver and `config.json`.

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use std::path::PathBuf;

use crate::engine::{HwConfig, UnitAdvanceArgs, UnitKind};
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
    hw: HwConfig,
    #[command(flatten)]
    advance: UnitAdvanceArgs,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Write every committed file set, one folder each (what generated-verilog/ holds): the
    /// accelerator's default configurations and the traversal unit's C files and config.json.
    #[arg(long)]
    defaults: bool,
}

pub fn run(a: Args) -> Result<()> {
    let advance = a.advance.of(a.unit)?;
    if a.unit == UnitKind::Traversal {
        if a.defaults {
            bail!("--defaults writes every committed file set, the traversal unit's among them; with --unit traversal give --format, --depth and --lanes");
        }
        return traversal_unit(&a.hw.unit_config(advance)?, &a.out, true);
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
