//! The BVH's candidate gathering plus the hit reduction must give exactly what the reference's
//! brute-force `trace` gave (every object, every triangle, per-object then across-object
//! strictly-nearer): same hit or miss, same triangle, same t bits.

use proptest::prelude::*;
use sw_renderer::bvh::{BoxRay, Bvh};
use sw_renderer::hit::{closest_hit, nearer, occluded, remaining_bound, Hit, Window, NO_BOUND};
use sw_renderer::intersect::mt_f32;
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

mod common;
use common::{brute_force_trace, query};

fn gathered(
    bvh: &Bvh,
    tris: &[WorldTriangle],
    orig: V3,
    dir: V3,
    bound: f32,
    skip: &[bool],
) -> (Vec<u32>, Vec<sw_renderer::intersect::MtResult>) {
    let mut cands = Vec::new();
    bvh.candidates(
        &BoxRay::new(orig, dir, bound),
        |t| !skip[tris[t as usize].object as usize],
        &mut cands,
    );
    let results = cands
        .iter()
        .map(|&t| mt_f32(&query(orig, dir, &tris[t as usize])))
        .collect();
    (cands, results)
}

/// The renderer's two passes: the nearest leaves (at least `enough` candidates), then the rest
/// bounded by the first pass' nearest hit (nothing more for a shadow ray already blocked).
fn two_pass(
    bvh: &Bvh,
    tris: &[WorldTriangle],
    (orig, dir, bound): (V3, V3, f32),
    skip: &[bool],
    enough: usize,
    shadow: bool,
) -> Option<Hit> {
    let keep = |t: u32| !skip[tris[t as usize].object as usize];
    let test = |cands: &[u32]| -> Vec<_> {
        cands
            .iter()
            .map(|&t| mt_f32(&query(orig, dir, &tris[t as usize])))
            .collect()
    };
    let (mut first, mut pending) = (Vec::new(), Vec::new());
    bvh.nearest_candidates(
        &BoxRay::new(orig, dir, bound),
        keep,
        enough,
        &mut first,
        &mut pending,
    );
    let found = closest_hit(&first, &test(&first), &Window::below(bound));
    if shadow && found.is_some() {
        return found;
    }
    let mut rest = Vec::new();
    let ray = BoxRay::new(orig, dir, remaining_bound(found, bound));
    bvh.remaining_candidates(&ray, keep, &pending, &mut rest);
    assert!(
        rest.iter().all(|t| !first.contains(t)),
        "a triangle gathered twice"
    );
    nearer(
        found,
        closest_hit(&rest, &test(&rest), &Window::below(bound)),
    )
}

fn v3() -> impl Strategy<Value = V3> {
    (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0).prop_map(|(x, y, z)| V3::new(x, y, z))
}

