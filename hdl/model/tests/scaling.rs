//! Scaling a query by a power of two is exact in a float format: origin, direction and
//! vertices times 2^k give the same hits and the same t, u, v bits, as long as no
//! intermediate over- or underflows and the determinant stays on the same side of the
//! parallel-ray threshold (which is not scaled: docs/precision.md).

use hw_model::mt::DET_EPSILON;
use hw_model::{lookup, mt_model, mt_model_scaled, Edges, MtQuery};
use proptest::prelude::*;

/// A coordinate on the grid j·2^-8, |x| ≤ 64: every nonzero intermediate of the test is at
/// least 2^-48 and at most 2^26 in magnitude, so scales of 2^±24 neither over- nor underflow.
fn coord() -> impl Strategy<Value = f32> {
    (-(64 << 8)..=(64i32 << 8)).prop_map(|j| j as f32 / 256.0)
}

fn point() -> impl Strategy<Value = [f32; 3]> {
    [coord(), coord(), coord()]
}

/// Rays aimed inside (or just outside) random triangles.
fn query() -> impl Strategy<Value = MtQuery> {
    (point(), point(), point(), point(), 0i32..20, 0i32..20).prop_map(|(orig, v0, v1, v2, a, b)| {
        let (a, b) = (a as f32 / 16.0 - 0.125, b as f32 / 16.0 - 0.125);
        MtQuery::aimed(orig, [v0, v1, v2], (a, b), 0.0)
    })
}

fn det(q: &MtQuery) -> f64 {
    let f = |v: [f32; 3]| v.map(f64::from);
    let (d, v0, v1, v2) = (f(q.dir), f(q.v0), f(q.v1), f(q.v2));
    let e1: [f64; 3] = std::array::from_fn(|k| v1[k] - v0[k]);
    let e2: [f64; 3] = std::array::from_fn(|k| v2[k] - v0[k]);
    let p = [
        d[1] * e2[2] - d[2] * e2[1],
        d[2] * e2[0] - d[0] * e2[2],
        d[0] * e2[1] - d[1] * e2[0],
    ];
    e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2]
}

proptest! {
    // Negative k often pushes the determinant below the threshold: those cases are skipped.
    #![proptest_config(ProptestConfig { cases: 4000, max_global_rejects: 40_000, ..ProptestConfig::default() })]

    #[test]
    fn scaled_fp32_equals_unscaled_bit_for_bit(q in query(), k in -24i32..=24) {
        let eps = f64::from(DET_EPSILON);
        let det = det(&q).abs();
        prop_assume!(det > 2.0 * eps && det * 2f64.powi(3 * k) > 2.0 * eps);
        let fp32 = lookup("fp32").unwrap();
        let want = mt_model(&fp32, &q);
        let got = mt_model_scaled(&fp32, k, Edges::Exact, &q);
        prop_assert_eq!(got.hit, want.hit);
        prop_assert_eq!(got.t.to_bits(), want.t.to_bits(), "t {} vs {}", got.t, want.t);
        prop_assert_eq!(got.u.to_bits(), want.u.to_bits());
        prop_assert_eq!(got.v.to_bits(), want.v.to_bits());
    }
}

/// Past the format's range scaling is not exact: fp16 overflows at 2^16.
#[test]
fn scaling_beyond_the_range_changes_results() {
    let q = MtQuery {
        orig: [0.25, 0.25, 2.0],
        dir: [0.0, 0.0, -1.0],
        v0: [0.0, 0.0, 0.0],
        v1: [1.0, 0.0, 0.0],
        v2: [0.0, 1.0, 0.0],
        t_min: 0.0,
    };
    let fp16 = lookup("fp16").unwrap();
    assert_eq!(mt_model_scaled(&fp16, 3, Edges::Exact, &q).t, 2.0);
    assert!(
        !mt_model_scaled(&fp16, 8, Edges::Exact, &q).hit,
        "det = 2^24 overflows fp16"
    );
}
