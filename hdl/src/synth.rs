//! Resource and logic-depth reports from yosys' Xilinx 7-series synthesis.
//!
//! Script: `read_verilog; synth_xilinx -family xc7 -top TOP -flatten -noiopad -noclkbuf; stat
//! -json; ltp …; write_json`. `-noiopad -noclkbuf` because the accelerator is a core inside a block design,
//! not a chip top: I/O and clock buffers would only add noise to the counts.
//!
//! `abc` versus `-abc9`: measured on a 32-bit add/compare/shift + 216-bit XOR test design,
//! both gave the same logic depth (12), abc9 used ~10 % fewer LUTs but no MUXF7/8 and took ~20 %
//! longer. The default is plain `abc` (the recipe the project documents); `abc9` is an option.
//!
//! Logic depth is the number of combinational cells (LUT1–6, MUXF7/8, CARRY4, and DSP48E1s that
//! have no internal pipeline register) on the longest register-to-register path, from yosys'
//! `ltp` over a selection of all wires plus those cells. Flip-flops, SRLs, block RAMs and
//! registered DSP48E1s are left out of the selection, so paths end at them. A registered
//! DSP48E1 therefore counts as a register boundary: the multiplier delay in front of its
//! internal register is not counted, an underestimate worth knowing when comparing depths.
//!
//! The same run writes the mapped netlist, from which [`crate::timing`] estimates the critical
//! path and Fmax on the XC7Z020-1 (cell delays plus a calibrated routing model; the depth
//! above counts cells, the estimate weighs them and their nets).

use serde::Serialize;
use std::collections::BTreeMap;

use crate::timing::{self, CriticalPath, TimingError};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// How many lines of yosys' output go into an error.
const ERROR_LINES: usize = 30;

/// Cells counted as one level of logic by the depth measurement (as a yosys selection).
const COMBINATIONAL_CELLS: &str = "t:LUT* %u t:MUXF* %u t:CARRY4 %u \
     t:DSP48E1 r:AREG=0 %i r:BREG=0 %i r:MREG=0 %i r:PREG=0 %i %u";

#[derive(Debug, thiserror::Error)]
pub enum SynthError {
    #[error(
        "yosys not found on PATH: install it with `apt-get install yosys` (or run `make setup`)"
    )]
    YosysNotFound,
    #[error("yosys failed to synthesise top `{top}`:\n{output}")]
    Failed { top: String, output: String },
    #[error("unexpected yosys output ({what}): {detail}")]
    Parse { what: String, detail: String },
    #[error(transparent)]
    Timing(#[from] TimingError),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}

/// Synthesis settings.
#[derive(Clone, Debug)]
pub struct SynthOptions {
    /// Map with `-abc9` (timing-driven) instead of `abc`.
    pub abc9: bool,
    /// The yosys binary (a name looked up on PATH, or a path).
    pub yosys: PathBuf,
    /// Also keep the mapped netlist (yosys JSON, the one the timing estimate reads) here.
    pub netlist: Option<PathBuf>,
}

impl Default for SynthOptions {
    fn default() -> Self {
        SynthOptions {
            abc9: false,
            yosys: PathBuf::from("yosys"),
            netlist: None,
        }
    }
}

/// What a design costs on a Xilinx 7-series device, as yosys maps it.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SynthReport {
    /// LUT1…LUT6 used as logic.
    pub lut: u64,
    /// Flip-flops (FDRE, FDSE, FDCE, FDPE).
    pub ff: u64,
    pub dsp48e1: u64,
    pub carry4: u64,
    /// Block RAM primitives (RAMB18E1 + RAMB36E1).
    pub bram: u64,
    pub muxf7: u64,
    pub muxf8: u64,
    /// LUTs used as shift registers (SRL16E, SRLC32E).
    pub srl: u64,
    /// Distributed-RAM cells (RAM32M, RAM64X1D, …): each occupies 1–8 LUTs, which
    /// `top::fit::Usage` counts.
    pub lutram: u64,
    /// Combinational cells on the longest register-to-register path (see the module docs).
    pub logic_depth: u64,
    /// Every cell type and its count, for anything the fields above do not cover.
    pub cells: BTreeMap<String, u64>,
    /// The estimated critical path on the XC7Z020-1 ([`crate::timing`]); none when the design
    /// has no register-to-register path. `rtfpga synth --json` writes it beside the report.
    #[serde(skip)]
    pub critical_path: Option<CriticalPath>,
}

