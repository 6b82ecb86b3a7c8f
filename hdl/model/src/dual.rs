//! Dual precision (docs/precision.md, "Dual precision"): a narrow *filter* format decides
//! the Möller-Trumbore tests that are certainly misses; every other test goes to the
//! *fallback* format, whose answer is the answer. A test is a certain miss only if one of
//! the filter's compared values is beyond its threshold by more than a derived bound of
//! the filter's and the fallback's rounding errors ([`Filter::certain_miss`]), so every
//! hit, and every (hit, t, u, v) the renderer reads, is the fallback's bit for bit.

use std::fmt;
use std::str::FromStr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use sw_renderer::intersect::{Intersector, MtQuery, MtResult};
use sw_renderer::rays::EngineError;
use thiserror::Error;

use crate::mt::{mt_model, mt_traced, scale_query, DET_EPSILON};

pub mod bfp;
mod linear;
pub mod plucker;
pub mod signs;
use crate::{catalogue, lookup, Format, FormatError};

#[derive(Debug, Error, PartialEq, Eq)]
pub enum DualError {
    #[error("format pair `{0}`: expected FILTER/FALLBACK, two formats such as fp16/fp32")]
    Malformed(String),
    #[error("format pair `{pair}`: the {half} half: {source}")]
    Half {
        pair: String,
        half: &'static str,
        source: FormatError,
    },
    #[error("format pair `{0}`: both halves are the same format; use it alone")]
    Equal(String),
    #[error(
        "format pair `{pair}`: the filter {filter} is not narrower than the fallback {fallback} (it needs at most the fallback's exponent and fraction bits)"
    )]
    NotNarrower {
        pair: String,
        filter: String,
        fallback: String,
    },
    #[error(
        "format pair `{pair}`: {half} {format} is fixed point; the dual-precision bound covers float formats only"
    )]
    Fixed {
        pair: String,
        half: &'static str,
        format: String,
    },
    #[error(
        "format pair `{pair}`: block floating point `{filter}` needs a mantissa width of {min} to {max} bits, as in bfp18"
    )]
    BfpWidth {
        pair: String,
        filter: String,
        min: u32,
        max: u32,
    },
    #[error(
        "format pair `{pair}`: a block-floating-point filter needs a fallback that holds fp32 exactly (8 exponent and 23 fraction bits or more), not {fallback}"
    )]
    BfpFallback { pair: String, fallback: String },
    #[error("format pair `{pair}`: the {kind} filter needs {needs}")]
    Kind {
        pair: String,
        kind: FilterKind,
        needs: &'static str,
    },
    #[error(
        "format pair `{pair}`: a block-floating-point filter is not scaled (its exponents are per vector); scale 2^{scale_exp} asked"
    )]
    BfpScaled { pair: String, scale_exp: i32 },
}

/// What a pair's filter computes in: a float format, or block floating point with W-bit
/// mantissas (`bfpW`, [`bfp`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterFormat {
    Float(Format),
    Bfp(u32),
}

impl FilterFormat {
    /// Bits per value: a float's width, a block's mantissa width (its exponent is shared by
    /// three components).
    pub fn width(&self) -> u32 {
        match self {
            FilterFormat::Float(format) => format.width(),
            FilterFormat::Bfp(width) => *width,
        }
    }
}

impl fmt::Display for FilterFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FilterFormat::Float(format) => f.write_str(&label(format)),
            FilterFormat::Bfp(width) => write!(f, "bfp{width}"),
        }
    }
}

/// A filter format and the fallback whose answers it must reproduce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FormatPair {
    pub filter: FilterFormat,
    pub fallback: Format,
}

