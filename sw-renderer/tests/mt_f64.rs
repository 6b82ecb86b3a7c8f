//! Möller-Trumbore in f32 (the reference) against the same algorithm in f64 on the same
//! (exactly widened) inputs.
//!
//! # Tolerance band
//! f32 rounding moves every computed quantity by a few ulps of the magnitudes that went into
//! it (cross products cancel, so the magnitudes are products of input lengths). With
//! κ = |e1|·|d|·|e2|/|det| (the conditioning of det) these magnitudes are
//! - m_u = |s|·|d|·|e2|/|det| + |u|·κ,
//! - m_v = |d|·|s|·|e1|/|det| + |v|·κ,
//! - m_t = |e2|·|s|·|e1|/|det| + |t|·κ,
//!
//! where |·| of a vector is its Euclidean norm. A case is "inside the band" when one of the
//! f64 values is within `BAND` (relative, about 170 f32 ulps) times its magnitude of its
//! decision boundary: |u| or |1 − u| ≤ BAND·m_u, |v| ≤ BAND·m_v, |1 − u − v| ≤ BAND·(m_u + m_v),
//! |t| ≤ BAND·m_t, or ||det| − 1e-8| ≤ BAND·|e1|·|d|·|e2| (the parallel-ray epsilon).
//! Outside the band hit/miss must agree; inside it the disagreements are counted and must stay
//! a small share of the cases. Where both hit outside the band, t, u, v must agree within
//! BAND times their magnitudes.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sw_renderer::intersect::{mt_f32, MtQuery};

const BAND: f64 = 1e-5;

type D3 = [f64; 3];

fn sub(a: D3, b: D3) -> D3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: D3, b: D3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: D3, b: D3) -> D3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: D3) -> f64 {
    dot(a, a).sqrt()
}
fn wide(a: [f32; 3]) -> D3 {
    a.map(f64::from)
}

struct Mt64 {
    hit: bool,
    t: f64,
    u: f64,
    v: f64,
    in_band: bool,
    /// Magnitudes of the terms u, v, t were computed from (their conditioning).
    mu: f64,
    mv: f64,
    mt: f64,
}

fn mt_f64(q: &MtQuery) -> Mt64 {
    let (o, d, v0) = (wide(q.orig), wide(q.dir), wide(q.v0));
    let e1 = sub(wide(q.v1), v0);
    let e2 = sub(wide(q.v2), v0);
    let p = cross(d, e2);
    let det = dot(e1, p);
    let s = sub(o, v0);
    let u = dot(s, p) / det;
    let qv = cross(s, e1);
    let v = dot(d, qv) / det;
    let t = dot(e2, qv) / det;
    let hit = det.abs() >= f64::from(1e-8f32)
        && (0.0..=1.0).contains(&u)
        && v >= 0.0
        && u + v <= 1.0
        && t > 0.0;
    let (ns, nd, n1, n2) = (norm(s), norm(d), norm(e1), norm(e2));
    let kappa = n1 * nd * n2 / det.abs();
    let mu = ns * nd * n2 / det.abs() + u.abs() * kappa;
    let mv = nd * ns * n1 / det.abs() + v.abs() * kappa;
    let mt = n2 * ns * n1 / det.abs() + t.abs() * kappa;
    let in_band = u.abs() <= BAND * mu
        || (1.0 - u).abs() <= BAND * mu
        || v.abs() <= BAND * mv
        || (1.0 - u - v).abs() <= BAND * (mu + mv)
        || t.abs() <= BAND * mt
        || (det.abs() - f64::from(1e-8f32)).abs() <= BAND * n1 * nd * n2;
    Mt64 {
        hit,
        t,
        u,
        v,
        in_band,
        mu,
        mv,
        mt,
    }
}

fn random_point(rng: &mut StdRng, scale: f32) -> [f32; 3] {
    [0; 3].map(|_| rng.gen_range(-scale..scale))
}

