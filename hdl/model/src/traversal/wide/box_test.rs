//! The box test of a wide node: every child's quantized box in one beat, in integer
//! arithmetic after a few fp32 operations per node — the bit-exact definition the box stage
//! of the RTL is checked against. The derivation of its bounds is in docs/wide-nodes.md.
//!
//! A child box's plane on axis `a` is the real number `p_a + q·2^e_a` (`q` its 8-bit code);
//! the ray crosses it at `t = (p_a − o_a)/d_a + q·2^e_a/d_a = α_a + q·r_a`. Per node the unit
//! computes `α_a` in fp32 (one subtraction, one multiplication by the ray's reciprocal
//! direction) and takes `r_a` exactly from the reciprocal's bits. Both are turned into
//! integers on a fixed-point grid whose unit `2^U` is chosen per node from the node's extent
//! in t, as intervals `[α_lo, α_hi]`, `[r_lo, r_hi]` that contain the exact values: the
//! fp32 rounding errors, the ray's origin padding and the reciprocal's rounding are margins.
//! Then every plane is one multiply-add (a DSP48E1: `A + q·R`, 48 bits), an entry plane from
//! the lower bounds and an exit plane from the upper bounds, and the slab test compares
//! 16-bit codes. The result is conservative: a child whose quantized box (grown by the ray's
//! padding) the ray enters within `[t0, t_hi]` is always entered; the entry distance
//! reported is never beyond the exact one.
//!
//! Values that leave the integer ranges saturate the sound way: a lower bound that is too
//! large is clamped down and one that is too small becomes −∞; an upper bound that is too
//! small is clamped up and one that is too large becomes +∞. An entry at −∞ is 0, an exit at
//! +∞ is the largest code. So a NaN (no bound at all) or a direction component of zero
//! (the reciprocal's huge slope) cost culling on that axis, never a missed box.

use crate::format::Format;

use super::{Child, WideNode};
use crate::traversal::box_test::{ray_setup, RaySetup};

const F: Format = Format::FP32;

/// Bits of a slab code: distances in units of `2^U` from the node's origin in t.
pub const CODE_BITS: u32 = 16;
/// The largest code: an entry beyond it saturates there (and is never entered).
pub const CODE_MAX: i64 = (1 << CODE_BITS) - 1;
/// Every exit that matters is at most this many units beyond the node's origin in t (the
/// unit is chosen so; the +1 covers the origin's rounding down): the far end is clamped here.
pub const CODE_LIMIT: i64 = (1 << (CODE_BITS - 2)) + 1;
/// Fraction bits of the multiply-add's operands below the unit.
pub const FRAC_BITS: u32 = 8;
/// The offsets `α − τ` (and their margins) saturate beyond this magnitude, so that
/// `A + q·R` fits the DSP48E1's 48-bit post-adder.
pub const OFFSET_SAT: i64 = 1 << 45;
/// The steps `R` are 25-bit signed (the DSP48E1's A port): at most this magnitude.
pub const STEP_MAX: i64 = (1 << 24) - 1;
/// A node's width exponent when nothing bounds it (the root): its slab bounds then come from
/// the node's own values.
pub const WIDTH_UNBOUNDED: i16 = 511;
/// The smallest width exponent kept (a smaller one is rounded up to it: still a bound).
pub const WIDTH_MIN: i16 = -512;

/// A ray prepared for wide box tests once, when it enters the unit: the fp32 box test's
/// setup (reciprocal direction, padding, far end) plus the origin and the padding in t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WideRay {
    pub orig: [f32; 3],
    pub inv_dir: [f32; 3],
    /// `pad · |inv_dir|` (fp32): how far the padding `pad` moves a plane, in t.
    pub pad_t: [f32; 3],
    pub pad: f32,
    /// The far end of the slab interval (`box_test::t_hi` of the ray's bound).
    pub t_hi: f32,
}

impl WideRay {
    /// Prepares `(orig, dir)` with hit bound `bound` (the ray's t_max).
    pub fn new(orig: [f32; 3], dir: [f32; 3], bound: f32) -> WideRay {
        WideRay::from_setup(orig, &ray_setup(orig, dir, bound))
    }

    /// The wide test's setup from the fp32 box test's (which shares its reciprocal, padding
    /// and far end).
    pub fn from_setup(orig: [f32; 3], s: &RaySetup) -> WideRay {
        let pad_t = s
            .inv_dir
            .map(|inv| word(F.mul(bits(s.pad), bits(inv) & 0x7FFF_FFFF)));
        WideRay {
            orig,
            inv_dir: s.inv_dir,
            pad_t,
            pad: s.pad,
            t_hi: s.t_hi,
        }
    }
}

