//! The reference's shading arithmetic (castRay, the lights, reflect, refract, Fresnel), each
//! formula in the C++ evaluation order and precision.

use crate::hit::{Hit, NO_BOUND};
use crate::math::{clamp, cpp_max, mult_dir, mult_point, V3};
use crate::scene::{Light, LightKind};
use crate::world::WorldTriangle;

/// The reference's diffuse "pattern": a solid grey (albedo is not used for diffuse).
pub const DIFFUSE_PATTERN: f32 = 0.9;
/// Weight of a mirror's reflection.
pub const MIRROR_WEIGHT: f32 = 0.8;

/// A light with its world-space placement computed once, as the reference's constructors did.
#[derive(Clone, Debug)]
pub enum PreparedLight {
    Distant { dir: V3, intensity: V3 },
    Point { pos: V3, color: V3, intensity: f32 },
}

/// What `illuminate` returns for a shaded point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Illumination {
    /// Direction the light travels (from the light towards the point), normalised.
    pub dir: V3,
    pub intensity: V3,
    /// Bound of the shadow ray.
    pub distance: f32,
}

impl PreparedLight {
    pub fn new(light: &Light) -> PreparedLight {
        let color = V3::from(light.color);
        match light.kind {
            LightKind::Distant => PreparedLight::Distant {
                dir: mult_dir(&light.light_to_world, V3::new(0.0, 0.0, -1.0)).normalized(),
                intensity: color * light.intensity,
            },
            LightKind::Point => PreparedLight::Point {
                pos: mult_point(&light.light_to_world, V3::ZERO),
                color,
                intensity: light.intensity,
            },
        }
    }

    pub fn illuminate(&self, p: V3) -> Illumination {
        match *self {
            PreparedLight::Distant { dir, intensity } => Illumination {
                dir,
                intensity,
                distance: NO_BOUND,
            },
            PreparedLight::Point {
                pos,
                color,
                intensity,
            } => {
                let l = p - pos;
                let r2 = l.dot(l);
                // `sqrt(r2)` and `4 * M_PI * r2` were evaluated in double in the C++.
                let distance = f64::from(r2).sqrt() as f32;
                let falloff = (4.0 * std::f64::consts::PI * f64::from(r2)) as f32;
                Illumination {
                    dir: l.div_s(distance),
                    intensity: (color * intensity).div_s(falloff),
                    distance,
                }
            }
        }
    }
}

/// `hitPoint = orig + dir * tNear`.
pub fn hit_point(orig: V3, dir: V3, hit: &Hit) -> V3 {
    orig + dir * hit.t
}

/// Smooth normal `(1 − u − v)·n0 + u·n1 + v·n2`, normalised.
pub fn hit_normal(tri: &WorldTriangle, hit: &Hit) -> V3 {
    let [n0, n1, n2] = tri.normals;
    let w = 1.0 - hit.u - hit.v;
    (n0 * w + n1 * hit.u + n2 * hit.v).normalized()
}

/// `I − 2(I·N)N`.
pub fn reflect(i: V3, n: V3) -> V3 {
    i - n * (2.0 * i.dot(n))
}

/// Snell refraction direction, or zero on total internal reflection.
pub fn refract(i: V3, n: V3, ior: f32) -> V3 {
    let mut cosi = clamp(-1.0, 1.0, i.dot(n));
    let (mut etai, mut etat) = (1.0f32, ior);
    let mut normal = n;
    if cosi < 0.0 {
        cosi = -cosi;
    } else {
        std::mem::swap(&mut etai, &mut etat);
        normal = -n;
    }
    let eta = etai / etat;
    let k = 1.0 - eta * eta * (1.0 - cosi * cosi);
    if k < 0.0 {
        V3::ZERO
    } else {
        i * eta + normal * (eta * cosi - k.sqrt())
    }
}

/// The Fresnel reflectance kr (1 on total internal reflection).
pub fn fresnel(i: V3, n: V3, ior: f32) -> f32 {
    let cosi = clamp(-1.0, 1.0, i.dot(n));
    let (mut etai, mut etat) = (1.0f32, ior);
    if cosi > 0.0 {
        std::mem::swap(&mut etai, &mut etat);
    }
    let sint = etai / etat * cpp_max(0.0, 1.0 - cosi * cosi).sqrt();
    if sint >= 1.0 {
        return 1.0;
    }
    let cost = cpp_max(0.0, 1.0 - sint * sint).sqrt();
    let cosi = cosi.abs();
    let rs = ((etat * cosi) - (etai * cost)) / ((etat * cosi) + (etai * cost));
    let rp = ((etai * cosi) - (etat * cost)) / ((etai * cosi) + (etat * cost));
    (rs * rs + rp * rp) / 2.0
}

/// One light's contribution to a diffuse or Phong point, before visibility is known.
#[derive(Clone, Copy, Debug)]
pub struct LightTerm {
    pub intensity: V3,
    /// `max(0, N·(−L))`.
    pub cos: f32,
    /// Phong only: `pow(max(0, reflect(L, N)·(−d)), n)`.
    pub specular: f32,
}