impl FormatPair {
    /// `FILTER/FALLBACK`, each half anything [`lookup`] takes, or the filter `bfpW`. Both
    /// must be float formats (the bound is a float analysis), different, and the filter no
    /// wider than the fallback in exponent and fraction bits; a `bfpW` filter needs W in
    /// [`bfp::WIDTHS`] and a fallback that holds fp32.
    pub fn parse(s: &str) -> Result<FormatPair, DualError> {
        let pair = s.trim().to_string();
        let halves: Vec<&str> = pair.split('/').map(str::trim).collect();
        let [filter, fallback] = halves[..] else {
            return Err(DualError::Malformed(pair));
        };
        if filter.is_empty() || fallback.is_empty() {
            return Err(DualError::Malformed(pair));
        }
        let half = |name: &'static str, text: &str| {
            let format = lookup(text).map_err(|source| DualError::Half {
                pair: pair.clone(),
                half: name,
                source,
            })?;
            match format {
                Format::Float { exp, man } => Ok((format, exp, man)),
                Format::Fixed { .. } => Err(DualError::Fixed {
                    pair: pair.clone(),
                    half: name,
                    format: label(&format),
                }),
            }
        };
        let (fallback, be, bm) = half("fallback", fallback)?;
        if let Some(width) = filter.to_ascii_lowercase().strip_prefix("bfp") {
            let width = width
                .parse()
                .ok()
                .filter(|w| bfp::WIDTHS.contains(w))
                .ok_or_else(|| DualError::BfpWidth {
                    pair: pair.clone(),
                    filter: filter.to_string(),
                    min: *bfp::WIDTHS.start(),
                    max: *bfp::WIDTHS.end(),
                })?;
            if !holds_fp32(&fallback) {
                return Err(DualError::BfpFallback {
                    pair,
                    fallback: label(&fallback),
                });
            }
            return Ok(FormatPair {
                filter: FilterFormat::Bfp(width),
                fallback,
            });
        }
        let (filter, fe, fm) = half("filter", filter)?;
        if filter == fallback {
            return Err(DualError::Equal(pair));
        }
        if fe > be || fm > bm {
            return Err(DualError::NotNarrower {
                pair,
                filter: label(&filter),
                fallback: label(&fallback),
            });
        }
        Ok(FormatPair {
            filter: FilterFormat::Float(filter),
            fallback,
        })
    }
}

/// A catalogue name where there is one, else the generic spelling.
fn label(format: &Format) -> String {
    catalogue()
        .iter()
        .find(|n| n.format == *format)
        .map_or_else(|| format.to_string(), |n| n.name.to_string())
}

impl fmt::Display for FormatPair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.filter, label(&self.fallback))
    }
}

impl FromStr for FormatPair {
    type Err = DualError;
    fn from_str(s: &str) -> Result<Self, DualError> {
        FormatPair::parse(s)
    }
}

/// What a `--format` names: one format, or a filter/fallback pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatChoice {
    Single(Format),
    Pair(FormatPair),
}

#[derive(Debug, Error, PartialEq, Eq)]
pub enum ChoiceError {
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error(transparent)]
    Pair(#[from] DualError),
}

impl FromStr for FormatChoice {
    type Err = ChoiceError;
    /// A `/` makes it a pair ([`FormatPair::parse`]), else [`lookup`].
    fn from_str(s: &str) -> Result<Self, ChoiceError> {
        Ok(if s.contains('/') {
            FormatChoice::Pair(FormatPair::parse(s)?)
        } else {
            FormatChoice::Single(lookup(s)?)
        })
    }
}

impl fmt::Display for FormatChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FormatChoice::Single(format) => f.write_str(&label(format)),
            FormatChoice::Pair(pair) => pair.fmt(f),
        }
    }
}

/// One rounding of a float format with FTZ (the SPEC in `crate::format`): a result `x`
/// comes out as `x(1 + δ)`, |δ| ≤ `unit` = 2^-(M+1), or, below the smallest normal
/// `tiny`, as 0; so |fl(x) − x| ≤ max(unit·|x|, tiny). Magnitudes up to `max` do not
/// overflow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rounding {
    pub unit: f64,
    pub tiny: f64,
    pub max: f64,
}

impl Rounding {
    /// The rounding of a float format; `None` for fixed point.
    pub fn of(format: &Format) -> Option<Rounding> {
        let Format::Float { exp, man } = *format else {
            return None;
        };
        let bias = (1i32 << (exp - 1)) - 1;
        Some(Rounding {
            unit: 2f64.powi(-(man as i32) - 1),
            tiny: 2f64.powi(1 - bias),
            max: (2.0 - 2f64.powi(-(man as i32))) * 2f64.powi(bias),
        })
    }

    /// The largest error of rounding a value of at most `magnitude`.
    #[inline]
    fn error(&self, magnitude: f64) -> f64 {
        (self.unit * magnitude).max(self.tiny)
    }
}