/// Where a walk enters a node: the distance `t0` at which its box was entered (0 for the
/// root) and an exponent `w` with every exit that matters within `[t0, t0 + 2^w]`
/// ([`WIDTH_UNBOUNDED`] for the root).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeEntry {
    pub t0: f32,
    pub width_exp: i16,
}

impl NodeEntry {
    /// The root: entered at 0, unbounded.
    pub const ROOT: NodeEntry = NodeEntry {
        t0: 0.0,
        width_exp: WIDTH_UNBOUNDED,
    };
}

/// A child the ray enters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Entered {
    /// Its slot in the node.
    pub slot: usize,
    /// Where the walk enters it: a lower bound of the entry distance, and its width.
    pub entry: NodeEntry,
    /// Its entry code (the sort key, with the slot).
    pub near_code: i64,
}

#[inline]
fn bits(x: f32) -> u64 {
    x.to_bits() as u64
}

#[inline]
fn word(b: u64) -> f32 {
    f32::from_bits(b as u32)
}

/// The unbiased exponent of an fp32 word's magnitude: `|x| < 2^(ex + 1)`. Zero and
/// subnormals (flushed) give −127; Inf and NaN give `None`.
fn exponent(x: u64) -> Option<i32> {
    match (x >> 23) & 0xFF {
        0xFF => None,
        0 => Some(-127),
        b => Some(b as i32 - 127),
    }
}

/// A lower bound: `None` is −∞.
type Lower = Option<i64>;
/// An upper bound: `None` is +∞.
type Upper = Option<i64>;

/// Bounds of `x · 2^shift` for an fp32 word `x` (subnormals flushed): `floor` and `ceil`
/// for a finite `x`; for an infinite one (an operation that overflowed: its exact operand
/// was beyond `2^127`, rounding errors included) `2^127 · 2^shift` on the near side and the
/// infinity on the other; `None` for NaN. Magnitudes beyond `2^100` are reported as `±2^100`
/// (every caller saturates far below).
fn scaled(x: u64, shift: i32) -> Option<(i128, i128)> {
    const HUGE: i128 = 1 << 100;
    let negative = x & 0x8000_0000 != 0;
    // floor and ceil of m · 2^k, saturated at HUGE.
    let magnitude = |m: i128, k: i32| -> (i128, i128) {
        if k >= 76 {
            (HUGE, HUGE)
        } else if k >= 0 {
            (m << k, m << k)
        } else if k <= -25 {
            (0, i128::from(m != 0))
        } else {
            let fl = m >> -k;
            (fl, fl + i128::from(m & ((1 << -k) - 1) != 0))
        }
    };
    let (lo, hi) = match (x >> 23) & 0xFF {
        0 => (0, 0),
        0xFF if x & 0x7F_FFFF != 0 => return None,
        0xFF => (magnitude(1, 127 + shift).0, HUGE),
        b => magnitude((x & 0x7F_FFFF | 0x80_0000) as i128, b as i32 - 150 + shift),
    };
    Some(if negative { (-hi, -lo) } else { (lo, hi) })
}

/// A lower bound within `±sat`: clamped down from above, −∞ below.
fn lower(v: i128, sat: i64) -> Lower {
    (v > -(sat as i128)).then(|| v.min(sat as i128) as i64)
}

/// An upper bound within `±sat`: clamped up from below, +∞ above.
fn upper(v: i128, sat: i64) -> Upper {
    (v < sat as i128).then(|| v.max(-(sat as i128)) as i64)
}

/// `a + q·r` of lower bounds (`q ≥ 0`): −∞ if either is, where `q·r` matters.
fn lower_plane(a: Lower, q: u8, r: Lower) -> Lower {
    match (a, r) {
        (Some(a), _) if q == 0 => Some(a),
        (Some(a), Some(r)) => Some(a + i64::from(q) * r),
        _ => None,
    }
}

/// `a + q·r` of upper bounds (`q ≥ 0`).
fn upper_plane(a: Upper, q: u8, r: Upper) -> Upper {
    lower_plane(a, q, r)
}

/// One axis of a node, as intervals on the node's fixed-point grid.
#[derive(Clone, Copy, Debug, Default)]
struct Axis {
    /// `α − τ`, lowered (entries) and raised (exits; with `2^FRAC_BITS − 1` added so that an
    /// arithmetic shift rounds the exit up).
    offset_lo: Lower,
    offset_hi: Upper,
    step_lo: Lower,
    step_hi: Upper,
    /// The direction's sign: entries use the lower planes.
    positive: bool,
}

