//! proptest strategies of meshes and rays for tests of the traversal unit against
//! references (the model against brute force in hw-model, the Verilated unit against the
//! model in sim). Feature `strategies`.

use proptest::prelude::*;
use sw_renderer::hit::NO_BOUND;
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

use super::UnitRay;

/// A point of a coarse grid: shared vertices, shared edges and duplicates become likely.
pub fn v3() -> impl Strategy<Value = V3> {
    (-4i32..=4, -4i32..=4, -4i32..=4)
        .prop_map(|(x, y, z)| V3::new(x as f32, y as f32, z as f32) * 0.5)
}

/// 1 to 39 grid triangles in objects of 8 (odd objects, for the caller's casts-shadow flags),
/// with duplicates of the previous triangle (equal t: the lower index must win) and
/// neighbours sharing its edge.
pub fn mesh() -> impl Strategy<Value = Vec<WorldTriangle>> {
    prop::collection::vec((v3(), v3(), v3(), 0usize..3), 1..40).prop_map(|raw| {
        let mut tris: Vec<WorldTriangle> = Vec::new();
        for (k, (a, b, c, kind)) in raw.into_iter().enumerate() {
            let verts = match (kind, tris.last()) {
                (1, Some(p)) => p.verts,
                (2, Some(p)) => [p.verts[0], p.verts[2], c],
                _ => [a, b, c],
            };
            tris.push(WorldTriangle {
                verts,
                normals: [V3::new(0.0, 0.0, 1.0); 3],
                object: (k / 8) as u32,
            });
        }
        tris
    })
}

/// A ray from just off the grid: between grid points, or axis-parallel (parallel to the
/// faces of many grid triangles and to box slabs); unbounded, t_max = 0 or bounded;
/// closest-hit or any-hit; a spawned ray's t_min and excluded triangle (indices beyond the
/// mesh exclude nothing); any id.
pub fn ray() -> impl Strategy<Value = UnitRay> {
    let dir = prop_oneof![
        (v3(), v3()).prop_map(|(a, b)| (b - a).to_array()),
        (0usize..3, prop::bool::ANY).prop_map(|(a, neg)| {
            let mut d = [0.0f32; 3];
            d[a] = if neg { -1.0 } else { 1.0 };
            d
        }),
    ];
    let t_max = prop_oneof![Just(NO_BOUND), Just(0.0f32), 0.1f32..6.0];
    let t_min = prop_oneof![Just(0.0f32), 0.0f32..3.0];
    let exclude = prop::option::of(0u32..40);
    (
        (v3(), dir, t_max, prop::bool::ANY, any::<u32>()),
        (t_min, exclude),
    )
        .prop_map(|((o, dir, t_max, any_hit, id), (t_min, exclude))| UnitRay {
            orig: (o + V3::new(0.13, 0.07, -0.11)).to_array(),
            dir,
            t_max,
            t_min,
            exclude,
            any_hit,
            id,
        })
}
