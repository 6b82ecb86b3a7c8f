//! The project's TOML scene format (documented in `scenes/README.md`): the thesis' options,
//! lights and materials with named fields, and geometry that is either a thesis `.geo` file or
//! one of the generators of `procedural.rs`.
//!
//! Every problem is reported with the file, the line and what was expected; unknown fields
//! are errors, so a misspelt key never silently falls back to a default.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Deserializer};
use toml::Spanned;

use super::procedural::{self, Backdrop, GeometryError};
use super::{
    thesis, Light, LightKind, Mat44, Material, MaterialKind, Mesh, Object, Options, Scene,
    SceneError,
};

/// Read and load a `.toml` scene file; `.geo` references are relative to its directory.
pub fn load_file(path: &Path) -> Result<Scene, SceneError> {
    let text = super::read_text(path)?;
    load_str(&text, path)
}

/// Load a scene from TOML text. `origin` names it in messages, gives the scene its name (the
/// file stem) and is the base of relative `.geo` paths.
pub fn load_str(text: &str, origin: &Path) -> Result<Scene, SceneError> {
    let source = Source { text, path: origin };
    let def: SceneDef =
        toml::from_str(text).map_err(|e| source.error(e.span(), syntax_message(text, &e)))?;
    let options = def.options.build(&source)?;
    let lights = def.lights.into_iter().map(LightDef::build).collect();
    let mut meshes = MeshCache::default();
    let objects = def
        .objects
        .into_iter()
        .map(|object| object_from(object, &source, &mut meshes))
        .collect::<Result<Vec<_>, _>>()?;
    let name = origin.file_stem().map_or_else(
        || origin.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    Ok(Scene {
        name,
        options,
        lights,
        objects,
    })
}

/// The toml crate's message for a syntax error. It has none for some characters (a carriage
/// return not followed by a line feed, found by `fuzz/`): then name the character. Also used
/// by the sweep config (`sim::sweep::config`).
pub fn syntax_message(text: &str, e: &toml::de::Error) -> String {
    let message = e.message().trim_end();
    if !message.is_empty() {
        return message.to_string();
    }
    let found = e
        .span()
        .and_then(|s| text.get(s.start..))
        .and_then(|rest| rest.chars().next());
    match found {
        Some('\r') => {
            "invalid TOML: a carriage return (\\r) must be followed by a line feed".into()
        }
        Some(c) => format!("invalid TOML: unexpected character {c:?}"),
        None => "invalid TOML syntax".into(),
    }
}

/// The text being loaded and its name, for error messages with a line number.
struct Source<'a> {
    text: &'a str,
    path: &'a Path,
}

impl Source<'_> {
    fn error(&self, span: Option<Range<usize>>, what: String) -> SceneError {
        let Some(span) = span else {
            return SceneError::Invalid {
                path: self.path.to_path_buf(),
                what,
            };
        };
        let start = span.start.min(self.text.len());
        let end = span.end.clamp(start, self.text.len());
        let line = self.text.as_bytes()[..start]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        let found = self.text.get(start..end).unwrap_or("");
        let token: String = found
            .lines()
            .next()
            .unwrap_or("")
            .chars()
            .take(60)
            .collect();
        SceneError::Syntax {
            path: self.path.to_path_buf(),
            line,
            token,
            what,
        }
    }

    fn error_at<T>(&self, at: &Spanned<T>, what: String) -> SceneError {
        self.error(Some(at.span()), what)
    }
}

/// A number that must be finite (TOML allows `nan` and `inf`) and fit an f32. Integers are
/// accepted where numbers are expected.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Num(f32);

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Num, D::Error> {
        let x = f64::deserialize(deserializer)?;
        if !x.is_finite() {
            return Err(serde::de::Error::custom(format!(
                "expected a finite number, found {x}"
            )));
        }
        if x.abs() > f32::MAX as f64 {
            return Err(serde::de::Error::custom(format!(
                "{x} does not fit a 32-bit float"
            )));
        }
        Ok(Num(x as f32))
    }
}

fn vec3(v: [Num; 3]) -> Vec3 {
    Vec3::new(v[0].0, v[1].0, v[2].0)
}

