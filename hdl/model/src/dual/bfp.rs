//! The block-floating-point filter (docs/precision.md, "The block-floating-point filter"):
//! the bit-exact specification of a filter built from integer adders, DSP multipliers and
//! exponent adders. Step 1 ([`translate`]) moves the query to v0 = 0 in integers; step 2
//! ([`to_block`]) gives each of dir, e1, e2, s one block exponent and W-bit mantissas; step 3
//! computes det and the numerators exactly in integers; step 4 ([`margin`]) bounds the
//! filter's and the fp32 fallback's errors by a constant per width shifted by the three
//! block exponents; step 5 ([`Filter::decide_bfp`]) decides the fallback's tests by exact
//! integer comparisons, every rounding in the direction that keeps a decision certain.

use std::ops::RangeInclusive;

use sw_renderer::intersect::{MtQuery, MtResult};

use super::{Filter, FilterFormat, FP32_ROUNDING};
use crate::mt::DET_EPSILON;

/// The mantissa widths a `bfpW` filter may have: products of three mantissas stay well
/// inside the model's i128, and below 8 bits nothing is decided.
pub const WIDTHS: RangeInclusive<u32> = 8..=24;

/// Guard bits of the translation's alignment (step 1): exponents within this distance
/// subtract exactly.
pub const GUARD_BITS: i32 = 3;

/// The block exponents the bound covers: each vector's in [`EXP_MIN`, `EXP_MAX`], each
/// triple's sum at least [`SUM_MIN`]. Inside, the fp32 fallback neither overflows nor has
/// flush-to-zero errors above 2^-39 of 2^(sum); outside, the query is forwarded.
pub const EXP_MIN: i32 = -40;
pub const EXP_MAX: i32 = 40;
pub const SUM_MIN: i32 = -80;

/// An exact value m·2^e.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fx {
    pub m: i128,
    pub e: i32,
}

impl Fx {
    fn new(m: i128, e: i32) -> Fx {
        Fx { m, e }
    }

    /// The value, in f64 (for tests and reports; exact when m has at most 53 bits).
    pub fn to_f64(self) -> f64 {
        self.m as f64 * 2f64.powi(self.e)
    }

    /// m shifted left by `by` bits, if it fits.
    fn mantissa_at(self, e: i32) -> Option<i128> {
        let by = u32::try_from(self.e - e).ok()?;
        let room = if self.m < 0 {
            self.m.leading_ones()
        } else {
            self.m.leading_zeros()
        };
        (self.m == 0 || by < room).then(|| self.m << by)
    }

    /// Both mantissas at the smaller exponent; `None` if a shift would overflow.
    fn aligned(self, other: Fx) -> Option<(i128, i128, i32)> {
        let e = self.e.min(other.e);
        Some((self.mantissa_at(e)?, other.mantissa_at(e)?, e))
    }

    fn add(self, other: Fx) -> Option<Fx> {
        let (a, b, e) = self.aligned(other)?;
        Some(Fx::new(a.checked_add(b)?, e))
    }

    /// self < other, exactly, at any exponents: different signs or leading-bit positions
    /// decide alone, and equal leading-bit positions align without overflow.
    fn lt(self, other: Fx) -> bool {
        let (sa, sb) = (self.m.signum(), other.m.signum());
        if sa != sb || sa == 0 {
            return sa < sb;
        }
        let top = |x: Fx| x.e + (128 - x.m.unsigned_abs().leading_zeros()) as i32;
        let (ta, tb) = (top(self), top(other));
        if ta != tb {
            // The larger leading bit is the larger magnitude.
            return (ta < tb) == (sa > 0);
        }
        let (a, b, _) = self
            .aligned(other)
            .expect("equal leading bits align within i128");
        a < b
    }

    /// self·k·2^shift for a small integer k.
    fn times(self, k: i128, shift: i32) -> Option<Fx> {
        Some(Fx::new(self.m.checked_mul(k)?, self.e + shift))
    }
}

/// An fp32 number as the datapath reads it: signed significand and the exponent of its last
/// bit; subnormals flush to 0, which reads as 0·2^-150 (the exponent field 0), so a zero
/// never decides an alignment. `None` for ±Inf and NaN.
pub fn split(x: f32) -> Option<Fx> {
    if !x.is_finite() {
        return None;
    }
    let bits = x.to_bits();
    let field = ((bits >> 23) & 0xff) as i32;
    let significand = if field == 0 {
        0
    } else {
        i128::from((bits & 0x7f_ffff) | 0x80_0000)
    };
    let m = if x.is_sign_negative() {
        -significand
    } else {
        significand
    };
    Some(Fx::new(m, field - 150))
}

