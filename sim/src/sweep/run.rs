//! Running a sweep: one job by id (what each manifest line does), or the whole sweep on this
//! machine (manifest, prepare, every job on a pool of threads with a progress bar, merge).

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::config::{Stage, SweepConfig};
use super::layout::Layout;
use super::manifest::{self, Job};
use super::merge::merge;
use super::table::Results;
use super::{dual, hardware, quality, render_job};

pub fn run_job(config: &SweepConfig, layout: &Layout, job: &Job) -> Result<()> {
    match job {
        Job::Prepare => {
            if config.runs(Stage::Quality) {
                render_job::prepare(config, layout)?;
            }
        }
        Job::Quality(format) => {
            quality::run(config, layout, format)?;
        }
        Job::Dual(pair) => {
            dual::run(config, layout, pair)?;
        }
        Job::Point(id) => {
            let point = config.point(id).with_context(|| format!("no point {id}"))?;
            hardware::run(config, layout, point)?;
        }
    }
    Ok(())
}

pub struct LocalRun {
    /// Jobs at once (their renders share rayon's global pool).
    pub threads: usize,
    pub progress: bool,
    /// The rtfpga binary the manifest's command lines call.
    pub program: String,
}

/// Writes the manifest, runs every job here, merges.
pub fn run_local(config: &SweepConfig, out: &Path, opts: &LocalRun) -> Result<Results> {
    let layout = Layout::new(out);
    let manifest = manifest::manifest(config, out, &opts.program);
    manifest::write(config, &manifest)?;
    let jobs = manifest::jobs(config);
    let bar = if opts.progress {
        ProgressBar::with_draw_target(Some(jobs.len() as u64 + 2), ProgressDrawTarget::stderr())
    } else {
        ProgressBar::hidden()
    };
    if let Ok(style) =
        ProgressStyle::with_template("sweep [{bar:40}] {pos}/{len} jobs {elapsed}/{eta} {msg}")
    {
        bar.set_style(style);
    }
    bar.set_message("prepare (reference renders)");
    run_job(config, &layout, &Job::Prepare).context("job prepare")?;
    bar.inc(1);

    // A queue: each worker takes the next job in manifest order (longest first).
    let failures = Mutex::new(Vec::new());
    let next = AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for _ in 0..opts.threads.max(1) {
            scope.spawn(|| {
                while let Some(job) = jobs.get(next.fetch_add(1, Ordering::SeqCst)) {
                    bar.set_message(job.id());
                    if let Err(e) = run_job(config, &layout, job) {
                        // Also without a terminal (a hidden bar prints nothing).
                        bar.suspend(|| eprintln!("job {} failed: {e:#}", job.id()));
                        failures
                            .lock()
                            .unwrap_or_else(|p| p.into_inner())
                            .push(job.id());
                    }
                    bar.inc(1);
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap_or_else(|p| p.into_inner());
    if !failures.is_empty() {
        bar.abandon();
        bail!(
            "{} job(s) failed: {} (re-run them from {})",
            failures.len(),
            failures.join(", "),
            layout.manifest().display()
        );
    }
    bar.set_message("merge");
    let results = merge(&layout)?;
    bar.inc(1);
    bar.finish_with_message("done");
    Ok(results)
}