/// How a bound is evaluated: exactly (in f64; [`F64_SLACK`] covers f64's own roundings), or
/// as a hardware bound network would, in a coarse float of `bits` fraction bits with every
/// result rounded up. The bound's operations (sums, products, max) are monotone on
/// non-negative values, so rounding each result up keeps every value an upper bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundArith {
    Exact,
    Coarse(u32),
}

impl BoundArith {
    /// `x` ≥ 0, rounded up onto the arithmetic's grid.
    fn up(self, x: f64) -> f64 {
        match self {
            BoundArith::Exact => x,
            BoundArith::Coarse(bits) => round_up_to_bits(x, bits),
        }
    }
}

/// `x` ≥ 0 rounded up to a float of `bits` fraction bits (0 and non-finite values stay): the
/// numbers of a hardware bound network.
pub(crate) fn round_up_to_bits(x: f64, bits: u32) -> f64 {
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

/// A format's rounding and the arithmetic its bound is evaluated in.
#[derive(Clone, Copy, Debug)]
struct Ctx {
    r: Rounding,
    arith: BoundArith,
}

impl Ctx {
    fn exact(r: Rounding) -> Ctx {
        Ctx {
            r,
            arith: BoundArith::Exact,
        }
    }

    fn up(&self, x: f64) -> f64 {
        self.arith.up(x)
    }

    /// The largest error of rounding a value of at most `magnitude`, on the grid.
    fn error(&self, magnitude: f64) -> f64 {
        self.up(self.r.error(magnitude))
    }

    fn bounded(&self, mag: f64, err: f64) -> Bounded {
        Bounded {
            mag: self.up(mag),
            err: self.up(err),
        }
    }
}

/// An intermediate of the datapath: |exact| ≤ `mag`, |computed − exact| ≤ `err`.
#[derive(Clone, Copy, Debug)]
struct Bounded {
    mag: f64,
    err: f64,
}

/// A coordinate fed to a datapath: `value` (an fp32 number), within `off` of the exact
/// coordinate it stands for.
#[derive(Clone, Copy, Debug)]
struct Fed {
    value: f64,
    off: f64,
}

impl Bounded {
    /// A fed coordinate converted into the format (one rounding, none if `exact`).
    fn input(x: Fed, c: &Ctx, exact: bool) -> Bounded {
        let conversion = if exact { 0.0 } else { c.error(x.value.abs()) };
        c.bounded(x.value.abs() + x.off, x.off + conversion)
    }

    /// The difference of two fed coordinates: its magnitude is known (f64 rounds it by at
    /// most 2^-52), not only the sum of theirs.
    fn difference(x: Fed, y: Fed, a: Bounded, b: Bounded, c: &Ctx) -> Bounded {
        let mag = (x.value - y.value).abs() * (1.0 + f64::EPSILON) + x.off + y.off;
        let carried = a.err + b.err - x.off - y.off;
        c.bounded(mag, a.err + b.err + c.error(mag + carried))
    }

    /// a ± b: the operands' errors add, then one rounding of a value ≤ mag + err.
    fn add(a: Bounded, b: Bounded, c: &Ctx) -> Bounded {
        let (mag, carried) = (c.up(a.mag + b.mag), c.up(a.err + b.err));
        c.bounded(mag, carried + c.error(mag + carried))
    }

    /// a·b: |ãb̃ − ab| ≤ |a|·err_b + |b|·err_a + err_a·err_b, then one rounding.
    fn mul(a: Bounded, b: Bounded, c: &Ctx) -> Bounded {
        let mag = c.up(a.mag * b.mag);
        let carried = c.up(c.up(a.mag * b.err) + c.up(b.mag * a.err) + c.up(a.err * b.err));
        c.bounded(mag, carried + c.error(mag + carried))
    }

    /// The largest magnitude the computed value can have.
    fn reach(&self) -> f64 {
        self.mag + self.err
    }
}

type BV = [Bounded; 3];

/// The bounds of the datapath's det and numerators (s·p, dir·q, e2·q), in the operation
/// order of `crate::mt` (cross a.y·b.z − a.z·b.y, …; dot (x + y) + z), for the fed
/// coordinates `q` (orig, dir, v0, v1, v2) converted into the format (exactly if
/// `exact_inputs`); `None` if an intermediate could overflow.
fn datapath_bounds(
    q: &[[Fed; 3]; 5],
    r: &Rounding,
    exact_inputs: bool,
) -> Option<(Bounded, [Bounded; 3])> {
    let c = Ctx::exact(*r);
    let [orig, dir, v0, v1, v2] = q.map(|v| v.map(|x| Bounded::input(x, &c, exact_inputs)));
    let sub = |i: usize, a: &BV| -> BV {
        std::array::from_fn(|k| Bounded::difference(q[i][k], q[2][k], a[k], v0[k], &c))
    };
    let (e1, e2, s) = (sub(3, &v1), sub(4, &v2), sub(0, &orig));
    let loads: Vec<Bounded> = [orig, v0, v1, v2].into_iter().flatten().collect();
    product_bounds([dir, e1, e2, s], &loads, &c)
}

/// The bounds of det and the numerators from those of dir, e1, e2 and s (`inputs`);
/// `loads` are other values the datapath holds, which must not overflow either.
fn product_bounds(inputs: [BV; 4], loads: &[Bounded], c: &Ctx) -> Option<(Bounded, [Bounded; 3])> {
    let mul = |a, b| Bounded::mul(a, b, c);
    let add = |a, b| Bounded::add(a, b, c);
    let cross = |a: &BV, b: &BV| {
        [
            add(mul(a[1], b[2]), mul(a[2], b[1])),
            add(mul(a[2], b[0]), mul(a[0], b[2])),
            add(mul(a[0], b[1]), mul(a[1], b[0])),
        ]
    };
    let dot = |a: &BV, b: &BV| add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]));
    let [dir, e1, e2, s] = inputs;
    let (p, qv) = (cross(&dir, &e2), cross(&s, &e1));
    let det = dot(&e1, &p);
    let num = [dot(&s, &p), dot(&dir, &qv), dot(&e2, &qv)];
    // Inside a cross or dot every product and partial sum has a smaller mag and err than
    // the result (all terms are added in magnitude), so the results and the inputs cover
    // every intermediate's reach.
    let reach = inputs
        .iter()
        .chain(&[p, qv])
        .flatten()
        .chain(loads)
        .chain(&num)
        .chain([&det])
        .map(Bounded::reach)
        .fold(0.0, f64::max);
    (reach <= c.r.max).then_some((det, num))
}

