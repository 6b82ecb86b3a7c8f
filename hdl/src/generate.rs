//! The file set `rtfpga verilog` writes for one configuration: `rtfpga_top.v` (wrapper +
//! body), the C register header and bare-metal driver ([`crate::cgen`]) and `config.json`.
use std::path::Path;

use hw_model::HwFormat;

use crate::cgen;
use crate::regmap;
use crate::top::stream::{FIFO_DEPTH, IN_LANE_BITS, OUT_LANE_BITS};
use crate::top::wrapper::{self, TopPort};
use crate::top::{TopConfig, TopError};

/// File name of the Verilog (what constraints/ expects).
pub const VERILOG_FILE: &str = "rtfpga_top.v";
pub const CONFIG_FILE: &str = "config.json";

/// The configurations committed under generated-verilog/ (`make verilog`).
pub fn default_configs() -> Vec<TopConfig> {
    vec![
        TopConfig::new(HwFormat::FP32, 1, 1),
        TopConfig::new(HwFormat::FP32, 1, 4),
        TopConfig::new(HwFormat::named("fp16"), 1, 1),
    ]
}

/// What config.json records about a generated accelerator.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    pub format: HwFormat,
    pub depth: usize,
    pub lanes: usize,
    /// Cycles from a query entering a lane to its result.
    pub lane_latency: usize,
    /// Cycles from an accepted input beat to `m_axis_tvalid` of its results (FIFO included),
    /// with `m_axis_tready` high.
    pub stream_latency: usize,
    /// The CONFIG register's value and the ID register's.
    pub config_word: u32,
    pub id_word: u32,
    pub top: String,
    pub stream_in_lane_bits: usize,
    pub stream_out_lane_bits: usize,
    pub result_fifo_depth: usize,
    pub ports: Vec<TopPort>,
}

/// A generated configuration: file names and contents, in writing order.
#[derive(Clone, Debug)]
pub struct Generated {
    pub summary: Summary,
    pub files: Vec<(String, String)>,
}

/// Generates every file of `config` in memory (the configuration is checked first).
pub fn generate(config: &TopConfig) -> Result<Generated, TopError> {
    config.validate()?;
    let lane_latency = config.lane_latency()?;
    let summary = Summary {
        format: config.format,
        depth: config.depth,
        lanes: config.lanes,
        lane_latency,
        stream_latency: lane_latency + 2,
        config_word: config.config_word()?.pack(),
        id_word: regmap::ID_VALUE,
        top: wrapper::TOP.to_string(),
        stream_in_lane_bits: IN_LANE_BITS,
        stream_out_lane_bits: OUT_LANE_BITS,
        result_fifo_depth: FIFO_DEPTH,
        ports: wrapper::ports(config.lanes),
    };
    let verilog = crate::top::top_verilog(config)?;
    let (driver_h, driver_c) = cgen::c_driver();
    let json = serde_json::to_string_pretty(&summary).expect("plain data serialises") + "\n";
    Ok(Generated {
        summary,
        files: vec![
            (VERILOG_FILE.to_string(), verilog),
            (cgen::HEADER_FILE.to_string(), cgen::c_header()),
            (cgen::DRIVER_HEADER_FILE.to_string(), driver_h),
            (cgen::DRIVER_SOURCE_FILE.to_string(), driver_c),
            (CONFIG_FILE.to_string(), json),
        ],
    })
}

impl Generated {
    /// The text of file `name`.
    pub fn file(&self, name: &str) -> Option<&str> {
        self.files
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, t)| t.as_str())
    }

    /// Writes every file into `dir` (created if missing).
    pub fn write_to(&self, dir: &Path) -> anyhow::Result<()> {
        use anyhow::Context;
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        for (name, text) in &self.files {
            let path = dir.join(name);
            std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?;
        }
        Ok(())
    }
}
