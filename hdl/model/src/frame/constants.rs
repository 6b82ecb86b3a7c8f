//! What the frame unit's scene memory holds beside the traversal unit's triangles: the
//! camera, the lights, one material per object and per triangle its object and vertex
//! normals. The host computes them once per frame (where the reference computed them once
//! per render: world-space normals, light directions) and they are checked here: sizes
//! against [`FrameLimits`], every value finite, Phong exponents whole and within the limit.

use sw_renderer::camera::fov_scale;
use sw_renderer::math::{mult_point, V3};
use sw_renderer::scene::{Mat44, MaterialKind, Scene};
use sw_renderer::shade::PreparedLight;
use sw_renderer::trace::PreparedScene;

use super::{FrameError, FrameLimits};
use crate::fp32::{Fp32, Vec3};

/// The camera: pixel (i, j) → primary ray ([`super::raygen`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConstants {
    pub origin: Vec3,
    /// Rows 0 to 2 of camera-to-world (directions ignore the translation row).
    pub rows: [Vec3; 3],
    /// x = i·dx + x0 and y = j·dy + y0, the reference's
    /// `(2(i + 0.5)/width − 1)·aspect·scale` and `(1 − 2(j + 0.5)/height)·scale` rearranged:
    /// dx = 2·aspect·scale/width, x0 = (1/width − 1)·aspect·scale, dy = −2·scale/height,
    /// y0 = (1 − 1/height)·scale, each evaluated in double from the reference's float aspect
    /// and scale and rounded once.
    pub dx: Fp32,
    pub x0: Fp32,
    pub dy: Fp32,
    pub y0: Fp32,
}

/// A light as the shading reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightConstants {
    /// Direction the light travels (normalised) and colour·intensity: the reference's.
    Distant { dir: Vec3, intensity: Vec3 },
    /// Position and colour·intensity/(4π) (each component in double, rounded once): the
    /// shading multiplies it by recip(r²).
    Point { pos: Vec3, intensity_over_4pi: Vec3 },
}

/// One object's material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialConstants {
    pub kind: MaterialKind,
    pub ior: Fp32,
    /// 1/ior, correctly rounded: the reference's `etai / etat` outside the object.
    pub inv_ior: Fp32,
    pub albedo: Vec3,
    pub kd: Fp32,
    pub ks: Fp32,
    /// Phong's exponent, a whole number (0 for the other materials, which do not read it).
    pub exponent: u32,
}

/// Bits of each vertex-normal component in the triangle memory. The host snaps a normalised
/// component to the grid k·2^−(NORMAL_BITS−1), |k| < 2^(NORMAL_BITS−1) ([`normal_code`]);
/// the hardware stores k and converts it back exactly ([`normal_value`]; the frame engine's
/// thread start), 150 bits a triangle where fp32 normals would take 294. At 320×180 against
/// the software renderer the worst thesis
/// scene is Glass pen at 75.1 dB with 16 bits, 65.6 dB with 12 and 49.5 dB with 10 (docs/frame.md,
/// "Against the software renderer").
pub const NORMAL_BITS: u32 = 16;
const _: () = assert!(
    NORMAL_BITS >= 2 && NORMAL_BITS <= 25,
    "codes must be exact in fp32"
);

/// The grid's steps in 1.0.
const NORMAL_SCALE: f32 = (1u32 << (NORMAL_BITS - 1)) as f32;

/// A normal component's code on the triangle memory's grid: the nearest step (ties away from
/// zero), clamped to the codes the field holds (1.0 becomes the top code,
/// 1 − 2^−(NORMAL_BITS−1)).
pub fn normal_code(x: Fp32) -> i32 {
    // x·2^(NORMAL_BITS−1) is exact (a power of two): the rounding to a whole step is the
    // only one.
    (x.f32() * NORMAL_SCALE)
        .round()
        .clamp(1.0 - NORMAL_SCALE, NORMAL_SCALE - 1.0) as i32
}

/// The value of a normal component's code, exact in fp32 (at most NORMAL_BITS − 1 ≤ 24
/// significant bits).
pub fn normal_value(code: i32) -> Fp32 {
    Fp32::new(code as f32 / NORMAL_SCALE)
}

/// One triangle's record: its object and its corner normals (world space, normalised by the
/// reference's arithmetic on the host, then snapped to the grid of [`NORMAL_BITS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleConstants {
    pub object: u32,
    pub normals: [Vec3; 3],
}

/// Everything the frame reads besides the traversal unit's answers.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameConstants {
    pub width: u32,
    pub height: u32,
    pub camera: CameraConstants,
    pub lights: Vec<LightConstants>,
    pub materials: Vec<MaterialConstants>,
    pub triangles: Vec<TriangleConstants>,
    pub background: Vec3,
    pub bias: Fp32,
    pub max_depth: u32,
}

/// Names every value loaded into the scene memory and refuses a NaN or an infinity.
struct Checker<'a> {
    scene: &'a str,
}

