//! The thesis `.sod` parser (options and lights) on arbitrary text.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::{check_thesis_error, text};
use sw_renderer::scene::thesis::parse_sod;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("fuzz/scene.sod");
    match parse_sod(&text, path) {
        Ok((options, lights)) => {
            assert!(options.width >= 1 && options.height >= 1);
            assert!(options.fov_deg > 0.0 && options.fov_deg < 180.0);
            assert!(lights
                .iter()
                .all(|l| l.color.is_finite() && l.intensity.is_finite()));
        }
        Err(e) => check_thesis_error(&text, path, &e),
    }
});
