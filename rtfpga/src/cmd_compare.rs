//! `rtfpga compare`: PSNR between two images, last line `psnr_db=<number|inf>`.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use sw_renderer::compare;
use sw_renderer::render::save_png;

#[derive(ClapArgs)]
pub struct Args {
    a: PathBuf,
    b: PathBuf,
    /// Write an error heat-map here.
    #[arg(long)]
    diff: Option<PathBuf>,
}

fn open(p: &PathBuf) -> Result<image::RgbImage> {
    Ok(image::open(p)
        .with_context(|| format!("reading {}", p.display()))?
        .to_rgb8())
}

pub fn run(a: Args) -> Result<()> {
    let (ia, ib) = (open(&a.a)?, open(&a.b)?);
    let stats = compare::compare(&ia, &ib)?;
    if let Some(d) = &a.diff {
        save_png(&compare::diff_heatmap(&ia, &ib)?, d)
            .with_context(|| format!("writing {}", d.display()))?;
    }
    println!(
        "differing_pixels={} max_abs_error={}",
        stats.differing_pixels, stats.max_abs_error
    );
    let psnr = if stats.psnr_db.is_infinite() {
        "inf".to_string()
    } else {
        format!("{:.4}", stats.psnr_db)
    };
    println!("psnr_db={psnr}");
    Ok(())
}
