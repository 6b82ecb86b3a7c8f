//! The Plücker filter (docs/precision.md, "The Plücker filter"): det and the numerators of
//! u, v, t as dot products of per-ray and per-triangle block vectors, so a test needs no
//! translation and no conversion from fp32, only 27 integer products at W = 18. With
//! s = orig − v0, n = e1 × e2, e3 = v2 − v1 and the ray's moment m = orig × dir:
//! - det = e1·(dir × e2) = −dir·n;
//! - N_u = s·(dir × e2) = e2·m + dir·(v0 × e2);
//! - N_v = dir·(s × e1) = −(e1·m + dir·(v0 × e1));
//! - N_w = det − N_u − N_v = −(e3·m + dir·(v1 × e3));
//! - N_t = e2·(s × e1) = orig·n − v0·n.
//!
//! Per ray the filter holds dir, m and orig as blocks, per triangle n, e1, e2, e3, v0 × e1,
//! v0 × e2, v1 × e3 and the scalar v0·n; each is computed once (here in f64, within a tracked
//! error) and truncated to W-bit mantissas on one grid per vector. The values are exact
//! integers, a sum of two dots floored onto the coarser grid ([`align_add`]): [`datapath`]
//! is what hardware computes, bit for bit. The margins come from block exponents only; the
//! decisions are the division-free filter's ([`Filter::decide_numerators`]) or sign tests
//! against short-float margins ([`PluckerDecisions::Signs`], in f64, not yet bit-exact).

use sw_renderer::intersect::{MtQuery, MtResult};

use super::bfp::Fx;
use super::linear::certainly_below;
use super::{
    coords, product_bounds, round_up_to_bits, Bounded, Ctx, Filter, FilterFormat, PluckerDecisions,
    Rounding, BV, F64_SLACK, HW_BOUND_BITS,
};

/// f64's unit roundoff.
const F64_UNIT: f64 = f64::EPSILON / 2.0;

/// Block exponents the filter covers (an 8-bit field); outside, the query is forwarded.
pub const EXP_RANGE: std::ops::RangeInclusive<i32> = -128..=127;

/// Extra mantissa bits of the t test's vectors, orig and n (25 bits at W = 18, a DSP48E1's
/// wide port): N_t = orig·n − v0·n cancels when a ray starts near a triangle's plane, as
/// spawned rays do beside the surface they leave, and at W bits the t test decided almost
/// none of the queries whose ray line passes inside the edges behind the origin.
pub const T_EXTRA_BITS: u32 = 7;

/// The width of the t test's vectors (orig and n) in a `bfpW` Plücker filter.
pub const fn wide(width: u32) -> u32 {
    width + T_EXTRA_BITS
}

/// The width of the stored −v0·n: that of orig·n's products, 2·[`wide`] − 1 (its sign
/// shared), so it cancels against orig·n without a coarser grid.
pub const fn offset_bits(width: u32) -> u32 {
    2 * wide(width) - 1
}

/// Bits of the coarse subtraction that bounds |s| = |orig − v0| for the fallback's bound:
/// orig and v0 aligned to the larger block exponent E and cut to this many bits, so the
/// difference is within 2^(E − S_BOUND_BITS + 2) of |s| (two truncations).
pub const S_BOUND_BITS: i32 = 9;

/// k with x = f·2^k, f in [1, 2), for a positive normal x.
fn exponent(x: f64) -> i32 {
    ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023
}

/// A value computed in f64 within `err` of the exact value it stands for.
#[derive(Clone, Copy, Debug)]
struct Approx {
    v: f64,
    err: f64,
}

impl Approx {
    fn exact(v: f64) -> Approx {
        Approx { v, err: 0.0 }
    }

    /// |ãb̃ − ab| ≤ |ã|·δb + |b̃|·δa + δa·δb, before the product's own rounding.
    fn product_err(a: Approx, b: Approx) -> f64 {
        a.v.abs() * b.err + b.v.abs() * a.err + a.err * b.err
    }

    /// a − b of two exact values: one rounding.
    fn difference(a: f64, b: f64) -> Approx {
        let v = a - b;
        Approx {
            v,
            err: F64_UNIT * v.abs(),
        }
    }
}

