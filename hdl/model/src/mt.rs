//! The Möller-Trumbore test in any format, in exactly the hardware's operation order.

use crate::edges::{tolerances, Edges, LaneValues, Rounding};
use crate::float::FloatFormat;
use crate::format::{with_arith, Arith, Format};

// The query and result types belong to the renderer's seam; the model answers them.
pub use sw_renderer::intersect::{MtQuery, MtResult};

/// The parallel-ray threshold of the reference renderer, converted into the format.
pub const DET_EPSILON: f32 = 1e-8;

type V = [u64; 3];

#[inline]
fn sub<A: Arith>(f: A, a: &V, b: &V) -> V {
    [f.sub(a[0], b[0]), f.sub(a[1], b[1]), f.sub(a[2], b[2])]
}

/// a×b component by component as a.y·b.z − a.z·b.y, a.z·b.x − a.x·b.z, a.x·b.y − a.y·b.x.
#[inline]
fn cross<A: Arith>(f: A, a: &V, b: &V) -> V {
    [
        f.sub(f.mul(a[1], b[2]), f.mul(a[2], b[1])),
        f.sub(f.mul(a[2], b[0]), f.mul(a[0], b[2])),
        f.sub(f.mul(a[0], b[1]), f.mul(a[1], b[0])),
    ]
}

/// (a.x·b.x + a.y·b.y) + a.z·b.z.
#[inline]
fn dot<A: Arith>(f: A, a: &V, b: &V) -> u64 {
    f.add(
        f.add(f.mul(a[0], b[0]), f.mul(a[1], b[1])),
        f.mul(a[2], b[2]),
    )
}

#[inline]
fn load<A: Arith>(f: A, x: &[f32; 3]) -> V {
    [
        f.convert_in_f32(x[0]),
        f.convert_in_f32(x[1]),
        f.convert_in_f32(x[2]),
    ]
}

/// `q` with every coordinate times 2^`scale_exp` (exact in fp32 unless it over- or
/// underflows). Möller-Trumbore's t, u, v are ratios of products of equal degree in lengths,
/// so they do not change, and neither does `t_min`; a format's datapath sees the scene at
/// another magnitude (`crate::precision::auto_scale_exp`).
pub fn scale_query(q: &MtQuery, scale_exp: i32) -> MtQuery {
    let f = 2f32.powi(scale_exp);
    let s = |v: [f32; 3]| v.map(|x| x * f);
    MtQuery {
        orig: s(q.orig),
        dir: s(q.dir),
        v0: s(q.v0),
        v1: s(q.v1),
        v2: s(q.v2),
        t_min: q.t_min,
    }
}

/// The test in `format` with the edge test `edges` on `q` scaled by 2^`scale_exp`
/// ([`scale_query`]; 0: as given).
#[inline]
pub fn mt_model_scaled(format: &Format, scale_exp: i32, edges: Edges, q: &MtQuery) -> MtResult {
    if scale_exp == 0 {
        mt_model_edges(format, edges, q)
    } else {
        mt_model_edges(format, edges, &scale_query(q, scale_exp))
    }
}

/// The test in `format`: fp32 inputs converted in, every operation rounded in the format,
/// t, u, v converted back to fp32 (also on a miss).
///
/// The lower bound is compared in the format: `t_min` is converted in like the other 15
/// words and a hit needs `t_min < t` by the format's `lt` (docs/precision.md, "Where t_min
/// is applied"). So `t_min = 0` is exactly the reference's `t > 0`. In a float format a NaN
/// `t_min` rejects every hit, `-Inf` accepts every `t` but NaN and `+Inf` rejects all; a fixed
/// format converts NaN to 0 and ±Inf to its largest/smallest value (the SPEC's conversion).
#[inline]
pub fn mt_model(format: &Format, q: &MtQuery) -> MtResult {
    mt_model_edges(format, Edges::Exact, q)
}

/// [`mt_model`] with the edge test `edges` (`crate::edges`; the hardware lanes are
/// [`Edges::Exact`]).
#[inline]
pub fn mt_model_edges(format: &Format, edges: Edges, q: &MtQuery) -> MtResult {
    let rounding = (edges == Edges::Conservative).then(|| Rounding::of(format));
    with_arith!(format, f => tests(f, &datapath(f, q), rounding.as_ref()))
}

