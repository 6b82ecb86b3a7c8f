//! Scenes and rays shared by the traversal unit's rust-hdl tests.

#[macro_use]
mod bench;
#[macro_use]
mod loader;

use hw_model::traversal::UnitRay;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

/// `count` random triangles in a box of ±4, every other object casting shadows.
pub fn mesh(seed: u64, count: usize) -> (Vec<WorldTriangle>, Vec<bool>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut v = || {
        V3::new(
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
        )
    };
    let tris: Vec<WorldTriangle> = (0..count)
        .map(|k| WorldTriangle {
            verts: [v(), v(), v()],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: (k / 3) as u32,
        })
        .collect();
    let casts = tris.iter().map(|t| t.object % 2 == 0).collect();
    (tris, casts)
}

/// `count` random rays towards the box (closest-hit and any-hit, some with t_max, t_min
/// and an excluded triangle), ids 0, 1, ….
pub fn rays(seed: u64, count: usize, triangles: u32) -> Vec<UnitRay> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..count)
        .map(|id| {
            let orig = [0; 3].map(|_| rng.gen_range(-9.0f32..9.0));
            let target = [0; 3].map(|_| rng.gen_range(-3.0f32..3.0));
            UnitRay {
                orig,
                dir: std::array::from_fn(|k| target[k] - orig[k]),
                t_max: if rng.gen_bool(0.3) {
                    rng.gen_range(0.0..1.5)
                } else {
                    f32::MAX
                },
                t_min: if rng.gen_bool(0.2) {
                    rng.gen_range(0.0..0.5)
                } else {
                    0.0
                },
                exclude: rng.gen_bool(0.2).then(|| rng.gen_range(0..triangles)),
                any_hit: rng.gen_bool(0.4),
                id: id as u32,
            }
        })
        .collect()
}
