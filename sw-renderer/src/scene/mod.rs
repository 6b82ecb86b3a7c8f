//! Scenes: what the renderer draws, independent of where it was read from.
//!
//! Two sources produce a [`Scene`]: the thesis' file formats (`.sod` + `.ood` + `.geo` with
//! `objects.txt`, see `thesis.rs`) and the project's own TOML format (`toml_scene.rs`), whose
//! geometry may be generated procedurally (`procedural.rs`). Built-in scene names resolve to
//! the TOML files of `scenes/` embedded in the binary (`builtin.rs`).

pub mod builtin;
pub mod error;
pub mod procedural;
pub mod thesis;
pub mod toml_scene;

use std::path::Path;
use std::sync::Arc;

use glam::{Vec2, Vec3};

pub use error::SceneError;

/// The text of a scene file (`.toml`, `.sod`, `objects.txt`, `.ood`, `.geo`). Only regular
/// files are read: a device or a pipe named as a scene file (`/dev/zero`, a FIFO) would never
/// end or never open (found while fuzzing the TOML scenes' `geo = "..."`).
pub(crate) fn read_text(path: &Path) -> Result<String, SceneError> {
    let io_error = |source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    };
    if !std::fs::metadata(path).map_err(io_error)?.is_file() {
        return Err(io_error(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a directory, a device or a pipe); expected a scene file",
        )));
    }
    std::fs::read_to_string(path).map_err(io_error)
}

/// A 4×4 matrix, row-major, row-vector convention: a point p maps to p·M, the translation is
/// in the last row (exactly as the thesis' `.sod`/`.ood` files store it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat44(pub [[f32; 4]; 4]);

impl Mat44 {
    pub const IDENTITY: Mat44 = Mat44([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);

    /// From 16 values in file order (row-major).
    pub fn from_row_major(v: [f32; 16]) -> Mat44 {
        let mut m = [[0.0; 4]; 4];
        for (i, x) in v.iter().enumerate() {
            m[i / 4][i % 4] = *x;
        }
        Mat44(m)
    }
}

/// Global render options (the `.sod` file minus its lights).
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    pub width: u32,
    pub height: u32,
    /// Vertical field of view in degrees.
    pub fov_deg: f32,
    pub background: Vec3,
    pub camera_to_world: Mat44,
    pub bias: f32,
    pub max_depth: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightKind {
    /// Shines along light-to-world applied to (0, 0, −1).
    Distant,
    /// Sits at light-to-world applied to (0, 0, 0), falls off with 1/(4πr²).
    Point,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    pub color: Vec3,
    pub intensity: f32,
    pub light_to_world: Mat44,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaterialKind {
    Diffuse,
    Reflection,
    ReflectionRefraction,
    Phong,
}

/// The `.ood` material block.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub kind: MaterialKind,
    pub ior: f32,
    pub albedo: Vec3,
    pub kd: f32,
    pub ks: f32,
    /// Phong specular exponent.
    pub n: f32,
}

/// A triangle mesh in object space. Triangles index `positions`; normals and texture
/// coordinates are per triangle corner (the `.geo` format stores them per face-vertex).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub normals: Vec<[Vec3; 3]>,
    pub uvs: Vec<[Vec2; 3]>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Where it came from (file names or TOML object name), for messages.
    pub name: String,
    pub mesh: Arc<Mesh>,
    pub object_to_world: Mat44,
    pub material: Material,
}

/// A complete scene. Object order matters: it decides ties between equally near hits.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub name: String,
    pub options: Options,
    pub lights: Vec<Light>,
    pub objects: Vec<Object>,
}

impl Scene {
    /// Load a scene from a thesis scene directory (with `objects.txt`), a `.toml` scene file,
    /// or a built-in scene name.
    pub fn load(spec: &str) -> Result<Scene, SceneError> {
        let path = Path::new(spec);
        if path.is_dir() {
            thesis::load_dir(path)
        } else if path.extension().is_some_and(|e| e == "toml") {
            toml_scene::load_file(path)
        } else if let Some(scene) = builtin::load(spec) {
            scene
        } else {
            Err(SceneError::NotFound {
                spec: spec.to_string(),
                builtins: builtin::names().join(", "),
            })
        }
    }

    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangles.len()).sum()
    }
}
