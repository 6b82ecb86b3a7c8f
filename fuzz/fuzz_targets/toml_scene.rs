//! The project's TOML scene format on arbitrary text: parse, check and build the scene,
//! generating its procedural meshes. The scene's directory does not exist, so a relative
//! `geo = "..."` reference fails with a read error instead of reading the file system.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::{check_mesh, check_toml_error, text};
use sw_renderer::scene::toml_scene::load_str;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("/nonexistent-rtfpga-fuzz/scene.toml");
    match load_str(&text, path) {
        Ok(scene) => {
            assert_eq!(scene.name, "scene");
            assert!(scene.options.width >= 1 && scene.options.height >= 1);
            for object in &scene.objects {
                check_mesh(&object.mesh);
            }
        }
        Err(e) => check_toml_error(&text, path, &e),
    }
});