fn mat44(v: [Num; 16]) -> Mat44 {
    Mat44::from_row_major(v.map(|x| x.0))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneDef {
    options: OptionsDef,
    #[serde(default)]
    lights: Vec<LightDef>,
    #[serde(default)]
    objects: Vec<Spanned<ObjectDef>>,
}

/// The thesis' `kDefaultBackgroundColor`, its default bias and max depth (`scene_default.sod`).
const DEFAULT_BACKGROUND: [Num; 3] = [Num(0.235294), Num(0.67451), Num(0.843137)];
const DEFAULT_BIAS: Num = Num(0.0001);
const DEFAULT_MAX_DEPTH: u32 = 4;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OptionsDef {
    width: Spanned<u32>,
    height: Spanned<u32>,
    /// Vertical field of view, degrees.
    fov: Spanned<Num>,
    #[serde(default = "default_background")]
    background: [Num; 3],
    camera_to_world: Option<Spanned<[Num; 16]>>,
    look_at: Option<Spanned<LookAtDef>>,
    #[serde(default = "default_bias")]
    bias: Num,
    #[serde(default = "default_max_depth")]
    max_depth: u32,
}

fn default_background() -> [Num; 3] {
    DEFAULT_BACKGROUND
}
fn default_bias() -> Num {
    DEFAULT_BIAS
}
fn default_max_depth() -> u32 {
    DEFAULT_MAX_DEPTH
}

impl OptionsDef {
    fn build(self, source: &Source) -> Result<Options, SceneError> {
        for side in [&self.width, &self.height] {
            if *side.get_ref() == 0 {
                return Err(
                    source.error_at(side, "expected an image size of at least 1 pixel".into())
                );
            }
        }
        let fov = self.fov.get_ref().0;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(source.error_at(
                &self.fov,
                "expected a fov in degrees between 0 and 180, exclusive".into(),
            ));
        }
        let camera_to_world = match (self.camera_to_world, self.look_at) {
            (Some(m), None) => mat44(m.into_inner()),
            (None, Some(look)) => look.get_ref().camera_to_world().map_err(|what| source.error_at(&look, what))?,
            (Some(_), Some(look)) => {
                return Err(source.error_at(&look, "expected either camera_to_world or look_at, not both".into()))
            }
            (None, None) => {
                return Err(SceneError::Invalid {
                    path: source.path.to_path_buf(),
                    what: "[options] needs the camera: camera_to_world (16 numbers) or look_at = { from, to, up }".into(),
                })
            }
        };
        Ok(Options {
            width: self.width.into_inner(),
            height: self.height.into_inner(),
            fov_deg: fov,
            background: vec3(self.background),
            camera_to_world,
            bias: self.bias.0,
            max_depth: self.max_depth,
        })
    }
}

/// A camera at `from` looking at `to`, `up` giving the image's up direction.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LookAtDef {
    from: [Num; 3],
    to: [Num; 3],
    #[serde(default = "default_up")]
    up: [Num; 3],
}

fn default_up() -> [Num; 3] {
    [Num(0.0), Num(1.0), Num(0.0)]
}

impl LookAtDef {
    /// The camera looks along its −z: z points from `to` back to `from`.
    fn camera_to_world(&self) -> Result<Mat44, String> {
        let (from, to, up) = (vec3(self.from), vec3(self.to), vec3(self.up));
        let z = (from - to)
            .try_normalize()
            .ok_or("look_at: from and to must differ")?;
        let x = up
            .cross(z)
            .try_normalize()
            .ok_or("look_at: up must not be parallel to the view direction")?;
        let y = z.cross(x);
        Ok(Mat44([
            [x.x, x.y, x.z, 0.0],
            [y.x, y.y, y.z, 0.0],
            [z.x, z.y, z.z, 0.0],
            [from.x, from.y, from.z, 1.0],
        ]))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    kind: LightKindDef,
    color: [Num; 3],
    intensity: Num,
    #[serde(default = "identity")]
    light_to_world: [Num; 16],
}

fn identity() -> [Num; 16] {
    let m = Mat44::IDENTITY.0;
    std::array::from_fn(|i| Num(m[i / 4][i % 4]))
}

#[derive(Deserialize)]
#[serde(rename_all = "snake_case")]
enum LightKindDef {
    Distant,
    Point,
}

impl LightDef {
    fn build(self) -> Light {
        Light {
            kind: match self.kind {
                LightKindDef::Distant => LightKind::Distant,
                LightKindDef::Point => LightKind::Point,
            },
            color: vec3(self.color),
            intensity: self.intensity.0,
            light_to_world: mat44(self.light_to_world),
        }
    }
}

/// Unset material fields take the thesis' `object_default.ood` values.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    kind: MaterialKindDef,
    #[serde(default = "one")]
    ior: Num,
    #[serde(default = "default_albedo")]
    albedo: [Num; 3],
    #[serde(default = "default_kd")]
    kd: Num,
    #[serde(default = "default_ks")]
    ks: Num,
    #[serde(default = "default_n")]
    n: Num,
}

