//! `rtfpga golden`: regenerate the golden images of the built-in scenes.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;

#[derive(ClapArgs)]
pub struct Args {
    /// Output directory (the repository's `golden/`).
    #[arg(long, default_value = "golden")]
    out: PathBuf,
}

pub fn run(a: Args) -> Result<()> {
    sw_renderer::golden::write_all(&a.out)?;
    println!(
        "wrote golden images and manifest.toml to {}",
        a.out.display()
    );
    Ok(())
}
