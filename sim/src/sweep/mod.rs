//! Design-space sweeps: formats × depths × lanes, each point's hardware (Verilog, yosys
//! resources and logic depth, latency, co-simulation), each format's image quality per spawn
//! policy and origin advance, and each dual-precision pair's exactness and forwarded share,
//! merged into tables, plots and image grids with the projected ZedBoard frame time.
//!
//! - [`config`]: SWEEP.toml, checked before any work;
//! - [`manifest`]: the sweep as independent jobs and their command lines;
//! - [`render_job`], [`quality`], [`dual`], [`hardware`], [`synth_cache`]: what the jobs do;
//! - [`merge`], [`table`], [`plots`], [`grid`], [`projection`]: the merged results;
//! - [`run`]: one job, or the whole sweep locally.
//!
//! docs/sweep.md describes the files and reports the default sweep.

pub mod config;
pub mod dual;
pub mod grid;
pub mod hardware;
pub mod layout;
pub mod manifest;
pub mod merge;
pub mod plots;
pub mod point;
pub mod projection;
pub mod quality;
pub mod render_job;
pub mod run;
pub mod synth_cache;
pub mod table;

pub use config::{load, parse, ConfigError, Stage, SweepConfig};
pub use layout::Layout;
pub use manifest::{Job, Manifest};
pub use merge::merge;
pub use point::Point;
pub use run::{run_job, run_local, LocalRun};
pub use table::Results;