/// a × b in f64: per component two products and a difference, each rounded (at most 3
/// roundings of the terms' magnitudes, bounded by 4u), plus the operands' errors carried.
fn cross(a: [Approx; 3], b: [Approx; 3]) -> [Approx; 3] {
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let (x, y) = (a[j].v * b[k].v, a[k].v * b[j].v);
        Approx {
            v: x - y,
            err: Approx::product_err(a[j], b[k])
                + Approx::product_err(a[k], b[j])
                + 4.0 * F64_UNIT * (x.abs() + y.abs()),
        }
    })
}

/// a·b in f64: three products and two sums (at most 5 roundings of the terms' magnitudes,
/// bounded by 6u), plus the operands' errors carried.
fn dot_f64(a: [Approx; 3], b: [Approx; 3]) -> Approx {
    let p: [f64; 3] = std::array::from_fn(|k| a[k].v * b[k].v);
    Approx {
        v: (p[0] + p[1]) + p[2],
        err: (0..3).map(|k| Approx::product_err(a[k], b[k])).sum::<f64>()
            + 6.0 * F64_UNIT * p.iter().map(|x| x.abs()).sum::<f64>(),
    }
}

/// N values as the filter stores them: W-bit signed mantissas on one grid 2^`lsb`, the
/// block exponent `lsb` + W − 1 bounding every component (|x| < 2^E), each mantissa times
/// 2^`lsb` within `delta` of the exact value.
#[derive(Clone, Copy, Debug)]
struct Block<const N: usize> {
    m: [i64; N],
    lsb: i32,
    delta: f64,
    width: u32,
}

impl<const N: usize> Block<N> {
    /// Truncated toward zero onto the grid of the smallest E with every |v| < 2^E; `None`
    /// if E leaves [`EXP_RANGE`] or a value is not finite. A zero vector has all mantissas 0
    /// and E = [`EXP_RANGE`]'s low end.
    fn new(v: [Approx; N], width: u32) -> Option<Block<N>> {
        if v.iter().any(|x| !x.v.is_finite() || !x.err.is_finite()) {
            return None;
        }
        let top = v.iter().map(|x| x.v.abs()).fold(0.0, f64::max);
        let e = if top == 0.0 {
            *EXP_RANGE.start()
        } else {
            // The smallest E with top < 2^E.
            exponent(top) + 1
        };
        if !EXP_RANGE.contains(&e) {
            return None;
        }
        let lsb = e - (width as i32 - 1);
        let step = 2f64.powi(lsb);
        let m = v.map(|x| (x.v / step).trunc() as i64);
        let err = v.iter().map(|x| x.err).fold(0.0, f64::max);
        Some(Block {
            m,
            lsb,
            delta: step + err,
            width,
        })
    }

    /// The bound 2^E of every component.
    fn top(&self) -> f64 {
        2f64.powi(self.lsb + self.width as i32 - 1)
    }

    fn value(&self, k: usize) -> f64 {
        self.m[k] as f64 * 2f64.powi(self.lsb)
    }
}

/// Σ ã_k·b̃_k, exact in integers (a + b + 1 bits for a- and b-bit mantissas), within
/// Σ_k (2^Ea·δb + 2^Eb·δa + δa·δb) of the exact Σ a_k·b_k: the bound from block exponents,
/// which is what a hardware margin knows.
fn dot(a: &Block<3>, b: &Block<3>) -> Value {
    let sum: i128 = (0..3).map(|k| a.m[k] as i128 * b.m[k] as i128).sum();
    let fx = Fx::new(sum, a.lsb + b.lsb);
    // Above 53 bits (W > 19 on the t test's wide vectors) f64 rounds the value once.
    let err = 3.0 * (a.top() * b.delta + b.top() * a.delta + a.delta * b.delta)
        + F64_UNIT * fx.to_f64().abs();
    Value {
        fx,
        bits: a.width + b.width + 1,
        v: fx.to_f64(),
        err,
        parts: [err, 0.0, 0.0],
    }
}

/// A value of the datapath: `fx` on its grid in `bits` two's-complement bits (`v` its f64),
/// within `err` of the exact one; `parts` are the terms of `err` as a hardware margin
/// network adds them (each dot's bound, the alignment's unit).
#[derive(Clone, Copy, Debug)]
struct Value {
    fx: Fx,
    bits: u32,
    v: f64,
    err: f64,
    parts: [f64; 3],
}

