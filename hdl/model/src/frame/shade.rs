//! Shading without a recursion stack: a returned ray and the traversal unit's answer →
//! contributions to the ray's pixel and the rays it spawns.
//!
//! The reference's castRay is linear in the colours its children return: a mirror returns
//! 0.8·child, glass kr·reflection + (1−kr)·refraction, diffuse and Phong a sum over lights
//! of visibility times a light term, a miss (or a ray past the maximum depth) the background.
//! So a pixel's colour is a sum over the leaves of its ray tree of the products of the
//! weights along the path: each ray carries that product (its RGB weight, fp32, 1 for a
//! primary ray), and each leaf adds weight × what the reference returns there. A shadow ray
//! carries the contribution it adds if nothing occludes it.
//!
//! Formulas in fp32 ([`crate::fp32`]), operation by operation (the RTL's order; `a/b` is
//! written `a × recip(b)` where the reference divided):
//! - hit point P = o + d·t; smooth normal N = normalise((n0·w + n1·u) + n2·v), w = (1 − u) − v;
//! - light (`illuminate`): distant: L and I as loaded, distance = MAX; point: l = P − pos,
//!   r² = l·l, distance = sqrt(r²), L = l·recip(distance), I = (intensity/4π)·recip(r²);
//! - diffuse, per light: cos = max(0, N·(−L)), term = (I·0.9)·cos;
//! - Phong, per light: cos as above, R = L − N·(2·(L·N)), spec = max(0, R·(−d))^n
//!   (`Fp32::powi`), term = ((albedo⊙I)·cos)·Kd + (I·spec)·Ks;
//! - diffuse and Phong: per light the contribution weight⊙term, converted to fixed point;
//!   if it is not zero, a shadow ray from P + N·bias along −L bounded by the light's distance
//!   carries it (a zero one would add nothing: no ray);
//! - mirror: a reflection ray from P + N·bias along normalise(d − N·(2·(d·N))) with weight
//!   weight·0.8;
//! - glass (`fresnel`, `refract` with cos = d·N computed once): if kr < 1 a refraction ray
//!   with weight·(1 − kr) from P ∓ N·bias (− when outside: d·N < 0); a reflection ray with
//!   weight·kr from P ± N·bias;
//! - a spawned reflection or refraction ray deeper than the maximum depth is not traced: it
//!   contributes its weight⊙background; so does a miss.

use sw_renderer::hit::Hit;
use sw_renderer::scene::MaterialKind;
use sw_renderer::shade::{DIFFUSE_PATTERN, MIRROR_WEIGHT};

use super::accumulate::Contribution;
use super::constants::{FrameConstants, LightConstants, MaterialConstants};
use super::raygen::primary;
use crate::fp32::{Fp32, Vec3};

/// What a ray is, for the counters and the shading.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RayKind {
    Primary,
    Reflection,
    Refraction,
    Shadow,
}

impl RayKind {
    pub const ALL: [RayKind; 4] = [
        RayKind::Primary,
        RayKind::Reflection,
        RayKind::Refraction,
        RayKind::Shadow,
    ];
}

/// What a ray carries besides its geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Load {
    /// A castRay of the reference (primary, reflection or refraction): its depth (0 for
    /// primary rays) and the product of the weights on its path.
    Cast {
        kind: RayKind,
        depth: u32,
        weight: Vec3,
    },
    /// A shadow ray: what it adds to its pixel if it arrives unoccluded.
    Shadow { contribution: Contribution },
}

/// A ray in flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRay {
    /// Row-major pixel index: j·width + i.
    pub pixel: u32,
    pub orig: Vec3,
    pub dir: Vec3,
    /// Hits count below this distance ([`Fp32::MAX`] but for a point light's shadow ray).
    pub t_max: Fp32,
    pub load: Load,
}

impl FrameRay {
    /// Pixel (i, j)'s primary ray ([`super::raygen::primary`]): depth 0, weight 1.
    pub fn primary(c: &FrameConstants, i: u32, j: u32) -> FrameRay {
        let (orig, dir) = primary(&c.camera, i, j);
        FrameRay {
            pixel: j * c.width + i,
            orig,
            dir,
            t_max: Fp32::MAX,
            load: Load::Cast {
                kind: RayKind::Primary,
                depth: 0,
                weight: Vec3::of([1.0; 3]),
            },
        }
    }