fn one() -> Num {
    Num(1.0)
}
fn default_albedo() -> [Num; 3] {
    [Num(0.18); 3]
}
fn default_kd() -> Num {
    Num(0.8)
}
fn default_ks() -> Num {
    Num(0.2)
}
fn default_n() -> Num {
    Num(10.0)
}

#[derive(Deserialize)]
#[serde(rename_all = "snake_case")]
enum MaterialKindDef {
    Diffuse,
    Reflection,
    ReflectionRefraction,
    Phong,
}

impl MaterialDef {
    fn build(self) -> Material {
        Material {
            kind: match self.kind {
                MaterialKindDef::Diffuse => MaterialKind::Diffuse,
                MaterialKindDef::Reflection => MaterialKind::Reflection,
                MaterialKindDef::ReflectionRefraction => MaterialKind::ReflectionRefraction,
                MaterialKindDef::Phong => MaterialKind::Phong,
            },
            ior: self.ior.0,
            albedo: vec3(self.albedo),
            kd: self.kd.0,
            ks: self.ks.0,
            n: self.n.0,
        }
    }
}

/// An object: exactly one of the geometry keys (`geo`, `plane`, …) must be given.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    name: String,
    #[serde(default = "identity")]
    object_to_world: [Num; 16],
    material: MaterialDef,
    geo: Option<Spanned<String>>,
    plane: Option<Spanned<PlaneDef>>,
    lathe: Option<Spanned<LatheDef>>,
    cylinder: Option<Spanned<CylinderDef>>,
    pen: Option<Spanned<PenDef>>,
    backdrop: Option<Spanned<BackdropDef>>,
    teapot: Option<Spanned<TeapotDef>>,
}

const GEOMETRY_KEYS: &str = "geo, plane, lathe, cylinder, pen, backdrop, teapot";

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct PlaneDef {
    width: Num,
    depth: Num,
    #[serde(default = "one_by_one")]
    segments: [u32; 2],
}

