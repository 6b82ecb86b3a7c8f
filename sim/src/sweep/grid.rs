//! A format's image grid: one row per scene, its render then its error heat-map.

use std::path::Path;

use anyhow::Result;
use image::{Rgb, RgbImage};
use sw_renderer::render::save_png;

use super::layout::parent_dir;

/// Pixels between cells (white).
const GAP: u32 = 4;

pub fn write_grid(rows: &[[RgbImage; 2]], path: &Path) -> Result<()> {
    let cell_w = rows
        .iter()
        .flatten()
        .map(RgbImage::width)
        .max()
        .unwrap_or(0);
    let cell_h = rows
        .iter()
        .flatten()
        .map(RgbImage::height)
        .max()
        .unwrap_or(0);
    let cols = 2;
    let mut grid = RgbImage::from_pixel(
        cols * cell_w + (cols + 1) * GAP,
        rows.len() as u32 * cell_h + (rows.len() as u32 + 1) * GAP,
        Rgb([255, 255, 255]),
    );
    for (r, row) in rows.iter().enumerate() {
        for (c, cell) in row.iter().enumerate() {
            let x = GAP + c as u32 * (cell_w + GAP);
            let y = GAP + r as u32 * (cell_h + GAP);
            image::imageops::replace(&mut grid, cell, i64::from(x), i64::from(y));
        }
    }
    parent_dir(path)?;
    save_png(&grid, path)?;
    Ok(())
}
