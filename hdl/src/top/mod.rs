//! The accelerator's top level: MT lanes behind an AXI4-Lite slave (register mode, one test
//! on lane 0) and an AXI4-Stream front end (batches, every lane busy each cycle), wrapped in
//! `rtfpga_top` with Vitis port names.
//!
//! - [`stream`]: the stream front end (packet format in docs/stream.md);
//! - [`accelerator`]: the body, instantiated per format;
//! - [`wrapper`]: the Verilog top `rtfpga_top` around rust-hdl's body.

pub mod accelerator;
pub mod fit;
pub mod stream;
pub mod wrapper;

use hw_model::HwFormat;

use crate::regmap::ConfigWord;

/// Most lanes a configuration may have: the input beat is 512 bits a lane, and 4096 bits is
/// the widest AXI4-Stream `tdata` Vivado's infrastructure takes.
pub const MAX_LANES: usize = 8;

/// Which accelerator to build.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct TopConfig {
    /// The datapath's number format.
    pub format: HwFormat,
    /// Pipeline registers per operator (`crate::mt`).
    pub depth: usize,
    pub lanes: usize,
}

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum TopError {
    #[error("lanes = 0: the accelerator needs at least one lane")]
    NoLanes,
    #[error("lanes = {0}: at most {MAX_LANES} (the stream beat is 512 bits a lane; Vivado takes 4096-bit tdata at most)")]
    TooManyLanes(usize),
    #[error("depth = {depth}: format {format} has pipeline registers for depth 0 to {max}")]
    DepthTooLarge {
        format: HwFormat,
        depth: usize,
        max: usize,
    },
}

impl TopConfig {
    pub fn new(format: HwFormat, depth: usize, lanes: usize) -> Self {
        TopConfig {
            format,
            depth,
            lanes,
        }
    }

    /// Checks the configuration without building anything.
    pub fn validate(&self) -> Result<(), TopError> {
        let max = crate::mt::max_depth(self.format);
        if self.lanes == 0 {
            return Err(TopError::NoLanes);
        }
        if self.lanes > MAX_LANES {
            return Err(TopError::TooManyLanes(self.lanes));
        }
        if self.depth > max {
            return Err(TopError::DepthTooLarge {
                format: self.format,
                depth: self.depth,
                max,
            });
        }
        Ok(())
    }

    /// Cycles from a query entering a lane to its result.
    pub fn lane_latency(&self) -> Result<usize, TopError> {
        self.validate()?;
        Ok(crate::mt::latency(self.format, self.depth))
    }

    /// What the CONFIG register reads: the format's catalogue index, depth, lanes.
    pub fn config_word(&self) -> Result<ConfigWord, TopError> {
        self.validate()?;
        Ok(ConfigWord {
            format_code: self.format.code(),
            depth: self.depth as u8,
            lanes: self.lanes as u8,
        })
    }

    /// Folder name of the configuration under generated-verilog/, e.g. `fp32_d5_l2`.
    pub fn dir_name(&self) -> String {
        format!("{}_d{}_l{}", self.format, self.depth, self.lanes)
    }
}

/// Stack for building and generating a body: the lanes are large structs built by value and
/// rust-hdl walks the hierarchy recursively, which overflows a default 2 MB thread stack.
const BUILD_STACK: usize = 512 << 20;

/// Runs `f` on a thread with [`BUILD_STACK`] of stack (only the touched pages are committed).
pub fn with_build_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .name("rust-hdl build".into())
        .stack_size(BUILD_STACK)
        .spawn(f)
        .expect("spawning the build thread")
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
}

/// The complete `rtfpga_top.v` (wrapper + body) of a configuration.
pub fn top_verilog(config: &TopConfig) -> Result<String, TopError> {
    let word = config.config_word()?.pack();
    let (format, depth, lanes) = (config.format, config.depth, config.lanes);
    let body = with_build_stack(move || accelerator::body_verilog(format, depth, lanes, word));
    Ok(wrapper::top_verilog(&body, config.lanes))
}