/// An fp32 input as the datapath sees it: subnormals flushed (SPEC), exact in f64.
fn flushed(x: f32) -> f64 {
    if x.is_subnormal() {
        0.0
    } else {
        f64::from(x)
    }
}

fn coords(q: &MtQuery) -> [[f64; 3]; 5] {
    [q.orig, q.dir, q.v0, q.v1, q.v2].map(|v| v.map(flushed))
}

/// Whether converting fp32 into `format` is exact (a superset of fp32's normal numbers).
fn holds_fp32(format: &Format) -> bool {
    matches!(*format, Format::Float { exp, man } if exp >= 8 && man >= 23)
}

/// What the filter lane is fed: the query moved to v0 = 0 by fp32 subtractions (orig − v0,
/// v1 − v0, v2 − v0; the exact test does not change under translation), then scaled by
/// 2^`scale_exp`; with each coordinate's distance from the exact translated and scaled one:
/// the distance itself if `known_offsets`, else the bound of one fp32 rounding (what
/// hardware knows). `None` if the scaling is inexact (a coordinate leaves fp32's normal
/// range).
fn filter_input(
    q: &MtQuery,
    scale_exp: i32,
    known_offsets: bool,
) -> Option<(MtQuery, [[Fed; 3]; 5])> {
    let flush = |x: f32| if x.is_subnormal() { 0.0 } else { x };
    let v0 = q.v0.map(flush);
    let moved = |p: [f32; 3]| -> [f32; 3] { std::array::from_fn(|k| flush(flush(p[k]) - v0[k])) };
    let translated = MtQuery {
        orig: moved(q.orig),
        dir: q.dir.map(flush),
        v0: [0.0; 3],
        v1: moved(q.v1),
        v2: moved(q.v2),
        t_min: q.t_min,
    };
    let fed_query = scale_query(&translated, scale_exp);
    let c = 2f64.powi(scale_exp);
    let exact = coords(q);
    let exact_moved = |i: usize, k: usize| match i {
        1 => exact[1][k],
        2 => 0.0,
        _ => exact[i][k] - exact[2][k],
    };
    let fed = coords(&fed_query);
    let unscaled = coords(&translated);
    let mut out = [[Fed {
        value: 0.0,
        off: 0.0,
    }; 3]; 5];
    for i in 0..5 {
        for k in 0..3 {
            if fed[i][k] != unscaled[i][k] * c {
                return None;
            }
            let off = if known_offsets {
                // f64 rounds the exact difference by at most 2^-53 of it.
                let want = exact_moved(i, k);
                (unscaled[i][k] - want).abs() + want.abs() * f64::EPSILON
            } else if matches!(i, 0 | 3 | 4) {
                // |fl(z) − z| ≤ max(u·|z|, λ) with |z| ≤ |fl(z)|/(1 − u).
                FP32_ROUNDING.error(unscaled[i][k].abs() * (1.0 + 4.0 * FP32_ROUNDING.unit))
            } else {
                0.0
            };
            out[i][k] = Fed {
                value: fed[i][k],
                off: off * c,
            };
        }
    }
    Some((fed_query, out))
}

