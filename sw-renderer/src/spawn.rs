//! Spawning secondary and shadow rays: where they start and which hits near the start count.
//!
//! The thesis offsets the origin by the scene's bias along the normal and counts every hit
//! ([`SpawnPolicy::Thesis`]). That needs a datapath whose error near the spawn point is below
//! the bias; in a narrower format a spawned ray re-hits the surface it leaves. The
//! format-aware policy keeps the thesis' origin and adds a per-ray `t_min` (a first-order
//! bound on the datapath's error of t for a surface through the spawn point) and excludes the
//! triangle the ray leaves. The derivation of the bound is in `docs/precision.md`; the
//! constants below are its terms. The renderer knows no formats: the policy carries the
//! format's rounding errors as numbers (`hw_model::precision::spawn_policy` computes them).

use crate::math::V3;

/// How spawned rays get their `t_min` and excluded triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SpawnPolicy {
    /// The thesis: `t_min = 0`, nothing excluded (fp32 renders equal the golden images).
    #[default]
    Thesis,
    /// `t_min` from the datapath's rounding error at the spawn point, and the triangle left
    /// excluded.
    FormatAware(RoundingError),
}

/// The error of one rounding of a value of magnitude `m`, in scene units: at most
/// `unit_roundoff · m + absolute`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundingError {
    /// A float format's 2^-(M+1) (0 for fixed point).
    pub unit_roundoff: f64,
    /// A fixed-point format's quantisation step divided by the scene's scale (0 for floats).
    pub absolute: f64,
}

impl RoundingError {
    fn at(&self, magnitude: f64) -> f64 {
        self.unit_roundoff * magnitude + self.absolute
    }
}

/// Rounding errors, in units of one rounding of the largest magnitude, of the distance from
/// the surface (docs/precision.md): inputs of the parent and child tests (origin and plane,
/// √3 each), the recip and the multiply by it (2) …
const FIXED_TERMS: f64 = 4.0 * SQRT_3 + 2.0;
/// … and, per unit of the triangle's shape factor σ, the numerators of both tests (16 each)
/// and the parent's determinant (8).
const SHAPE_TERMS: f64 = 40.0;
const SQRT_3: f64 = 1.732_050_807_568_877_2;

/// What the policy decided for the rays leaving one hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Departure(Option<Leaving>);

#[derive(Clone, Copy, Debug, PartialEq)]
struct Leaving {
    triangle: u32,
    /// Bound on the spawn point's and the child test's error, as a distance from the surface.
    slab: f64,
    /// The triangle's unit geometric normal.
    normal: [f64; 3],
}

fn to64(v: V3) -> [f64; 3] {
    [v.x as f64, v.y as f64, v.z as f64]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn max_abs(a: [f64; 3]) -> f64 {
    a.iter().fold(0.0, |m, x| m.max(x.abs()))
}

impl SpawnPolicy {
    /// The departure from the hit at `t` of the ray `(orig, dir)` on triangle `triangle` with
    /// world vertices `verts`.
    pub fn depart(&self, orig: V3, dir: V3, t: f32, triangle: u32, verts: &[V3; 3]) -> Departure {
        let SpawnPolicy::FormatAware(error) = self else {
            return Departure(None);
        };
        let v = verts.map(to64);
        let (e1, e2) = (sub(v[1], v[0]), sub(v[2], v[0]));
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let area = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let a = |i: usize, j: usize| e1[i].abs() * e2[j].abs() + e1[j].abs() * e2[i].abs();
        // σ = ‖|e1| ×₊ |e2|‖₁ / |e1 × e2| ≥ 1: how much cancellation the triple products of
        // this triangle's plane suffer.
        let shape = (a(1, 2) + a(2, 0) + a(0, 1)) / area;
        let magnitude = v
            .iter()
            .map(|&p| max_abs(p))
            .fold(max_abs(to64(orig)), f64::max)
            .max(t.abs() as f64 * max_abs(to64(dir)));
        Departure(Some(Leaving {
            triangle,
            slab: error.at(magnitude) * (FIXED_TERMS + SHAPE_TERMS * shape),
            normal: n.map(|x| x / area),
        }))
    }
}

impl Departure {
    /// `(t_min, exclude)` of a ray leaving along `dir` (normalised): the slab's thickness
    /// along the ray.
    pub fn ray(&self, dir: V3) -> (f32, Option<u32>) {
        let Some(l) = self.0 else {
            return (0.0, None);
        };
        let d = to64(dir);
        let cos = (d[0] * l.normal[0] + d[1] * l.normal[1] + d[2] * l.normal[2]).abs();
        // Rounded up so that the f32 bound is not below the f64 one.
        let t_min = (l.slab / cos) as f32;
        let t_min = if (t_min as f64) < l.slab / cos {
            t_min.next_up()
        } else {
            t_min
        };
        (t_min, Some(l.triangle))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn policy(unit_roundoff: f64) -> SpawnPolicy {
        SpawnPolicy::FormatAware(RoundingError {
            unit_roundoff,
            absolute: 0.0,
        })
    }

    /// A right triangle in the plane z = 0 at `offset`, hit from straight above at t = 1.
    fn t_min(p: SpawnPolicy, offset: f32, dir: V3) -> (f32, Option<u32>) {
        let o = V3::new(offset, offset, 0.0);
        let verts = [o, o + V3::new(1.0, 0.0, 0.0), o + V3::new(0.0, 1.0, 0.0)];
        let from = o + V3::new(0.25, 0.25, 1.0);
        p.depart(from, V3::new(0.0, 0.0, -1.0), 1.0, 7, &verts)
            .ray(dir)
    }

    #[test]
    fn thesis_spawns_reference_rays() {
        let up = V3::new(0.0, 0.0, 1.0);
        assert_eq!(t_min(SpawnPolicy::Thesis, 100.0, up), (0.0, None));
    }

    #[test]
    fn format_aware_t_min_grows_with_magnitude_unit_roundoff_and_grazing() {
        let up = V3::new(0.0, 0.0, 1.0);
        let u = 2f64.powi(-11);
        let (near, ex) = t_min(policy(u), 1.0, up);
        assert_eq!(ex, Some(7));
        // Axis-aligned right triangle: σ = 1, the largest magnitude is 2 (the vertices).
        let want = u * 2.0 * (FIXED_TERMS + SHAPE_TERMS);
        assert!((near as f64) >= want && (near as f64) < want * (1.0 + 1e-6));
        let far = t_min(policy(u), 64.0, up).0;
        assert!(far > 30.0 * near, "{far} vs {near}");
        let coarse = t_min(policy(4.0 * u), 1.0, up).0;
        assert!(coarse > 3.9 * near, "{coarse} vs {near}");
        let grazing = t_min(policy(u), 1.0, V3::new(1.0, 0.0, 0.1).normalized()).0;
        assert!(grazing > 9.0 * near);
        // Fixed point: the same bound from the absolute step, whatever the magnitude.
        let fixed = SpawnPolicy::FormatAware(RoundingError {
            unit_roundoff: 0.0,
            absolute: 2f64.powi(-8),
        });
        assert_eq!(t_min(fixed, 1.0, up).0, t_min(fixed, 64.0, up).0);
        assert!(t_min(fixed, 1.0, up).0 > 0.0);
    }
}