/// x + y of two values on their grids as a hardware adder takes them ([`align_add`]),
/// within one unit of the coarser grid more.
fn combine(x: Value, y: Value) -> Value {
    let (fx, bits) = align_add((x.fx, x.bits), (y.fx, y.bits));
    let v = fx.to_f64();
    let unit = 2f64.powi(fx.e) + F64_UNIT * v.abs();
    Value {
        fx,
        bits,
        v,
        err: x.err + y.err + unit,
        parts: [x.err, y.err, unit],
    }
}

/// The sum of two N-bit two's-complement values a·2^ea and b·2^eb on the coarser grid: the
/// finer shifted right arithmetically by the exponent difference, at most N − 1 (beyond, it
/// is its sign, 0 or −1, either way), so the sum is floor-truncated, below the exact one by
/// less than one unit; N + 1 bits, N the wider operand's width.
pub fn align_add((a, a_bits): (Fx, u32), (b, b_bits): (Fx, u32)) -> (Fx, u32) {
    let n = a_bits.max(b_bits);
    let (coarse, fine) = if a.e >= b.e { (a, b) } else { (b, a) };
    let shift = (coarse.e - fine.e).min(n as i32 - 1);
    (Fx::new(coarse.m + (fine.m >> shift), coarse.e), n + 1)
}

/// What the filter holds of a ray.
struct Ray {
    dir: Block<3>,
    moment: Block<3>,
    orig: Block<3>,
}

/// What the filter holds of a triangle.
struct Triangle {
    n: Block<3>,
    e1: Block<3>,
    e2: Block<3>,
    v0_e1: Block<3>,
    v0_e2: Block<3>,
    /// e3 = v2 − v1 and v1 × e3: the third edge's value N_w = w·det (the sign decisions).
    e3: Block<3>,
    v1_e3: Block<3>,
    /// v0·n.
    offset: Block<1>,
    /// The bound 2^E of v0's components (for the fallback's |s|).
    v0_top: f64,
}

fn exact3(v: [f64; 3]) -> [Approx; 3] {
    v.map(Approx::exact)
}

impl Ray {
    fn new(orig: [f64; 3], dir: [f64; 3], width: u32) -> Option<Ray> {
        Some(Ray {
            dir: Block::new(exact3(dir), width)?,
            moment: Block::new(cross(exact3(orig), exact3(dir)), width)?,
            orig: Block::new(exact3(orig), wide(width))?,
        })
    }
}

impl Triangle {
    /// n takes [`wide`] bits, as orig does, and v0·n [`offset_bits`], the width of their
    /// products: it is compared with orig·n, and the two cancel when the ray starts near the
    /// triangle's plane.
    fn new(v0: [f64; 3], v1: [f64; 3], v2: [f64; 3], width: u32) -> Option<Triangle> {
        let e1: [Approx; 3] = std::array::from_fn(|k| Approx::difference(v1[k], v0[k]));
        let e2: [Approx; 3] = std::array::from_fn(|k| Approx::difference(v2[k], v0[k]));
        let e3: [Approx; 3] = std::array::from_fn(|k| Approx::difference(v2[k], v1[k]));
        let n = cross(e1, e2);
        let v0_block = Block::new(exact3(v0), width)?;
        Some(Triangle {
            n: Block::new(n, wide(width))?,
            e1: Block::new(e1, width)?,
            e2: Block::new(e2, width)?,
            v0_e1: Block::new(cross(exact3(v0), e1), width)?,
            v0_e2: Block::new(cross(exact3(v0), e2), width)?,
            e3: Block::new(e3, width)?,
            v1_e3: Block::new(cross(exact3(v1), e3), width)?,
            offset: Block::new([dot_f64(exact3(v0), n)], offset_bits(width))?,
            v0_top: v0_block.top(),
        })
    }
}

/// A bound on every |s_k| = |orig_k − v0_k| as the coarse subtraction gives it at its
/// worst ([`S_BOUND_BITS`]): |s| plus twice its truncations' 2^(E − S_BOUND_BITS + 2).
fn s_top(orig: [f64; 3], v0: [f64; 3], ray: &Ray, tri: &Triangle) -> f64 {
    let cut = ray.orig.top().max(tri.v0_top) * 2f64.powi(2 - S_BOUND_BITS);
    let s = (0..3).map(|k| (orig[k] - v0[k]).abs()).fold(0.0, f64::max);
    s * (1.0 + f64::EPSILON) + 2.0 * cut
}

