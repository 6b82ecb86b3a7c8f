//! Comparing a render with a golden image: PSNR, differing pixels, a heat map, and the two
//! images and their heat map side by side.

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

/// `a | b | diff_heatmap(a, b)` in one image, three widths wide and as tall as the inputs: the
/// first third is `a`, the second `b`, the third the heat map `--diff` writes.
pub fn side_by_side(a: &RgbImage, b: &RgbImage) -> Result<RgbImage, CompareError> {
    let diff = diff_heatmap(a, b)?;
    Ok(hconcat(&[a, b, &diff]))
}

/// [`side_by_side`] with a caption strip under it: `labels[i]` is written under panel `i`
/// (upper case, in a built-in 5×7 pixel font; characters it lacks are drawn as `?`, text
/// longer than its panel is cut). The top `a.height()` rows are exactly [`side_by_side`].
pub fn side_by_side_labelled(
    a: &RgbImage,
    b: &RgbImage,
    labels: [&str; 3],
) -> Result<RgbImage, CompareError> {
    let montage = side_by_side(a, b)?;
    let strip = caption_strip(a.width(), &labels);
    let mut out = RgbImage::new(montage.width(), montage.height() + strip.height());
    image::imageops::replace(&mut out, &montage, 0, 0);
    image::imageops::replace(&mut out, &strip, 0, i64::from(montage.height()));
    Ok(out)
}

/// The images next to each other, left to right, top-aligned (black below shorter ones).
pub fn hconcat(images: &[&RgbImage]) -> RgbImage {
    let width = images.iter().map(|i| i.width()).sum();
    let height = images.iter().map(|i| i.height()).max().unwrap_or(0);
    let mut out = RgbImage::new(width, height);
    let mut x = 0i64;
    for i in images {
        image::imageops::replace(&mut out, *i, x, 0);
        x += i64::from(i.width());
    }
    out
}

const CAPTION_BACKGROUND: [u8; 3] = [24, 24, 24];
const CAPTION_INK: [u8; 3] = [235, 235, 235];

/// A dark strip `labels.len()` panels of `panel_width` wide, each label in light text at the
/// left of its panel. Glyphs are drawn at twice their size when a panel is 240 pixels or wider.
pub fn caption_strip(panel_width: u32, labels: &[&str]) -> RgbImage {
    let scale = if panel_width >= 240 { 2 } else { 1 };
    let (margin, pad) = (3 * scale, 4 * scale);
    let height = GLYPH_ROWS * scale + 2 * pad;
    let mut strip = RgbImage::from_pixel(
        panel_width * labels.len() as u32,
        height,
        image::Rgb(CAPTION_BACKGROUND),
    );
    for (p, label) in labels.iter().enumerate() {
        let panel_x = p as u32 * panel_width;
        let mut x = margin;
        for ch in label.chars() {
            if x + GLYPH_COLS * scale > panel_width {
                break;
            }
            let rows = glyph(ch);
            for (r, bits) in rows.iter().enumerate() {
                for c in 0..GLYPH_COLS {
                    if bits >> (GLYPH_COLS - 1 - c) & 1 == 1 {
                        for dy in 0..scale {
                            for dx in 0..scale {
                                strip.put_pixel(
                                    panel_x + x + c * scale + dx,
                                    pad + r as u32 * scale + dy,
                                    image::Rgb(CAPTION_INK),
                                );
                            }
                        }
                    }
                }
            }
            x += (GLYPH_COLS + 1) * scale;
        }
    }
    strip
}

const GLYPH_COLS: u32 = 5;
const GLYPH_ROWS: u32 = 7;

