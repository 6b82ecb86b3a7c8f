//! The modelled Möller-Trumbore test: fp32 equals a native-f32 MT with the same operation
//! order whenever no value along the way is subnormal; every catalogue format computes an
//! exactly representable case exactly; the lower bound `t_min` is compared in the format.

mod common;

use common::rng;
use hw_model::mt::mt_model;
use hw_model::{catalogue, Format, MtQuery, MtResult};
use rand::rngs::StdRng;
use rand::Rng;

/// Records whether any value passing through is subnormal.
#[derive(Default)]
struct Watch(bool);

impl Watch {
    fn n(&mut self, x: f32) -> f32 {
        self.0 |= x.is_subnormal();
        x
    }
    fn sub(&mut self, a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        [
            self.n(a[0] - b[0]),
            self.n(a[1] - b[1]),
            self.n(a[2] - b[2]),
        ]
    }
    fn mul(&mut self, a: f32, b: f32) -> f32 {
        self.n(a * b)
    }
    fn cross(&mut self, a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
        let x = self.mul(a[1], b[2]) - self.mul(a[2], b[1]);
        let y = self.mul(a[2], b[0]) - self.mul(a[0], b[2]);
        let z = self.mul(a[0], b[1]) - self.mul(a[1], b[0]);
        [self.n(x), self.n(y), self.n(z)]
    }
    fn dot(&mut self, a: [f32; 3], b: [f32; 3]) -> f32 {
        let xy = self.mul(a[0], b[0]) + self.mul(a[1], b[1]);
        let xy = self.n(xy);
        let z = self.mul(a[2], b[2]);
        self.n(xy + z)
    }
}

/// Native f32 MT in the hardware's order; also says whether any input or intermediate is
/// subnormal (where flush-to-zero may legitimately differ).
#[allow(clippy::nonminimal_bool, clippy::neg_cmp_op_on_partial_ord)] // the C++ rejections, NaN behaviour included
fn mt_native(q: &MtQuery) -> (MtResult, bool) {
    let mut w = Watch::default();
    for a in [q.orig, q.dir, q.v0, q.v1, q.v2] {
        a.iter().for_each(|&x| {
            w.n(x);
        });
    }
    w.n(q.t_min);
    let e1 = w.sub(q.v1, q.v0);
    let e2 = w.sub(q.v2, q.v0);
    let p = w.cross(q.dir, e2);
    let det = w.dot(e1, p);
    let inv = w.n(1.0 / det);
    let s = w.sub(q.orig, q.v0);
    let u = w.dot(s, p) * inv;
    let u = w.n(u);
    let qv = w.cross(s, e1);
    let v = w.dot(q.dir, qv) * inv;
    let v = w.n(v);
    let t = w.dot(e2, qv) * inv;
    let t = w.n(t);
    let uv = w.n(u + v);
    let eps = 1e-8f32;
    let hit = !(det < eps && -eps < det)
        && !(u < 0.0)
        && !(1.0 < u)
        && !(v < 0.0)
        && !(1.0 < uv)
        && q.t_min < t;
    (MtResult { hit, t, u, v }, w.0)
}

/// Equal bits, NaN matching NaN (native NaN payloads are the host's, the model's canonical).
fn same(a: &MtResult, b: &MtResult) -> bool {
    let eq = |x: f32, y: f32| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan());
    a.hit == b.hit && eq(a.t, b.t) && eq(a.u, b.u) && eq(a.v, b.v)
}

fn point(r: &mut StdRng, span: f32) -> [f32; 3] {
    [
        r.gen_range(-span..span),
        r.gen_range(-span..span),
        r.gen_range(-span..span),
    ]
}

/// Rays aimed near random triangles (about half hit), at scales from tiny to huge, plus
/// degenerate triangles and rays of arbitrary bits; one in five with a lower bound below or
/// beyond the hit.
fn random_query(r: &mut StdRng) -> MtQuery {
    let span = 2f32.powi(r.gen_range(-30..30));
    let (v0, v1, v2) = (point(r, span), point(r, span), point(r, span));
    let orig = point(r, span * 4.0);
    let (a, b) = (r.gen_range(-0.2f32..1.0), r.gen_range(-0.2f32..1.0));
    let target: [f32; 3] =
        std::array::from_fn(|k| v0[k] + a * (v1[k] - v0[k]) + b * (v2[k] - v0[k]));
    let mut dir: [f32; 3] = std::array::from_fn(|k| target[k] - orig[k]);
    let len = dir.iter().map(|x| x * x).sum::<f32>().sqrt();
    dir.iter_mut().for_each(|x| *x /= len);
    let t_min = if r.gen_range(0..5) == 0 {
        r.gen_range(-1.0..1.0) * span * 8.0
    } else {
        0.0
    };
    let mut q = MtQuery {
        orig,
        dir,
        v0,
        v1,
        v2,
        t_min,
    };
    match r.gen_range(0..10) {
        0 => q.v2 = q.v1, // degenerate: det = 0
        1 => q.dir = std::array::from_fn(|_| f32::from_bits(r.gen())),
        _ => {}
    }
    q
}