/// The filter's values and the fallback's error bounds of one query: det = −dir·n and
/// the numerators, N_w = w·det = −(e3·m + dir·(v1 × e3)) beside them.
struct Values {
    det: Value,
    nu: Value,
    nv: Value,
    nw: Value,
    nt: Value,
    det_b: Bounded,
    num_b: [Bounded; 3],
}

/// The smallest power of two ≥ x (0 stays 0): a margin as a leading-one position.
fn up2(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let p = 2f64.powi(exponent(x));
    if p == x {
        x
    } else {
        2.0 * p
    }
}

/// A bound of a sum as a hardware margin network forms it: each term and each partial sum
/// rounded up to a float of [`HW_BOUND_BITS`] fraction bits (the division-free filter's
/// coarse grid), so a margin is a short float compared with a value's top bits.
fn coarse_sum(terms: &[f64]) -> f64 {
    let up = |x: f64| round_up_to_bits(x, HW_BOUND_BITS);
    terms.iter().fold(0.0, |acc, &t| up(acc + up(t)))
}

/// The datapath's values from the blocks: dir·n (det = −dir·n), N_u, e1·m + dir·(v0 × e1)
/// (N_v is its negative), e3·m + dir·(v1 × e3) (N_w is its negative), N_t.
fn values_of(ray: &Ray, tri: &Triangle) -> [Value; 5] {
    // A value a·m + dir·b of an edge vector a and its moment b.
    let edge = |a: &Block<3>, b: &Block<3>| combine(dot(a, &ray.moment), dot(&ray.dir, b));
    let offset = Value {
        fx: Fx::new(-(tri.offset.m[0] as i128), tri.offset.lsb),
        bits: tri.offset.width,
        v: -tri.offset.value(0),
        err: tri.offset.delta,
        parts: [tri.offset.delta, 0.0, 0.0],
    };
    [
        dot(&ray.dir, &tri.n),
        edge(&tri.e2, &tri.v0_e2),
        edge(&tri.e1, &tri.v0_e1),
        edge(&tri.e3, &tri.v1_e3),
        combine(dot(&ray.orig, &tri.n), offset),
    ]
}

/// A stored block as hardware reads it: the mantissas and the exponent of their last bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockBits<const N: usize> {
    pub m: [i64; N],
    pub lsb: i32,
}

impl<const N: usize> From<&Block<N>> for BlockBits<N> {
    fn from(b: &Block<N>) -> BlockBits<N> {
        BlockBits { m: b.m, lsb: b.lsb }
    }
}

/// What the datapath reads for one test: the ray's blocks (dir, m = orig × dir at W bits,
/// orig at W + [`T_EXTRA_BITS`]) and the triangle's (n at W + [`T_EXTRA_BITS`], the edge
/// vectors and their moments at W bits, −v0·n at 2(W + [`T_EXTRA_BITS`]) − 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Operands {
    pub dir: BlockBits<3>,
    pub moment: BlockBits<3>,
    pub orig: BlockBits<3>,
    pub n: BlockBits<3>,
    /// e1, e2, e3.
    pub edges: [BlockBits<3>; 3],
    /// v0 × e1, v0 × e2, v1 × e3.
    pub moments: [BlockBits<3>; 3],
    /// −v0·n (stored negated: the datapath adds it).
    pub offset: BlockBits<1>,
}

/// The ray's and the triangle's blocks of `q`, beside its coordinates (orig, dir, v0, v1,
/// v2); `None` for a non-finite coordinate or a block exponent outside [`EXP_RANGE`] (the
/// filter forwards such a query).
fn blocks(q: &MtQuery, width: u32) -> Option<([[f64; 3]; 5], Ray, Triangle)> {
    let given = coords(q);
    if given.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let [orig, dir, v0, v1, v2] = given;
    Some((
        given,
        Ray::new(orig, dir, width)?,
        Triangle::new(v0, v1, v2, width)?,
    ))
}

