//! `rtfpga compare`: PSNR between two images, last line `psnr_db=<number|inf>`; optionally an
//! error heat-map and a side-by-side montage A | B | heat-map.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args as ClapArgs;
use sw_renderer::compare;
use sw_renderer::render::save_png;

use crate::report::{self, Line};

#[derive(ClapArgs)]
pub struct Args {
    /// The first image (the reference: PNG or any format the image crate reads).
    a: PathBuf,
    /// The image compared with A, of A's size.
    b: PathBuf,
    /// Write an error heat-map here (.png; its folder is created).
    #[arg(long, value_name = "DIFF.png")]
    diff: Option<PathBuf>,
    /// Write A, B and the error heat-map side by side here (three widths wide), captioned
    /// underneath unless --no-labels.
    #[arg(long, value_name = "OUT.png")]
    side_by_side: Option<PathBuf>,
    /// Captions of the panels of --side-by-side, comma-separated: A,B or A,B,DIFF [default:
    /// the file names of A and B; DIFF: "difference, PSNR <x> dB" or "difference, identical"].
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "A,B[,DIFF]",
        requires = "side_by_side"
    )]
    labels: Option<Vec<String>>,
    /// --side-by-side without the caption strip: exactly A | B | heat-map.
    #[arg(long, conflicts_with = "labels", requires = "side_by_side")]
    no_labels: bool,
}

fn open(p: &PathBuf) -> Result<image::RgbImage> {
    Ok(image::open(p)
        .with_context(|| format!("reading {}", p.display()))?
        .to_rgb8())
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
}

/// The three captions of the montage: --labels (A,B or A,B,DIFF) or the file names, and
/// "difference, PSNR <x> dB" / "difference, identical" unless given.
fn captions(a: &Args, stats: &compare::ImageDiff) -> Result<Vec<String>> {
    let mut labels = match &a.labels {
        Some(l) if !(2..=3).contains(&l.len()) => {
            anyhow::bail!("--labels takes A,B or A,B,DIFF, not {} values", l.len())
        }
        Some(l) => l.clone(),
        None => vec![file_name(&a.a), file_name(&a.b)],
    };
    if labels.len() == 2 {
        labels.push(if stats.psnr_db.is_infinite() {
            "difference, identical".to_string()
        } else {
            format!("difference, PSNR {:.2} dB", stats.psnr_db)
        });
    }
    Ok(labels)
}

pub fn run(a: Args) -> Result<()> {
    if let Some(d) = &a.diff {
        report::image_out("--diff", d)?;
    }
    if let Some(m) = &a.side_by_side {
        report::image_out("--side-by-side", m)?;
    }
    let (ia, ib) = (open(&a.a)?, open(&a.b)?);
    let stats = compare::compare(&ia, &ib)?;
    if let Some(d) = &a.diff {
        save_png(&compare::diff_heatmap(&ia, &ib)?, d)?;
        Line::new().path("diff", d).print();
    }
    if let Some(out) = &a.side_by_side {
        let montage = if a.no_labels {
            compare::side_by_side(&ia, &ib)?
        } else {
            let labels = captions(&a, &stats)?;
            compare::side_by_side_labelled(&ia, &ib, [&labels[0], &labels[1], &labels[2]])?
        };
        save_png(&montage, out)?;
        Line::new().path("side_by_side", out).print();
    }
    Line::new()
        .kv("differing_pixels", stats.differing_pixels)
        .kv("max_abs_error", stats.max_abs_error)
        .print();
    Line::new()
        .kv("psnr_db", report::psnr(stats.psnr_db))
        .print();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use image::{Rgb, RgbImage};

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }

    fn parse(argv: &[&str]) -> Args {
        Cli::try_parse_from(std::iter::once("compare").chain(argv.iter().copied()))
            .unwrap()
            .args
    }

    #[test]
    fn side_by_side_is_a_b_and_the_diff_image() {
        let dir = tempfile::tempdir().unwrap();
        let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
        let (w, h) = (24, 10);
        let a = RgbImage::from_fn(w, h, |x, y| Rgb([x as u8 * 9, y as u8 * 20, 77]));
        let mut b = a.clone();
        b.put_pixel(3, 2, Rgb([255, 255, 255]));
        b.put_pixel(20, 9, Rgb([0, 0, 1]));
        save_png(&a, Path::new(&p("a.png"))).unwrap();
        save_png(&b, Path::new(&p("b.png"))).unwrap();
        run(parse(&[
            &p("a.png"),
            &p("b.png"),
            "--diff",
            &p("d.png"),
            "--side-by-side",
            &p("m.png"),
            "--no-labels",
        ]))
        .unwrap();
        let m = image::open(p("m.png")).unwrap().to_rgb8();
        let d = image::open(p("d.png")).unwrap().to_rgb8();
        assert_eq!(m.dimensions(), (3 * w, h));
        let third = |i| image::imageops::crop_imm(&m, i * w, 0, w, h).to_image();
        assert_eq!(third(0), a);
        assert_eq!(third(1), b);
        assert_eq!(third(2), d);
        assert_ne!(
            d,
            RgbImage::new(w, h),
            "the diff shows the two changed pixels"
        );

        // Captioned: the same montage on top of a caption strip.
        run(parse(&[
            &p("a.png"),
            &p("b.png"),
            "--side-by-side",
            &p("l.png"),
            "--labels",
            "sw,hw,diff",
        ]))
        .unwrap();
        let l = image::open(p("l.png")).unwrap().to_rgb8();
        assert_eq!(l.width(), 3 * w);
        assert!(l.height() > h);
        assert_eq!(image::imageops::crop_imm(&l, 0, 0, 3 * w, h).to_image(), m);
    }

    #[test]
    fn labels_take_two_or_three_values() {
        let stats = |psnr_db| compare::ImageDiff {
            mse: 0.0,
            psnr_db,
            differing_pixels: 0,
            differing_share: 0.0,
            max_abs_error: 0,
        };
        let with = |labels: &str| {
            let a = parse(&[
                "x/a.png",
                "b.png",
                "--side-by-side",
                "m.png",
                "--labels",
                labels,
            ]);
            captions(&a, &stats(41.234))
        };
        assert!(with("x").is_err());
        assert!(with("w,x,y,z").is_err());
        assert_eq!(
            with("x,y").unwrap(),
            ["x", "y", "difference, PSNR 41.23 dB"]
        );
        assert_eq!(with("x,y,z").unwrap(), ["x", "y", "z"]);
        let default = parse(&["x/a.png", "b.png", "--side-by-side", "m.png"]);
        assert_eq!(
            captions(&default, &stats(f64::INFINITY)).unwrap(),
            ["a.png", "b.png", "difference, identical"]
        );
        let orphan = Cli::try_parse_from(["compare", "a.png", "b.png", "--labels", "x,y"]);
        assert!(orphan.is_err(), "--labels needs --side-by-side");
    }
}