    pub fn kind(&self) -> RayKind {
        match self.load {
            Load::Cast { kind, .. } => kind,
            Load::Shadow { .. } => RayKind::Shadow,
        }
    }
}

/// What shading one ray produced.
#[derive(Clone, Debug, Default)]
pub struct Shaded {
    /// Contributions to the ray's pixel.
    pub contributions: Vec<Contribution>,
    pub spawned: Vec<FrameRay>,
    /// Shadow rays not spawned: their contribution was zero.
    pub zero_shadows: u64,
    /// Reflection and refraction rays not traced: deeper than the maximum depth.
    pub past_depth: u64,
    /// Glass hits with kr = 1 (total internal reflection): no refraction ray.
    pub total_internal: u64,
}

impl Shaded {
    pub fn clear(&mut self) {
        self.contributions.clear();
        self.spawned.clear();
    }
}

/// A light as seen from a point.
struct Illumination {
    /// Direction the light travels.
    dir: Vec3,
    intensity: Vec3,
    distance: Fp32,
}

fn illuminate(light: &LightConstants, p: Vec3) -> Illumination {
    match *light {
        LightConstants::Distant { dir, intensity } => Illumination {
            dir,
            intensity,
            distance: Fp32::MAX,
        },
        LightConstants::Point {
            pos,
            intensity_over_4pi,
        } => {
            let l = p - pos;
            let r2 = l.dot(l);
            let distance = r2.sqrt();
            Illumination {
                dir: l.scale(distance.recip()),
                intensity: intensity_over_4pi.scale(r2.recip()),
                distance,
            }
        }
    }
}

/// The Fresnel reflectance kr from cos = d·N (1 on total internal reflection):
/// cosi = clamp(cos, −1, 1); (etai, etat) = (1, ior), swapped if cosi > 0, and eta = etai/etat
/// is ior or the loaded 1/ior; sint = eta·sqrt(max(0, 1 − cosi·cosi)); kr = 1 if sint ≥ 1,
/// else cost = sqrt(max(0, 1 − sint·sint)), c = |cosi|,
/// rs = (etat·c − etai·cost)·recip(etat·c + etai·cost),
/// rp = (etai·c − etat·cost)·recip(etai·c + etat·cost), kr = (rs·rs + rp·rp)·0.5.
pub fn fresnel(cos: Fp32, m: &MaterialConstants) -> Fp32 {
    let one = Fp32::ONE;
    let cosi = cos.clamp(-one, one);
    let (etai, etat, eta) = if Fp32::ZERO.lt(cosi) {
        (m.ior, one, m.ior)
    } else {
        (one, m.ior, m.inv_ior)
    };
    let sint = eta * Fp32::ZERO.max(one - cosi * cosi).sqrt();
    if one.le(sint) {
        return one;
    }
    let cost = Fp32::ZERO.max(one - sint * sint).sqrt();
    let c = cosi.abs();
    let rs = (etat * c - etai * cost) * (etat * c + etai * cost).recip();
    let rp = (etai * c - etat * cost) * (etai * c + etat * cost).recip();
    (rs * rs + rp * rp) * Fp32::new(0.5)
}

/// Snell's refraction direction (not normalised) from cos = d·N, zero on total internal
/// reflection: cosi = clamp(cos, −1, 1); if cosi < 0: cosi = −cosi, eta = 1/ior, n = N; else
/// eta = ior, n = −N; k = 1 − (eta·eta)·(1 − cosi·cosi); zero if k < 0, else
/// d·eta + n·(eta·cosi − sqrt(k)).
pub fn refract(d: Vec3, normal: Vec3, cos: Fp32, m: &MaterialConstants) -> Vec3 {
    let one = Fp32::ONE;
    let mut cosi = cos.clamp(-one, one);
    let (eta, n) = if cosi.lt(Fp32::ZERO) {
        cosi = -cosi;
        (m.inv_ior, normal)
    } else {
        (m.ior, -normal)
    };
    let k = one - eta * eta * (one - cosi * cosi);
    if k.lt(Fp32::ZERO) {
        Vec3::ZERO
    } else {
        d.scale(eta) + n.scale(eta * cosi - k.sqrt())
    }
}