/// Step 1: a − b in integers. Both significands are aligned to the larger exponent with
/// [`GUARD_BITS`] guard bits, the smaller operand shifted right with its lost bits dropped
/// (an arithmetic shift: floor), then subtracted. Exact when the exponents differ by at
/// most [`GUARD_BITS`] (or one operand is 0); else the error is below one unit of the
/// result's last bit 2^e, and |a − b| ≥ 2^(e + 22 + GUARD_BITS), so the error is below
/// 2^-(22 + GUARD_BITS) of the result. `None` for a non-finite operand.
pub fn translate(a: f32, b: f32) -> Option<Fx> {
    let (a, b) = (split(a)?, split(b)?);
    let e = a.e.max(b.e) - GUARD_BITS;
    // A right shift beyond the significand leaves its sign only (0 or -1).
    let at = |x: Fx| match x.e - e {
        up @ 0.. => x.m << up,
        down => x.m >> (-down).min(64),
    };
    Some(Fx::new(at(a) - at(b), e))
}

/// Step 2: a vector in block floating point: component k is `m[k]`·2^(e − W + 1), and
/// every component of the value it came from lies in [−2^e, 2^e).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    pub m: [i128; 3],
    pub e: i32,
}

/// Step 2: the smallest block exponent e with every component in [−2^e, 2^e) (in hardware
/// the leading one of each component XOR its sign, then a 3-way max), then each component
/// shifted to W-bit two's-complement mantissas by an arithmetic right shift: truncation
/// towards −∞, error in [0, 2^(e − W + 1)). Truncation rather than rounding: no incrementer
/// and no carry out of the W bits (a rounded 2^e − ε would need W + 1); it doubles the
/// quantisation error, which the margin carries. `None` for the zero vector.
pub fn to_block(v: [Fx; 3], width: u32) -> Option<Block> {
    let e = v
        .iter()
        .filter(|x| x.m != 0)
        .map(|x| x.e + (128 - (x.m ^ (x.m >> 127)).leading_zeros()) as i32)
        .max()?;
    let lsb = e - (width as i32 - 1);
    let m = v.map(|x| match x.e - lsb {
        up @ 0.. => x.m << up,
        down => x.m >> (-down).min(127),
    });
    Some(Block { m, e })
}

fn cross(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: &[i128; 3], b: &[i128; 3]) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Extra mantissa bits of s = orig − v0: it spans the ray's whole distance to the
/// triangle, and a small component of it (a shadow ray's offset from the plane it leaves)
/// must survive beside a large one. W + 7 = 25 at W = 18: the DSP48E1's 25-bit port, so
/// s × e1 stays one DSP48E1 a product.
pub const S_EXTRA_BITS: u32 = 7;

/// The vectors of step 2, in the order of [`widths`]: dir, e1, e2, s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Vector {
    Dir,
    E1,
    E2,
    S,
}

/// The mantissa widths of dir, e1, e2 (W) and s (W + [`S_EXTRA_BITS`]).
pub fn widths(width: u32) -> [u32; 4] {
    [width, width, width, width + S_EXTRA_BITS]
}

/// Step 4: the margin of a triple product of three vectors (det = e1·(dir × e2),
/// N_u = s·(dir × e2), N_v = dir·(s × e1), N_t = e2·(s × e1)), in units of its last bit
/// 2^(E_a + E_b + E_c − Σ(W_i − 1)): ⌈K·2^Σ(W_i − 1)⌉ with
/// K = 3√3·(ε_a + ε_b + ε_c)(1 + τ)² (the filter: Hadamard's inequality on the telescoped
/// trilinear error) + 6γ₇(1 + τ)³ (the fp32 fallback: seven roundings on each of the six
/// terms) + 2^-39 (its flushes, inside the exponent range), where ε = 2^(1−W_i) for dir and
/// 2^(1−W_i) + τ for a translated vector, τ = 2^-(23 + GUARD_BITS). `margin_scale` = 1 is
/// the derived bound (tests shrink it).
fn margin(width: u32, triple: [Vector; 3], margin_scale: f64) -> i128 {
    let tau = 2f64.powi(-23 - GUARD_BITS);
    let w = widths(width);
    let bits = |v: Vector| w[v as usize] as i32 - 1;
    let eps = |v: Vector| 2f64.powi(-bits(v)) + if v == Vector::Dir { 0.0 } else { tau };
    let u = FP32_ROUNDING.unit;
    let gamma7 = 7.0 * u / (1.0 - 7.0 * u);
    let k = 3f64.powf(1.5) * triple.map(eps).iter().sum::<f64>() * (1.0 + tau).powi(2)
        + 6.0 * gamma7 * (1.0 + tau).powi(3)
        + 2f64.powi(-39);
    let lsb: i32 = triple.map(bits).iter().sum();
    // f64's own roundings (a few of 2^-53) are covered 10^4 times over before rounding up.
    (k * margin_scale * (1.0 + 1e-12) * 2f64.powi(lsb)).ceil() as i128
}