/// The slab codes of one child: entry (`≥ 0`) and exit (`≥ −1`) per axis.
fn slab(axis: &Axis, lo: u8, hi: u8) -> (i64, i64) {
    let (q_entry, q_exit) = if axis.positive { (lo, hi) } else { (hi, lo) };
    let entry = lower_plane(axis.offset_lo, q_entry, axis.step_lo)
        .map_or(0, |p| (p >> FRAC_BITS).clamp(0, CODE_MAX));
    let exit = upper_plane(axis.offset_hi, q_exit, axis.step_hi)
        .map_or(CODE_MAX, |p| (p >> FRAC_BITS).clamp(-1, CODE_MAX));
    (entry, exit)
}

/// The box test of every child of `node`, entered at `at`: the children the ray enters,
/// nearest first (by entry code, then slot), each with where the walk enters it.
pub fn wide_box_test(ray: &WideRay, node: &WideNode, at: NodeEntry) -> Vec<Entered> {
    let alpha: [u64; 3] = std::array::from_fn(|a| {
        F.mul(
            F.sub(bits(node.origin[a]), bits(ray.orig[a])),
            bits(ray.inv_dir[a]),
        )
    });
    // |t| of every plane of axis a (margins included) is below 2^bound[a].
    let bound = |a: usize| -> Option<i32> {
        // A flushed reciprocal bounds nothing (see the axes below).
        let inv = exponent(bits(ray.inv_dir[a])).filter(|&e| e > -127)?;
        let terms = [
            exponent(alpha[a])? + 1,
            i32::from(node.exp[a]) + inv + 9,
            exponent(bits(ray.pad_t[a]))? + 1,
        ];
        Some(terms.into_iter().max().unwrap() + 2)
    };
    let width = (at.width_exp < WIDTH_UNBOUNDED).then_some(i32::from(at.width_exp));
    let extent = (0..3).filter_map(bound).chain(width).min();
    let unknown = || everything_entered(node, at);
    let Some(extent) = extent else {
        return unknown();
    };
    // The unit: 2^U, with every exit that matters within 2^(CODE_BITS − 2) units.
    let unit = extent - (CODE_BITS as i32 - 2);
    let shift = FRAC_BITS as i32 - unit;
    let Some((tau, _)) = scaled(bits(at.t0), shift) else {
        return unknown();
    };
    if tau >= OFFSET_SAT as i128 {
        return unknown();
    }
    // A walk's t0 is never negative; a negative one counts as 0 (a later start, within the
    // exact test's window [0, t_hi]), so that the offsets below keep within 48 bits.
    let tau = tau.max(0) as i64;
    let axes: [Axis; 3] = std::array::from_fn(|a| {
        let inv = bits(ray.inv_dir[a]);
        let positive = inv & 0x8000_0000 == 0;
        let no_bound = Axis {
            positive,
            ..Axis::default()
        };
        // A flushed subtraction errs by up to 2^-126·|inv| in t, a flushed product by
        // 2^-126; where that could reach a quarter of the grid's step, this axis bounds
        // nothing (the margin below has half a step for both).
        // A reciprocal flushed to zero (|d| ≥ 2^126) is no slope either.
        // The ray setup's reciprocal is finite; a non-finite word bounds nothing either.
        let Some(inv_exp) = exponent(inv) else {
            return no_bound;
        };
        if inv_exp == -127 || (inv_exp - 125).max(-126) + shift > -2 {
            return no_bound;
        }
        let (Some((a_lo, a_hi)), Some((_, pad))) =
            // pad_t is a magnitude (`pad·|inv|`): its sign bit is not read.
            (scaled(alpha[a], shift), scaled(bits(ray.pad_t[a]) & 0x7FFF_FFFF, shift))
        else {
            return no_bound;
        };
        let sat = OFFSET_SAT as i128;
        if pad >= sat {
            return no_bound;
        }
        // fp32 α is within 2^-22·|α| of (p − o)/d (three roundings), plus the ray's padding
        // in t, pad·|1/d| ≤ pad_t·(1 + 2^-22).
        let rounding = (a_lo.abs().max(a_hi.abs()).min(sat) >> 22) + 2;
        let margin = rounding + pad + (pad >> 22) + 1;
        let tau = tau as i128;
        let up = (1i128 << FRAC_BITS) - 1;
        // r = 2^e/d: the reciprocal's bits scaled exactly, within 2^-23 of the exact slope.
        let (r_lo, r_hi) = scaled(inv, i32::from(node.exp[a]) + shift).expect("finite");
        Axis {
            offset_lo: (a_lo > -sat).then(|| (a_lo.min(sat) - margin - tau) as i64),
            offset_hi: (a_hi < sat).then(|| (a_hi.max(-sat) + margin - tau + up) as i64),
            step_lo: lower(r_lo - (r_lo.abs() >> 23) - 1, STEP_MAX),
            step_hi: upper(r_hi + (r_hi.abs() >> 23) + 1, STEP_MAX),
            positive,
        }
    });
    // The far end in codes: ceil((t_hi − τ)/unit); NaN enters nothing.
    let t_hi_code = match scaled(bits(ray.t_hi), shift) {
        None => -1,
        Some((_, hi)) => {
            let v = (hi - tau as i128 + (1 << FRAC_BITS) - 1) >> FRAC_BITS;
            v.clamp(-1, CODE_MAX as i128) as i64
        }
    };
    let mut entered: Vec<(i64, usize, i64)> = node
        .children
        .iter()
        .enumerate()
        .filter_map(|(slot, child)| {
            let mut near = 0;
            let mut far = t_hi_code.min(CODE_LIMIT);
            for (a, axis) in axes.iter().enumerate() {
                let (entry, exit) = slab(axis, child.lo[a], child.hi[a]);
                near = near.max(entry);
                far = far.min(exit);
            }
            (near <= far).then_some((near, slot, far))
        })
        .collect();
    entered.sort_unstable_by_key(|&(near, slot, _)| (near, slot));
    entered
        .into_iter()
        .map(|(near, slot, far)| {
            let t0 = to_f32_down(tau + (near << FRAC_BITS), unit - FRAC_BITS as i32);
            Entered {
                slot,
                entry: NodeEntry {
                    t0,
                    width_exp: child_width(unit, far - near, t0),
                },
                near_code: near,
            }
        })
        .collect()
}