#[test]
fn fp32_model_equals_native_f32_without_subnormals() {
    let fp32 = hw_model::lookup("fp32").unwrap();
    let mut r = rng(21);
    let (mut compared, mut skipped, mut hits) = (0, 0, 0);
    for _ in 0..100_000 {
        let q = random_query(&mut r);
        let (native, subnormal) = mt_native(&q);
        let model = mt_model(&fp32, &q);
        if subnormal {
            skipped += 1;
            continue;
        }
        assert!(
            same(&model, &native),
            "{q:?}: model {model:?}, native {native:?}"
        );
        compared += 1;
        hits += native.hit as u32;
    }
    eprintln!("compared {compared}, skipped (subnormal somewhere) {skipped}, hits {hits}");
    assert!(
        compared > 90_000 && hits > 15_000,
        "the query generator lost its coverage"
    );
}

/// A ray down the z axis onto the unit right triangle at (0.25, 0.5), t = 2: det = 1, so
/// every value is a short binary fraction that all formats hold.
fn exact_case() -> MtQuery {
    MtQuery {
        orig: [0.25, 0.5, 2.0],
        dir: [0.0, 0.0, -1.0],
        v0: [0.0, 0.0, 0.0],
        v1: [1.0, 0.0, 0.0],
        v2: [0.0, 1.0, 0.0],
        t_min: 0.0,
    }
}

#[test]
fn every_catalogue_format_computes_an_exact_case_exactly() {
    let q = exact_case();
    let outside = MtQuery {
        orig: [0.75, 0.5, 2.0],
        ..q
    };
    let behind = MtQuery {
        orig: [0.25, 0.5, -2.0],
        ..q
    };
    for named in catalogue() {
        let r = mt_model(&named.format, &q);
        assert!(
            r.hit && (r.t, r.u, r.v) == (2.0, 0.25, 0.5),
            "{}: {r:?}",
            named.name
        );
        let r = mt_model(&named.format, &outside);
        assert!(!r.hit && (r.u, r.v) == (0.75, 0.5), "{}: {r:?}", named.name);
        let r = mt_model(&named.format, &behind);
        assert!(!r.hit && r.t == -2.0, "{}: {r:?}", named.name);
    }
}

#[test]
fn narrow_formats_deviate_from_fp32_on_general_queries() {
    // A model that ignored its format would agree with fp32 everywhere.
    let fp32 = hw_model::lookup("fp32").unwrap();
    let mut r = rng(22);
    let queries: Vec<MtQuery> = (0..2_000).map(|_| random_query(&mut r)).collect();
    for name in ["bf16", "fp16", "fx16_10", "fx32_16_rnd_sat"] {
        let format = hw_model::lookup(name).unwrap();
        let differ = queries
            .iter()
            .filter(|q| !same(&mt_model(&format, q), &mt_model(&fp32, q)))
            .count();
        assert!(
            differ > 100,
            "{name}: only {differ} of 2000 queries differ from fp32"
        );
    }
}

#[test]
fn a_hit_needs_t_above_t_min_in_every_format() {
    // t = 2 exactly in every format; 1.75 and 2.25 too.
    let base = exact_case();
    let hit = |format, t_min| mt_model(format, &MtQuery { t_min, ..base }).hit;
    for named in catalogue() {
        let (f, name) = (&named.format, named.name);
        assert!(hit(f, 0.0) && hit(f, 1.75) && hit(f, -1.0), "{name}");
        assert!(!hit(f, 2.0) && !hit(f, 2.25), "{name}: t = t_min is a miss");
        assert!(!hit(f, f32::INFINITY), "{name}: +Inf rejects every t");
        assert!(
            hit(f, f32::NEG_INFINITY),
            "{name}: -Inf rejects no finite t"
        );
        // NaN: no t is above it in a float format; fixed point converts it to 0.
        let fixed = matches!(named.format, Format::Fixed { .. });
        assert_eq!(hit(f, f32::NAN), fixed, "{name}: NaN t_min");
        // t, u, v do not depend on the bound.
        let (a, b) = (
            mt_model(f, &base),
            mt_model(f, &MtQuery { t_min: 3.0, ..base }),
        );
        assert_eq!((a.t, a.u, a.v), (b.t, b.u, b.v), "{name}");
    }
}

#[test]
fn fp32_t_min_just_below_t_hits_and_at_t_misses() {
    let fp32 = hw_model::lookup("fp32").unwrap();
    let mut r = rng(23);
    let mut checked = 0;
    for _ in 0..20_000 {
        let q = MtQuery {
            t_min: 0.0,
            ..random_query(&mut r)
        };
        let base = mt_model(&fp32, &q);
        if !base.hit || !base.t.is_normal() {
            continue;
        }
        let at = |t_min: f32| mt_model(&fp32, &MtQuery { t_min, ..q }).hit;
        let below = f32::from_bits(base.t.to_bits() - 1);
        assert!(at(below), "{q:?}: t {} just above t_min", base.t);
        assert!(!at(base.t), "{q:?}: t = t_min {}", base.t);
        assert!(!at(f32::from_bits(base.t.to_bits() + 1)), "{q:?}");
        checked += 1;
    }
    assert!(checked > 2_000, "only {checked} hits");
}
