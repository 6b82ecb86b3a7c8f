//! The thesis `.ood` parser (placement and material) on arbitrary text.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::{check_thesis_error, text};
use sw_renderer::scene::thesis::parse_ood;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("fuzz/object.ood");
    match parse_ood(&text, path) {
        Ok((m, material)) => {
            assert!(m.0.iter().flatten().all(|x| x.is_finite()));
            assert!(material.albedo.is_finite() && material.ior.is_finite());
        }
        Err(e) => check_thesis_error(&text, path, &e),
    }
});
