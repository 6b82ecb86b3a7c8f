//! The project's TOML scene format. (In progress.)
use super::{Scene, SceneError};
use std::path::Path;

pub fn load_file(_path: &Path) -> Result<Scene, SceneError> {
    unimplemented!("TOML scene loading")
}