/// The fallback when the node's grid cannot be set up (a NaN ray, an origin in t beyond the
/// grid's range): every child entered where the node was.
fn everything_entered(node: &WideNode, at: NodeEntry) -> Vec<Entered> {
    (0..node.children.len())
        .map(|slot| Entered {
            slot,
            entry: NodeEntry {
                t0: at.t0,
                width_exp: WIDTH_UNBOUNDED,
            },
            near_code: 0,
        })
        .collect()
}

/// `n · 2^k` (n ≥ 0) as fp32, rounded toward zero (subnormals flushed, overflow to the
/// largest finite value): a lower bound.
fn to_f32_down(n: i64, k: i32) -> f32 {
    if n <= 0 {
        return 0.0;
    }
    let len = 64 - n.leading_zeros() as i32;
    let e = len - 1 + k;
    if e < -126 {
        return 0.0;
    }
    if e > 127 {
        return f32::MAX;
    }
    let m = if len > 24 {
        n >> (len - 24)
    } else {
        n << (24 - len)
    } as u32;
    f32::from_bits(((e + 127) as u32) << 23 | (m & 0x7F_FFFF))
}

/// The width exponent of a child entered at `t0` (the entry code rounded to fp32) whose
/// exits that matter are at most `span` units beyond its entry code: the span, the rounding
/// of `t0` (an ulp) and the child's own flooring of `t0` sum to less than `2^(w)`.
fn child_width(unit: i32, span: i64, t0: f32) -> i16 {
    let span_exp = unit + (64 - span.max(0).leading_zeros() as i32);
    let ulp_exp = exponent(bits(t0)).expect("finite") - 23;
    let w = span_exp.max(ulp_exp) + 2;
    w.clamp(i32::from(WIDTH_MIN), i32::from(WIDTH_UNBOUNDED) - 1) as i16
}

/// The quantized box of `child` on `node`'s grid, exactly: `(min, max)` per axis as
/// `p + q·2^e` in f64 where that is exact (every test scene's case), for reports and tests.
pub fn child_box(node: &WideNode, child: &Child) -> ([f64; 3], [f64; 3]) {
    let plane = |a: usize, q: u8| {
        f64::from(node.origin[a]) + f64::from(q) * 2f64.powi(i32::from(node.exp[a]))
    };
    (
        std::array::from_fn(|a| plane(a, child.lo[a])),
        std::array::from_fn(|a| plane(a, child.hi[a])),
    )
}
