//! Calibrates the routing model of `hdl::timing` against published Vivado results
//! (docs/timing.md, "Calibration"). `scripts/timing_calibration.sh` fetches the designs'
//! Verilog and runs this as `timing_calibration DIR`: DIR/<design>/ holds the design's
//! Verilog files; the mapped netlist is kept as DIR/<design>/netlist.json and reused.
//!
//! For each design it synthesises (hdl::synth, the flow `rtfpga synth` uses), scales the
//! published period to the XC7Z020-1, fits the routing model's two constants by least squares
//! on the log of the period ratio (a grid), and prints the residuals of the fit and of a
//! leave-one-out fit (each design predicted from the others' constants) as Markdown.

use std::path::Path;

use anyhow::{Context, Result};
use hdl::synth::{synthesize, SynthOptions};
use hdl::timing::{RoutingModel, TimingGraph, ROUTING};

/// Period of the 2015 PicoRV32 on each 7-series device and speed grade (PicoRV32 README,
/// 2015 revision: Vivado 2015.1, post-route `report_timing`), in ns: the family and
/// speed-grade scaling of this calibration. The XC7Z020-1's fabric is Artix-7 -1's.
const ARTIX7_1: f64 = 5.1;
const ARTIX7_3: f64 = 3.6;
const KINTEX7_2: f64 = 2.6;
const KINTEX7_3: f64 = 2.5;
const VIRTEX7_2: f64 = 2.6;
const VIRTEX7_3: f64 = 2.4;

/// A published result: the device, its period in ns, and that device's period in the
/// scaling table.
struct Published {
    device: &'static str,
    period_ns: f64,
    scaling_ns: f64,
}

struct Design {
    name: &'static str,
    files: &'static [&'static str],
    top: &'static str,
    /// What the figures are of.
    source: &'static str,
    published: &'static [Published],
}

const DESIGNS: &[Design] = &[
    Design {
        name: "picorv32",
        files: &["tabtest.v", "picorv32.v"],
        top: "top",
        source: "PicoRV32 README (Vivado 2017.3, `picorv32_axi` with TWO_CYCLE_ALU in scripts/vivado/tabtest.v, binary search on the period)",
        published: &[
            Published { device: "xc7k70t-2", period_ns: 2.4, scaling_ns: KINTEX7_2 },
            Published { device: "xc7k70t-3", period_ns: 2.2, scaling_ns: KINTEX7_3 },
            Published { device: "xc7v585t-2", period_ns: 2.3, scaling_ns: VIRTEX7_2 },
            Published { device: "xc7v585t-3", period_ns: 2.2, scaling_ns: VIRTEX7_3 },
        ],
    },
    Design {
        name: "vexriscv_min",
        files: &["VexRiscv_Min.v"],
        top: "VexRiscv",
        source: "VexRiscv README, \"small (RV32I, no datapath bypass)\", 240 MHz; the LiteX build VexRiscv_Min (RV32I, no bypass, no caches) stands for it",
        published: &[Published { device: "Artix-7 -3", period_ns: 1000.0 / 240.0, scaling_ns: ARTIX7_3 }],
    },
    Design {
        name: "vexriscv_full",
        files: &["VexRiscv_Full.v"],
        top: "VexRiscv",
        source: "VexRiscv README, \"full (RV32IM, 4 KB I$ and D$, single-cycle barrel shifter, catch exceptions, static branch)\", 199 MHz; the LiteX build VexRiscv_Full stands for it",
        published: &[Published { device: "Artix-7 -3", period_ns: 1000.0 / 199.0, scaling_ns: ARTIX7_3 }],
    },
];

impl Design {
    /// The published periods scaled to the XC7Z020-1, averaged.
    fn target_ns(&self) -> f64 {
        let scaled: Vec<f64> = self
            .published
            .iter()
            .map(|p| p.period_ns * ARTIX7_1 / p.scaling_ns)
            .collect();
        scaled.iter().sum::<f64>() / scaled.len() as f64
    }
}

