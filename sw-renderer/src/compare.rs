//! Comparing a render with a golden image: PSNR, differing pixels, a heat map.

use image::RgbImage;
use thiserror::Error;

#[derive(Debug, Error, PartialEq, Eq)]
pub enum CompareError {
    #[error("images differ in size: {a_width}×{a_height} vs {b_width}×{b_height}")]
    SizeMismatch {
        a_width: u32,
        a_height: u32,
        b_width: u32,
        b_height: u32,
    },
}

/// How two images of equal size differ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageDiff {
    /// Mean squared error over all R, G, B samples.
    pub mse: f64,
    /// `10·log10(255²/MSE)` in dB; `f64::INFINITY` for identical images.
    pub psnr_db: f64,
    pub differing_pixels: u64,
    /// Share of pixels with any channel different, 0…1.
    pub differing_share: f64,
    /// Largest absolute channel difference.
    pub max_abs_error: u8,
}

fn check_size(a: &RgbImage, b: &RgbImage) -> Result<(), CompareError> {
    if a.dimensions() == b.dimensions() {
        Ok(())
    } else {
        Err(CompareError::SizeMismatch {
            a_width: a.width(),
            a_height: a.height(),
            b_width: b.width(),
            b_height: b.height(),
        })
    }
}

/// The largest channel difference of each pixel, row by row.
fn pixel_errors<'a>(a: &'a RgbImage, b: &'a RgbImage) -> impl Iterator<Item = u8> + 'a {
    a.pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0))
}

pub fn compare(a: &RgbImage, b: &RgbImage) -> Result<ImageDiff, CompareError> {
    check_size(a, b)?;
    let squared: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&x, &y)| u64::from(x.abs_diff(y)).pow(2))
        .sum();
    let samples = a.as_raw().len().max(1) as f64;
    let mse = squared as f64 / samples;
    let psnr_db = if squared == 0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    };
    let (mut differing_pixels, mut max_abs_error) = (0u64, 0u8);
    for e in pixel_errors(a, b) {
        differing_pixels += u64::from(e > 0);
        max_abs_error = max_abs_error.max(e);
    }
    let pixels = (u64::from(a.width()) * u64::from(a.height())).max(1) as f64;
    Ok(ImageDiff {
        mse,
        psnr_db,
        differing_pixels,
        differing_share: differing_pixels as f64 / pixels,
        max_abs_error,
    })
}

/// Standard PSNR in dB over R, G, B; `f64::INFINITY` when the images are identical.
pub fn psnr(a: &RgbImage, b: &RgbImage) -> Result<f64, CompareError> {
    compare(a, b).map(|d| d.psnr_db)
}

/// Per-pixel largest channel error as colour: black where identical, then (logarithmically)
/// dark blue, cyan, green, yellow, red for errors from 1 to 255.
pub fn diff_heatmap(a: &RgbImage, b: &RgbImage) -> Result<RgbImage, CompareError> {
    check_size(a, b)?;
    let mut out = RgbImage::new(a.width(), a.height());
    for (px, e) in out.pixels_mut().zip(pixel_errors(a, b)) {
        *px = image::Rgb(ramp(e));
    }
    Ok(out)
}

fn ramp(error: u8) -> [u8; 3] {
    if error == 0 {
        return [0, 0, 0];
    }
    const STOPS: [[f64; 3]; 5] = [
        [0.0, 0.0, 160.0],
        [0.0, 255.0, 255.0],
        [0.0, 255.0, 0.0],
        [255.0, 255.0, 0.0],
        [255.0, 0.0, 0.0],
    ];
    // 1 → 0, 255 → 1 on a log scale, so single-LSB differences stay visible.
    let s = f64::from(error).ln() / 255.0f64.ln() * (STOPS.len() - 1) as f64;
    let k = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - k as f64;
    [0, 1, 2].map(|c| (STOPS[k][c] + (STOPS[k + 1][c] - STOPS[k][c]) * f).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_is_black_only_for_zero_and_ends_red() {
        assert_eq!(ramp(0), [0, 0, 0]);
        assert_eq!(ramp(1), [0, 0, 160]);
        assert_eq!(ramp(255), [255, 0, 0]);
        assert!((1..=255).all(|e| ramp(e) != [0, 0, 0]));
    }
}
