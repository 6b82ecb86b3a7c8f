//! The thesis' scene formats: a directory with one `.sod` (options and lights), an
//! `objects.txt` listing `geometry-file object-file` pairs in render order, `.ood` files
//! (placement and material) and `.geo` meshes, as the thesis' reference renderer reads them;
//! each parser's doc gives its file's layout.

mod tokens;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::{
    read_text, Light, LightKind, Mat44, Material, MaterialKind, Mesh, Object, Options, Scene,
    SceneError,
};
use tokens::Tokens;

const OBJECT_LIST: &str = "objects.txt";
const U32_MAX: u64 = u32::MAX as u64;

/// Load a thesis scene directory: its one `.sod`, and the objects listed in `objects.txt`.
/// A `.geo` listed for several objects is read once and shared.
pub fn load_dir(dir: &Path) -> Result<Scene, SceneError> {
    let sod_path = find_sod(dir)?;
    let (options, lights) = parse_sod(&read_text(&sod_path)?, &sod_path)?;
    let list_path = dir.join(OBJECT_LIST);
    let list = read_text(&list_path)?;
    let entries = parse_object_list(&list, &list_path)?;

    let mut meshes: HashMap<PathBuf, Arc<Mesh>> = HashMap::new();
    let mut objects = Vec::with_capacity(entries.len());
    for (geo, ood) in entries {
        let geo_path = dir.join(geo);
        let mesh = match meshes.get(&geo_path) {
            Some(mesh) => Arc::clone(mesh),
            None => {
                let mesh = Arc::new(load_geo(&geo_path)?);
                meshes.insert(geo_path, Arc::clone(&mesh));
                mesh
            }
        };
        let ood_path = dir.join(ood);
        let (object_to_world, material) = parse_ood(&read_text(&ood_path)?, &ood_path)?;
        objects.push(Object {
            name: format!("{geo}+{ood}"),
            mesh,
            object_to_world,
            material,
        });
    }
    Ok(Scene {
        name: scene_name(dir),
        options,
        lights,
        objects,
    })
}

/// Read and parse one `.geo` file.
pub fn load_geo(path: &Path) -> Result<Mesh, SceneError> {
    parse_geo(&read_text(path)?, path)
}

/// `.sod`: width, height, fov, background (3), camera-to-world (16), bias, max depth, number of
/// lights, then per light: type, colour (3), intensity, light-to-world (16).
pub fn parse_sod(text: &str, path: &Path) -> Result<(Options, Vec<Light>), SceneError> {
    let mut t = Tokens::new(text, path);
    let width = t.whole(1..=U32_MAX, "the image width (a whole number ≥ 1)")? as u32;
    let height = t.whole(1..=U32_MAX, "the image height (a whole number ≥ 1)")? as u32;
    let fov_deg = t.number_where(
        |fov| fov > 0.0 && fov < 180.0,
        "the fov in degrees (a finite number between 0 and 180, exclusive)",
    )?;
    let background = t.vec3("the background colour")?;
    let camera_to_world = t.mat44("the camera-to-world matrix")?;
    let bias = t.number("the shadow bias")?;
    let max_depth = t.whole(0..=U32_MAX, "the max depth (a whole number)")? as u32;
    let count = t.whole(0..=U32_MAX, "the number of lights (a whole number)")?;

    let mut lights = Vec::new();
    for i in 1..=count {
        let kind = match t.whole(
            0..=1,
            format_args!("the type of light {i} of {count} (0 distant, 1 point)"),
        )? {
            0 => LightKind::Distant,
            _ => LightKind::Point,
        };
        let color = t.vec3(format_args!("the colour of light {i} of {count}"))?;
        let intensity = t.number(format_args!("the intensity of light {i} of {count}"))?;
        let light_to_world = t.mat44(format_args!(
            "the light-to-world matrix of light {i} of {count}"
        ))?;
        lights.push(Light {
            kind,
            color,
            intensity,
            light_to_world,
        });
    }
    t.finish(format_args!("the {count} light(s) the file announces"))?;

    let options = Options {
        width,
        height,
        fov_deg,
        background,
        camera_to_world,
        bias,
        max_depth,
    };
    Ok((options, lights))
}