impl SynthReport {
    /// Sums the cell counts into the report's categories.
    pub fn from_cells(cells: BTreeMap<String, u64>, logic_depth: u64) -> Self {
        let sum = |pred: &dyn Fn(&str) -> bool| {
            cells
                .iter()
                .filter(|(c, _)| pred(c))
                .map(|(_, n)| n)
                .sum::<u64>()
        };
        let is_lut = |c: &str| {
            c.len() == 4 && c.starts_with("LUT") && matches!(c.as_bytes()[3], b'1'..=b'6')
        };
        SynthReport {
            lut: sum(&is_lut),
            ff: sum(&|c| c.starts_with("FD")),
            dsp48e1: sum(&|c| c == "DSP48E1"),
            carry4: sum(&|c| c == "CARRY4"),
            bram: sum(&|c| c.starts_with("RAMB")),
            muxf7: sum(&|c| c == "MUXF7"),
            muxf8: sum(&|c| c == "MUXF8"),
            srl: sum(&|c| c.starts_with("SRL")),
            lutram: sum(&|c| c.starts_with("RAM") && !c.starts_with("RAMB")),
            logic_depth,
            cells,
            critical_path: None,
        }
    }

    /// The estimated Fmax on the XC7Z020-1 in MHz ([`crate::timing`]).
    pub fn fmax_mhz_estimate(&self) -> Option<f64> {
        self.critical_path.as_ref().map(CriticalPath::fmax_mhz)
    }

    /// Header of the Markdown table that [`SynthReport::markdown_row`] fills.
    pub fn markdown_header() -> String {
        "| design | LUT | FF | DSP48E1 | CARRY4 | BRAM | MUXF7 | MUXF8 | SRL | LUTRAM | logic depth |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            .to_string()
    }

    /// One Markdown table row, labelled `design`.
    pub fn markdown_row(&self, design: &str) -> String {
        format!(
            "| {design} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            self.lut,
            self.ff,
            self.dsp48e1,
            self.carry4,
            self.bram,
            self.muxf7,
            self.muxf8,
            self.srl,
            self.lutram,
            self.logic_depth
        )
    }
}

/// Cell counts of module `top` from the output of `stat -json`.
pub fn parse_stat_json(json: &str, top: &str) -> Result<BTreeMap<String, u64>, SynthError> {
    let parse_err = |detail: String| SynthError::Parse {
        what: "stat -json".into(),
        detail,
    };
    let v: serde_json::Value = serde_json::from_str(json).map_err(|e| parse_err(e.to_string()))?;
    let module = v["modules"]
        .get(format!("\\{top}"))
        .ok_or_else(|| parse_err(format!("no module `{top}` in the statistics")))?;
    // A module without cells has no `num_cells_by_type`.
    let empty = serde_json::Map::new();
    let by_type = match module.get("num_cells_by_type") {
        Some(m) => m
            .as_object()
            .ok_or_else(|| parse_err("num_cells_by_type is not an object".into()))?,
        None => &empty,
    };
    by_type
        .iter()
        .map(|(cell, n)| {
            let n = n
                .as_u64()
                .ok_or_else(|| parse_err(format!("count of {cell} is not a number")))?;
            Ok((cell.trim_start_matches('\\').to_string(), n))
        })
        .collect()
}