/// A query of a random kind: free rays, rays aimed inside a triangle, nearly parallel rays,
/// rays aimed just inside or outside an edge (by 1e-4…1e-1 in barycentrics: outside the
/// band, so a sloppy edge test shows), tiny triangles; with `on_edges`, rays aimed exactly
/// at an edge (u = 0 or u + v = 1).
fn random_query(rng: &mut StdRng, on_edges: bool) -> MtQuery {
    let scale = [1.0, 10.0, 100.0][rng.gen_range(0..3)];
    let v0 = random_point(rng, scale);
    let size = if rng.gen_bool(0.2) {
        scale * 1e-3
    } else {
        scale
    };
    let v1 = {
        let d = random_point(rng, size);
        [v0[0] + d[0], v0[1] + d[1], v0[2] + d[2]]
    };
    let v2 = {
        let d = random_point(rng, size);
        [v0[0] + d[0], v0[1] + d[1], v0[2] + d[2]]
    };
    let orig = random_point(rng, 2.0 * scale);
    let kind = if on_edges {
        rng.gen_range(2..4)
    } else {
        [0, 1, 4, 5, 6][rng.gen_range(0..5)]
    };
    let dir = match kind {
        0 => random_point(rng, 1.0),
        kind => {
            let (mut a, mut b): (f32, f32) = (rng.gen(), rng.gen());
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            let mut near = || {
                10f32.powf(rng.gen_range(-4.0..-1.0)) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 }
            };
            match kind {
                2 => a = 0.0,
                3 => b = 1.0 - a,
                5 => a = near(),
                6 => b = 1.0 - a + near(),
                _ => {}
            }
            let target = [0, 1, 2].map(|k| v0[k] + (v1[k] - v0[k]) * a + (v2[k] - v0[k]) * b);
            let mut d = [0, 1, 2].map(|k| target[k] - orig[k]);
            if kind == 4 {
                // Nearly parallel: push the direction into the triangle's plane.
                let n = cross(
                    wide([v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]]),
                    wide([v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]]),
                );
                let k = dot(wide(d), n) / dot(n, n) * (1.0 - 1e-6);
                d = [0, 1, 2].map(|i| (f64::from(d[i]) - k * n[i]) as f32);
            }
            d
        }
    };
    MtQuery {
        orig,
        dir,
        v0,
        v1,
        v2,
        t_min: 0.0,
    }
}

fn check(cases: usize, seed: u64, on_edges: bool) -> (usize, usize, usize) {
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut hits, mut exceptions, mut in_band) = (0, 0, 0);
    for i in 0..cases {
        let q = random_query(&mut rng, on_edges);
        let (a, b) = (mt_f32(&q), mt_f64(&q));
        in_band += usize::from(b.in_band);
        if a.hit != b.hit {
            assert!(
                b.in_band,
                "case {i}: f32 hit={} f64 hit={} outside the band: {q:?} f64 t={} u={} v={}",
                a.hit, b.hit, b.t, b.u, b.v
            );
            exceptions += 1;
        } else if a.hit && !b.in_band {
            hits += 1;
            let close =
                |x: f32, y: f64, magnitude: f64| (f64::from(x) - y).abs() <= BAND * magnitude;
            assert!(
                close(a.u, b.u, b.mu) && close(a.v, b.v, b.mv) && close(a.t, b.t, b.mt),
                "case {i}: {a:?} vs t={} u={} v={}",
                b.t,
                b.u,
                b.v
            );
        }
    }
    (hits, exceptions, in_band)
}

#[test]
fn f32_and_f64_agree_outside_the_tolerance_band() {
    let cases = 200_000;
    let (hits, exceptions, in_band) = check(cases, 2021, false);
    eprintln!("general: {cases} cases, {hits} clear hits, {in_band} in the band, {exceptions} disagreements");
    // Enough hits and band cases to mean something; disagreements (all inside the band,
    // mostly near-edge rays at tiny far triangles, measured 0.3%) stay under 1%.
    assert!(hits > cases / 10, "{hits} hits");
    assert!(in_band > cases / 1000, "{in_band} cases in the band");
    assert!(exceptions * 100 <= cases, "{exceptions} disagreements");
}

/// Rays aimed exactly at edges are decided by rounding; every disagreement must still be
/// inside the band.
#[test]
fn on_edges_disagreements_stay_inside_the_band() {
    let cases = 100_000;
    let (hits, exceptions, in_band) = check(cases, 1, true);
    eprintln!("edges: {cases} cases, {hits} clear hits, {in_band} in the band, {exceptions} disagreements");
    assert!(in_band > cases / 2 && exceptions > 0);
}

/// The same on 10M cases: `cargo test --release -p sw-renderer --test mt_f64 -- --ignored`.
#[test]
#[ignore]
fn f32_and_f64_agree_outside_the_tolerance_band_10m() {
    let (hits, exceptions, in_band) = check(10_000_000, 7, false);
    eprintln!("10M cases: {hits} clear hits, {in_band} in the band, {exceptions} disagreements");
    assert!(exceptions * 100 <= 10_000_000);
}
