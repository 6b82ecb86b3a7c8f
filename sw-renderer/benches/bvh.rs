//! Closest-hit throughput on a ~10k-triangle mesh: BVH gathering + Möller-Trumbore + reduction
//! against the reference's brute force over every triangle (rays per second).
//! Run: `cargo bench -p sw-renderer --bench bvh`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sw_renderer::bvh::{BoxRay, Bvh};
use sw_renderer::hit::{closest_hit, Window, NO_BOUND};
use sw_renderer::intersect::{F32Intersector, Intersector, MtQuery, MtResult};
use sw_renderer::math::V3;
use sw_renderer::world::WorldTriangle;

/// A bumpy sphere of 2·rings·segments triangles.
fn mesh(rings: u32, segments: u32) -> Vec<WorldTriangle> {
    let point = |r: u32, s: u32| {
        let (theta, phi) = (
            std::f32::consts::PI * r as f32 / rings as f32,
            std::f32::consts::TAU * s as f32 / segments as f32,
        );
        let radius = 1.0 + 0.05 * (7.0 * theta).sin() * (5.0 * phi).cos();
        V3::new(
            theta.sin() * phi.cos(),
            theta.cos(),
            theta.sin() * phi.sin(),
        ) * radius
    };
    let mut tris = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let n = [V3::new(0.0, 1.0, 0.0); 3];
            tris.push(WorldTriangle {
                verts: [point(r, s), point(r + 1, s), point(r + 1, s + 1)],
                normals: n,
                object: 0,
            });
            tris.push(WorldTriangle {
                verts: [point(r, s), point(r + 1, s + 1), point(r, s + 1)],
                normals: n,
                object: 0,
            });
        }
    }
    tris
}

fn rays(n: usize) -> Vec<(V3, V3)> {
    let mut rng = StdRng::seed_from_u64(1);
    (0..n)
        .map(|_| {
            let o = V3::new(rng.gen_range(-3.0..3.0), rng.gen_range(-3.0..3.0), 4.0);
            let target = V3::new(rng.gen_range(-1.2..1.2), rng.gen_range(-1.2..1.2), 0.0);
            (o, (target - o).normalized())
        })
        .collect()
}

fn query(o: V3, d: V3, t: &WorldTriangle) -> MtQuery {
    MtQuery {
        orig: o.to_array(),
        dir: d.to_array(),
        v0: t.verts[0].to_array(),
        v1: t.verts[1].to_array(),
        v2: t.verts[2].to_array(),
        t_min: 0.0,
    }
}

fn bench(c: &mut Criterion) {
    let tris = mesh(70, 72);
    let bvh = Bvh::build(&tris);
    let all: Vec<u32> = (0..tris.len() as u32).collect();
    let mut group = c.benchmark_group(format!("closest hit, {} triangles", tris.len()));
    for (name, count) in [("bvh", 4096), ("brute force", 64)] {
        let rays = rays(count);
        group.throughput(Throughput::Elements(count as u64));
        group.bench_with_input(BenchmarkId::new(name, count), &rays, |b, rays| {
            let (mut cands, mut queries, mut results) = (Vec::new(), Vec::new(), Vec::new());
            b.iter(|| {
                let mut hits = 0;
                for &(o, d) in rays {
                    cands.clear();
                    if name == "bvh" {
                        bvh.candidates(&BoxRay::new(o, d, NO_BOUND), |_| true, &mut cands);
                    } else {
                        cands.extend_from_slice(&all);
                    }
                    queries.clear();
                    queries.extend(cands.iter().map(|&t| query(o, d, &tris[t as usize])));
                    results.resize(queries.len(), MtResult::default());
                    F32Intersector
                        .intersect_batch(&queries, &mut results)
                        .expect("the f32 reference cannot fail");
                    hits += usize::from(
                        closest_hit(&cands, &results, &Window::below(NO_BOUND)).is_some(),
                    );
                }
                hits
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
