//! Built-in scenes: the TOML files of `scenes/`, embedded. (In progress.)
use super::{Scene, SceneError};

pub fn load(_name: &str) -> Option<Result<Scene, SceneError>> {
    None
}

pub fn names() -> Vec<&'static str> {
    Vec::new()
}