/// A mesh of random triangles plus a shared-edge grid (ties and edge hits), split into objects.
fn mesh() -> impl Strategy<Value = Vec<WorldTriangle>> {
    let random = prop::collection::vec((v3(), v3(), v3()), 1..80);
    let grid = (0usize..6, -5.0f32..5.0);
    (random, grid, 1u32..5).prop_map(|(random, (cells, z), objects)| {
        let mut verts: Vec<[V3; 3]> = random.into_iter().map(|(a, b, c)| [a, b, c]).collect();
        for i in 0..cells {
            for j in 0..cells {
                let (x, y) = (i as f32 - 3.0, j as f32 - 3.0);
                let p = |dx: f32, dy: f32| V3::new(x + dx, y + dy, z);
                verts.push([p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
                verts.push([p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)]);
                // A duplicate on every other cell: equal t, the lower index must win.
                if (i + j) % 2 == 0 {
                    verts.push([p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]);
                }
            }
        }
        let n = verts.len() as u32;
        verts
            .into_iter()
            .enumerate()
            .map(|(i, verts)| WorldTriangle {
                verts,
                normals: [V3::new(0.0, 0.0, 1.0); 3],
                // Contiguous object ranges, as objects' triangles are in the global list.
                object: (i as u32 * objects) / n,
            })
            .collect()
    })
}

/// Parameters of one ray: origin, random direction, aim mode, triangle pick, barycentrics.
type RayParams = (V3, V3, u32, f64, f32, f32);

fn ray_params() -> impl Strategy<Value = RayParams> {
    (v3(), v3(), 0u32..6, 0.0f64..1.0, 0.0f32..1.0, 0.0f32..1.0)
}

/// Mode 0 and 1: a random direction. Otherwise aimed at a point of a random triangle:
/// 2 inside, 3 on the edge v0-v2 (u = 0), 4 on the edge v1-v2 (u + v = 1), 5 at a vertex.
fn make_ray(tris: &[WorldTriangle], (o, d, mode, pick, a, b): RayParams) -> (V3, V3) {
    let o = o * 1.5;
    if mode < 2 {
        return (o, d.normalized());
    }
    let [v0, v1, v2] = tris[((pick * tris.len() as f64) as usize).min(tris.len() - 1)].verts;
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    let (a, b) = match mode {
        2 => (a, b),
        3 => (0.0, b),
        4 => (a, 1.0 - a),
        _ => (0.0, 0.0),
    };
    let target = v0 + (v1 - v0) * a + (v2 - v0) * b;
    (o, (target - o).normalized())
}

fn assert_same(bvh: Option<Hit>, brute: Option<Hit>) -> Result<(), TestCaseError> {
    match (bvh, brute) {
        (None, None) => Ok(()),
        (Some(x), Some(y)) => {
            prop_assert_eq!(x.triangle, y.triangle);
            prop_assert_eq!(x.t.to_bits(), y.t.to_bits());
            prop_assert_eq!(
                (x.u.to_bits(), x.v.to_bits()),
                (y.u.to_bits(), y.v.to_bits())
            );
            Ok(())
        }
        (x, y) => Err(TestCaseError::fail(format!(
            "bvh {x:?} vs brute force {y:?}"
        ))),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn closest_hit_equals_brute_force(tris in mesh(), rays in prop::collection::vec(ray_params(), 24)) {
        let bvh = Bvh::build(&tris);
        let no_skip = vec![false; 8];
        for params in rays {
            let (o, d) = make_ray(&tris, params);
            let (cands, results) = gathered(&bvh, &tris, o, d, NO_BOUND, &no_skip);
            assert_same(closest_hit(&cands, &results, &Window::below(NO_BOUND)), brute_force_trace(&tris, o, d, NO_BOUND, |k| no_skip[k]))?;
        }
    }

    #[test]
    fn bounded_closest_hit_equals_brute_force(
        tris in mesh(),
        rays in prop::collection::vec((ray_params(), 0.0f32..25.0), 24),
    ) {
        let bvh = Bvh::build(&tris);
        let no_skip = vec![false; 8];
        for (params, bound) in rays {
            let (o, d) = make_ray(&tris, params);
            let (cands, results) = gathered(&bvh, &tris, o, d, bound, &no_skip);
            assert_same(closest_hit(&cands, &results, &Window::below(bound)), brute_force_trace(&tris, o, d, bound, |k| no_skip[k]))?;
        }
    }

    #[test]
    fn shadow_rays_skip_objects_and_equal_brute_force(
        tris in mesh(),
        skip in prop::collection::vec(prop::bool::ANY, 8),
        rays in prop::collection::vec((ray_params(), prop::option::of(0.0f32..25.0)), 24),
    ) {
        let bvh = Bvh::build(&tris);
        for (params, bound) in rays {
            let bound = bound.unwrap_or(NO_BOUND);
            let (o, d) = make_ray(&tris, params);
            let (cands, results) = gathered(&bvh, &tris, o, d, bound, &skip);
            prop_assert_eq!(occluded(&cands, &results, &Window::below(bound)), brute_force_trace(&tris, o, d, bound, |k| skip[k]).is_some());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn two_pass_closest_hit_equals_brute_force(
        tris in mesh(),
        skip in prop::collection::vec(prop::bool::ANY, 8),
        enough in 1usize..12,
        rays in prop::collection::vec((ray_params(), prop::option::of(0.0f32..25.0)), 24),
    ) {
        let bvh = Bvh::build(&tris);
        for (params, bound) in rays {
            let bound = bound.unwrap_or(NO_BOUND);
            let (o, d) = make_ray(&tris, params);
            let want = brute_force_trace(&tris, o, d, bound, |k| skip[k]);
            assert_same(two_pass(&bvh, &tris, (o, d, bound), &skip, enough, false), want)?;
            let blocked = two_pass(&bvh, &tris, (o, d, bound), &skip, enough, true).is_some();
            prop_assert_eq!(blocked, want.is_some());
        }
    }
}

/// The gathering must also prune: on a fine grid only a few leaves are candidates.
#[test]
fn gathering_prunes_most_triangles() {
    let mut tris = Vec::new();
    for i in 0..100 {
        for j in 0..100 {
            let p = |dx: f32, dy: f32| V3::new(i as f32 + dx, j as f32 + dy, 0.0);
            tris.push(WorldTriangle {
                verts: [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)],
                normals: [V3::new(0.0, 0.0, 1.0); 3],
                object: 0,
            });
        }
    }
    let bvh = Bvh::build(&tris);
    let (cands, results) = gathered(
        &bvh,
        &tris,
        V3::new(50.2, 50.2, 3.0),
        V3::new(0.0, 0.0, -1.0),
        NO_BOUND,
        &[false],
    );
    assert!(cands.len() <= 16, "{} candidates", cands.len());
    assert_eq!(
        closest_hit(&cands, &results, &Window::below(NO_BOUND)).map(|h| h.triangle),
        Some(50 * 100 + 50)
    );
}
