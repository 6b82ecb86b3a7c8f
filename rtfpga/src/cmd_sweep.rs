//! `rtfpga sweep`, `sweep-job`, `sweep-merge`: design-space sweeps (`sim::sweep`,
//! docs/sweep.md). `sweep` writes the manifest and runs everything here; `sweep-job` runs one
//! manifest line (GNU parallel, Slurm arrays); `sweep-merge` gathers the results.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use sim::sweep::{self, Job, Layout, LocalRun, Results};

#[derive(ClapArgs)]
pub struct Args {
    /// Sweep configuration (see sweeps/default.toml).
    #[arg(long)]
    config: PathBuf,
    /// Output directory (results, plots, grids, per-job files, the synthesis cache).
    #[arg(long)]
    out: PathBuf,
    /// Jobs at once (1 to 256).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u16).range(1..=256))]
    jobs: u16,
    /// Only check the configuration and write manifest.json and jobs.txt.
    #[arg(long)]
    manifest_only: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(ClapArgs)]
pub struct JobArgs {
    /// Sweep configuration (the sweep's).
    #[arg(long)]
    config: PathBuf,
    /// The sweep's output directory.
    #[arg(long)]
    out: PathBuf,
    /// `prepare`, `quality/FORMAT` or `point/ID` (manifest.json lists them).
    #[arg(long)]
    job: String,
}

#[derive(ClapArgs)]
pub struct MergeArgs {
    /// The sweep's output directory.
    dir: PathBuf,
}

fn program() -> String {
    std::env::current_exe().map_or_else(|_| "rtfpga".to_string(), |p| p.display().to_string())
}

pub fn run(a: Args) -> Result<()> {
    let config = sweep::load(&a.config)?;
    if a.manifest_only {
        let manifest = sweep::manifest::manifest(&config, &a.out, &program());
        sweep::manifest::write(&config, &manifest)?;
        println!(
            "{} points, {} jobs after `prepare`: {}",
            config.points.len(),
            manifest.jobs.len(),
            Layout::new(&a.out).manifest().display()
        );
        return Ok(());
    }
    let opts = LocalRun {
        threads: usize::from(a.jobs),
        progress: !a.quiet,
        program: program(),
    };
    let results = sweep::run_local(&config, &a.out, &opts)?;
    summary(&results, &Layout::new(&a.out));
    Ok(())
}

pub fn run_job(a: JobArgs) -> Result<()> {
    let config = sweep::load(&a.config)?;
    let job = Job::parse(&a.job, &config)?;
    sweep::run_job(&config, &Layout::new(&a.out), &job).with_context(|| format!("job {}", a.job))
}

pub fn run_merge(a: MergeArgs) -> Result<()> {
    let layout = Layout::new(&a.dir);
    let results = sweep::merge(&layout)?;
    summary(&results, &layout);
    Ok(())
}

fn summary(results: &Results, layout: &Layout) {
    println!(
        "{} rows (points × spawn policies, the hardware lane) merged: {}, {}, {}, {}",
        results.rows.len(),
        layout.results("csv").display(),
        layout.quality_csv().display(),
        layout.results("json").display(),
        layout.results("md").display()
    );
    let hardware: Vec<_> = results
        .quality
        .iter()
        .filter(|q| !results.model_formats.contains(&q.format))
        .collect();
    for &variant in &results.variants {
        match sweep::table::smallest_format_above(hardware.iter().copied(), variant, 40.0) {
            Some(q) => println!(
                "smallest format with a PSNR of at least 40 dB on every scene, {variant}: {} ({} bits)",
                q.format, q.bits
            ),
            None if !hardware.is_empty() => {
                println!("no format reaches a PSNR of 40 dB on every scene with the {variant}")
            }
            None => {}
        }
    }
    for d in &results.dual {
        println!(
            "dual_precision pair={} policy={} forwarded_share={:.4} equals_fallback={}",
            d.pair,
            d.policy,
            d.forwarded_share(),
            d.exact()
        );
    }
}
