//! Reduced precision that renders: what a format needs from the renderer (`docs/precision.md`).
//!
//! - [`spawn_policy`]: the format-aware spawn policy, carrying the format's rounding error in
//!   scene units (the renderer knows no formats); [`SpawnChoice`]: a policy by name, as
//!   `rtfpga --spawn` and the sweep's `policies` spell it.
//! - [`auto_scale_exp`]: the power of two the model engines multiply every query coordinate
//!   by so that Möller-Trumbore's intermediates fit the format's range. Scaling origin,
//!   direction and vertices by the same 2^k leaves t, u, v unchanged, and in a float format
//!   every intermediate is scaled exactly unless it over- or underflows; in a fixed format it
//!   moves the values against the fixed quantisation step.

use serde::{Deserialize, Serialize};
use sw_renderer::math::{mult_point, V3};
use sw_renderer::scene::Scene;
use sw_renderer::spawn::{RoundingError, SpawnPolicy};
use sw_renderer::world::{World, WorldError};

use crate::format::{Format, Quant};

/// The error of one rounding in `format`, in scene units, once the scene is scaled by
/// 2^`scale_exp`: a float's unit roundoff 2^-(M+1) (relative, so scaling changes nothing);
/// a fixed format's largest quantisation error (2^-F truncating, 2^-(F+1) rounding), which
/// is 2^-F-k scene units.
pub fn rounding_error(format: &Format, scale_exp: i32) -> RoundingError {
    match *format {
        Format::Float { man, .. } => RoundingError {
            unit_roundoff: 2f64.powi(-(man as i32) - 1),
            absolute: 0.0,
        },
        Format::Fixed { frac, quant, .. } => {
            let step = match quant {
                Quant::Trn => frac as i32,
                Quant::Rnd => frac as i32 + 1,
            };
            RoundingError {
                unit_roundoff: 0.0,
                absolute: 2f64.powi(-step - scale_exp),
            }
        }
    }
}

/// The format-aware spawn policy of `format` for a scene scaled by 2^`scale_exp`.
pub fn spawn_policy(format: &Format, scale_exp: i32) -> SpawnPolicy {
    SpawnPolicy::FormatAware(rounding_error(format, scale_exp))
}

/// A spawn policy by name, before it meets a format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpawnChoice {
    /// The thesis: origin offset by the scene's bias, every hit counts.
    Thesis,
    /// Also a t_min from the format's rounding error at the spawn point, and the triangle
    /// left excluded.
    FormatAware,
}

impl SpawnChoice {
    pub const ALL: [SpawnChoice; 2] = [SpawnChoice::Thesis, SpawnChoice::FormatAware];

    pub fn name(self) -> &'static str {
        match self {
            SpawnChoice::Thesis => "thesis",
            SpawnChoice::FormatAware => "format-aware",
        }
    }

    /// The policy of a datapath answering in `format` on queries scaled by 2^`scale_exp`.
    pub fn policy(self, format: &Format, scale_exp: i32) -> SpawnPolicy {
        match self {
            SpawnChoice::Thesis => SpawnPolicy::Thesis,
            SpawnChoice::FormatAware => spawn_policy(format, scale_exp),
        }
    }
}

named_choice!(SpawnChoice, "spawn policy");

/// The sizes that bound Möller-Trumbore's intermediates in a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneRange {
    /// The largest coordinate magnitude of a vertex or the camera.
    pub extent: f64,
    /// The largest coordinate magnitude of a triangle edge.
    pub edge: f64,
}

