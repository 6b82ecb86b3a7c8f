//! Test-only references shared by the integration tests.

use sw_renderer::hit::Hit;
use sw_renderer::intersect::{mt_f32, MtQuery};
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

/// The query of one ray against one triangle.
pub fn query(orig: V3, dir: V3, t: &WorldTriangle) -> MtQuery {
    MtQuery {
        orig: orig.to_array(),
        dir: dir.to_array(),
        v0: t.verts[0].to_array(),
        v1: t.verts[1].to_array(),
        v2: t.verts[2].to_array(),
        t_min: 0.0,
    }
}

/// The reference's `trace`, literally: objects in order, triangles in order, the nearest hit
/// per object, then across objects the strictly nearer one below `bound`. Objects for which
/// `skip` says so (transparent ones for shadow rays) never block.
pub fn brute_force_trace(
    tris: &[WorldTriangle],
    orig: V3,
    dir: V3,
    bound: f32,
    skip: impl Fn(usize) -> bool,
) -> Option<Hit> {
    let mut isect_t = bound;
    let mut best = None;
    let objects = tris
        .iter()
        .map(|t| t.object as usize + 1)
        .max()
        .unwrap_or(0);
    for k in 0..objects {
        let mut t_near = f32::MAX;
        let mut found = None;
        for (i, tri) in tris
            .iter()
            .enumerate()
            .filter(|(_, t)| t.object as usize == k)
        {
            let r = mt_f32(&query(orig, dir, tri));
            if r.hit && r.t < t_near {
                t_near = r.t;
                found = Some(Hit {
                    triangle: i as u32,
                    t: r.t,
                    u: r.u,
                    v: r.v,
                });
            }
        }
        if found.is_some() && t_near < isect_t && !skip(k) {
            best = found;
            isect_t = t_near;
        }
    }
    best
}