/// The Plücker datapath of a `bfpW` filter, bit for bit what hardware computes: the
/// operands of `q` and the five values ([`values_of`]: dir·n, N_u, −N_v, −N_w, N_t), each an
/// exact integer on its grid; `None` where the filter forwards before any arithmetic (a
/// non-finite coordinate, a block exponent outside [`EXP_RANGE`]).
pub fn datapath(q: &MtQuery, width: u32) -> Option<(Operands, [Fx; 5])> {
    let (_, ray, tri) = blocks(q, width)?;
    let operands = Operands {
        dir: (&ray.dir).into(),
        moment: (&ray.moment).into(),
        orig: (&ray.orig).into(),
        n: (&tri.n).into(),
        edges: [&tri.e1, &tri.e2, &tri.e3].map(BlockBits::from),
        moments: [&tri.v0_e1, &tri.v0_e2, &tri.v1_e3].map(BlockBits::from),
        offset: BlockBits {
            m: [-tri.offset.m[0]],
            lsb: tri.offset.lsb,
        },
    };
    Some((operands, values_of(&ray, &tri).map(|v| v.fx)))
}

impl Filter {
    /// [`Filter::decide`] for [`super::FilterKind::Plucker`]: det and the numerators from
    /// the blocks (the module's identities), each within its dots' bounds, the alignment's
    /// unit and the fallback's error bound evaluated on the blocks' exponent bounds (|dir_k|
    /// ≤ 2^E_dir, |e1_k| ≤ 2^E_e1, |s_k| ≤ [`s_top`]), then `decisions`.
    pub(super) fn decide_plucker(
        &self,
        q: &MtQuery,
        margin_scale: f64,
        decisions: PluckerDecisions,
    ) -> Option<MtResult> {
        let FilterFormat::Bfp(width) = self.pair.filter else {
            unreachable!("Filter::new pairs the plucker kind with a bfpW filter")
        };
        let x = self.plucker_values(q, width)?;
        match decisions {
            PluckerDecisions::Linear => {
                let margin = |a: Value, b: Bounded| (a.err + b.err) * margin_scale * F64_SLACK;
                self.decide_numerators(
                    q,
                    -x.det.v,
                    margin(x.det, x.det_b),
                    [x.nu.v, -x.nv.v, x.nt.v],
                    [
                        margin(x.nu, x.num_b[0]),
                        margin(x.nv, x.num_b[1]),
                        margin(x.nt, x.num_b[2]),
                    ],
                )
            }
            PluckerDecisions::Signs => self.decide_signs(q, &x, margin_scale),
        }
    }

    fn plucker_values(&self, q: &MtQuery, width: u32) -> Option<Values> {
        let ([orig, _, v0, _, _], ray, tri) = blocks(q, width)?;
        let (det_b, num_b) = self.fallback_bounds(&ray, &tri, s_top(orig, v0, &ray, &tri))?;
        let [det, nu, nv, nw, nt] = values_of(&ray, &tri);
        Some(Values {
            det,
            nu,
            nv,
            nw,
            nt,
            det_b,
            num_b,
        })
    }