/// The fallback's t_min, moved down to τ' ≤ t_min − λ (λ = 2^-126, the fallback's smallest
/// normal): exact below 2^-102, else t_min − 1 ulp (one ulp ≥ λ there). `None` for a
/// non-finite t_min (never a certain miss by t).
fn t_min_below(t_min: f32) -> Option<Fx> {
    let t = split(t_min)?;
    Some(if t.e >= -126 {
        Fx::new(t.m - 1, t.e)
    } else {
        Fx::new((t.m << (t.e + 150)) - (1 << 24), -150)
    })
}

/// 2^24: the fallback's unit roundoff u = 2^-24 as an integer scale.
const U_INV: i128 = 1 << 24;

impl Filter {
    /// [`Filter::decide`] for [`super::FilterKind::Bfp`]: `decide_linear`'s tests (the
    /// table in docs/precision.md, "The division-free filter"), on exact integers: with
    /// σ = sign(det), n = σ·N, e the margins, L = |det| − e_D, H = |det| + e_D, and the
    /// fallback's u = 2^-24, λ = 2^-126:
    /// - |det| + e_D < eps (the fallback's parallel test fires);
    /// - otherwise only if |det| > e_D and nothing overflows or flushes (1 < L·max/2,
    ///   2λH < 1, |N| + e < L·max/4 for each numerator);
    /// - u < 0: n_u + e_u < 0 and 2λH < |n_u + e_u|(1 − u); v likewise;
    /// - u > 1: H(1 + 3u) < n_u − e_u;
    /// - u + v > 1: H(1 + 2u) < n_u + n_v − e_u − e_v − 3u(|n_u| + |n_v| + e_u + e_v)
    ///   (1 + 2u ≥ the derivation's 1 + u + 4λ);
    /// - t ≤ t_min: n_t + e_t + 3u(|n_t| + e_t) < τ'·(L if τ' ≥ 0 else H), τ' ≤ t_min − λ
    ///   ([`t_min_below`]; τ·M(τ) grows with τ, so a smaller τ is conservative).
    ///
    /// A sum or product that would overflow i128 leaves its test undecided (forwarded).
    pub(super) fn decide_bfp(&self, q: &MtQuery, margin_scale: f64) -> Option<MtResult> {
        let FilterFormat::Bfp(width) = self.pair.filter else {
            unreachable!("Filter::new pairs the bfp kind with a bfpW filter")
        };
        let moved = |p: &[f32; 3]| -> Option<[Fx; 3]> {
            Some([
                translate(p[0], q.v0[0])?,
                translate(p[1], q.v0[1])?,
                translate(p[2], q.v0[2])?,
            ])
        };
        let dir = [split(q.dir[0])?, split(q.dir[1])?, split(q.dir[2])?];
        let (e1, e2, s) = (moved(&q.v1)?, moved(&q.v2)?, moved(&q.orig)?);
        let w = widths(width);
        let [dir, e1, e2, s] = [
            to_block(dir, w[0])?,
            to_block(e1, w[1])?,
            to_block(e2, w[2])?,
            to_block(s, w[3])?,
        ];
        if [dir, e1, e2, s]
            .iter()
            .any(|b| !(EXP_MIN..=EXP_MAX).contains(&b.e))
        {
            return None;
        }
        // Step 3, exactly: p = dir × e2, q = s × e1, det = e1·p, N = (s·p, dir·q, e2·q);
        // each with its margin, both in units of its last bit.
        let (p, qv) = (cross(&dir.m, &e2.m), cross(&s.m, &e1.m));
        let block = |v: Vector| [dir, e1, e2, s][v as usize];
        let value = |m: i128, triple: [Vector; 3]| -> Option<(Fx, Fx)> {
            let sum: i32 = triple.map(|v| block(v).e).iter().sum();
            let lsb: i32 = triple.map(|v| w[v as usize] as i32 - 1).iter().sum();
            let units = margin(width, triple, margin_scale);
            (sum >= SUM_MIN).then_some((Fx::new(m, sum - lsb), Fx::new(units, sum - lsb)))
        };
        use Vector::{Dir, E1, E2, S};
        let (det, ed) = value(dot(&e1.m, &p), [E1, Dir, E2])?;
        let (nu, eu) = value(dot(&s.m, &p), [S, Dir, E2])?;
        let (nv, ev) = value(dot(&dir.m, &qv), [Dir, S, E1])?;
        let (nt, et) = value(dot(&e2.m, &qv), [E2, S, E1])?;
        let miss = Some(MtResult::default());
        let d_abs = Fx::new(det.m.abs(), det.e);
        let high = d_abs.add(ed)?;
        let eps = split(DET_EPSILON).expect("a finite constant");
        if high.lt(eps) {
            return miss;
        }
        let low = Fx::new(d_abs.m - ed.m, det.e);
        if low.m <= 0 {
            return None;
        }
        // No reciprocal overflows or flushes, no quotient overflows: max = (2^24 − 1)·2^104.
        let one = Fx::new(1, 0);
        let (half_max, quarter_max) = (low.times(U_INV - 1, 103)?, low.times(U_INV - 1, 102)?);
        let mut in_range = one.lt(half_max) && high.times(1, -125)?.lt(one);
        for (n, e) in [(nu, eu), (nv, ev), (nt, et)] {
            in_range = in_range && Fx::new(n.m.abs() + e.m, n.e).lt(quarter_max);
        }
        if !in_range {
            return None;
        }
        let sigma = det.m.signum();
        let [nu, nv, nt] = [nu, nv, nt].map(|n| Fx::new(sigma * n.m, n.e));
        let below_zero = |n: Fx, e: Fx| -> Option<bool> {
            let top = Fx::new(n.m + e.m, n.e);
            Some(top.m < 0 && high.times(1, -125)?.lt(top.times(-(U_INV - 1), -24)?))
        };
        let above_one = |n: Fx, e: Fx| -> Option<bool> {
            Some(high.times(U_INV + 3, -24)?.lt(Fx::new(n.m - e.m, n.e)))
        };
        // (n − e) − 3u(|n| + e), scaled by 2^24: a numerator's lowest value after rounding.
        let lowest = |n: Fx, e: Fx| -> Option<Fx> {
            let m = (n.m - e.m).checked_mul(U_INV)? - 3 * (n.m.abs() + e.m);
            Some(Fx::new(m, n.e - 24))
        };
        let uv_above_one = || -> Option<bool> {
            let uv_low = lowest(nu, eu)?.add(lowest(nv, ev)?)?;
            Some(high.times(U_INV + 2, -24)?.lt(uv_low))
        };
        let t_below = || -> Option<bool> {
            let tau = t_min_below(q.t_min)?;
            let t_high = Fx::new(
                (nt.m + et.m).checked_mul(U_INV)? + 3 * (nt.m.abs() + et.m),
                nt.e - 24,
            );
            let bound = if tau.m >= 0 { low } else { high };
            Some(t_high.lt(Fx::new(tau.m.checked_mul(bound.m)?, tau.e + bound.e)))
        };
        let certain = [
            below_zero(nu, eu),
            above_one(nu, eu),
            below_zero(nv, ev),
            uv_above_one(),
            t_below(),
        ]
        .contains(&Some(true));
        if certain {
            miss
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// An fp32 number of either sign with exponent in [lo, hi), or ±0.
    fn float(lo: i32, hi: i32) -> impl Strategy<Value = f32> {
        prop_oneof![
            1 => Just(0.0f32),
            20 => (any::<bool>(), lo..hi, 0u32..1 << 23).prop_map(|(neg, e, frac)| {
                let x = f32::from_bits(((e + 127) as u32) << 23 | frac);
                if neg { -x } else { x }
            }),
        ]
    }

    proptest! {
        /// Step 1 against f64 (exact for these exponents): exact within GUARD_BITS of
        /// exponent, else off by less than one unit of the result's last bit, which is
        /// below 2^-(22 + GUARD_BITS) of the result.
        #[test]
        fn translation_is_exact_or_within_one_unit(a in float(-20, 20), b in float(-20, 20)) {
            let d = translate(a, b).unwrap();
            let want = f64::from(a) - f64::from(b);
            let err = (d.to_f64() - want).abs();
            let (ea, eb) = (split(a).unwrap().e, split(b).unwrap().e);
            if a == 0.0 || b == 0.0 || (ea - eb).abs() <= GUARD_BITS {
                prop_assert_eq!(err, 0.0);
            } else {
                prop_assert!(err < 2f64.powi(d.e));
                prop_assert!(err <= want.abs() * 2f64.powi(-22 - GUARD_BITS));
            }
        }

        /// Step 2: the block exponent is the smallest with every component in [−2^e, 2^e),
        /// the mantissas fit W signed bits, and the truncation error is in [0, 2^(e−W+1)).
        #[test]
        fn blocks_are_minimal_and_truncate_within_one_step(
            v in proptest::array::uniform3(float(-30, 30)),
            w in 8u32..=24,
        ) {
            let x = v.map(|c| split(c).unwrap());
            let Some(b) = to_block(x, w) else {
                prop_assert!(v.iter().all(|c| *c == 0.0));
                return Ok(());
            };
            let top = 2f64.powi(b.e);
            let step = 2f64.powi(b.e - w as i32 + 1);
            for (c, m) in v.iter().zip(b.m) {
                let c = f64::from(*c);
                prop_assert!(-top <= c && c < top);
                prop_assert!(-(1i128 << (w - 1)) <= m && m < 1 << (w - 1));
                let err = c - m as f64 * step;
                prop_assert!((0.0..step).contains(&err), "{} {}", c, err);
            }
            // Minimal: some component needs e (it is outside [−2^(e−1), 2^(e−1))).
            prop_assert!(v.iter().any(|&c| f64::from(c) < -top / 2.0 || f64::from(c) >= top / 2.0));
        }

        /// Exact integer comparisons: `lt` and `add` agree with f64 where f64 is exact.
        #[test]
        fn scaled_integers_compare_and_add_exactly(
            a in -(1i128 << 40)..1 << 40, ea in -30i32..30,
            b in -(1i128 << 40)..1 << 40, eb in -30i32..30,
        ) {
            let (x, y) = (Fx::new(a, ea), Fx::new(b, eb));
            prop_assert_eq!(x.lt(y), x.to_f64() < y.to_f64());
            prop_assert_eq!(x.add(y).unwrap().to_f64(), x.to_f64() + y.to_f64());
        }
    }

    #[test]
    fn splits_flush_and_refuse_non_finite() {
        assert_eq!(split(1.0), Some(Fx::new(1 << 23, -23)));
        assert_eq!(split(-1.5), Some(Fx::new(-(3 << 22), -23)));
        assert_eq!(split(f32::MIN_POSITIVE / 2.0), Some(Fx::new(0, -150)));
        assert_eq!(split(-0.0), Some(Fx::new(0, -150)));
        for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            assert_eq!(split(x), None);
            assert_eq!(translate(x, 1.0), None);
        }
        // Far-apart exponents: the small operand is floored away, the result within 1 unit.
        let d = translate(1.0, 1e-20).unwrap();
        assert_eq!(d, Fx::new(1 << 26, -26));
        assert_eq!(translate(1.0, -1e-20).unwrap(), Fx::new((1 << 26) + 1, -26));
        assert_eq!(to_block([Fx::new(0, 3); 3], 16), None);
    }

    #[test]
    fn t_min_moves_down_by_at_least_the_smallest_normal() {
        let lambda = 2f64.powi(-126);
        for t in [0.0f32, 1e-35, -1e-35, 1e-31, 0.5, -2.0, 1e30] {
            let tau = t_min_below(t).unwrap().to_f64();
            assert!(tau <= f64::from(t) - lambda, "{t}: {tau}");
            assert!(
                tau >= f64::from(t) - f64::from(t).abs() * 1.2e-7 - lambda,
                "{t}"
            );
        }
        assert_eq!(t_min_below(f32::NAN), None);
    }

    #[test]
    fn margins_grow_as_the_width_shrinks() {
        use Vector::{Dir, E1, E2, S};
        // In units of 2^(sum of exponents): K, decreasing with W; s's extra bits make the
        // numerators' margins smaller than det's.
        let k = |w: u32, t: [Vector; 3]| {
            let lsb: i32 = t.map(|v| widths(w)[v as usize] as i32 - 1).iter().sum();
            margin(w, t, 1.0) as f64 * 2f64.powi(-lsb)
        };
        for w in 9..=24 {
            assert!(k(w, [E1, Dir, E2]) < k(w - 1, [E1, Dir, E2]));
            assert!(k(w, [S, Dir, E2]) < k(w, [E1, Dir, E2]));
        }
        // W = 18: det's 3√3·3·2^-17 ≈ 1.19e-4 plus the fallback's 6γ₇ ≈ 2.5e-6.
        assert!((1.21e-4..1.23e-4).contains(&k(18, [E1, Dir, E2])));
        assert!(margin(18, [E1, Dir, E2], 0.5) < margin(18, [E1, Dir, E2], 1.0));
    }
}