impl LightTerm {
    pub fn diffuse(light: &Illumination, normal: V3) -> LightTerm {
        LightTerm {
            intensity: light.intensity,
            cos: cpp_max(0.0, normal.dot(-light.dir)),
            specular: 0.0,
        }
    }

    pub fn phong(light: &Illumination, normal: V3, view: V3, exponent: f32) -> LightTerm {
        let r = reflect(light.dir, normal);
        LightTerm {
            specular: cpp_max(0.0, r.dot(-view)).powf(exponent),
            ..LightTerm::diffuse(light, normal)
        }
    }
}

/// `(bool)vis` as the float it becomes in the C++ products.
fn vis_f(visible: bool) -> f32 {
    if visible {
        1.0
    } else {
        0.0
    }
}

/// `hitColor += vis * pattern * lightIntensity * max(0, N·(−L))` over the lights.
pub fn diffuse_colour(terms: impl Iterator<Item = (LightTerm, bool)>) -> V3 {
    terms.fold(V3::ZERO, |acc, (l, visible)| {
        acc + l.intensity * (vis_f(visible) * DIFFUSE_PATTERN) * l.cos
    })
}

/// Phong: `diffuse += vis·albedo·I·cos`, `specular += vis·I·spec`, then `diffuse·Kd + specular·Ks`.
pub fn phong_colour(
    terms: impl Iterator<Item = (LightTerm, bool)>,
    albedo: V3,
    kd: f32,
    ks: f32,
) -> V3 {
    let (diffuse, specular) = terms.fold((V3::ZERO, V3::ZERO), |(d, s), (l, visible)| {
        let v = vis_f(visible);
        (
            d + (albedo * v).mul_v(l.intensity) * l.cos,
            s + l.intensity * v * l.specular,
        )
    });
    diffuse * kd + specular * ks
}

/// `hitColor += 0.8 * castRay(reflection)`.
pub fn mirror_colour(reflection: V3) -> V3 {
    V3::ZERO + reflection * MIRROR_WEIGHT
}

/// `hitColor += reflectionColor * kr + refractionColor * (1 − kr)`.
pub fn fresnel_colour(reflection: V3, refraction: V3, kr: f32) -> V3 {
    V3::ZERO + (reflection * kr + refraction * (1.0 - kr))
}

/// `(char)(255 * clamp(0, 1, x))` per channel: truncation, no gamma.
pub fn to_rgb8(c: V3) -> [u8; 3] {
    [c.x, c.y, c.z].map(|x| (255.0 * clamp(0.0, 1.0, x)) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflect_mirrors_about_the_normal() {
        assert_eq!(
            reflect(V3::new(1.0, -1.0, 0.0), V3::new(0.0, 1.0, 0.0)),
            V3::new(1.0, 1.0, 0.0)
        );
    }

    #[test]
    fn fresnel_at_normal_incidence_and_total_internal_reflection() {
        let n = V3::new(0.0, 0.0, 1.0);
        // ((1.5 − 1)/(1.5 + 1))² = 0.04 at normal incidence, both polarisations.
        let kr = fresnel(V3::new(0.0, 0.0, -1.0), n, 1.5);
        assert!((kr - 0.04).abs() < 1e-6, "{kr}");
        // From inside at a grazing angle: total internal reflection.
        let inside = V3::new(0.9, 0.0, 0.1).normalized();
        assert_eq!(fresnel(inside, n, 1.5), 1.0);
        assert_eq!(refract(inside, n, 1.5), V3::ZERO);
    }

    #[test]
    fn refraction_bends_towards_the_normal_entering_glass() {
        let i = V3::new(1.0, 0.0, -1.0).normalized();
        let r = refract(i, V3::new(0.0, 0.0, 1.0), 1.5).normalized();
        // Snell: sin θt = sin 45° / 1.5.
        let sin_t = r.x;
        assert!((sin_t - (0.5f32.sqrt() / 1.5)).abs() < 1e-6, "{r:?}");
        assert!(r.z < 0.0);
    }

    #[test]
    fn point_light_falls_off_with_four_pi_r_squared() {
        let light = PreparedLight::Point {
            pos: V3::new(0.0, 0.0, 2.0),
            color: V3::new(1.0, 1.0, 1.0),
            intensity: 100.0,
        };
        let il = light.illuminate(V3::ZERO);
        assert_eq!(il.distance, 2.0);
        assert_eq!(il.dir, V3::new(0.0, 0.0, -1.0));
        assert_eq!(
            il.intensity.x,
            100.0f32 / (16.0 * std::f64::consts::PI) as f32
        );
    }

    #[test]
    fn output_truncates_and_clamps() {
        assert_eq!(to_rgb8(V3::new(-1.0, 0.5, 2.0)), [0, 127, 255]);
        assert_eq!(
            to_rgb8(V3::new(f32::NAN, 1.0 / 255.0, 0.999)),
            [255, 1, 254]
        );
    }
}