    /// The sign decisions ([`PluckerDecisions::Signs`]): every margin a short float
    /// ([`coarse_sum`]), every test the sign of a value whose magnitude exceeds its margin
    /// (a comparison of its top bits), a value's magnitude in a margin its leading one
    /// (up2), one product for t_min > 0. With σ = sign(D), D = −det_A, n_x = σ·N_x, M_x the
    /// margins (filter plus fallback; N_w's: its own, det's filter error and whole margin,
    /// the fallback's of N_u and N_v, and the fallback's quotient roundings; derived in
    /// docs/precision.md, "The Plücker filter"), and |D| ≥ 2M_D (so |D|/2 ≤ L ≤ H ≤ 2|D|,
    /// else forward):
    /// - up2(|D|) + M_D < eps: the parallel test fires;
    /// - no reciprocal overflows or flushes and no quotient of u, v, t overflows (exponent
    ///   comparisons against |D|), else forward;
    /// - u < 0: n_u < −M_u and |n_u| > 16λ·up2(|D|) (not flushed to −0); v likewise;
    /// - u + v > 1: n_w < −M_w (u > 1 is left to v and w: v + w = 1 − u);
    /// - t ≤ t_min: n_t + M_t < τ·(|D| − M_D) for τ = t_min − λ ≥ 0 (one product), else
    ///   n_t + M_t < 2τ·up2(|D|) (for t_min = 0 a sign and an exponent comparison).
    fn decide_signs(&self, q: &MtQuery, x: &Values, margin_scale: f64) -> Option<MtResult> {
        let miss = Some(MtResult::default());
        let Rounding { unit: u, tiny, max } = self.b;
        let margin = |terms: &[f64]| coarse_sum(terms) * margin_scale * F64_SLACK;
        let d = -x.det.v;
        // Each margin adds its value's parts and the fallback's bound, in this order.
        let of = |x: &Value, b: &Bounded| margin(&[x.parts[0], x.parts[1], x.parts[2], b.err]);
        let m_d = of(&x.det, &x.det_b);
        let (dd, ud) = (d.abs(), up2(d.abs()));
        if ud + m_d < self.eps_b {
            return miss;
        }
        if dd < 2.0 * m_d {
            return None;
        }
        let sigma = d.signum();
        let [nu, nv, nw, nt] = [x.nu.v, -x.nv.v, -x.nw.v, x.nt.v].map(|v| sigma * v);
        let m_u = of(&x.nu, &x.num_b[0]);
        let m_v = of(&x.nv, &x.num_b[1]);
        let m_t = of(&x.nt, &x.num_b[2]);
        // |n| + M ≤ 2·max(up2(|n|), M): no reciprocal overflows or flushes, no quotient
        // overflows.
        let reach = |n: f64, m: f64| 2.0 * up2(n.abs()).max(m);
        let in_range = 4.0 < dd * max
            && 4.0 * tiny * ud < 1.0
            && [(nu, m_u), (nv, m_v), (nt, m_t)]
                .iter()
                .all(|&(n, m)| reach(n, m) < dd * max / 8.0);
        if !in_range {
            return None;
        }
        let below_zero = |n: f64, m: f64| n < -m && -n > 16.0 * tiny * ud;
        let m_w = margin(&[
            x.nw.parts[0],
            x.nw.parts[1],
            x.nw.parts[2],
            x.det.err,
            m_d,
            x.num_b[0].err,
            x.num_b[1].err,
            3.0 * u * (reach(nu, m_u) + reach(nv, m_v)),
            2.0 * ud * (u + 4.0 * tiny),
        ]);
        let t_min = self.fallback_t_min(q);
        let tau = t_min - tiny;
        let m_tq = margin(&[m_t, 3.0 * u * reach(nt, m_t)]);
        let t_below = t_min.is_finite()
            && certainly_below(
                nt + m_tq,
                tau * if tau >= 0.0 { dd - m_d } else { 2.0 * ud },
            );
        let certain = below_zero(nu, m_u) || below_zero(nv, m_v) || nw < -m_w || t_below;
        if certain {
            miss
        } else {
            None
        }
    }

    /// The fallback's error bounds of det and the numerators from the blocks' exponent
    /// bounds and [`s_top`]: it holds dir as given, and e1, e2, s as one rounding of their
    /// exact values.
    fn fallback_bounds(
        &self,
        ray: &Ray,
        tri: &Triangle,
        s_top: f64,
    ) -> Option<(Bounded, [Bounded; 3])> {
        let c = Ctx::exact(self.b);
        let vector = |mag: f64, rounded: bool| -> BV {
            let err = if rounded { c.error(mag) } else { 0.0 };
            [c.bounded(mag, err); 3]
        };
        product_bounds(
            [
                vector(ray.dir.top(), false),
                vector(tri.e1.top(), true),
                vector(tri.e2.top(), true),
                vector(s_top, true),
            ],
            &[],
            &c,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            1 => Just(0.0),
            10 => (-1000.0f32..1000.0).prop_map(f64::from),
            3 => (-1e-3f32..1e-3).prop_map(f64::from),
        ]
    }

    fn vector() -> impl Strategy<Value = [f64; 3]> {
        proptest::array::uniform3(coordinate())
    }

    /// |a − b| ≤ err, checked in exact rational arithmetic of f64 pairs: a and b are sums
    /// of f64 products, compared here through their f64 difference with its own rounding.
    fn within(a: f64, b: f64, err: f64) -> bool {
        (a - b).abs() <= err + (a.abs() + b.abs()) * f64::EPSILON
    }

