//! The edge test of a Möller-Trumbore lane: exact comparisons, or comparisons widened by a
//! running bound on the rounding error of u, v and u + v (docs/precision.md, "The edge test").
//!
//! Two triangles sharing an edge share its converted vertices in any format, so in exact
//! arithmetic on the converted inputs a ray through the edge hits at least one of them. The
//! lane's roundings move u and v of each triangle independently, and in a narrow format a ray
//! near the edge can miss both (a crack: a speckle of the background). The conservative test
//! accepts whenever the computed value is within its error bound of the edge, so it accepts
//! every query the exact arithmetic on the converted inputs accepts, and the crack closes.
//!
//! The bound is what a hardware lane can evaluate beside its datapath: a running error
//! analysis (Higham, *Accuracy and Stability of Numerical Algorithms*, §3.3) from the
//! datapath's own values, in a short float of [`HW_BOUND_BITS`] fraction bits with every
//! result rounded up (small multipliers and adders, no division).

use serde::{Deserialize, Serialize};

use crate::format::Format;
use crate::precision::rounding_error;

/// Which edge test a lane applies to u and v.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Edges {
    /// `u ≥ 0, u ≤ 1, v ≥ 0, u + v ≤ 1` on the computed values: the hardware lanes' test.
    #[default]
    Exact,
    /// Each comparison widened by the running bound on the computed value's error
    /// ([`tolerances`]); model-only so far.
    Conservative,
}

impl Edges {
    pub const ALL: [Edges; 2] = [Edges::Exact, Edges::Conservative];

    pub fn name(self) -> &'static str {
        match self {
            Edges::Exact => "exact",
            Edges::Conservative => "conservative",
        }
    }
}

named_choice!(Edges, "edge test");

/// The largest error of one rounding in a format.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rounding {
    /// Round to nearest with subnormals flushed: a nonzero result is within half an ulp of
    /// the exact one, which is at most `unit`·|exact|; a result of 0 may be a flushed value
    /// below `tiny`, the smallest normal.
    Float { unit: f64, tiny: f64 },
    /// Sums and differences exact (without overflow); products and reciprocals quantised by
    /// at most `step`; magnitudes beyond `max` wrap or saturate.
    Fixed { step: f64, max: f64 },
}

/// Which kind of operation rounded a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Sum,
    Product,
}

impl Rounding {
    pub fn of(format: &Format) -> Rounding {
        let error = rounding_error(format, 0);
        match *format {
            Format::Float { exp, .. } => Rounding::Float {
                unit: error.unit_roundoff,
                tiny: 2f64.powi(2 - (1 << (exp - 1))),
            },
            Format::Fixed { int, frac, .. } => Rounding::Fixed {
                step: error.absolute,
                max: 2f64.powi(int as i32 - 1) - 2f64.powi(-(frac as i32)),
            },
        }
    }

    /// The largest magnitude the bound holds for (a float overflows to Inf, which the bound
    /// carries as not finite).
    fn max(&self) -> f64 {
        match *self {
            Rounding::Float { .. } => f64::INFINITY,
            Rounding::Fixed { max, .. } => max,
        }
    }

    /// The error of the value `c` an operation computed.
    fn of_result(&self, c: f64, op: Op) -> f64 {
        match *self {
            Rounding::Float { tiny, .. } if c == 0.0 => tiny,
            // Half an ulp: the unit roundoff times the power of two at or below |c|.
            Rounding::Float { unit, .. } => unit * f64::from_bits(c.to_bits() & EXPONENT_BITS),
            Rounding::Fixed { step, .. } => step * f64::from(op == Op::Product),
        }
    }

    /// The error of rounding an exact result of magnitude at most `x`, its computed value not
    /// at hand (a product or partial sum inside a cross or dot product).
    fn of_magnitude(&self, x: f64, op: Op) -> f64 {
        match *self {
            Rounding::Float { unit, tiny } => (unit * x).max(tiny),
            Rounding::Fixed { step, .. } => step * f64::from(op == Op::Product),
        }
    }
}

const EXPONENT_BITS: u64 = 0x7ff0_0000_0000_0000;

/// Fraction bits of the bound network's coarse float.
pub const HW_BOUND_BITS: u32 = 3;

/// `x` ≥ 0 rounded up to [`HW_BOUND_BITS`] fraction bits: the bound network's numbers.
fn up(x: f64) -> f64 {
    round_up_to_bits(x, HW_BOUND_BITS)
}

/// `x` ≥ 0 rounded up to a float of `bits` fraction bits (0 and non-finite values stay).
fn round_up_to_bits(x: f64, bits: u32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let dropped = f64::MANTISSA_DIGITS - 1 - bits;
    let raw = x.to_bits();
    let low = raw & ((1u64 << dropped) - 1);
    if low == 0 {
        x
    } else {
        // Carrying into the exponent field gives the next power of two, as it should.
        f64::from_bits((raw - low) + (1u64 << dropped))
    }
}

