//! The thesis `.geo` mesh parser on arbitrary text: a mesh it accepts must be usable (every
//! index in range, per-corner normals and texture coordinates for every triangle).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::{check_mesh, check_thesis_error, text};
use sw_renderer::scene::thesis::parse_geo;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("fuzz/mesh.geo");
    match parse_geo(&text, path) {
        Ok(mesh) => {
            assert!(!mesh.triangles.is_empty());
            check_mesh(&mesh);
        }
        Err(e) => check_thesis_error(&text, path, &e),
    }
});