    /// An exact triple product from f32-sized inputs: products of two f32s are exact in
    /// f64; the third factor is an f64 difference of f32s, exact for these magnitudes.
    fn cross_exact(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            a[j] * b[k] - a[k] * b[j]
        })
    }

    proptest! {
        /// A block's mantissas fit W signed bits, every component is below 2^E, E is the
        /// smallest such, and each mantissa is within one step (plus the tracked error).
        #[test]
        fn blocks_truncate_within_their_delta(v in vector(), w in 8u32..=24) {
            let b = Block::new(exact3(v), w).unwrap();
            let step = 2f64.powi(b.lsb);
            for (k, x) in v.iter().enumerate() {
                prop_assert!(b.m[k].unsigned_abs() < 1 << (w - 1));
                prop_assert!(x.abs() < b.top());
                prop_assert!((x - b.value(k)).abs() < step);
                prop_assert!(b.value(k).abs() <= x.abs());
            }
            prop_assert_eq!(b.delta, step);
            if v.iter().any(|x| *x != 0.0) {
                prop_assert!(v.iter().any(|x| x.abs() >= b.top() / 2.0));
            }
        }

        /// The alignment floors: the sum on the coarser grid is at most the exact sum and
        /// less than one unit below it, in N + 1 bits.
        #[test]
        fn align_add_floors_onto_the_coarser_grid(
            a in -(1i128 << 36)..(1i128 << 36), b in -(1i128 << 36)..(1i128 << 36),
            ea in -40i32..40, eb in -40i32..40,
        ) {
            let (sum, bits) = align_add((Fx::new(a, ea), 37), (Fx::new(b, eb), 37));
            prop_assert_eq!(bits, 38);
            prop_assert_eq!(sum.e, ea.max(eb));
            prop_assert!(sum.m >= -(1i128 << 37) && sum.m < 1i128 << 37);
            // Everything on the grid 2^(min − 0): exact integers.
            let low = ea.min(eb);
            let exact = (a << (ea - low)) + (b << (eb - low));
            let got = sum.m << (sum.e - low);
            prop_assert!(got <= exact && exact - got < 1i128 << (sum.e - low), "{} {}", got, exact);
        }

        /// The identities and the dot bound: det and N_u from the blocks are within their
        /// bounds of the same quantities computed the Möller-Trumbore way in f64 (exact
        /// within f64's few roundings for these f32-sized inputs).
        #[test]
        fn plucker_numerators_are_within_their_bounds(
            orig in vector(), dir in vector(), v0 in vector(), v1 in vector(), v2 in vector(),
            w in 8u32..=24,
        ) {
            let ray = Ray::new(orig, dir, w).unwrap();
            let tri = Triangle::new(v0, v1, v2, w).unwrap();
            let sub = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| a[k] - b[k]) };
            let dotf = |a: [f64; 3], b: [f64; 3]| (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
            let (e1, e2, s) = (sub(v1, v0), sub(v2, v0), sub(orig, v0));
            let p = cross_exact(dir, e2);
            let want_det = dotf(e1, p);
            let want_nu = dotf(s, p);
            // f64's own error of the reference: products of terms up to 2^33.
            let slack = 1e-12 * (1.0 + want_det.abs() + want_nu.abs())
                + 1e-15 * dotf(s.map(f64::abs), p.map(f64::abs)) * 16.0
                + 1e-15 * dotf(e1.map(f64::abs), p.map(f64::abs)) * 16.0;
            let [det, nu, nv, nw, nt] = values_of(&ray, &tri);
            prop_assert!(within(-det.v, want_det, det.err + slack), "det {} {} {}", -det.v, want_det, det.err);
            prop_assert!(within(nu.v, want_nu, nu.err + slack), "nu {} {} {}", nu.v, want_nu, nu.err);
            let q = cross_exact(s, e1);
            let (want_nv, want_nt) = (dotf(dir, q), dotf(e2, q));
            let slack = slack + 1e-15 * 16.0 * (dotf(dir.map(f64::abs), q.map(f64::abs))
                + dotf(e2.map(f64::abs), q.map(f64::abs)));
            prop_assert!(within(-nv.v, want_nv, nv.err + slack), "nv {} {} {}", -nv.v, want_nv, nv.err);
            prop_assert!(within(nt.v, want_nt, nt.err + slack), "nt {} {} {}", nt.v, want_nt, nt.err);
            // w·det = det − N_u − N_v = −(e3·m + dir·(v1 × e3)).
            let want_nw = want_det - want_nu - want_nv;
            prop_assert!(within(-nw.v, want_nw, nw.err + 3.0 * slack), "nw {} {} {}", -nw.v, want_nw, nw.err);
        }
    }
}
