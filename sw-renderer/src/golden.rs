//! The golden images: every built-in scene rendered by the reference `F32` engine at one
//! documented size, stored in `golden/` with a manifest. Hardware renders are judged against
//! them; `rtfpga golden` regenerates them and a test proves the committed ones are current.

use std::fmt::Write as _;
use std::path::Path;

use image::RgbImage;
use thiserror::Error;

use crate::intersect::F32Intersector;
use crate::render::{render, save_png, RenderError, RenderOptions};
use crate::scene::{builtin, Scene, SceneError};

/// Golden resolution: 16:9 like the thesis' 1920×1080 and 1280×720, small enough for tests.
pub const WIDTH: u32 = 640;
pub const HEIGHT: u32 = 360;

#[derive(Debug, Error)]
pub enum GoldenError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("cannot write {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

/// Render built-in scene `name` as its golden image.
pub fn render_builtin(name: &str) -> Result<RgbImage, GoldenError> {
    let scene = Scene::load(name)?;
    let opts = RenderOptions {
        width: Some(WIDTH),
        height: Some(HEIGHT),
        ..Default::default()
    };
    Ok(render(&scene, &F32Intersector, &opts)?.image)
}

/// Write every golden image and `manifest.toml` into `dir`.
pub fn write_all(dir: &Path) -> Result<(), GoldenError> {
    let io = |path: &Path, source| GoldenError::Io {
        path: path.display().to_string(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut manifest = format!(
        "# Golden images of scenes/: engine f32 (the reference renderer), {WIDTH}x{HEIGHT}.\n\
         # Regenerate with `make golden`; sw-renderer/tests/golden.rs checks they are current.\n"
    );
    for name in builtin::names() {
        let image = render_builtin(name)?;
        save_png(&image, &dir.join(format!("{name}.png")))?;
        writeln!(manifest, "\n[[image]]\nscene = \"{name}\"\nfile = \"{name}.png\"\nwidth = {WIDTH}\nheight = {HEIGHT}\nengine = \"f32\"")
            .expect("writing to a String");
    }
    let path = dir.join("manifest.toml");
    std::fs::write(&path, manifest).map_err(|e| io(&path, e))
}