/// fp32's rounding (unit 2^-24, smallest normal 2^-126): the filter's subtractors.
const FP32_ROUNDING: Rounding = Rounding {
    unit: 1.0 / 16_777_216.0,
    tiny: f32::MIN_POSITIVE as f64,
    max: f32::MAX as f64,
};

/// Rounding errors, relative to f64's: the bounds are evaluated in f64 (a few dozen
/// roundings of 2^-53 each); the final margins are widened by this factor to cover them.
const F64_SLACK: f64 = 1.0 + 1e-9;

/// A numerator N of u, v or t: the filter's computed value in scene units and in its own
/// (scaled) units, and the error bounds of the filter (`err_a`) and the fallback (`err_b`).
struct Numerator {
    n: f64,
    n_scaled: f64,
    err_a: f64,
    err_b: f64,
}

/// The filter's computed determinant (scene units and its own units) and the two error
/// bounds (scene units).
struct Det {
    d: f64,
    d_scaled: f64,
    err_a: f64,
    err_b: f64,
}

impl Det {
    /// The smallest |exact det|, if the fallback's computed det cannot be zero.
    fn lowest(&self) -> Option<f64> {
        let low = self.d.abs() - self.err_a;
        (low > self.err_b).then_some(low)
    }
}

/// The rounding error of fl(Ñ·fl(1/D̃)) against Ñ/D̃ for |Ñ| ≤ `n`, |D̃| ≥ `d`: the
/// reciprocal's error (≤ max(u/|D̃|, tiny)) times Ñ, then the product's rounding.
fn quotient_rounding(r: &Rounding, n: f64, d: f64) -> f64 {
    let carried = n * r.error(1.0 / d);
    carried + r.error(n / d + carried)
}

/// |computed − exact| of r = N/D, computed as N·(1/D) with two roundings, in the filter
/// and in the fallback; `None` if the fallback's det could be zero or its quotient overflow.
/// Ñ/D̃ − N/D = ((Ñ − N)·D̃ − Ñ·(D̃ − D)) / (D·D̃), then [`quotient_rounding`].
fn quotient_errors(n: &Numerator, det: &Det, a: &Rounding, b: &Rounding) -> Option<(f64, f64)> {
    let low = det.lowest()?;
    let n_high = n.n.abs() + n.err_a;
    let ratio_a = n.n.abs() / det.d.abs();
    // The filter's roundings happen in its own (scaled) units.
    let err_a = (n.err_a + ratio_a * det.err_a) / low
        + quotient_rounding(a, n.n_scaled.abs(), det.d_scaled.abs());
    // The fallback's Ñ and D̃ are within its bounds of the exact N, D, which are within
    // the filter's bounds of the filter's values.
    let (low_b, n_high_b) = (low - det.err_b, n_high + n.err_b);
    let rounding_b = quotient_rounding(b, n_high_b, low_b);
    let err_b = (n.err_b + n_high / low * det.err_b) / low_b + rounding_b;
    (n_high_b / low_b + rounding_b <= b.max && 1.0 / low_b <= b.max).then_some((err_a, err_b))
}

/// Fraction bits of a hardware bound network's coarse float.
pub const HW_BOUND_BITS: u32 = 3;

/// The filter the engines use: the one hardware can build.
pub const DEFAULT_FILTER: FilterKind = FilterKind::Linear(BoundArith::Coarse(HW_BOUND_BITS));

