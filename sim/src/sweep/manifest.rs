//! The sweep as independent jobs: `prepare` (the f32 reference renders), then one job per
//! format (model-engine quality), one per dual-precision pair (its model, and its hardware if built) and one per point
//! (hardware), in any order or on any machine
//! sharing the output directory, then `merge`. The manifest lists each as a command line, and
//! `jobs.txt` holds the middle stage one per line for `parallel < jobs.txt` or a Slurm array.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};

use super::config::{Stage, SweepConfig};
use super::dual;
use super::layout::{write_json, Layout};

/// One unit of work.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Job {
    /// Render every scene with the f32 reference once.
    Prepare,
    /// Model-engine renders of every scene in one format.
    Quality(String),
    /// Model renders of every scene through one dual-precision pair (`bfp18/fp32`).
    Dual(String),
    /// Verilog, synthesis, latency and co-simulation of one point (by id).
    Point(String),
}

impl Job {
    /// How the job is named on the command line: `prepare`, `quality/fp16`, `dual/bfp18/fp32`,
    /// `point/fp16_d1_l2`.
    pub fn id(&self) -> String {
        match self {
            Job::Prepare => "prepare".into(),
            Job::Quality(f) => format!("quality/{f}"),
            Job::Dual(p) => format!("dual/{p}"),
            Job::Point(p) => format!("point/{p}"),
        }
    }

    /// Parses [`Job::id`], checking the format or point against `config`.
    pub fn parse(id: &str, config: &SweepConfig) -> Result<Job> {
        let job = match id.split_once('/') {
            None if id == "prepare" => Job::Prepare,
            Some(("quality", f)) if config.quality_formats().iter().any(|x| x == f) => Job::Quality(f.into()),
            Some(("dual", p)) if config.pairs.iter().any(|x| x == p) => Job::Dual(p.into()),
            Some(("point", p)) if config.point(p).is_some() => Job::Point(p.into()),
            _ => bail!(
                "job `{id}` is not a job of sweep {}: expected `prepare`, `quality/FORMAT`, `dual/FILTER/FALLBACK` or `point/ID` (see manifest.json)",
                config.path.display()
            ),
        };
        Ok(job)
    }
}

/// A job and the command that runs it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct JobLine {
    pub id: String,
    pub command: String,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Manifest {
    pub config: PathBuf,
    pub out: PathBuf,
    /// Run first, once.
    pub prepare: JobLine,
    /// Independent of each other; each writes its own result file.
    pub jobs: Vec<JobLine>,
    /// Run last: results.csv/json/md and the plots.
    pub merge: JobLine,
}

/// The jobs of a configuration after `prepare`, the longest first so that a queue of
/// workers finishes together: the pair built in hardware when it is synthesised or
/// co-simulated, syntheses (wide formats and more lanes first), co-simulations, the other
/// dual-precision renders (two per scene and policy), quality renders, then the points that
/// only need their latency.
pub fn jobs(config: &SweepConfig) -> Vec<Job> {
    let mut points: Vec<_> = config.points.iter().collect();
    points.sort_by_key(|p| {
        let class = if config.synthesises(p) {
            0
        } else if config.cosimulates(p) {
            1
        } else {
            3
        };
        (
            class,
            std::cmp::Reverse(p.lanes),
            std::cmp::Reverse(p.bits()),
        )
    });
    let (slow, fast): (Vec<_>, Vec<_>) = points
        .into_iter()
        .partition(|p| config.synthesises(p) || config.cosimulates(p));
    // The pair built in hardware synthesises two designs and co-simulates four in its job:
    // with those stages it is the longest job of all.
    let (built, model): (Vec<_>, Vec<_>) = if config.runs(Stage::Quality) {
        config.pairs.iter().cloned().partition(|pair| {
            dual::has_hardware(pair) && (config.runs(Stage::Synth) || config.runs(Stage::Cosim))
        })
    } else {
        Default::default()
    };
    let mut jobs: Vec<Job> = built.into_iter().map(Job::Dual).collect();
    jobs.extend(slow.into_iter().map(|p| Job::Point(p.id())));
    jobs.extend(model.into_iter().map(Job::Dual));
    if config.runs(Stage::Quality) {
        jobs.extend(config.quality_formats().into_iter().map(Job::Quality));
    }
    jobs.extend(fast.into_iter().map(|p| Job::Point(p.id())));
    jobs
}

fn quote(s: &str) -> String {
    if s.chars()
        .all(|c| c.is_ascii_alphanumeric() || "/._-+=:".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}

/// The manifest of `config` into `out`, commands calling `program` (the rtfpga binary).
pub fn manifest(config: &SweepConfig, out: &Path, program: &str) -> Manifest {
    let line = |job: &Job| JobLine {
        id: job.id(),
        command: format!(
            "{} sweep-job --config {} --out {} --job {}",
            quote(program),
            quote(&config.path.display().to_string()),
            quote(&out.display().to_string()),
            job.id()
        ),
    };
    Manifest {
        config: config.path.clone(),
        out: out.to_path_buf(),
        prepare: line(&Job::Prepare),
        jobs: jobs(config).iter().map(line).collect(),
        merge: JobLine {
            id: "merge".into(),
            command: format!(
                "{} sweep-merge {}",
                quote(program),
                quote(&out.display().to_string())
            ),
        },
    }
}

/// Writes manifest.json, jobs.txt and the checked configuration (sweep.json, what the merge
/// reads) into the output directory.
pub fn write(config: &SweepConfig, manifest: &Manifest) -> Result<()> {
    let layout = Layout::new(&manifest.out);
    write_json(&layout.manifest(), manifest)?;
    let lines: Vec<&str> = manifest.jobs.iter().map(|j| j.command.as_str()).collect();
    let jobs = layout.jobs_txt();
    std::fs::write(&jobs, lines.join("\n") + "\n")
        .with_context(|| format!("writing {}", jobs.display()))?;
    write_json(&layout.config(), config)
}