/// a + b of two bound values, rounded up: f64's sum, moved up one step if it was inexact
/// (`s − a` is exact for |a| ≥ |b|), so the result is the exact sum's rounding up.
fn add(a: f64, b: f64) -> f64 {
    let (a, b) = if a >= b { (a, b) } else { (b, a) };
    let s = a + b;
    up(if s - a == b { s } else { s.next_up() })
}

/// a·b of two bound values, rounded up (the product of two short significands is exact).
fn mul(a: f64, b: f64) -> f64 {
    up(a * b)
}

/// An intermediate for the bound: its computed magnitude (rounded up) and an upper bound on
/// its distance from the exact value on the converted inputs.
#[derive(Clone, Copy, Debug)]
struct Val {
    mag: f64,
    err: f64,
}

/// The datapath's values the bound reads (exact f64 values of the format's numbers), in
/// `crate::mt`'s operation order: `e1 = v1 − v0`, `e2 = v2 − v0`, `s = o − v0`,
/// `p = dir × e2`, `q = s × e1`, `det = e1·p`, `inv = 1/det`, `u = (s·p)·inv`,
/// `v = (dir·q)·inv`, `uv = u + v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneValues {
    pub dir: [f64; 3],
    pub e1: [f64; 3],
    pub e2: [f64; 3],
    pub s: [f64; 3],
    pub p: [f64; 3],
    pub q: [f64; 3],
    pub det: f64,
    /// s·p and dir·q.
    pub su: f64,
    pub dq: f64,
    pub inv: f64,
    pub u: f64,
    pub v: f64,
    pub uv: f64,
}

/// Upper bounds on |computed − exact| of u, v and u + v, the exact values computed on the
/// lane's converted inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    pub u: f64,
    pub v: f64,
    pub uv: f64,
}

impl Tolerances {
    /// The widened edge test: `u ≥ −w_u`, `u ≤ 1 + w_u`, `v ≥ −w_v`, `u + v ≤ 1 + w_uv`,
    /// compared exactly (`x − 1` is exact for x in [1/2, 2], and beyond it the comparison's
    /// outcome does not depend on the rounding).
    pub fn accept(&self, x: &LaneValues) -> bool {
        x.u >= -self.u && x.u - 1.0 <= self.u && x.v >= -self.v && x.uv - 1.0 <= self.uv
    }

    /// The same tolerances times `factor` (tests: a smaller bound must lose queries).
    pub fn scaled(&self, factor: f64) -> Tolerances {
        Tolerances {
            u: self.u * factor,
            v: self.v * factor,
            uv: self.uv * factor,
        }
    }
}