/// What the filter computes and how its bound is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterKind {
    /// A whole lane in the filter format (u, v, t as quotients, compared as the fallback
    /// compares them); the bound evaluated exactly, from the subtractions' exact errors.
    Quotient,
    /// No reciprocal: the numerators compared with det ([`linear`]); the bound in the given
    /// arithmetic (coarse: from the fp32 subtractors' rounding bound, as hardware knows it).
    Linear(BoundArith),
    /// Block floating point ([`bfp`]): the pair's `bfpW` filter, integer products, margins
    /// from the bits actually dropped, decisions on short floats rounded outward.
    Bfp,
    /// Plücker form ([`plucker`]), for a `bfpW` filter: det and the numerators as dot
    /// products of per-ray and per-triangle blocks, no translation per test, margins from
    /// block exponents.
    Plucker(PluckerDecisions),
}

/// How the Plücker filter decides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PluckerDecisions {
    /// The bfp filter's step 5 (`bfp::decide`: the division-free filter's tests on short
    /// floats rounded outward) on the values and their integer margins, bit for bit what
    /// the `Decide` stage computes (model only since the lane takes the sign decisions).
    Table,
    /// Sign decisions ([`signs::decide`]): bfp's rows made stronger so that they compare
    /// signs and bit lengths, u + v > 1 from the third edge's value; bit for bit what the
    /// hardware lane decides.
    Signs,
}

impl FilterKind {
    /// The engines' filter for `pair`: [`FilterKind::Bfp`] for a `bfpW` filter, else
    /// [`DEFAULT_FILTER`].
    pub fn default_for(pair: &FormatPair) -> FilterKind {
        match pair.filter {
            FilterFormat::Bfp(_) => FilterKind::Bfp,
            FilterFormat::Float(_) => DEFAULT_FILTER,
        }
    }
}

impl fmt::Display for FilterKind {
    /// The CLI's names (`--dual-filter`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FilterKind::Quotient => f.write_str("quotient"),
            FilterKind::Linear(BoundArith::Exact) => f.write_str("linear-exact"),
            FilterKind::Linear(BoundArith::Coarse(HW_BOUND_BITS)) => f.write_str("linear"),
            FilterKind::Linear(BoundArith::Coarse(bits)) => write!(f, "linear-coarse{bits}"),
            FilterKind::Bfp => f.write_str("bfp"),
            FilterKind::Plucker(PluckerDecisions::Table) => f.write_str("plucker"),
            FilterKind::Plucker(PluckerDecisions::Signs) => f.write_str("plucker-signs"),
        }
    }
}

/// The filter: `pair.filter` on the query moved to v0 = 0 in fp32 and scaled by
/// 2^`scale_exp` ([`filter_input`]), or for a `bfpW` filter moved exactly in integers
/// ([`bfp`]). Moving first is what makes a narrow filter useful:
/// converted as given, coordinates of 10–50 scene units carry a rounding error of the
/// format's precision times 50 into every edge, which dwarfs small triangles; the
/// differences carry it relative to their own size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Filter {
    pub pair: FormatPair,
    pub scale_exp: i32,
    pub kind: FilterKind,
    b: Rounding,
    /// The fallback's parallel-ray threshold, as it compares it.
    eps_b: f64,
}

impl Filter {
    /// `kind` must fit the pair's filter: [`FilterKind::Bfp`] or [`FilterKind::Plucker`] for
    /// a `bfpW` filter (unscaled), a float kind for a float filter.
    pub fn new(pair: FormatPair, scale_exp: i32, kind: FilterKind) -> Result<Filter, DualError> {
        let mismatch = |needs| DualError::Kind {
            pair: pair.to_string(),
            kind,
            needs,
        };
        match (pair.filter, kind) {
            (FilterFormat::Bfp(_), FilterKind::Bfp | FilterKind::Plucker(_)) if scale_exp != 0 => {
                return Err(DualError::BfpScaled {
                    pair: pair.to_string(),
                    scale_exp,
                })
            }
            (FilterFormat::Bfp(_), FilterKind::Bfp | FilterKind::Plucker(_)) => {}
            (FilterFormat::Bfp(_), _) => return Err(mismatch("a float filter such as fp16")),
            (FilterFormat::Float(_), FilterKind::Bfp | FilterKind::Plucker(_)) => {
                return Err(mismatch("a block-floating-point filter such as bfp18"))
            }
            (FilterFormat::Float(_), _) => {}
        }
        let fb = pair.fallback;
        Ok(Filter {
            pair,
            scale_exp,
            kind,
            b: Rounding::of(&fb).expect("FormatPair::parse admits float fallbacks only"),
            eps_b: fb.to_f64(fb.from_f32(DET_EPSILON)),
        })
    }