/// `.ood`: object-to-world (16), material type, ior, albedo (3), Kd, Ks, n.
pub fn parse_ood(text: &str, path: &Path) -> Result<(Mat44, Material), SceneError> {
    let mut t = Tokens::new(text, path);
    let object_to_world = t.mat44("the object-to-world matrix")?;
    let kind = match t.whole(
        0..=3,
        "the material type (0 diffuse, 1 reflection, 2 reflection+refraction, 3 Phong)",
    )? {
        0 => MaterialKind::Diffuse,
        1 => MaterialKind::Reflection,
        2 => MaterialKind::ReflectionRefraction,
        _ => MaterialKind::Phong,
    };
    let ior = t.number("the index of refraction")?;
    let albedo = t.vec3("the albedo")?;
    let kd = t.number("Kd, the Phong diffuse weight")?;
    let ks = t.number("Ks, the Phong specular weight")?;
    let n = t.number("n, the Phong specular exponent")?;
    t.finish("n, the Phong specular exponent")?;
    Ok((
        object_to_world,
        Material {
            kind,
            ior,
            albedo,
            kd,
            ks,
            n,
        },
    ))
}

/// `.geo`: F faces; F face-vertex counts summing to S; S vertex indices (the vertex count is
/// the largest index + 1); 3 numbers per vertex position; 3 per face-vertex normal; 2 per
/// face-vertex texture coordinate. Polygons are fanned into triangles as scratchapixel's
/// `TriangleMesh` does, carrying the normals and texture coordinates of the same face-vertices.
pub fn parse_geo(text: &str, path: &Path) -> Result<Mesh, SceneError> {
    let mut t = Tokens::new(text, path);
    let faces = t.whole(1..=U32_MAX, "the number of faces (a whole number ≥ 1)")?;
    let mut face_sizes = Vec::new();
    for f in 1..=faces {
        let size = t.whole(
            3..=U32_MAX,
            format_args!("face-vertex count ≥ 3 for face {f} of {faces}"),
        )?;
        face_sizes.push(size as usize);
    }
    let corners: usize = face_sizes.iter().sum();

    let mut indices = Vec::new();
    let mut largest = None;
    for i in 1..=corners {
        let index = t.whole(
            0..=U32_MAX - 1,
            format_args!("vertex index {i} of {corners} (a whole number below {U32_MAX})"),
        )? as u32;
        indices.push(index);
        if largest.is_none_or(|(max, _)| index > max) {
            largest = Some((index, t.previous()));
        }
    }
    let (largest_index, largest_token) = largest.expect("a face has at least 3 corners");
    let vertices = largest_index as usize + 1;
    check_vertex_count(&t, largest_index, largest_token, corners)?;

    let mut positions = Vec::new();
    for v in 1..=vertices {
        positions.push(t.vec3(format_args!("the position of vertex {v} of {vertices}"))?);
    }
    let mut corner_normals = Vec::new();
    for c in 1..=corners {
        corner_normals.push(t.vec3(format_args!(
            "normal {c} of {corners} (one per face-vertex)"
        ))?);
    }
    let mut corner_uvs = Vec::new();
    for c in 1..=corners {
        corner_uvs.push(t.vec2(format_args!(
            "texture coordinate {c} of {corners} (one per face-vertex)"
        ))?);
    }
    t.finish("the texture coordinates")?;

    let mut mesh = Mesh {
        positions,
        ..Mesh::default()
    };
    let mut first = 0;
    for size in face_sizes {
        for j in 0..size - 2 {
            let fan = [first, first + j + 1, first + j + 2];
            mesh.triangles.push(fan.map(|c| indices[c]));
            mesh.normals.push(fan.map(|c| corner_normals[c]));
            mesh.uvs.push(fan.map(|c| corner_uvs[c]));
        }
        first += size;
    }
    Ok(mesh)
}