/// The datapath's values before the tests, as raw bits of the format.
struct Datapath {
    dir: V,
    e1: V,
    e2: V,
    s: V,
    p: V,
    q: V,
    inv: u64,
    det: u64,
    /// The numerators s·p, dir·q, e2·q of u, v, t.
    num: [u64; 3],
    u: u64,
    v: u64,
    t: u64,
    /// u + v, as the last test adds them.
    uv: u64,
    /// The query's t_min in the format: a hit needs t_min < t.
    t_min: u64,
}

fn datapath<A: Arith>(f: A, q: &MtQuery) -> Datapath {
    let (orig, dir, v0) = (load(f, &q.orig), load(f, &q.dir), load(f, &q.v0));
    let e1 = sub(f, &load(f, &q.v1), &v0);
    let e2 = sub(f, &load(f, &q.v2), &v0);
    let p = cross(f, &dir, &e2);
    let det = dot(f, &e1, &p);
    let inv = f.recip(det);
    let s = sub(f, &orig, &v0);
    let su = dot(f, &s, &p);
    let u = f.mul(su, inv);
    let qv = cross(f, &s, &e1);
    let dq = dot(f, &dir, &qv);
    let v = f.mul(dq, inv);
    let eq = dot(f, &e2, &qv);
    let t = f.mul(eq, inv);
    Datapath {
        dir,
        e1,
        e2,
        s,
        p,
        q: qv,
        inv,
        det,
        num: [su, dq, eq],
        u,
        v,
        t,
        uv: f.add(u, v),
        t_min: f.convert_in_f32(q.t_min),
    }
}

/// The tests on the datapath's values, and the result converted back to fp32; with a
/// `rounding`, the conservative edge test of that rounding ([`Edges::Conservative`]).
fn tests<A: Arith>(f: A, d: &Datapath, rounding: Option<&Rounding>) -> MtResult {
    let (zero, one, eps) = (
        f.convert_in_f32(0.0),
        f.convert_in_f32(1.0),
        f.convert_in_f32(DET_EPSILON),
    );
    let parallel = f.lt(d.det, eps) && f.lt(f.neg(eps), d.det);
    let inside = !f.lt(d.u, zero) && !f.lt(one, d.u) && !f.lt(d.v, zero) && !f.lt(one, d.uv);
    // The widened test accepts a superset of the exact one: its bound is evaluated only for
    // the queries the exact comparisons reject.
    let widened = || {
        rounding.is_some_and(|r| {
            let x = lane_values(f, d);
            tolerances(r, &x).is_some_and(|w| w.accept(&x))
        })
    };
    let hit = !parallel && f.lt(d.t_min, d.t) && (inside || widened());
    MtResult {
        hit,
        t: f.convert_out_f32(d.t),
        u: f.convert_out_f32(d.u),
        v: f.convert_out_f32(d.v),
    }
}

/// The datapath's values the edge bound reads, exactly.
fn lane_values<A: Arith>(f: A, d: &Datapath) -> LaneValues {
    let x = |bits: u64| f64::from_bits(f.convert_out(FloatFormat::F64, bits));
    let v = |b: V| b.map(x);
    LaneValues {
        dir: v(d.dir),
        e1: v(d.e1),
        e2: v(d.e2),
        s: v(d.s),
        p: v(d.p),
        q: v(d.q),
        det: x(d.det),
        su: x(d.num[0]),
        dq: x(d.num[1]),
        inv: x(d.inv),
        u: x(d.u),
        v: x(d.v),
        uv: x(d.uv),
    }
}

/// [`mt_model`]'s datapath values in `format` and the tolerances of its conservative edge
/// test (`None`: the bound decides nothing and the lane keeps the exact comparisons).
pub fn edge_bound(format: &Format, q: &MtQuery) -> (LaneValues, Option<crate::edges::Tolerances>) {
    let x = with_arith!(format, f => lane_values(f, &datapath(f, q)));
    (x, tolerances(&Rounding::of(format), &x))
}