    /// The query's t_min as the fallback holds it: the fallback's hit needs t > this.
    fn fallback_t_min(&self, q: &MtQuery) -> f64 {
        let fallback = &self.pair.fallback;
        fallback.to_f64(fallback.from_f32(q.t_min))
    }

    /// A float filter's format and rounding (the float kinds' decisions).
    fn float_filter(&self) -> (Format, Rounding) {
        let FilterFormat::Float(format) = self.pair.filter else {
            unreachable!("Filter::new pairs float kinds with float filters")
        };
        let rounding = Rounding::of(&format).expect("FormatPair::parse admits floats only");
        (format, rounding)
    }

    /// Whether the fallback certainly answers "miss": one of its tests (|det| < eps,
    /// u < 0, u > 1, v < 0, u + v > 1, t ≤ t_min) is decided by the filter's value lying beyond
    /// the threshold by more than `margin_scale` × (the filter's + the fallback's error
    /// bound). `margin_scale` is 1 for the derived bound; the tests shrink it to show that
    /// a smaller margin is wrong. Non-finite inputs, inexact scaling and possible overflow
    /// are never certain.
    pub fn certain_miss(&self, q: &MtQuery, margin_scale: f64) -> bool {
        self.decide(q, margin_scale).is_some()
    }

    /// The filter's result, as a miss, if the query is a certain miss.
    fn decide(&self, q: &MtQuery, margin_scale: f64) -> Option<MtResult> {
        match self.kind {
            FilterKind::Quotient => self.decide_quotient(q, margin_scale),
            FilterKind::Linear(arith) => self.decide_linear(q, margin_scale, arith),
            FilterKind::Bfp => self.decide_bfp(q, margin_scale),
            FilterKind::Plucker(decisions) => self.decide_plucker(q, margin_scale, decisions),
        }
    }

    /// [`Filter::decide`] for [`FilterKind::Quotient`].
    fn decide_quotient(&self, q: &MtQuery, margin_scale: f64) -> Option<MtResult> {
        let (filter, a) = self.float_filter();
        let (a, b) = (&a, &self.b);
        let exact = coords(q);
        if exact.iter().flatten().any(|x| !x.is_finite()) {
            return None;
        }
        let (fed_query, fed_a) = filter_input(q, self.scale_exp, true)?;
        let fed_b = exact.map(|v| v.map(|value| Fed { value, off: 0.0 }));
        let (det_a, num_a) = datapath_bounds(&fed_a, a, holds_fp32(&filter))?;
        let (det_b, num_b) = datapath_bounds(&fed_b, b, holds_fp32(&self.pair.fallback))?;
        let (result, x) = mt_traced(&filter, &fed_query);
        let c = 2f64.powi(self.scale_exp);
        // det and the numerators are of degree 3 in lengths: back to scene units.
        let unscale = c.powi(-3);
        let margin = |bound: f64| bound * margin_scale * F64_SLACK;
        let det = Det {
            d: x.det * unscale,
            d_scaled: x.det,
            err_a: det_a.err * unscale,
            err_b: det_b.err,
        };
        // The filter's own tests may disagree (fp16's eps flushes to 0): the answer is a miss.
        let miss = Some(MtResult {
            hit: false,
            ..result
        });
        if det.d.abs() + margin(det.err_a + det.err_b) < self.eps_b {
            return miss;
        }
        if ![x.u, x.v, x.t, x.uv].iter().all(|v| v.is_finite()) {
            return None;
        }
        let errors = |k: usize| {
            let n = Numerator {
                n: x.num[k] * unscale,
                n_scaled: x.num[k],
                err_a: num_a[k].err * unscale,
                err_b: num_b[k].err,
            };
            quotient_errors(&n, &det, a, b)
        };
        let ((u_a, u_b), (v_a, v_b), (t_a, t_b)) = (errors(0)?, errors(1)?, errors(2)?);
        // A NaN t_min is left to the fallback, −∞ rules nothing out.
        let t_min = self.fallback_t_min(q);
        // u + v: both quotients' errors, then one rounding in each format.
        let uv_a = u_a + v_a + a.error(x.u.abs() + x.v.abs());
        let uv_b = u_b + v_b + b.error(x.u.abs() + u_a + u_b + x.v.abs() + v_a + v_b);
        let certain = x.u < -margin(u_a + u_b)
            || x.u - 1.0 > margin(u_a + u_b)
            || x.v < -margin(v_a + v_b)
            || x.uv - 1.0 > margin(uv_a + uv_b)
            || (t_min.is_finite() && x.t - t_min < -margin(t_a + t_b));
        if certain {
            miss
        } else {
            None
        }
    }
}