/// After the indices come 3 numbers per vertex and 5 per face-vertex. When the numbers left
/// fit that layout but for fewer vertices than the largest index needs, the index is what is
/// wrong (or positions are missing): say so at the index rather than at the end of the file.
fn check_vertex_count(
    t: &Tokens<'_>,
    largest_index: u32,
    largest_token: Option<tokens::Token<'_>>,
    corners: usize,
) -> Result<(), SceneError> {
    let numbers = t.remaining();
    let Some(position_numbers) = numbers.checked_sub(5 * corners) else {
        return Ok(());
    };
    let vertices_in_file = position_numbers / 3;
    if position_numbers % 3 != 0 || vertices_in_file > largest_index as usize {
        return Ok(());
    }
    let token = largest_token.expect("the largest index was read");
    Err(t.problem_at(
        token,
        format!(
            "vertex index {largest_index} out of range: the file has {vertices_in_file} vertices \
             ({numbers} numbers follow the {corners} indices: 3 per vertex position, then 3 per \
             face-vertex normal and 2 per face-vertex texture coordinate)"
        ),
    ))
}

/// `objects.txt`: one `geometry-file object-file` pair a line; blank lines and lines starting
/// with `#` are skipped. Public (like [`parse_sod`], [`parse_ood`] and [`parse_geo`]) so that
/// one file's text can be parsed on its own, e.g. by the fuzz targets of `fuzz/`.
pub fn parse_object_list<'a>(
    text: &'a str,
    path: &Path,
) -> Result<Vec<(&'a str, &'a str)>, SceneError> {
    let mut entries = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let content = line.trim();
        if content.is_empty() || content.starts_with('#') {
            continue;
        }
        let names: Vec<&str> = content.split_whitespace().collect();
        match names[..] {
            [geo, ood] => entries.push((geo, ood)),
            _ => {
                return Err(SceneError::Syntax {
                    path: path.to_path_buf(),
                    line: index + 1,
                    token: content.to_string(),
                    what: format!(
                        "expected a `geometry-file object-file` pair (2 file names, found {})",
                        names.len()
                    ),
                })
            }
        }
    }
    if entries.is_empty() {
        return Err(SceneError::Invalid {
            path: path.to_path_buf(),
            what: "lists no objects (expected `geometry-file object-file` lines)".to_string(),
        });
    }
    Ok(entries)
}

/// The directory's one `.sod` file.
fn find_sod(dir: &Path) -> Result<PathBuf, SceneError> {
    let io_error = |source| SceneError::Io {
        path: dir.to_path_buf(),
        source,
    };
    let mut sods = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(io_error)? {
        let path = entry.map_err(io_error)?.path();
        if path.extension().is_some_and(|e| e == "sod") && path.is_file() {
            sods.push(path);
        }
    }
    sods.sort();
    match sods.len() {
        1 => Ok(sods.remove(0)),
        0 => Err(SceneError::Invalid {
            path: dir.to_path_buf(),
            what: "no .sod scene options file (a thesis scene directory holds exactly one)"
                .to_string(),
        }),
        n => {
            let names: Vec<String> = sods
                .iter()
                .filter_map(|p| p.file_name())
                .map(|n| n.to_string_lossy().into_owned())
                .collect();
            Err(SceneError::Invalid {
                path: dir.to_path_buf(),
                what: format!(
                    "{n} .sod scene options files ({}); a thesis scene directory holds exactly one",
                    names.join(", ")
                ),
            })
        }
    }
}

/// The directory's own name (also for `.` or `..`).
fn scene_name(dir: &Path) -> String {
    let canonical = dir.canonicalize().ok();
    let name = dir
        .file_name()
        .or_else(|| canonical.as_deref().and_then(Path::file_name));
    name.map_or_else(
        || dir.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}