/// The running bound of the lane's u, v and u + v; `None` when it decides nothing: the
/// determinant's sign is not certain (its error bound above half its magnitude), or a value
/// is not finite (then the lane keeps the exact comparisons).
pub fn tolerances(r: &Rounding, x: &LaneValues) -> Option<Tolerances> {
    // The largest magnitude an intermediate can reach: beyond the format's range nothing holds.
    let reach = std::cell::Cell::new(0f64);
    let reached = |v: Val| {
        reach.set(reach.get().max(add(v.mag, v.err)));
        v
    };
    let mag = |c: f64| up(c.abs());
    // A difference of two converted inputs: one rounding of its computed value.
    let input_difference = |c: f64| Val {
        mag: mag(c),
        err: up(r.of_result(c, Op::Sum)),
    };
    // a·b rounded, its computed value not at hand:
    // |âb̂ − ab| ≤ |â|·err_b + (|b̂| + err_b)·err_a, plus the rounding of |âb̂|.
    let product = |a: Val, b: Val| {
        let exact = mul(a.mag, b.mag);
        let carried = add(mul(a.mag, b.err), mul(add(b.mag, b.err), a.err));
        let rounding = up(r.of_magnitude(exact, Op::Product));
        reached(Val {
            mag: add(exact, rounding),
            err: add(carried, rounding),
        })
    };
    // a ± b rounded, its computed value not at hand (a dot product's first sum).
    let partial_sum = |a: Val, b: Val| {
        let exact = add(a.mag, b.mag);
        let rounding = up(r.of_magnitude(exact, Op::Sum));
        reached(Val {
            mag: add(exact, rounding),
            err: add(add(a.err, b.err), rounding),
        })
    };
    // a ± b rounded to the computed value c.
    let sum = |a: Val, b: Val, c: f64| {
        reached(Val {
            mag: mag(c),
            err: add(add(a.err, b.err), up(r.of_result(c, Op::Sum))),
        })
    };
    let exact = |c: f64| Val {
        mag: mag(c),
        err: 0.0,
    };
    let cross = |a: [Val; 3], b: [Val; 3], c: [f64; 3]| -> [Val; 3] {
        [
            sum(product(a[1], b[2]), product(a[2], b[1]), c[0]),
            sum(product(a[2], b[0]), product(a[0], b[2]), c[1]),
            sum(product(a[0], b[1]), product(a[1], b[0]), c[2]),
        ]
    };
    let dot = |a: [Val; 3], b: [Val; 3], c: f64| {
        sum(
            partial_sum(product(a[0], b[0]), product(a[1], b[1])),
            product(a[2], b[2]),
            c,
        )
    };
    let dir = x.dir.map(exact);
    let (e1, e2, s) = (
        x.e1.map(input_difference),
        x.e2.map(input_difference),
        x.s.map(input_difference),
    );
    let p = cross(dir, e2, x.p);
    let q = cross(s, e1, x.q);
    let det = dot(e1, p, x.det);
    let su = dot(s, p, x.su);
    let dq = dot(dir, q, x.dq);
    // inv = fl(1/det). With I ≥ 1/|det̂| (|inv| plus its rounding) and ρ = err_det·I ≤ 1/2,
    // |det| ≥ |det̂|(1 − ρ), so |1/det̂ − 1/det| ≤ err_det·I²·(1 + 2ρ): products only.
    let inv_rounding = up(r.of_result(x.inv, Op::Product));
    let big_i = add(mag(x.inv), inv_rounding);
    let rho = mul(det.err, big_i);
    // NaN (a non-finite value upstream) does not decide either.
    if 2.0 * rho > 1.0 || rho.is_nan() {
        return None;
    }
    let inv = Val {
        mag: mag(x.inv),
        err: add(mul(mul(rho, big_i), add(1.0, 2.0 * rho)), inv_rounding),
    };
    // u = fl(num·inv) with the computed u at hand: the product rule, then its rounding.
    let quotient = |num: Val, c: f64| {
        let carried = add(mul(num.mag, inv.err), mul(add(inv.mag, inv.err), num.err));
        reached(Val {
            mag: mul(num.mag, add(inv.mag, inv.err)),
            err: add(carried, up(r.of_result(c, Op::Product))),
        })
        .err
    };
    let (u, v) = (quotient(su, x.u), quotient(dq, x.v));
    let uv = add(add(u, v), up(r.of_result(x.uv, Op::Sum)));
    let t = Tolerances { u, v, uv };
    // Within the format's range (|1/det̂| included: the reciprocal did not overflow).
    let fits = reach.get() <= r.max() && x.det.abs() * r.max() >= 1.0;
    (fits && [u, v, uv].iter().all(|w| w.is_finite())).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lookup;

    #[test]
    fn rounding_up_keeps_four_significant_bits() {
        assert_eq!(up(1.0), 1.0);
        assert_eq!(up(1.0625), 1.125);
        assert_eq!(up(1.9), 2.0);
        assert_eq!(up(3.0 * 2f64.powi(-40)), 3.0 * 2f64.powi(-40));
        assert_eq!(
            add(1.0, 2f64.powi(-60)),
            1.125,
            "an inexact f64 sum still rounds up"
        );
        assert_eq!(add(1.0, 0.125), 1.125);
    }

    #[test]
    fn roundings_of_floats_and_fixed_formats() {
        let e5m14 = Rounding::of(&lookup("e5m14").unwrap());
        assert_eq!(
            e5m14,
            Rounding::Float {
                unit: 2f64.powi(-15),
                tiny: 2f64.powi(-14)
            }
        );
        // Half an ulp of 3 (binade [2, 4)) in 14 fraction bits.
        assert_eq!(e5m14.of_result(3.0, Op::Sum), 2f64.powi(-14));
        assert_eq!(e5m14.of_result(-3.0, Op::Product), 2f64.powi(-14));
        assert_eq!(e5m14.of_result(0.0, Op::Sum), 2f64.powi(-14));
        let fx = Rounding::of(&lookup("fx32_16").unwrap());
        assert_eq!(
            fx,
            Rounding::Fixed {
                step: 2f64.powi(-16),
                max: 32768.0 - 2f64.powi(-16)
            }
        );
        assert_eq!(fx.of_result(3.0, Op::Sum), 0.0);
        assert_eq!(fx.of_magnitude(3.0, Op::Product), 2f64.powi(-16));
    }

    proptest::proptest! {
        /// The coarse grid rounds up onto values of `bits` fraction bits, at most one
        /// grid step (2^(1-bits) relative) above, and leaves grid values alone.
        #[test]
        fn coarse_rounding_is_upward_onto_the_grid(x in 1e-300f64..1e300, bits in 0u32..8) {
            let up = round_up_to_bits(x, bits);
            proptest::prop_assert!(up >= x);
            proptest::prop_assert!(up <= x * (1.0 + 2f64.powi(1 - bits as i32)));
            let e = up.log2().floor() as i32;
            let steps = up / 2f64.powi(e - bits as i32);
            proptest::prop_assert!(steps == steps.trunc() && steps <= 2f64.powi(bits as i32 + 1));
            proptest::prop_assert_eq!(round_up_to_bits(up, bits), up);
        }
    }

    #[test]
    fn zero_infinity_and_grid_values_stay() {
        for x in [0.0, 1e-30, 0.3, 7.0, f64::INFINITY] {
            assert_eq!(up(x) == x, x == 0.0 || x.is_infinite() || x == 7.0);
        }
    }
}
