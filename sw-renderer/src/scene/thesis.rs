//! The thesis' scene formats. (In progress: being written by the thesis-format work.)
use super::{Scene, SceneError};
use std::path::Path;

/// Load a thesis scene directory: its one `.sod`, and the objects listed in `objects.txt`.
pub fn load_dir(_dir: &Path) -> Result<Scene, SceneError> {
    unimplemented!("thesis scene loading")
}