/// Counts of a [`DualIntersector`]'s work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DualStats {
    pub tests: u64,
    /// Tests the filter decided alone.
    pub certain_misses: u64,
}

impl DualStats {
    /// Tests answered by the fallback.
    pub fn forwarded(&self) -> u64 {
        self.tests - self.certain_misses
    }

    /// forwarded / tests (0 without tests).
    pub fn forwarded_share(&self) -> f64 {
        self.forwarded() as f64 / self.tests.max(1) as f64
    }
}

#[derive(Debug, Default)]
struct Counters {
    tests: AtomicU64,
    certain_misses: AtomicU64,
}

/// The dual-precision model as an [`Intersector`]: a certain miss answers with the filter's
/// result (`hit` false; a miss's t, u, v mean nothing); every other query is
/// [`mt_model`] in the fallback format, unscaled. Clones share their counters, so a caller
/// can keep one to read [`DualIntersector::stats`] after a render.
#[derive(Clone, Debug)]
pub struct DualIntersector {
    pub filter: Filter,
    counters: Arc<Counters>,
}

impl DualIntersector {
    /// `pair.filter` on queries scaled by 2^`filter_scale_exp`, the engines' filter for the
    /// pair ([`FilterKind::default_for`]); the fallback unscaled.
    pub fn new(pair: FormatPair, filter_scale_exp: i32) -> Result<DualIntersector, DualError> {
        let kind = FilterKind::default_for(&pair);
        Ok(DualIntersector::with_filter(Filter::new(
            pair,
            filter_scale_exp,
            kind,
        )?))
    }

    pub fn with_filter(filter: Filter) -> DualIntersector {
        DualIntersector {
            filter,
            counters: Arc::default(),
        }
    }

    pub fn stats(&self) -> DualStats {
        DualStats {
            tests: self.counters.tests.load(Ordering::Relaxed),
            certain_misses: self.counters.certain_misses.load(Ordering::Relaxed),
        }
    }
}

impl Intersector for DualIntersector {
    /// "model fp16/fp32".
    fn name(&self) -> String {
        format!("model {}", self.filter.pair)
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        let mut misses = 0;
        for (q, r) in queries.iter().zip(results.iter_mut()) {
            *r = match self.filter.decide(q, 1.0) {
                Some(miss) => {
                    misses += 1;
                    miss
                }
                None => mt_model(&self.filter.pair.fallback, q),
            };
        }
        self.counters
            .tests
            .fetch_add(queries.len() as u64, Ordering::Relaxed);
        self.counters
            .certain_misses
            .fetch_add(misses, Ordering::Relaxed);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::BoundArith;
    use proptest::prelude::*;

    proptest! {
        /// The coarse grid rounds up onto values of `bits` fraction bits, at most one
        /// grid step (2^(1-bits) relative) above, and leaves grid values alone.
        #[test]
        fn coarse_rounding_is_upward_onto_the_grid(x in 1e-300f64..1e300, bits in 0u32..8) {
            let up = BoundArith::Coarse(bits).up(x);
            prop_assert!(up >= x);
            prop_assert!(up <= x * (1.0 + 2f64.powi(1 - bits as i32)));
            let e = up.log2().floor() as i32;
            let steps = up / 2f64.powi(e - bits as i32);
            prop_assert!(steps == steps.trunc() && steps <= 2f64.powi(bits as i32 + 1));
            prop_assert_eq!(BoundArith::Coarse(bits).up(up), up);
        }
    }

    #[test]
    fn exact_bound_arithmetic_is_the_identity() {
        for x in [0.0, 1e-30, 0.3, 7.0, f64::INFINITY] {
            assert_eq!(BoundArith::Exact.up(x), x);
            assert_eq!(
                BoundArith::Coarse(3).up(x) == x,
                x == 0.0 || x.is_infinite() || x == 7.0
            );
        }
    }
}