/// A 5×7 glyph, one row per byte, the leftmost column in bit 4. Letters are upper case only.
fn glyph(ch: char) -> [u8; 7] {
    match ch.to_ascii_uppercase() {
        'A' => [
            0b01110, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001,
        ],
        'B' => [
            0b11110, 0b10001, 0b10001, 0b11110, 0b10001, 0b10001, 0b11110,
        ],
        'C' => [
            0b01110, 0b10001, 0b10000, 0b10000, 0b10000, 0b10001, 0b01110,
        ],
        'D' => [
            0b11100, 0b10010, 0b10001, 0b10001, 0b10001, 0b10010, 0b11100,
        ],
        'E' => [
            0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b11111,
        ],
        'F' => [
            0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b10000,
        ],
        'G' => [
            0b01110, 0b10001, 0b10000, 0b10111, 0b10001, 0b10001, 0b01111,
        ],
        'H' => [
            0b10001, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001,
        ],
        'I' => [
            0b01110, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110,
        ],
        'J' => [
            0b00111, 0b00010, 0b00010, 0b00010, 0b00010, 0b10010, 0b01100,
        ],
        'K' => [
            0b10001, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010, 0b10001,
        ],
        'L' => [
            0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b11111,
        ],
        'M' => [
            0b10001, 0b11011, 0b10101, 0b10101, 0b10001, 0b10001, 0b10001,
        ],
        'N' => [
            0b10001, 0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001,
        ],
        'O' => [
            0b01110, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110,
        ],
        'P' => [
            0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000,
        ],
        'Q' => [
            0b01110, 0b10001, 0b10001, 0b10001, 0b10101, 0b10010, 0b01101,
        ],
        'R' => [
            0b11110, 0b10001, 0b10001, 0b11110, 0b10100, 0b10010, 0b10001,
        ],
        'S' => [
            0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110,
        ],
        'T' => [
            0b11111, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100,
        ],
        'U' => [
            0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110,
        ],
        'V' => [
            0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100,
        ],
        'W' => [
            0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010,
        ],
        'X' => [
            0b10001, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001, 0b10001,
        ],
        'Y' => [
            0b10001, 0b10001, 0b10001, 0b01010, 0b00100, 0b00100, 0b00100,
        ],
        'Z' => [
            0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b11111,
        ],
        '0' => [
            0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110,
        ],
        '1' => [
            0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110,
        ],
        '2' => [
            0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111,
        ],
        '3' => [
            0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110,
        ],
        '4' => [
            0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010,
        ],
        '5' => [
            0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110,
        ],
        '6' => [
            0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110,
        ],
        '7' => [
            0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000,
        ],
        '8' => [
            0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110,
        ],
        '9' => [
            0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100,
        ],
        ' ' => [0; 7],
        '.' => [0, 0, 0, 0, 0, 0b01100, 0b01100],
        ',' => [0, 0, 0, 0, 0b01100, 0b00100, 0b01000],
        ':' => [0, 0b01100, 0b01100, 0, 0b01100, 0b01100, 0],
        '-' => [0, 0, 0, 0b11111, 0, 0, 0],
        '+' => [0, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0],
        '=' => [0, 0, 0b11111, 0, 0b11111, 0, 0],
        '_' => [0, 0, 0, 0, 0, 0, 0b11111],
        '/' => [0, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0],
        '|' => [0b00100; 7],
        '(' => [
            0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010,
        ],
        ')' => [
            0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000,
        ],
        '%' => [
            0b11000, 0b11001, 0b00010, 0b00100, 0b01000, 0b10011, 0b00011,
        ],
        '×' => [0, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001, 0],
        _ => [0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0, 0b00100],
    }
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

    fn gradient(w: u32, h: u32, seed: u8) -> RgbImage {
        RgbImage::from_fn(w, h, |x, y| {
            image::Rgb([
                (x as u8).wrapping_mul(7).wrapping_add(seed),
                (y as u8).wrapping_mul(13),
                seed.wrapping_mul(31) ^ (x + y) as u8,
            ])
        })
    }

    fn third(m: &RgbImage, i: u32, w: u32, h: u32) -> RgbImage {
        image::imageops::crop_imm(m, i * w, 0, w, h).to_image()
    }

    #[test]
    fn side_by_side_is_a_then_b_then_the_heatmap() {
        let (w, h) = (37, 11);
        let a = gradient(w, h, 3);
        let mut b = a.clone();
        b.put_pixel(5, 4, image::Rgb([0, 0, 0]));
        b.put_pixel(36, 10, image::Rgb([255, 1, 2]));
        let m = side_by_side(&a, &b).unwrap();
        assert_eq!(m.dimensions(), (3 * w, h));
        assert_eq!(third(&m, 0, w, h), a);
        assert_eq!(third(&m, 1, w, h), b);
        assert_eq!(third(&m, 2, w, h), diff_heatmap(&a, &b).unwrap());
        assert!(matches!(
            side_by_side(&a, &gradient(w + 1, h, 0)),
            Err(CompareError::SizeMismatch { .. })
        ));
    }

    #[test]
    fn labelled_montage_keeps_the_montage_above_its_captions() {
        for (w, h) in [(320, 18), (40, 9)] {
            let (a, b) = (gradient(w, h, 1), gradient(w, h, 2));
            let plain = side_by_side(&a, &b).unwrap();
            let labelled = side_by_side_labelled(&a, &b, ["sw", "hw fp32", "diff"]).unwrap();
            assert_eq!(labelled.width(), 3 * w);
            assert!(labelled.height() > h);
            assert_eq!(
                image::imageops::crop_imm(&labelled, 0, 0, 3 * w, h).to_image(),
                plain
            );
            // Each caption put ink in its own panel.
            let strip = caption_strip(w, &["sw", "hw fp32", "diff"]);
            assert_eq!(strip.width(), 3 * w);
            for p in 0..3 {
                let inked = (p * w..(p + 1) * w)
                    .flat_map(|x| (0..strip.height()).map(move |y| (x, y)))
                    .any(|(x, y)| strip.get_pixel(x, y).0 == CAPTION_INK);
                assert!(inked, "panel {p} of width {w} has no caption");
            }
        }
    }

    #[test]
    fn long_captions_stay_in_their_panel() {
        let strip = caption_strip(20, &["a very long caption", ""]);
        let second_panel_inked = (20..40)
            .flat_map(|x| (0..strip.height()).map(move |y| (x, y)))
            .any(|(x, y)| strip.get_pixel(x, y).0 == CAPTION_INK);
        assert!(!second_panel_inked);
    }

    #[test]
    fn every_drawn_character_has_a_distinct_glyph() {
        let chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 .,:-+=_/|()%×";
        let glyphs: Vec<[u8; 7]> = chars.chars().map(glyph).collect();
        for (i, g) in glyphs.iter().enumerate() {
            assert!(g.iter().all(|row| *row < 32));
            assert!(!glyphs[..i].contains(g), "{:?}", chars.chars().nth(i));
        }
        assert_eq!(glyph('a'), glyph('A'));
    }

    #[test]
    fn ramp_is_black_only_for_zero_and_ends_red() {
        assert_eq!(ramp(0), [0, 0, 0]);
        assert_eq!(ramp(1), [0, 0, 160]);
        assert_eq!(ramp(255), [255, 0, 0]);
        assert!((1..=255).all(|e| ramp(e) != [0, 0, 0]));
    }
}