/// The length from `ltp`'s "Longest topological path in TOP (length=N):" line.
pub fn parse_ltp(text: &str) -> Result<u64, SynthError> {
    let line = text
        .lines()
        .find(|l| l.contains("Longest topological path"))
        .ok_or_else(|| SynthError::Parse {
            what: "ltp".into(),
            detail: "no \"Longest topological path\" line".into(),
        })?;
    line.split("length=")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .and_then(|n| n.trim().parse().ok())
        .ok_or_else(|| SynthError::Parse {
            what: "ltp".into(),
            detail: line.to_string(),
        })
}

fn first_lines(out: &std::process::Output) -> String {
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stderr),
        String::from_utf8_lossy(&out.stdout)
    );
    let mut lines: Vec<&str> = text.lines().collect();
    // Errors first, so that warnings cannot push them out of the excerpt.
    lines.sort_by_key(|l| !l.contains("ERROR"));
    lines.truncate(ERROR_LINES);
    lines.join("\n")
}

fn write(path: &Path, text: &str) -> Result<(), SynthError> {
    std::fs::write(path, text).map_err(|source| SynthError::Io {
        path: path.to_path_buf(),
        source,
    })
}

fn read(path: &Path) -> Result<String, SynthError> {
    std::fs::read_to_string(path).map_err(|source| SynthError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// A Markdown table of the resources of several designs (label, Verilog with top module
/// [`crate::verilog::TOP`]), each synthesised with the default options.
pub fn markdown_table(designs: &[(String, String)]) -> Result<String, SynthError> {
    let mut table = SynthReport::markdown_header();
    for (label, verilog) in designs {
        let report = synthesize(verilog, crate::verilog::TOP, &SynthOptions::default())?;
        table.push('\n');
        table.push_str(&report.markdown_row(label));
    }
    Ok(table)
}

/// Synthesises `verilog` (top module `top`) for xc7 and reports its resources and logic depth.
pub fn synthesize(
    verilog: &str,
    top: &str,
    options: &SynthOptions,
) -> Result<SynthReport, SynthError> {
    let dir = tempfile::tempdir().map_err(|source| SynthError::Io {
        path: std::env::temp_dir(),
        source,
    })?;
    let (src, stat, ltp, netlist, script) = (
        dir.path().join("design.v"),
        dir.path().join("stat.json"),
        dir.path().join("ltp.txt"),
        dir.path().join("netlist.json"),
        dir.path().join("synth.ys"),
    );
    write(&src, verilog)?;
    let abc9 = if options.abc9 { " -abc9" } else { "" };
    write(
        &script,
        &format!(
            "read_verilog {src}\n\
             synth_xilinx -family xc7 -top {top} -flatten -noiopad -noclkbuf{abc9}\n\
             tee -q -o {stat} stat -json\n\
             tee -q -o {ltp} ltp w:* {COMBINATIONAL_CELLS}\n\
             hierarchy -purge_lib\n\
             attrmap -remove src\n\
             write_json {netlist}\n",
            src = src.display(),
            stat = stat.display(),
            ltp = ltp.display(),
            netlist = netlist.display(),
        ),
    )?;
    let out = Command::new(&options.yosys)
        .arg("-q")
        .arg("-s")
        .arg(&script)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => SynthError::YosysNotFound,
            _ => SynthError::Io {
                path: options.yosys.clone(),
                source: e,
            },
        })?;
    if !out.status.success() {
        return Err(SynthError::Failed {
            top: top.to_string(),
            output: first_lines(&out),
        });
    }
    let cells = parse_stat_json(&read(&stat)?, top)?;
    let mut report = SynthReport::from_cells(cells, parse_ltp(&read(&ltp)?)?);
    report.critical_path = timing::analyze(&read(&netlist)?, top, &timing::ROUTING)?;
    if let Some(keep) = &options.netlist {
        std::fs::copy(&netlist, keep).map_err(|source| SynthError::Io {
            path: keep.clone(),
            source,
        })?;
    }
    Ok(report)
}
