//! Built-in scenes: the TOML files of the repository's `scenes/` directory, embedded in the
//! binary so they load on a fresh clone, without the thesis' files. A built-in is named by its
//! file stem, e.g. `glass_pen`.

use std::path::Path;

use super::{toml_scene, Scene, SceneError};

macro_rules! scene_file {
    ($stem:literal) => {
        (
            $stem,
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../scenes/",
                $stem,
                ".toml"
            )),
        )
    };
}

/// (name, TOML text), in the order of the thesis' Appendix B.
const SCENES: [(&str, &str); 7] = [
    scene_file!("glass_pen"),
    scene_file!("simple_plane"),
    scene_file!("glasses"),
    scene_file!("glasses_point"),
    scene_file!("simple_plane2"),
    scene_file!("utah_teapot"),
    scene_file!("all_materials"),
];

/// The built-in scene names.
pub fn names() -> Vec<&'static str> {
    SCENES.iter().map(|(name, _)| *name).collect()
}

/// The TOML text of a built-in scene.
pub fn text(name: &str) -> Option<&'static str> {
    SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

/// Load a built-in scene; `None` if there is no built-in of that name.
pub fn load(name: &str) -> Option<Result<Scene, SceneError>> {
    let text = text(name)?;
    Some(toml_scene::load_str(
        text,
        &Path::new("scenes").join(format!("{name}.toml")),
    ))
}