impl SceneRange {
    pub fn of(scene: &Scene) -> Result<SceneRange, WorldError> {
        let world = World::new(scene)?;
        let abs_max = |v: V3| v.x.abs().max(v.y.abs()).max(v.z.abs()) as f64;
        let camera = mult_point(&scene.options.camera_to_world, V3::ZERO);
        let mut range = SceneRange {
            extent: abs_max(camera),
            edge: 0.0,
        };
        for t in &world.triangles {
            let [a, b, c] = t.verts;
            range.extent = range.extent.max(abs_max(a)).max(abs_max(b)).max(abs_max(c));
            range.edge = range
                .edge
                .max(abs_max(b - a))
                .max(abs_max(c - a))
                .max(abs_max(c - b));
        }
        Ok(range)
    }
}

/// log2 of the largest magnitude an intermediate may take: a float's 2^(bias−1), so that
/// both x and 1/x are normal; a fixed format's 2^(I−1).
fn log2_limit(format: &Format) -> f64 {
    match *format {
        Format::Float { exp, .. } => ((1i64 << (exp - 1)) - 2) as f64,
        Format::Fixed { int, .. } => int as f64 - 1.0,
    }
}

/// The largest k such that every intermediate of Möller-Trumbore (a ray from inside the
/// scene's extent X, unit direction, edges up to E), scaled by 2^k per length it is the
/// product of, stays within the format's limit. Bounds by degree (docs/precision.md):
/// s = o − v0 ≤ 2X, e ≤ E; p = d×e2 ≤ 2E, q = s×e1 ≤ 4XE; det ≤ 6E², s·p ≤ 12XE,
/// d·q ≤ 12XE, e2·q ≤ 12XE².
pub fn auto_scale_exp(format: &Format, range: &SceneRange) -> i32 {
    let (x, e) = (range.extent.max(f64::MIN_POSITIVE), range.edge);
    let by_degree = [
        (1, (2.0 * x).max(e)),
        (2, (2.0 * e).max(4.0 * x * e)),
        (3, (6.0 * e * e).max(12.0 * x * e).max(12.0 * x * e * e)),
    ];
    by_degree
        .iter()
        .filter(|(_, bound)| *bound > 0.0)
        .map(|&(degree, bound)| ((log2_limit(format) - bound.log2()) / degree as f64).floor())
        .fold(f64::INFINITY, f64::min)
        .clamp(-64.0, 64.0) as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lookup;

    #[test]
    fn rounding_errors_of_floats_and_fixed_formats() {
        let fp16 = rounding_error(&lookup("fp16").unwrap(), 5);
        assert_eq!((fp16.unit_roundoff, fp16.absolute), (2f64.powi(-11), 0.0));
        let trn = rounding_error(&lookup("fx32_16").unwrap(), 2);
        assert_eq!((trn.unit_roundoff, trn.absolute), (0.0, 2f64.powi(-18)));
        let rnd = rounding_error(&lookup("fx32_16_rnd_sat").unwrap(), -1);
        assert_eq!(rnd.absolute, 2f64.powi(-16));
    }

    #[test]
    fn spawn_choices_give_their_policies() {
        let fp16 = lookup("fp16").unwrap();
        assert_eq!(SpawnChoice::Thesis.policy(&fp16, 0), SpawnPolicy::Thesis);
        assert_eq!(
            SpawnChoice::FormatAware.policy(&fp16, 3),
            spawn_policy(&fp16, 3)
        );
    }

    #[test]
    fn the_scale_fits_the_degree_three_bound_into_the_range() {
        let range = SceneRange {
            extent: 100.0,
            edge: 100.0,
        };
        let fp16 = lookup("fp16").unwrap();
        let k = auto_scale_exp(&fp16, &range);
        // 12·X·E² = 1.2e7 ≈ 2^23.5 must scale to ≤ 2^14: 2^(3k) ≤ 2^-9.5.
        assert_eq!(k, -4);
        let fx = lookup("fx32_16").unwrap();
        let small = SceneRange {
            extent: 0.5,
            edge: 0.25,
        };
        assert!(auto_scale_exp(&fx, &small) > 0, "small scenes scale up");
        assert!(auto_scale_exp(&fx, &range) < auto_scale_exp(&fx, &small));
    }
}
