//! How many lanes of a configuration fit a device: synthesise the accelerator with 1 and 2
//! lanes, take the difference as the cost of a lane and the rest as the fixed part (AXI-Lite
//! slave, stream front end), and divide what the device has left by the per-lane cost.
use serde::Serialize;

use crate::synth::{synthesize, SynthError, SynthOptions, SynthReport};
use crate::top::{top_verilog, wrapper, TopConfig, TopError};

/// The resources of a device that bound the lane count.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Device {
    pub name: &'static str,
    pub lut: u64,
    pub ff: u64,
    pub dsp48e1: u64,
    /// Block RAM in RAMB18 halves (a RAMB36 counts 2).
    pub bram18: u64,
}

/// The ZedBoard's Zynq-7020 (DS190): 53,200 LUTs, 106,400 FFs, 220 DSP48E1, 140 RAMB36.
pub const XC7Z020: Device = Device {
    name: "XC7Z020",
    lut: 53_200,
    ff: 106_400,
    dsp48e1: 220,
    bram18: 280,
};

impl Device {
    /// Whether `usage` fits: every resource within the device's.
    pub fn holds(&self, usage: Usage) -> bool {
        usage.lut <= self.lut
            && usage.ff <= self.ff
            && usage.dsp48e1 <= self.dsp48e1
            && usage.bram18 <= self.bram18
    }
}

/// What a design uses of the resources a [`Device`] lists.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Usage {
    pub lut: u64,
    pub ff: u64,
    pub dsp48e1: u64,
    pub bram18: u64,
}

impl Usage {
    pub fn of(report: &SynthReport) -> Self {
        let cells = |name: &str| report.cells.get(name).copied().unwrap_or(0);
        let lut_ram: u64 = report
            .cells
            .iter()
            .map(|(cell, n)| n * lut_ram_luts(cell))
            .sum();
        Usage {
            // SRLs and LUT RAM occupy LUTs too.
            lut: report.lut + report.srl + lut_ram,
            ff: report.ff,
            dsp48e1: report.dsp48e1,
            bram18: cells("RAMB18E1") + 2 * cells("RAMB36E1"),
        }
    }

    /// `self − other` per resource, never below zero.
    pub fn minus(self, other: Usage) -> Usage {
        Usage {
            lut: self.lut.saturating_sub(other.lut),
            ff: self.ff.saturating_sub(other.ff),
            dsp48e1: self.dsp48e1.saturating_sub(other.dsp48e1),
            bram18: self.bram18.saturating_sub(other.bram18),
        }
    }

    /// The usage of `fixed` plus `lanes` copies of `per_lane`.
    pub fn with_lanes(fixed: Usage, per_lane: Usage, lanes: u64) -> Usage {
        Usage {
            lut: fixed.lut + lanes * per_lane.lut,
            ff: fixed.ff + lanes * per_lane.ff,
            dsp48e1: fixed.dsp48e1 + lanes * per_lane.dsp48e1,
            bram18: fixed.bram18 + lanes * per_lane.bram18,
        }
    }
}

/// The LUTs a cell occupies as distributed RAM (UG474, UG574: a RAM32M or RAM64M is a
/// SLICEM's four LUTs); 0 for other cells, and the largest, 8, for a RAM cell not listed.
pub fn lut_ram_luts(cell: &str) -> u64 {
    match cell {
        "RAM32X1S" | "RAM64X1S" => 1,
        "RAM32X1D" | "RAM64X1D" | "RAM128X1S" => 2,
        "RAM32M" | "RAM64M" | "RAM128X1D" | "RAM256X1S" => 4,
        c if c.starts_with("RAM") && !c.starts_with("RAMB") => 8,
        _ => 0,
    }
}

/// The lane estimate of one configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct LaneFit {
    pub device: &'static str,
    pub per_lane: Usage,
    pub fixed: Usage,
    pub lanes: u64,
    /// The resource that runs out first.
    pub limit: &'static str,
}

/// Lanes that fit `device` given the 1-lane and 2-lane usages.
pub fn fit_from(one: Usage, two: Usage, device: &Device) -> LaneFit {
    let per_lane = two.minus(one);
    fit(one.minus(per_lane), per_lane, device)
}

/// Lanes that fit `device` given the 1-lane usage and a fixed part measured elsewhere (the
/// same format's 1- and 2-lane pair at another depth): the rest of `one` is the lane.
pub fn fit_with_fixed(one: Usage, fixed: Usage, device: &Device) -> LaneFit {
    fit(fixed, one.minus(fixed), device)
}

/// Lanes of `per_lane` that fit `device` beside `fixed`, and the resource that limits them.
fn fit(fixed: Usage, per_lane: Usage, device: &Device) -> LaneFit {
    let candidates = [
        ("LUT", device.lut, fixed.lut, per_lane.lut),
        ("FF", device.ff, fixed.ff, per_lane.ff),
        ("DSP48E1", device.dsp48e1, fixed.dsp48e1, per_lane.dsp48e1),
        ("BRAM", device.bram18, fixed.bram18, per_lane.bram18),
    ];
    let (limit, lanes) = candidates
        .iter()
        .filter(|c| c.3 > 0)
        .map(|&(name, budget, fixed, lane)| (name, budget.saturating_sub(fixed) / lane))
        .min_by_key(|&(_, n)| n)
        .unwrap_or(("nothing", u64::MAX));
    LaneFit {
        device: device.name,
        per_lane,
        fixed,
        lanes,
        limit,
    }
}

#[derive(Debug, thiserror::Error)]
pub enum FitError {
    #[error(transparent)]
    Config(#[from] TopError),
    #[error(transparent)]
    Synth(#[from] SynthError),
}

/// yosys report of the whole accelerator (`rtfpga_top`) of `config`.
pub fn synthesize_top(config: &TopConfig, options: &SynthOptions) -> Result<SynthReport, FitError> {
    Ok(synthesize(&top_verilog(config)?, wrapper::TOP, options)?)
}