fn one_by_one() -> [u32; 2] {
    [1, 1]
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct LatheDef {
    /// (radius, height) points.
    profile: Vec<[Num; 2]>,
    #[serde(default = "default_round_segments")]
    segments: u32,
}

fn default_round_segments() -> u32 {
    32
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct CylinderDef {
    radius: Num,
    /// Defaults to `radius`.
    top_radius: Option<Num>,
    height: Num,
    #[serde(default = "default_round_segments")]
    segments: u32,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct PenDef {
    radius: Num,
    length: Num,
    tip_length: Num,
    #[serde(default = "default_pen_segments")]
    segments: u32,
}

fn default_pen_segments() -> u32 {
    8
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct BackdropDef {
    width: Num,
    depth: Num,
    height: Num,
    #[serde(default)]
    radius: Option<Num>,
    /// Defaults to `radius`.
    bend_height: Option<Num>,
    #[serde(default = "one_segment")]
    width_segments: u32,
    #[serde(default = "one_segment")]
    floor_segments: u32,
    #[serde(default = "default_bend_segments")]
    bend_segments: u32,
    #[serde(default = "one_segment")]
    wall_segments: u32,
}

fn one_segment() -> u32 {
    1
}
fn default_bend_segments() -> u32 {
    8
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct TeapotDef {
    #[serde(default = "default_teapot_segments")]
    segments: u32,
    #[serde(default = "one")]
    size: Num,
}

fn default_teapot_segments() -> u32 {
    10
}

/// What an object's mesh is made from; equal definitions share one mesh.
#[derive(Clone, Debug, PartialEq)]
enum GeometryDef {
    Geo(PathBuf),
    Plane(PlaneDef),
    Lathe(LatheDef),
    Cylinder(CylinderDef),
    Pen(PenDef),
    Backdrop(BackdropDef),
    Teapot(TeapotDef),
}

impl GeometryDef {
    /// Read or generate the mesh; errors point at `span`, the geometry's place in the file.
    fn mesh(&self, span: Range<usize>, source: &Source, object: &str) -> Result<Mesh, SceneError> {
        let generated = match self {
            GeometryDef::Geo(path) => {
                return thesis::load_geo(path).map_err(|e| match e {
                    // Say which scene line asked for the missing file.
                    SceneError::Io { path, source: io } => source.error(
                        Some(span),
                        format!("cannot read geometry file {}: {io}", path.display()),
                    ),
                    other => other,
                });
            }
            GeometryDef::Plane(p) => procedural::plane(p.width.0, p.depth.0, p.segments),
            GeometryDef::Lathe(l) => {
                let profile: Vec<Vec2> =
                    l.profile.iter().map(|[r, h]| Vec2::new(r.0, h.0)).collect();
                procedural::lathe(&profile, l.segments)
            }
            GeometryDef::Cylinder(c) => procedural::cylinder(
                c.radius.0,
                c.top_radius.unwrap_or(c.radius).0,
                c.height.0,
                c.segments,
            ),
            GeometryDef::Pen(p) => {
                procedural::pen(p.radius.0, p.length.0, p.tip_length.0, p.segments)
            }
            GeometryDef::Backdrop(b) => procedural::backdrop(&Backdrop {
                width: b.width.0,
                depth: b.depth.0,
                height: b.height.0,
                radius: b.radius.map_or(0.0, |r| r.0),
                bend_height: b.bend_height.or(b.radius).map_or(0.0, |h| h.0),
                width_segments: b.width_segments,
                floor_segments: b.floor_segments,
                bend_segments: b.bend_segments,
                wall_segments: b.wall_segments,
            }),
            GeometryDef::Teapot(t) => procedural::teapot(t.segments, t.size.0),
        };
        generated
            .map_err(|e: GeometryError| source.error(Some(span), format!("object `{object}`: {e}")))
    }
}

#[derive(Default)]
struct MeshCache {
    meshes: Vec<(GeometryDef, Arc<Mesh>)>,
}

fn object_from(
    object: Spanned<ObjectDef>,
    source: &Source,
    meshes: &mut MeshCache,
) -> Result<Object, SceneError> {
    let span = object.span();
    let def = object.into_inner();
    let base = source.path.parent().unwrap_or(Path::new(""));
    fn spanned<T: Clone>(
        g: &Option<Spanned<T>>,
        f: fn(T) -> GeometryDef,
    ) -> Option<(Range<usize>, GeometryDef)> {
        g.as_ref().map(|s| (s.span(), f(s.get_ref().clone())))
    }
    let given: Vec<(Range<usize>, GeometryDef)> = [
        def.geo
            .as_ref()
            .map(|g| (g.span(), GeometryDef::Geo(base.join(g.get_ref())))),
        spanned(&def.plane, GeometryDef::Plane),
        spanned(&def.lathe, GeometryDef::Lathe),
        spanned(&def.cylinder, GeometryDef::Cylinder),
        spanned(&def.pen, GeometryDef::Pen),
        spanned(&def.backdrop, GeometryDef::Backdrop),
        spanned(&def.teapot, GeometryDef::Teapot),
    ]
    .into_iter()
    .flatten()
    .collect();
    let (geometry_span, geometry) = match given.as_slice() {
        [one] => one.clone(),
        [] => {
            return Err(source.error(
                Some(span),
                format!(
                    "object `{}` has no geometry: expected one of {GEOMETRY_KEYS}",
                    def.name
                ),
            ))
        }
        [_, second, ..] => {
            return Err(source.error(
                Some(second.0.clone()),
                format!(
                "object `{}` has more than one geometry: expected exactly one of {GEOMETRY_KEYS}",
                def.name
            ),
            ))
        }
    };
    let mesh = match meshes.meshes.iter().find(|(g, _)| *g == geometry) {
        Some((_, mesh)) => Arc::clone(mesh),
        None => {
            let mesh = geometry.mesh(geometry_span, source, &def.name)?;
            let mesh = Arc::new(mesh);
            meshes.meshes.push((geometry, Arc::clone(&mesh)));
            mesh
        }
    };
    Ok(Object {
        name: def.name,
        mesh,
        object_to_world: mat44(def.object_to_world),
        material: def.material.build(),
    })
}