/// Shades `ray` given the traversal unit's answer `hit` (for a shadow ray: an occluder or
/// none), into `out` (cleared by the caller).
pub fn shade(c: &FrameConstants, ray: &FrameRay, hit: Option<&Hit>, out: &mut Shaded) {
    match (ray.load, hit) {
        (Load::Shadow { contribution }, None) => out.contributions.push(contribution),
        (Load::Shadow { .. }, Some(_)) => {}
        (Load::Cast { weight, .. }, None) => out
            .contributions
            .push(Contribution::of(weight.mul_v(c.background))),
        (Load::Cast { depth, weight, .. }, Some(hit)) => surface(c, ray, depth, weight, hit, out),
    }
}

fn surface(
    c: &FrameConstants,
    ray: &FrameRay,
    depth: u32,
    weight: Vec3,
    hit: &Hit,
    out: &mut Shaded,
) {
    let tri = &c.triangles[hit.triangle as usize];
    let m = &c.materials[tri.object as usize];
    let (t, u, v) = (Fp32::new(hit.t), Fp32::new(hit.u), Fp32::new(hit.v));
    let p = ray.orig + ray.dir.scale(t);
    let w = Fp32::ONE - u - v;
    let [n0, n1, n2] = tri.normals;
    let n = (n0.scale(w) + n1.scale(u) + n2.scale(v)).normalized();
    let bias = n.scale(c.bias);
    let mut cast = |kind, orig, dir: Vec3, weight: Vec3| {
        if depth + 1 > c.max_depth {
            out.past_depth += 1;
            out.contributions
                .push(Contribution::of(weight.mul_v(c.background)));
        } else {
            out.spawned.push(FrameRay {
                pixel: ray.pixel,
                orig,
                dir: dir.normalized(),
                t_max: Fp32::MAX,
                load: Load::Cast {
                    kind,
                    depth: depth + 1,
                    weight,
                },
            });
        }
    };
    match m.kind {
        MaterialKind::Reflection => {
            let r = ray.dir.reflect_with(n, ray.dir.dot(n));
            let weight = weight.scale(Fp32::new(MIRROR_WEIGHT));
            cast(RayKind::Reflection, p + bias, r, weight);
        }
        MaterialKind::ReflectionRefraction => {
            let cos = ray.dir.dot(n);
            let kr = fresnel(cos, m);
            let outside = cos.lt(Fp32::ZERO);
            if kr.lt(Fp32::ONE) {
                let d = refract(ray.dir, n, cos, m);
                let o = if outside { p - bias } else { p + bias };
                cast(RayKind::Refraction, o, d, weight.scale(Fp32::ONE - kr));
            }
            let d = ray.dir.reflect_with(n, cos);
            let o = if outside { p + bias } else { p - bias };
            cast(RayKind::Reflection, o, d, weight.scale(kr));
            out.total_internal += u64::from(!kr.lt(Fp32::ONE));
        }
        MaterialKind::Diffuse | MaterialKind::Phong => {
            for light in &c.lights {
                let il = illuminate(light, p);
                let cos = Fp32::ZERO.max(n.dot(-il.dir));
                let term = if m.kind == MaterialKind::Phong {
                    let r = il.dir.reflect_with(n, il.dir.dot(n));
                    let spec = Fp32::ZERO.max(r.dot(-ray.dir)).powi(m.exponent);
                    let diffuse = m.albedo.mul_v(il.intensity).scale(cos).scale(m.kd);
                    diffuse + il.intensity.scale(spec).scale(m.ks)
                } else {
                    il.intensity.scale(Fp32::new(DIFFUSE_PATTERN)).scale(cos)
                };
                let contribution = Contribution::of(weight.mul_v(term));
                if contribution.is_zero() {
                    out.zero_shadows += 1;
                    continue;
                }
                out.spawned.push(FrameRay {
                    pixel: ray.pixel,
                    orig: p + bias,
                    dir: -il.dir,
                    t_max: il.distance,
                    load: Load::Shadow { contribution },
                });
            }
        }
    }
}
