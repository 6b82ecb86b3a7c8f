//! `rtfpga verilog`: the accelerator's Verilog (`rtfpga_top.v`), C header and driver and
//! `config.json` for one configuration, or every committed default configuration; with
//! `--unit traversal` the traversal unit's Verilog (`traversal_unit.v`) and `config.json`.

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use std::path::PathBuf;

use crate::engine::{HwConfig, UnitKind};
use hdl::generate::{default_configs, generate, CONFIG_FILE};
use hdl::top::TopConfig;
use hdl::traversal::unit::unit_verilog;

#[derive(ClapArgs)]
pub struct Args {
    /// The hardware: the Möller-Trumbore accelerator, or the traversal unit.
    #[arg(long, value_enum, default_value_t = UnitKind::Mt)]
    unit: UnitKind,
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
    if a.unit == UnitKind::Traversal {
        if a.defaults {
            bail!("--defaults writes the accelerator's committed configurations; the traversal unit takes --format, --depth and --lanes");
        }
        return traversal_unit(&a.hw, &a.out);
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
    Ok(())
}

/// File name of the traversal unit's Verilog.
const UNIT_VERILOG_FILE: &str = "traversal_unit.v";

/// The traversal unit's Verilog (top module `top`, rust-hdl's port names,
/// docs/traversal-unit.md) and a config.json of what it was built from: the configuration,
/// its scene memory's capacity, the timing the schedule model takes and the port list.
fn traversal_unit(hw: &HwConfig, out: &std::path::Path) -> Result<()> {
    let config = hw.unit_config()?;
    let verilog = unit_verilog(&config)?;
    let ports = sim::verilator::parse_ports(&verilog, "top")?;
    let (nodes, triangles) = config.memory.capacity();
    let timing = config.timing();
    let summary = serde_json::json!({
        "unit": "traversal",
        "top": "top",
        "format": config.format,
        "depth": config.depth,
        "lanes": config.lanes,
        "slots": config.slots,
        "stack_depth": config.stack_depth,
        "memory": {
            "node_address_bits": config.memory.node_bits,
            "triangle_address_bits": config.memory.triangle_bits,
            "nodes": nodes,
            "triangles": triangles,
        },
        "timing": {
            "setup_latency": timing.setup_latency,
            "box_latency": timing.box_latency,
            "mt_latency": timing.mt_latency,
            "pop_latency": timing.pop_latency,
        },
        "ports": ports.iter().map(|p| serde_json::json!({
            "name": p.name,
            "direction": format!("{:?}", p.direction).to_lowercase(),
            "width": p.width,
        })).collect::<Vec<_>>(),
    });
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    for (name, text) in [
        (UNIT_VERILOG_FILE, verilog),
        (CONFIG_FILE, serde_json::to_string_pretty(&summary)? + "\n"),
    ] {
        let path = out.join(name);
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
    }
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
