//! `rtfpga compare`: the PSNR of two images, last line `psnr_db=<number|inf>`.

use image::{Rgb, RgbImage};
use sw_renderer::render::save_png;

use crate::common::*;

/// A test pattern: smooth gradients, so that changed pixels change the MSE by known amounts.
fn pattern(w: u32, h: u32) -> RgbImage {
    RgbImage::from_fn(w, h, |x, y| {
        Rgb([(x * 7) as u8, (y * 11) as u8, ((x + y) * 3) as u8])
    })
}

/// PSNR computed here from the pixels, independently of the library: MSE over every R, G and
/// B sample, peak 255.
fn psnr_independent(a: &RgbImage, b: &RgbImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let (mut sum, mut n) = (0.0f64, 0.0f64);
    for (p, q) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = f64::from(p[c]) - f64::from(q[c]);
            sum += d * d;
            n += 1.0;
        }
    }
    let mse = sum / n;
    if mse == 0.0 {
        f64::INFINITY
    } else {
        20.0 * 255.0f64.log10() - 10.0 * mse.log10()
    }
}

#[test]
fn identical_images_print_psnr_inf_last() {
    let dir = tmp();
    let (a, b, d) = (at(&dir, "a.png"), at(&dir, "b.png"), at(&dir, "d.png"));
    let img = pattern(23, 11);
    save_png(&img, &a).unwrap();
    save_png(&img, &b).unwrap();
    let out = rtfpga(&["compare", s(&a), s(&b), "--diff", s(&d)]).ok();
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
    assert_eq!(psnr_of(&out), f64::INFINITY);
    assert_eq!(read_png(&d).dimensions(), (23, 11), "--diff has A's size");
    let out = rtfpga(&["compare", s(&a), s(&a)]).ok();
    assert_eq!(last_line(&out), "psnr_db=inf", "{out}");
}

#[test]
fn different_images_print_the_psnr_of_their_pixels_and_a_heat_map() {
    let dir = tmp();
    let (a, b, d) = (at(&dir, "a.png"), at(&dir, "b.png"), at(&dir, "diff.png"));
    let ia = pattern(40, 30);
    let mut ib = ia.clone();
    // A few strongly and many slightly changed samples, in every channel.
    ib.put_pixel(0, 0, Rgb([255, 255, 255]));
    ib.put_pixel(39, 29, Rgb([0, 0, 0]));
    for x in 0..40 {
        let p = ib.get_pixel_mut(x, 7);
        p[x as usize % 3] = p[x as usize % 3].wrapping_add(3);
    }
    save_png(&ia, &a).unwrap();
    save_png(&ib, &b).unwrap();
    let expected = psnr_independent(&ia, &ib);
    assert!(expected.is_finite() && expected > 10.0);

    let out = rtfpga(&["compare", s(&a), s(&b), "--diff", s(&d)]).ok();
    let got = psnr_of(&out);
    assert!(
        (got - expected).abs() < 1e-3,
        "rtfpga compare says psnr_db={got}, the pixels give {expected:.6}\n{out}"
    );
    let out = rtfpga(&["compare", s(&b), s(&a)]).ok();
    assert!((psnr_of(&out) - expected).abs() < 1e-3, "symmetric: {out}");
    let diff = read_png(&d);
    assert_eq!(diff.dimensions(), ia.dimensions());
    assert_ne!(
        diff.get_pixel(0, 0),
        diff.get_pixel(20, 20),
        "the heat-map marks the changed pixel"
    );
}

#[test]
fn images_of_different_sizes_and_unreadable_files_are_errors_naming_them() {
    let dir = tmp();
    let (a, b) = (at(&dir, "a.png"), at(&dir, "b.png"));
    save_png(&pattern(8, 4), &a).unwrap();
    save_png(&pattern(4, 8), &b).unwrap();
    rtfpga(&["compare", s(&a), s(&b)]).fails(1, &["8×4", "4×8"]);
    let missing = at(&dir, "missing.png");
    rtfpga(&["compare", s(&a), s(&missing)]).fails(1, &["missing.png"]);
    let text = at(&dir, "notes.png");
    std::fs::write(&text, "not an image").unwrap();
    rtfpga(&["compare", s(&text), s(&a)]).fails(1, &["notes.png"]);
}
