//! yosys results of the sweep's points, kept in the output directory so that a re-run only
//! synthesises designs whose Verilog changed (the key is the Verilog's SHA-256 and the timing
//! estimate's routing model).

use std::time::Instant;

use anyhow::Result;
use hdl::synth::{synthesize, SynthOptions};
use hdl::timing::{CriticalPath, ROUTING};
use hdl::top::fit::Usage;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::layout::{read_json, write_json, Layout};

/// What the sweep keeps of a yosys report.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SynthRecord {
    /// LUTs as the device counts them (logic + shift registers + LUT RAM).
    pub lut: u64,
    pub ff: u64,
    pub dsp48e1: u64,
    pub carry4: u64,
    /// RAMB18 halves.
    pub bram18: u64,
    pub logic_depth: u64,
    /// The estimated critical path on the XC7Z020-1 (`hdl::timing`); none without a
    /// register-to-register path.
    pub critical_path: Option<CriticalPath>,
    /// yosys' wall time when it ran.
    pub seconds: u64,
    pub verilog_sha256: String,
    /// The routing model the critical path was estimated with ([`routing_key`]).
    pub routing_model: String,
}

impl SynthRecord {
    /// The estimated Fmax on the XC7Z020-1 in MHz.
    pub fn fmax_mhz_estimate(&self) -> Option<f64> {
        self.critical_path.as_ref().map(CriticalPath::fmax_mhz)
    }

    pub fn usage(&self) -> Usage {
        Usage {
            lut: self.lut,
            ff: self.ff,
            dsp48e1: self.dsp48e1,
            bram18: self.bram18,
        }
    }
}

fn sha256_hex(text: &str) -> String {
    Sha256::digest(text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The routing model in use, as a cache key: a recalibrated model re-estimates.
pub fn routing_key() -> String {
    format!(
        "{} ps + {} ps per fanout doubling",
        ROUTING.base_ps, ROUTING.per_fanout_doubling_ps
    )
}

/// The report of design `id` with Verilog `verilog`, top module `top`: from the cache when
/// the Verilog and the routing model are the same, else from yosys (then cached; a record
/// written before the timing estimate does not parse, and is replaced). Returns the record and
/// whether it was cached.
pub fn synthesize_cached(
    layout: &Layout,
    id: &str,
    top: &str,
    verilog: &str,
) -> Result<(SynthRecord, bool)> {
    let sha = sha256_hex(verilog);
    let path = layout.synth_cache(id);
    if path.exists() {
        if let Ok(cached) = read_json::<SynthRecord>(&path) {
            if cached.verilog_sha256 == sha && cached.routing_model == routing_key() {
                return Ok((cached, true));
            }
        }
    }
    let start = Instant::now();
    let report = synthesize(verilog, top, &SynthOptions::default())?;
    let usage = Usage::of(&report);
    let record = SynthRecord {
        lut: usage.lut,
        ff: usage.ff,
        dsp48e1: usage.dsp48e1,
        carry4: report.carry4,
        bram18: usage.bram18,
        logic_depth: report.logic_depth,
        critical_path: report.critical_path,
        seconds: start.elapsed().as_secs(),
        verilog_sha256: sha,
        routing_model: routing_key(),
    };
    write_json(&path, &record)?;
    Ok((record, false))
}
