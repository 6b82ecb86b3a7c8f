//! The project's own scenes: procedural meshes, the TOML format and the built-in scenes.

use glam::{Vec2, Vec3};
use std::collections::HashMap;
use sw_renderer::scene::procedural::{self, Backdrop};
use sw_renderer::scene::Mesh;

/// Indices in range, one normal and uv triple per triangle, no zero-area triangle, unit
/// normals, finite uvs.
fn assert_well_formed(mesh: &Mesh, what: &str) {
    assert!(!mesh.triangles.is_empty(), "{what}: no triangles");
    assert_eq!(mesh.normals.len(), mesh.triangles.len(), "{what}: normals");
    assert_eq!(mesh.uvs.len(), mesh.triangles.len(), "{what}: uvs");
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &i in tri {
            assert!((i as usize) < mesh.positions.len(), "{what}: triangle {t} index {i} out of range");
        }
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
        let face = (b - a).cross(c - a);
        assert!(face.length() > 0.0, "{what}: triangle {t} has no area");
        for n in mesh.normals[t] {
            assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-5, "{what}: triangle {t} normal {n} not unit");
        }
        for uv in mesh.uvs[t] {
            assert!(uv.is_finite(), "{what}: triangle {t} uv {uv}");
        }
    }
}

/// Share of corner normals on the side the triangle's winding faces (counter-clockwise seen
/// from the outside): 1 when winding and normals agree everywhere.
fn winding_agreement(mesh: &Mesh) -> f64 {
    let agreeing: usize = mesh
        .triangles
        .iter()
        .zip(&mesh.normals)
        .map(|(tri, normals)| {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let face = (b - a).cross(c - a);
            normals.iter().filter(|n| n.dot(face) > 0.0).count()
        })
        .sum();
    agreeing as f64 / (3 * mesh.triangles.len()) as f64
}

/// Every directed edge once and its reverse once: closed, and consistently wound.
fn assert_closed(mesh: &Mesh, what: &str) {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    for tri in &mesh.triangles {
        for k in 0..3 {
            *edges.entry((tri[k], tri[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "{what}: directed edge {a}->{b} used {count} times");
        assert!(edges.contains_key(&(b, a)), "{what}: edge {a}->{b} has no twin: the mesh is open there");
    }
}

fn bounds(mesh: &Mesh) -> (Vec3, Vec3) {
    mesh.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
}

/// Möller-Trumbore, written out here as an independent reference (no culling, t > 0).
fn ray_hits(mesh: &Mesh, o: Vec3, d: Vec3) -> usize {
    mesh.triangles
        .iter()
        .filter(|tri| {
            let [v0, v1, v2] = tri.map(|i| mesh.positions[i as usize]);
            let (e1, e2) = (v1 - v0, v2 - v0);
            let p = d.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-12 {
                return false;
            }
            let s = o - v0;
            let u = s.dot(p) / det;
            let q = s.cross(e1);
            let v = d.dot(q) / det;
            u >= 0.0 && v >= 0.0 && u + v <= 1.0 && e2.dot(q) / det > 0.0
        })
        .count()
}

/// Share of triangles whose normal, followed from just off the surface, leaves the solid (an
/// even number of crossings with the mesh).
fn outward_share(mesh: &Mesh) -> f64 {
    let scale = {
        let (lo, hi) = bounds(mesh);
        (hi - lo).length()
    };
    let outward = mesh
        .triangles
        .iter()
        .zip(&mesh.normals)
        .filter(|(tri, normals)| {
            let centre = tri.iter().map(|&i| mesh.positions[i as usize]).sum::<Vec3>() / 3.0;
            let n = (normals[0] + normals[1] + normals[2]).normalize();
            // A slightly skewed direction avoids grazing shared edges exactly.
            let d = (n + Vec3::new(0.013, 0.007, 0.011)).normalize();
            ray_hits(mesh, centre + n * (1e-4 * scale), d) % 2 == 0
        })
        .count();
    outward as f64 / mesh.triangles.len() as f64
}

#[test]
fn teapot_has_one_triangle_pair_per_quad_except_at_collapsed_edges() {
    for n in [2u32, 3, 10] {
        let mesh = procedural::teapot(n, 1.0).unwrap();
        assert_well_formed(&mesh, &format!("teapot {n}"));
        // 32 patches × n² quads; the 8 patches with an edge collapsed to a point (4 at the lid's
        // knob, 4 at the bottom centre) lose one triangle per quad along it. For n = 10 this is
        // the thesis teapot.geo's 6320.
        assert_eq!(mesh.triangles.len() as u32, 2 * 32 * n * n - 8 * n, "segments {n}");
    }
    let agreement = winding_agreement(&procedural::teapot(10, 1.0).unwrap());
    eprintln!("teapot winding agreement {agreement}");
    assert!(agreement > 0.99, "teapot: only {agreement} of corner normals agree with the winding");
}

#[test]
fn teapot_normals_point_outward() {
    let mesh = procedural::teapot(4, 1.0).unwrap();
    let share = outward_share(&mesh);
    // Not 100%: the handle and spout ends sit inside the body, the lid on the rim.
    assert!(share > 0.9, "only {share} of the teapot's normals point outward");
}