impl Checker<'_> {
    fn scalar(&self, what: impl FnOnce() -> String, x: f32) -> Result<Fp32, FrameError> {
        if x.is_finite() {
            Ok(Fp32::new(x))
        } else {
            Err(FrameError::NotFinite {
                scene: self.scene.to_string(),
                what: what(),
                value: x,
            })
        }
    }

    fn vector(&self, what: impl Fn() -> String, v: [f32; 3]) -> Result<Vec3, FrameError> {
        const AXES: [&str; 3] = ["x", "y", "z"];
        let mut out = [Fp32::ZERO; 3];
        for (k, (o, x)) in out.iter_mut().zip(v).enumerate() {
            *o = self.scalar(|| format!("{} {}", what(), AXES[k]), x)?;
        }
        Ok(Vec3::new(out[0], out[1], out[2]))
    }

    fn colour(&self, what: impl Fn() -> String, v: [f32; 3]) -> Result<Vec3, FrameError> {
        const CHANNELS: [&str; 3] = ["red", "green", "blue"];
        let mut out = [Fp32::ZERO; 3];
        for (k, (o, x)) in out.iter_mut().zip(v).enumerate() {
            *o = self.scalar(|| format!("{} {}", what(), CHANNELS[k]), x)?;
        }
        Ok(Vec3::new(out[0], out[1], out[2]))
    }
}

fn too_many(scene: &str, what: &'static str, count: usize, limit: usize) -> Result<(), FrameError> {
    if count > limit {
        return Err(FrameError::TooMany {
            scene: scene.to_string(),
            what,
            count,
            limit,
        });
    }
    Ok(())
}

