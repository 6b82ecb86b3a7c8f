//! One point of the design space: a number format, a pipeline depth and a lane count.

use hdl::top::TopConfig;
use hw_model::HwFormat;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Point {
    pub format: HwFormat,
    /// Pipeline registers per operator.
    pub depth: usize,
    pub lanes: usize,
}

impl Point {
    pub fn new(format: HwFormat, depth: usize, lanes: usize) -> Point {
        Point {
            format,
            depth,
            lanes,
        }
    }

    pub fn top_config(&self) -> TopConfig {
        TopConfig::new(self.format, self.depth, self.lanes)
    }

    /// The point's id in manifests and file names: the accelerator's folder name (`fp32_d1_l4`).
    pub fn id(&self) -> String {
        self.top_config().dir_name()
    }

    /// Width of the format in bits.
    pub fn bits(&self) -> u32 {
        self.format.format().width()
    }
}

/// Width in bits of a catalogue format (0 for a name outside the catalogue).
pub fn format_bits(format: &str) -> u32 {
    hw_model::lookup(format).map_or(0, |f| f.width())
}