fn netlist(dir: &Path, d: &Design) -> Result<TimingGraph> {
    let here = dir.join(d.name);
    let path = here.join("netlist.json");
    if !path.exists() {
        let mut verilog = String::new();
        for f in d.files {
            let file = here.join(f);
            verilog += &std::fs::read_to_string(&file)
                .with_context(|| format!("reading {}", file.display()))?;
            verilog.push('\n');
        }
        eprintln!("synthesising {} (yosys)…", d.name);
        let options = SynthOptions {
            netlist: Some(path.clone()),
            ..SynthOptions::default()
        };
        let report = synthesize(&verilog, d.top, &options)?;
        eprintln!(
            "{}: {} LUT, {} FF, logic depth {}",
            d.name, report.lut, report.ff, report.logic_depth
        );
    }
    let json = std::fs::read_to_string(&path)?;
    Ok(TimingGraph::from_json(&json, d.top)?)
}

fn estimate_ns(g: &TimingGraph, m: &RoutingModel) -> f64 {
    g.critical_path(m)
        .map_or(f64::NAN, |p| p.delay_ps as f64 / 1000.0)
}

/// The constants minimising the squared log ratio estimate/target over `designs`.
fn fit(designs: &[(&TimingGraph, f64)]) -> RoutingModel {
    let mut best = (f64::INFINITY, ROUTING);
    for base in (0..=1500).step_by(10) {
        for doubling in (0..=300).step_by(10) {
            let m = RoutingModel {
                base_ps: base as f64,
                per_fanout_doubling_ps: doubling as f64,
            };
            let err: f64 = designs
                .iter()
                .map(|(g, t)| (estimate_ns(g, &m) / t).ln().powi(2))
                .sum();
            if err < best.0 {
                best = (err, m);
            }
        }
    }
    best.1
}

fn main() -> Result<()> {
    let dir = std::env::args()
        .nth(1)
        .context("usage: timing_calibration DIR (see scripts/timing_calibration.sh)")?;
    let dir = Path::new(&dir);
    let graphs: Vec<TimingGraph> = DESIGNS
        .iter()
        .map(|d| netlist(dir, d))
        .collect::<Result<_>>()?;
    let targets: Vec<f64> = DESIGNS.iter().map(Design::target_ns).collect();
    let all: Vec<(&TimingGraph, f64)> = graphs.iter().zip(targets.iter().copied()).collect();
    let fitted = fit(&all);
    println!(
        "Fitted routing model: {} ps + {} ps per doubling of fanout (in use: {} + {}).\n",
        fitted.base_ps,
        fitted.per_fanout_doubling_ps,
        ROUTING.base_ps,
        ROUTING.per_fanout_doubling_ps
    );
    println!("| design | published | scaled to XC7Z020-1 | estimate (in use) | residual | cells / routing | levels | leave-one-out estimate | residual |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for (i, d) in DESIGNS.iter().enumerate() {
        let path = graphs[i]
            .critical_path(&ROUTING)
            .context("no register-to-register path")?;
        let est = path.delay_ps as f64 / 1000.0;
        let others: Vec<(&TimingGraph, f64)> = all
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &x)| x)
            .collect();
        let loo = estimate_ns(&graphs[i], &fit(&others));
        let published: Vec<String> = d
            .published
            .iter()
            .map(|p| format!("{} {:.2} ns", p.device, p.period_ns))
            .collect();
        println!(
            "| {} | {} | {:.2} ns | {:.2} ns | {:+.0} % | {:.2} / {:.2} ns | {} | {:.2} ns | {:+.0} % |",
            d.name,
            published.join(", "),
            targets[i],
            est,
            100.0 * (est / targets[i] - 1.0),
            path.cell_ps as f64 / 1000.0,
            path.routing_ps as f64 / 1000.0,
            path.levels,
            loo,
            100.0 * (loo / targets[i] - 1.0),
        );
    }
    println!();
    for d in DESIGNS {
        println!("- {}: {}.", d.name, d.source);
    }
    Ok(())
}