impl FrameConstants {
    /// The constants of `scene` (prepared as `prepared`) rendered at `width`×`height`, checked
    /// against `limits`.
    pub fn load(
        scene: &Scene,
        prepared: &PreparedScene,
        width: u32,
        height: u32,
        limits: &FrameLimits,
    ) -> Result<FrameConstants, FrameError> {
        let name = scene.name.as_str();
        if width == 0 || height == 0 || width > limits.width || height > limits.height {
            return Err(FrameError::ImageSize {
                scene: name.to_string(),
                width,
                height,
                max_width: limits.width,
                max_height: limits.height,
            });
        }
        too_many(name, "lights", prepared.lights.len(), limits.lights)?;
        too_many(
            name,
            "objects",
            prepared.world.materials.len(),
            limits.objects,
        )?;
        too_many(
            name,
            "triangles",
            prepared.world.triangles.len(),
            limits.triangles,
        )?;
        if prepared.max_depth > limits.max_depth {
            return Err(FrameError::MaxDepth {
                scene: name.to_string(),
                depth: prepared.max_depth,
                limit: limits.max_depth,
            });
        }
        let check = Checker { scene: name };
        let camera = camera(&check, scene, width, height)?;
        let lights = (prepared.lights.iter().enumerate())
            .map(|(k, l)| light(&check, k, l))
            .collect::<Result<_, _>>()?;
        let materials = (scene.objects.iter())
            .map(|o| {
                let m = &o.material;
                let what = |field: &str| format!("object `{}` {field}", o.name);
                let ior = check.scalar(|| what("ior"), m.ior)?;
                let inv_ior = ior.recip();
                if m.kind == MaterialKind::ReflectionRefraction && !inv_ior.is_finite() {
                    return Err(FrameError::NotFinite {
                        scene: name.to_string(),
                        what: what("1/ior"),
                        value: inv_ior.f32(),
                    });
                }
                Ok(MaterialConstants {
                    kind: m.kind,
                    ior,
                    inv_ior,
                    albedo: check.colour(|| what("albedo"), m.albedo.to_array())?,
                    kd: check.scalar(|| what("kd"), m.kd)?,
                    ks: check.scalar(|| what("ks"), m.ks)?,
                    exponent: match m.kind {
                        MaterialKind::Phong => {
                            phong_exponent(name, &o.name, m.n, limits.phong_exponent)?
                        }
                        _ => check.scalar(|| what("Phong exponent"), m.n).map(|_| 0)?,
                    },
                })
            })
            .collect::<Result<_, _>>()?;
        let triangles = (prepared.world.triangles.iter().enumerate())
            .map(|(t, tri)| {
                let object = &scene.objects[tri.object as usize].name;
                let mut normals = [Vec3::ZERO; 3];
                for (c, (n, world)) in normals.iter_mut().zip(tri.normals).enumerate() {
                    let what = || format!("triangle {t} (object `{object}`) corner {c} normal");
                    let v = check.vector(what, world.to_array())?;
                    let snap = |x| normal_value(normal_code(x));
                    *n = Vec3::new(snap(v.x), snap(v.y), snap(v.z));
                }
                Ok(TriangleConstants {
                    object: tri.object,
                    normals,
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(FrameConstants {
            width,
            height,
            camera,
            lights,
            materials,
            triangles,
            background: check.colour(|| "background".into(), prepared.background.to_array())?,
            bias: check.scalar(|| "bias".into(), prepared.bias)?,
            max_depth: prepared.max_depth,
        })
    }
}

impl CameraConstants {
    /// The camera of `camera_to_world` with a vertical field of view of `fov_deg` degrees at
    /// `width`×`height`: the reference's float aspect and scale, the rest in double, each
    /// constant rounded once.
    pub fn new(camera_to_world: &Mat44, fov_deg: f32, width: u32, height: u32) -> CameraConstants {
        let m = &camera_to_world.0;
        let aspect = f64::from(width as f32 / height as f32);
        let scale = f64::from(fov_scale(fov_deg));
        let (w, h) = (f64::from(width), f64::from(height));
        let round = |x: f64| Fp32::new(x as f32);
        CameraConstants {
            origin: Vec3::of(mult_point(camera_to_world, V3::ZERO).to_array()),
            rows: [0, 1, 2].map(|r| Vec3::of([m[r][0], m[r][1], m[r][2]])),
            dx: round(2.0 * aspect * scale / w),
            x0: round((1.0 / w - 1.0) * aspect * scale),
            dy: round(-2.0 * scale / h),
            y0: round((1.0 - 1.0 / h) * scale),
        }
    }
}

fn camera(
    check: &Checker,
    scene: &Scene,
    width: u32,
    height: u32,
) -> Result<CameraConstants, FrameError> {
    let o = &scene.options;
    check.scalar(|| "field of view".into(), o.fov_deg)?;
    for (r, row) in o.camera_to_world.0.iter().enumerate() {
        for (c, &x) in row.iter().enumerate() {
            check.scalar(|| format!("camera-to-world [{r}][{c}]"), x)?;
        }
    }
    let camera = CameraConstants::new(&o.camera_to_world, o.fov_deg, width, height);
    check.vector(|| "camera origin".into(), camera.origin.to_f32())?;
    for (what, x) in [
        ("dx", camera.dx),
        ("x0", camera.x0),
        ("dy", camera.dy),
        ("y0", camera.y0),
    ] {
        check.scalar(|| format!("camera {what}"), x.f32())?;
    }
    Ok(camera)
}

fn light(check: &Checker, k: usize, l: &PreparedLight) -> Result<LightConstants, FrameError> {
    Ok(match *l {
        PreparedLight::Distant { dir, intensity } => LightConstants::Distant {
            dir: check.vector(|| format!("light {k} (distant) direction"), dir.to_array())?,
            intensity: check.colour(
                || format!("light {k} (distant) intensity"),
                intensity.to_array(),
            )?,
        },
        PreparedLight::Point {
            pos,
            color,
            intensity,
        } => {
            let what = || format!("light {k} (point) intensity/4π");
            // colour·intensity in float, as the reference; then /(4π) in double.
            let ci = (color * intensity).to_array();
            let over = ci.map(|c| (f64::from(c) / (4.0 * std::f64::consts::PI)) as f32);
            check.colour(|| format!("light {k} (point) colour"), color.to_array())?;
            check.scalar(|| format!("light {k} (point) intensity"), intensity)?;
            LightConstants::Point {
                pos: check.vector(|| format!("light {k} (point) position"), pos.to_array())?,
                intensity_over_4pi: check.colour(what, over)?,
            }
        }
    })
}

/// Phong's exponent as the whole number the hardware raises to.
fn phong_exponent(scene: &str, object: &str, n: f32, limit: u32) -> Result<u32, FrameError> {
    if n >= 0.0 && n <= limit as f32 && n.fract() == 0.0 {
        Ok(n as u32)
    } else {
        Err(FrameError::PhongExponent {
            scene: scene.to_string(),
            object: object.to_string(),
            value: n,
            limit,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every code converts back exactly and to itself; 1.0, −1.0 and values past them clamp.
    #[test]
    fn normal_codes_round_trip_exactly() {
        let top = (1 << (NORMAL_BITS - 1)) - 1;
        for code in -top..=top {
            let value = normal_value(code);
            assert_eq!(f64::from(value.f32()), f64::from(code) / f64::from(top + 1));
            assert_eq!(normal_code(value), code);
        }
        assert_eq!(normal_code(Fp32::new(1.0)), top);
        assert_eq!(normal_code(Fp32::new(-1.0)), -top);
        assert_eq!(normal_code(Fp32::new(1.5)), top);
    }

    /// The nearest code, against f64 arithmetic, on random components in [−1, 1].
    #[test]
    fn normal_codes_are_nearest() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let step = 1.0 / f64::from(NORMAL_SCALE);
        for _ in 0..100_000 {
            let x: f32 = rng.gen_range(-1.0..=1.0);
            let error = f64::from(normal_value(normal_code(Fp32::new(x))).f32()) - f64::from(x);
            if x.abs() > 1.0 - 0.5 / NORMAL_SCALE {
                // Nearer ±1.0 than the top code: clamped to it.
                let top = NORMAL_SCALE as i32 - 1;
                assert_eq!(normal_code(Fp32::new(x)), top * x.signum() as i32, "{x}");
            } else {
                assert!(error.abs() <= step / 2.0, "{x}: off by {error}");
            }
        }
    }
}
