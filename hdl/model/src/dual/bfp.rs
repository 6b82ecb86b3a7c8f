//! The block-floating-point filter (docs/precision.md, "The block-floating-point filter"):
//! the bit-exact specification of a filter built from integer adders, DSP multipliers and
//! exponent adders. Step 1 ([`translate`]) moves the query to v0 = 0 in integers; step 2
//! ([`to_block`]) gives each of dir, e1, e2, s one block exponent, W-bit mantissas and the
//! exponent of its largest dropped part; step 3 computes the cross products exactly, cuts
//! them to blocks at a fixed exponent ([`cross_block`]) and the dots exactly; step 4
//! ([`margin_units`]) bounds the filter's and the fp32 fallback's errors by a few constants
//! shifted by block and dropped-part exponents; step 5 ([`certain_miss`]) decides the
//! fallback's tests on short floats rounded outward ([`round`]), every rounding in the
//! direction that keeps a decision certain.

use std::ops::RangeInclusive;

use sw_renderer::intersect::MtQuery;

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
    pub fn new(m: i128, e: i32) -> Fx {
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

    /// The exact sum; `None` if aligning would overflow (a zero's exponent never counts).
    /// What [`add_down`] is tested against, and how the Plücker filter's per-ray and
    /// per-triangle vectors are formed exactly.
    pub fn checked_add(self, other: Fx) -> Option<Fx> {
        if other.m == 0 {
            return Some(self);
        }
        if self.m == 0 {
            return Some(other);
        }
        let (a, b, e) = self.aligned(other)?;
        Some(Fx::new(a.checked_add(b)?, e))
    }

    /// self < other, exactly, at any exponents: different signs or leading-bit positions
    /// decide alone, and equal leading-bit positions align without overflow.
    pub fn lt(self, other: Fx) -> bool {
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

/// Step 2: a vector in block floating point: component k is `m[k]`·2^`lsb`, every
/// component of the value it came from lies in [−2^e, 2^e), and its truncation error is
/// below 2^`dropped` (`None`: nothing was dropped).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    pub m: [i128; 3],
    pub e: i32,
    pub lsb: i32,
    pub dropped: Option<i32>,
}

/// How far below its block exponent a dropped part is tracked: a smaller one is charged
/// as 2^(e − [`DROP_WINDOW`]) (a larger bound, so sound), which keeps the margin's terms
/// within a bounded window of bits.
pub const DROP_WINDOW: i32 = 64;

/// The exponent of x's leading bit (of x XOR its sign) plus one: x lies in [−2^t, 2^t).
pub fn top(x: Fx) -> i32 {
    x.e + (128 - (x.m ^ (x.m >> 127)).leading_zeros()) as i32
}

/// Step 2: the smallest block exponent e with every component in [−2^e, 2^e) (in hardware
/// the leading one of each component XOR its sign, then a 3-way max), then each component
/// shifted to W-bit two's-complement mantissas by an arithmetic right shift: truncation
/// towards −∞, error in [0, 2^(e − W + 1)). Truncation rather than rounding: no incrementer
/// and no carry out of the W bits (a rounded 2^e − ε would need W + 1); it doubles the
/// worst quantisation error, which the margin carries. The dropped parts' own bound
/// (`dropped`: the leading one of each component's dropped bits, a 3-way max, the same
/// logic again) is what the margin charges (step 4). `None` for the zero vector.
pub fn to_block(v: [Fx; 3], width: u32) -> Option<Block> {
    let e = v.iter().filter(|x| x.m != 0).map(|&x| top(x)).max()?;
    Some(place(v, e, width))
}

/// Step 3's truncated cross product x × y of two blocks: its components lie in
/// (−2^(E_x + E_y + 1), 2^(E_x + E_y + 1)) (each a difference of two products of mantissas
/// below 2^(W−1) in magnitude), so it is cut at that fixed block exponent: the top bits of
/// the exact product, no leading-bit search and no shifter. The dropped parts' exponent
/// (the leading one of the low bits, a 3-way max) is still what the margin charges.
pub fn cross_block(x: &Block, y: &Block, width: u32) -> Block {
    let v = cross(&x.m, &y.m).map(|m| Fx::new(m, x.lsb + y.lsb));
    place(v, x.e + y.e + CROSS_HEADROOM, width)
}

/// A cut cross product's block exponent above E_x + E_y ([`cross_block`]).
pub const CROSS_HEADROOM: i32 = 1;

/// How far below a block's last bit a component lies when [`place`] drops it whole and
/// charges 2^lsb for it (an i128 shift's limit; nearer, its dropped part's own leading bit
/// is charged). Hardware reproduces the threshold with one comparison.
pub const FAR_BELOW: i32 = i128::BITS as i32 - 1;

/// The W-bit block of `v` at block exponent e (every component in [−2^e, 2^e)): each
/// component shifted to the block's last bit by an arithmetic shift, and the exponent of
/// the largest dropped part.
fn place(v: [Fx; 3], e: i32, width: u32) -> Block {
    let lsb = e - (width as i32 - 1);
    let parts = v.map(|x| match x.e - lsb {
        up @ 0.. => (x.m << up, None),
        // Far below the block the whole component is dropped, and 2^lsb bounds it.
        down if -down >= FAR_BELOW => (x.m >> FAR_BELOW, if x.m == 0 { None } else { Some(lsb) }),
        down => {
            let m = x.m >> -down;
            // The dropped bits x − m·2^lsb, in [0, 2^lsb), at x's exponent.
            let rest = x.m - (m << -down);
            (
                m,
                (rest != 0).then(|| x.e + (128 - rest.leading_zeros()) as i32),
            )
        }
    });
    let dropped = parts
        .iter()
        .filter_map(|(_, d)| d.map(|d| d.max(e - DROP_WINDOW)))
        .max();
    Block {
        m: parts.map(|(m, _)| m),
        e,
        lsb,
        dropped,
    }
}

fn cross(a: &[i128; 3], b: &[i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Step 3's dots (det = e1·p̂, N_u = s·p̂, N_v = dir·q̂, N_t = e2·q̂) of two blocks'
/// mantissas, exactly: the value at the sum of their last bits.
pub fn dot(a: &[i128; 3], b: &[i128; 3]) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Extra mantissa bits of s = orig − v0 and of q = s × e1: s spans the ray's whole
/// distance to the triangle, and a small component of it (a shadow ray's offset from the
/// plane it leaves) must survive beside a large one. W + 7 = 25 at W = 18: the DSP48E1's
/// 25-bit port, so s × e1, s·p and dir·q, e2·q each stay one DSP48E1 a product.
pub const S_EXTRA_BITS: u32 = 7;

/// The vectors of steps 2 and 3, in the order of [`widths`]: dir, e1, e2, s, then the
/// truncated cross products p = dir × e2 and q = s × e1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vector {
    Dir,
    E1,
    E2,
    S,
    P,
    Q,
}

/// The four values [a, b, c, x] = a·trunc(b × c) of steps 3 to 5 (x = b × c cut):
/// det = e1·trunc(dir × e2), N_u = s·trunc(dir × e2), N_v = dir·trunc(s × e1),
/// N_t = e2·trunc(s × e1).
pub const DET: [Vector; 4] = [Vector::E1, Vector::Dir, Vector::E2, Vector::P];
pub const N_U: [Vector; 4] = [Vector::S, Vector::Dir, Vector::E2, Vector::P];
pub const N_V: [Vector; 4] = [Vector::Dir, Vector::S, Vector::E1, Vector::Q];
pub const N_T: [Vector; 4] = [Vector::E2, Vector::S, Vector::E1, Vector::Q];

/// The mantissa widths of dir, e1, e2, p (W) and s, q (W + [`S_EXTRA_BITS`]), in the
/// order of [`Vector`]: dir, e1, e2, s, p, q.
pub const fn widths(width: u32) -> [u32; 6] {
    let wide = width + S_EXTRA_BITS;
    [width, width, width, wide, width, wide]
}

/// Significant bits of the margin's wired constants (each rounded up).
pub const CONSTANT_BITS: i32 = 5;

/// c rounded up to [`CONSTANT_BITS`] significant bits, times 2^shift.
pub fn constant(c: f64, shift: i32) -> Fx {
    let e = c.log2().floor() as i32 - (CONSTANT_BITS - 1);
    // f64's own roundings (a few of 2^-53) are covered 10^4 times over before rounding up.
    let m = (c * (1.0 + 1e-12) * 2f64.powi(-e)).ceil() as i128;
    Fx::new(m, e + shift)
}

/// τ = 2^-(23 + GUARD_BITS): a translated component's error relative to its block (step 1).
fn tau() -> f64 {
    2f64.powi(-23 - GUARD_BITS)
}

/// The margin's three constants (docs/precision.md, "The block-floating-point filter",
/// step 4), each for a term of the bound of a value a·trunc(b × c):
/// - `dropped` (C_D): 3√3(1 + τ)², per vector times 2^(its dropped part's exponent + the other two
///   block exponents) (Hadamard's inequality on the telescoped trilinear error);
/// - `product` (C_P): 3, times 2^(E_a + the cut cross product's dropped exponent);
/// - `fixed` (C_F): times 2^(E_a + E_b + E_c): the translations' error 3·3√3·τ(1 + τ)², the fp32
///   fallback's 6γ₇(1 + τ)³ (seven roundings on each of the six terms) and 2^-39 (its flushes
///   inside the exponent range), and the fallback's quotient roundings folded in as
///   3u·6 (3u times a bound of 6·2^(E_a+E_b+E_c) on |value| + margin).
struct Constants {
    dropped: f64,
    product: f64,
    fixed: f64,
}

fn constants() -> Constants {
    let tau = tau();
    let hadamard = 3f64.powf(1.5);
    Constants {
        dropped: hadamard * (1.0 + tau).powi(2),
        product: 3.0,
        fixed: 3.0 * hadamard * tau * (1.0 + tau).powi(2) + fallback_constant(),
    }
}

/// fp32's unit roundoff 2^-24: the fallback's roundings.
const FP32_UNIT: f64 = 1.0 / 16_777_216.0;

/// The fp32 fallback's part of a margin, times 2^(E_a + E_b + E_c) of a value a·(b × c)
/// whose vectors have block exponents in [`EXP_MIN`, `EXP_MAX`] and a sum of at least
/// [`SUM_MIN`] (each |x_k| ≤ 2^E(1 + τ)): 6γ₇(1 + τ)³ (seven roundings on each of the six
/// terms), 2^-39 (its flushes inside the exponent range) and its quotient roundings folded
/// in as 3u·[`QUOTIENT_RANGE`]. Shared with the Plücker filter, whose fallback is the same.
pub fn fallback_constant() -> f64 {
    let tau = tau();
    let u = FP32_UNIT;
    let gamma7 = 7.0 * u / (1.0 - 7.0 * u);
    6.0 * gamma7 * (1.0 + tau).powi(3) + 2f64.powi(-39) + 3.0 * u * QUOTIENT_RANGE
}

/// A bound on |value| + margin in units of 2^(E_a + E_b + E_c) (the Hadamard bound 3√3 of
/// the filter's value with the cut cross product's slack, plus a margin below 1 at every
/// W ≥ 8; checked by `filter_values_are_within_their_margin_terms`): the fallback's
/// quotient roundings (3u of it) are folded into the margin with it.
pub const QUOTIENT_RANGE: f64 = 6.0;

/// Step 4: K of a value a·trunc(b × c) (det = e1·trunc(dir × e2), N_u = s·trunc(dir × e2),
/// N_v = dir·trunc(s × e1), N_t = e2·trunc(s × e1), given as [a, b, c, x]): its last bit is
/// 2^(E_a + E_b + E_c − K), fixed per kind and width because the cut cross product's block
/// exponent is E_b + E_c + [`CROSS_HEADROOM`] ([`cross_block`]).
pub const fn value_shift(width: u32, value: [Vector; 4]) -> i32 {
    let w = widths(width);
    let (a, x) = (w[value[0] as usize] as i32, w[value[3] as usize] as i32);
    (a - 1) + (x - 1) - CROSS_HEADROOM
}

/// The width of a value a·trunc(b × c) at step 5's input: its dot's exact width.
pub const fn value_bits(width: u32, value: [Vector; 4]) -> u32 {
    let w = widths(width);
    w[value[0] as usize] + w[value[3] as usize] + 1
}

/// The width of a value's margin in units of its last bit: |value| + margin is at most
/// [`QUOTIENT_RANGE`]·2^ΣE = [`QUOTIENT_RANGE`]·2^K units ([`value_shift`]).
pub const fn margin_bits(width: u32, value: [Vector; 4]) -> u32 {
    let mut range_bits = 0;
    while ((1u64 << range_bits) as f64) < QUOTIENT_RANGE {
        range_bits += 1;
    }
    value_shift(width, value) as u32 + range_bits
}

/// The exponents of a value's last bit that step 5 receives: ΣE − K for ΣE in
/// [[`SUM_MIN`], 3·[`EXP_MAX`]].
pub const fn lsb_range(width: u32, value: [Vector; 4]) -> RangeInclusive<i32> {
    let k = value_shift(width, value);
    SUM_MIN - k..=3 * EXP_MAX - k
}

/// One wired term of a margin in units of the value's last bit: `m`·2^(`shift` − below),
/// below the distance of a vector's dropped part under its own block exponent (0 for the
/// fixed term), rounded up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Term {
    /// The constant's mantissa, [`CONSTANT_BITS`] significant bits.
    pub m: i128,
    pub shift: i32,
}

impl Term {
    /// m·2^(shift − below) rounded up to an integer; `None` if it overflows.
    pub fn units(self, below: i32) -> Option<i128> {
        match self.shift - below {
            up @ 0.. => Fx::new(self.m, 0).mantissa_at(-up),
            // Below the last bit: ceil(m·2^-k), the shift plus its sticky bit.
            down => {
                let k = (-down).min(127) as u32;
                let fl = self.m >> k;
                Some(fl + i128::from(fl << k != self.m))
            }
        }
    }
}

/// What hardware wires for one value kind: the fixed term and, for a, b, c and the cut
/// cross product x, the term charged when that vector dropped something.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MarginTerms {
    pub fixed: Term,
    pub dropped: [Term; 4],
}

/// The terms of [`margin_units`] for `value` ([a, b, c, x], x = b × c) at mantissa width
/// `width`: with ΣE = E_a + E_b + E_c and the value's last bit 2^(ΣE − K) ([`value_shift`]),
/// C_F·2^ΣE is C_F·2^K units; a vector's C_D·2^(ΣE − E_v + D_v) is C_D·2^(K − below_v)
/// (below_v = E_v − D_v); the cut's C_P·2^(E_a + D_x) is C_P·2^(K + [`CROSS_HEADROOM`] −
/// below_x) (E_x = E_b + E_c + [`CROSS_HEADROOM`]). No term depends on an absolute exponent.
pub fn margin_terms(width: u32, value: [Vector; 4], margin_scale: f64) -> MarginTerms {
    let c = constants();
    let k = value_shift(width, value);
    let term = |c: f64, shift: i32| {
        let t = constant(c * margin_scale, shift);
        Term { m: t.m, shift: t.e }
    };
    let dropped = term(c.dropped, k);
    MarginTerms {
        fixed: term(c.fixed, k),
        dropped: [
            dropped,
            dropped,
            dropped,
            term(c.product, k + CROSS_HEADROOM),
        ],
    }
}

/// Step 4: the margin of a value a·trunc(b × c) (`value` = [a, b, c, x], as
/// [`value_shift`]), the filter's and the fallback's errors together:
///
/// ```text
/// C_D·(2^(D_a + E_b + E_c) + 2^(E_a + D_b + E_c) + 2^(E_a + E_b + D_c))
///     + C_P·2^(E_a + D_x) + C_F·2^(E_a + E_b + E_c)
/// ```
///
/// with D the dropped parts' exponents ([`Block`]; a vector with nothing dropped has no
/// term), x the cut cross product and the constants of [`constants`], each wired and
/// rounded up to [`CONSTANT_BITS`]. Each term is rounded up to the value's last bit, and the
/// result is in units of it. Computed from what hardware has ([`margin_terms`]): the width,
/// the kind and each vector's dropped distance below its own block exponent (`below`,
/// E − D; `None`: nothing dropped), so five shifted constants summed, no absolute exponent.
/// `margin_scale` = 1 is the derived bound (tests shrink it). `None` if a term overflows.
pub fn margin_units(
    width: u32,
    value: [Vector; 4],
    below: [Option<i32>; 4],
    margin_scale: f64,
) -> Option<i128> {
    let terms = margin_terms(width, value, margin_scale);
    terms
        .dropped
        .iter()
        .zip(below)
        .filter_map(|(t, below)| Some(t.units(below?)))
        .try_fold(terms.fixed.units(0)?, |acc, t| acc.checked_add(t?))
}

/// Significant bits (with the sign) of the short floats the decisions compare.
pub const SHORT_BITS: u32 = 10;

/// Step 5's normalisation: x rounded to a [`SHORT_BITS`]-bit two's-complement mantissa at
/// the exponent of its leading bit, **outward**: down (towards −∞, the arithmetic shift
/// alone) or up (the shift plus one if a dropped bit was set). Never moves a lower bound up
/// or an upper bound down; within one unit of the short mantissa's last bit.
pub fn round(x: Fx, up: bool) -> Fx {
    if x.m == 0 {
        return x;
    }
    let lsb = top(x) - (SHORT_BITS as i32 - 1);
    let Ok(shift @ 1..) = u32::try_from(lsb - x.e) else {
        return x;
    };
    let floor = x.m >> shift.min(127);
    let sticky = x.m != floor << shift.min(127);
    Fx::new(floor + i128::from(up && sticky), lsb)
}

/// The fallback's t_min, moved down to τ' ≤ t_min − λ (λ = 2^[`RECIPROCAL_MIN`], the
/// fallback's smallest normal): exact below 2^-102, else t_min − 1 ulp (one ulp ≥ λ there);
/// at t_min's own exponent, λ being 2^(−126 − e) units of its last bit 2^e below 2^-102.
/// `None` for a non-finite t_min (never a certain miss by t).
pub fn t_min_below(t_min: f32) -> Option<Fx> {
    let t = split(t_min)?;
    Some(Fx::new(t.m - (1 << (RECIPROCAL_MIN - t.e).max(0)), t.e))
}

/// The range row's powers of two: L ≥ 2^RECIPROCAL_MIN (the reciprocal does not
/// overflow), H < 2^QUOTIENT_MAX and max(hi, −lo) < L·2^QUOTIENT_MAX (no quotient
/// overflows); the u < 0 row's H·2^FLUSH_SHIFT (the quotient is not flushed to −0).
pub const RECIPROCAL_MIN: i32 = -126;
pub const QUOTIENT_MAX: i32 = 125;
pub const FLUSH_SHIFT: i32 = -124;

/// x + y rounded down ([`round`]) by a short adder: the operands (short floats, at most
/// [`SHORT_BITS`] + 1 bits with the sign) aligned at [`ADD_GUARD_BITS`] bits below the
/// larger one's short mantissa, the smaller floored to that grid (an arithmetic shift),
/// then added and rounded down. Equal to `round(x.checked_add(y), false)` wherever the exact
/// `Fx::checked_add` does not overflow: a floored operand lies more than two bits below the larger
/// one, so the sum's last short bit is above the grid, and flooring below it does not
/// change a floor. Defined at any exponents (no i128 shift can overflow), where the model
/// used to forward a query whose exact sum overflowed i128.
pub fn add_down(x: Fx, y: Fx) -> Fx {
    let t = |x: Fx| if x.m == 0 { i32::MIN } else { top(x) };
    let (tx, ty) = (t(x), t(y));
    if tx == i32::MIN || ty == i32::MIN {
        return round(if x.m == 0 { y } else { x }, false);
    }
    let grid = tx.max(ty) - (SHORT_BITS as i32 - 1) - ADD_GUARD_BITS;
    // Up exactly (an operand's top is at most the larger top), down by a floor.
    let at = |x: Fx| match x.e - grid {
        up @ 0.. => x.m << up,
        down => x.m >> (-down).min(127),
    };
    round(Fx::new(at(x) + at(y), grid), false)
}

/// Bits [`add_down`] aligns below the larger operand's short mantissa.
pub const ADD_GUARD_BITS: i32 = 3;

/// The fallback's parallel threshold `DET_EPSILON` as a short float.
pub fn det_epsilon() -> Fx {
    split(DET_EPSILON).expect("a finite constant")
}

/// Step 5's rows (docs/precision.md, the table of "The block-floating-point filter"), each
/// `true` where its condition holds; hardware evaluates them all at once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rows {
    /// H < eps: the fallback's parallel test fires.
    pub parallel: bool,
    /// L > 0, L ≥ 2^-126, H < 2^125, max(hi, −lo) < L·2^125 for u, v, t.
    pub in_range: bool,
    /// u < 0: hi_u < 0 and H·2^-124 ≤ −hi_u.
    pub u_below: bool,
    /// u > 1: H < lo_u.
    pub u_above: bool,
    /// v < 0: as u.
    pub v_below: bool,
    /// u + v > 1: H < down(lo_u + lo_v).
    pub uv_above: bool,
    /// t ≤ t_min: hi_t < down(τ'·(L if τ' ≥ 0 else H)).
    pub t_below: bool,
}

impl Rows {
    /// A certain miss: the fallback would answer no hit.
    pub fn miss(&self) -> bool {
        self.parallel
            || self.in_range
                && (self.u_below || self.u_above || self.v_below || self.uv_above || self.t_below)
    }
}

/// Steps 1–3 of the bfp filter at mantissa width `width`: the six blocks, in the order of
/// [`Vector`] (dir, e1, e2, s, p, q), that [`values`] takes its dots of. The points are
/// translated to v0, each vector is cut to its block, and p = dir × e2 and q = s × e1 are
/// computed exactly and cut. `None` forwards the query (a non-finite input, a zero vector,
/// a block exponent outside [`EXP_MIN`, `EXP_MAX`]).
pub fn blocks(q: &MtQuery, width: u32) -> Option<[Block; 6]> {
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
    let ranged = [dir, e1, e2, s];
    if ranged.iter().any(|b| !(EXP_MIN..=EXP_MAX).contains(&b.e)) {
        return None;
    }
    // Step 3: p = dir × e2 and q = s × e1 exactly, cut to blocks.
    let p = cross_block(&dir, &e2, w[Vector::P as usize]);
    let qv = cross_block(&s, &e1, w[Vector::Q as usize]);
    Some([dir, e1, e2, s, p, qv])
}

/// Steps 1–4 of the bfp filter at mantissa width `width`: det, N_u, N_v, N_t, each an
/// integer at its last bit's exponent with its margin in units of that bit ([`margin`]).
/// `None` forwards the query (a non-finite input, a zero vector, a block exponent outside
/// [`EXP_MIN`, `EXP_MAX`], a triple below [`SUM_MIN`]).
pub fn values(q: &MtQuery, width: u32, margin_scale: f64) -> Option<[(Fx, i128); 4]> {
    let blocks = blocks(q, width)?;
    // Step 3's dots exactly; each value with its margin; a triple below SUM_MIN is forwarded.
    let value = |vectors: [Vector; 4]| -> Option<(Fx, i128)> {
        let [a, b, c, x] = vectors.map(|v| blocks[v as usize]);
        let lsb = a.lsb + x.lsb;
        let below = [a, b, c, x].map(|v| v.dropped.map(|d| v.e - d));
        let e = margin_units(width, vectors, below, margin_scale)?;
        (a.e + b.e + c.e >= SUM_MIN).then_some((Fx::new(dot(&a.m, &x.m), lsb), e))
    };
    Some([value(DET)?, value(N_U)?, value(N_V)?, value(N_T)?])
}

/// Step 5 ([`certain_miss`]): the rows of the decision table from det and its margin
/// `e_det`, the numerators N_u, N_v, N_t with theirs (values at their last bit's exponent,
/// margins in units of that bit) and the query's t_min. `None` only if an i128 adder
/// overflows (never at the filter's widths): forwarded.
pub fn decide(det: Fx, e_det: i128, nums: [(Fx, i128); 3], t_min: f32) -> Option<Rows> {
    // Value ± margin: integer adders at the value's last bit.
    let at = |m: Option<i128>, x: Fx| Some(Fx::new(m?, x.e));
    let d_abs = det.m.abs();
    let high = round(at(d_abs.checked_add(e_det), det)?, true);
    let low = round(Fx::new(d_abs - e_det, det.e), false);
    let sigma = det.m.signum();
    // Per numerator σN + e rounded up and σN − e rounded down.
    let bounds = |(n, e): (Fx, i128)| -> Option<(Fx, Fx)> {
        let m = sigma * n.m;
        Some((
            round(at(m.checked_add(e), n)?, true),
            round(at(m.checked_sub(e), n)?, false),
        ))
    };
    let [u, v, t] = [bounds(nums[0])?, bounds(nums[1])?, bounds(nums[2])?];
    // No reciprocal overflows or flushes, no quotient overflows (powers of two: exponent
    // comparisons in hardware).
    let pow2 = |e: i32| Fx::new(1, e);
    let room = low.times(1, QUOTIENT_MAX)?;
    let in_range = low.m > 0
        && !low.lt(pow2(RECIPROCAL_MIN))
        && high.lt(pow2(QUOTIENT_MAX))
        && [u, v, t]
            .iter()
            .all(|&(hi, lo)| hi.lt(room) && Fx::new(-lo.m, lo.e).lt(room));
    let flush = high.times(1, FLUSH_SHIFT)?;
    let below_zero = |(hi, _): (Fx, Fx)| hi.m < 0 && !Fx::new(-hi.m, hi.e).lt(flush);
    let t_below = || -> Option<bool> {
        let tau = t_min_below(t_min)?;
        let bound = if tau.m >= 0 { low } else { high };
        let product = Fx::new(tau.m.checked_mul(bound.m)?, tau.e + bound.e);
        Some(t.0.lt(round(product, false)))
    };
    Some(Rows {
        parallel: high.lt(det_epsilon()),
        in_range,
        u_below: below_zero(u),
        u_above: high.lt(u.1),
        v_below: below_zero(v),
        uv_above: high.lt(add_down(u.1, v.1)),
        t_below: t_below() == Some(true),
    })
}

/// Whether the bfp filter of `width` decides `q` a certain miss: the fallback's tests (the
/// table in docs/precision.md, "Deciding without a division") on short floats rounded
/// outward ([`round`]): steps 1–4 ([`values`]), then step 5 ([`decide`]). With
/// σ = sign(det), n = σ·N and the margins e (the fallback's quotient roundings folded
/// in, [`margin_units`]): H = up(|det| + e_D), L = down(|det| − e_D), and per numerator
/// hi = up(n + e), lo = down(n − e):
/// - H < eps (the fallback's parallel test fires);
/// - otherwise only if L > 0, L ≥ 2^-126, H < 2^125 and max(hi, −lo) < L·2^125 (no
///   reciprocal overflows or flushes, no quotient overflows);
/// - u < 0: hi_u < 0 and H·2^-124 ≤ −hi_u (the quotient is not flushed to −0); v likewise;
/// - u > 1: H < lo_u;
/// - u + v > 1: H < down(lo_u + lo_v) ([`add_down`]);
/// - t ≤ t_min: hi_t < down(τ'·(L if τ' ≥ 0 else H)), τ' ≤ t_min − λ ([`t_min_below`]).
pub fn certain_miss(q: &MtQuery, width: u32, margin_scale: f64) -> bool {
    values(q, width, margin_scale)
        .and_then(|[det, nu, nv, nt]| decide(det.0, det.1, [nu, nv, nt], q.t_min))
        .is_some_and(|rows| rows.miss())
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
            prop_assert_eq!(x.checked_add(y).unwrap().to_f64(), x.to_f64() + y.to_f64());
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

    /// A vector of three fp32 numbers as exact values.
    fn exact(v: [f32; 3]) -> [Fx; 3] {
        v.map(|c| split(c).unwrap())
    }

    /// Exact a·(b × c) of exact vectors (exponents small enough for i128).
    fn triple(a: [Fx; 3], b: [Fx; 3], c: [Fx; 3]) -> Fx {
        let mul = |x: Fx, y: Fx| Fx::new(x.m * y.m, x.e + y.e);
        let sub = |x: Fx, y: Fx| x.checked_add(Fx::new(-y.m, y.e)).unwrap();
        let bc = [
            sub(mul(b[1], c[2]), mul(b[2], c[1])),
            sub(mul(b[2], c[0]), mul(b[0], c[2])),
            sub(mul(b[0], c[1]), mul(b[1], c[0])),
        ];
        (0..3)
            .map(|k| mul(a[k], bc[k]))
            .try_fold(Fx::new(0, 0), Fx::checked_add)
            .unwrap()
    }

    proptest! {
        /// Outward rounding never moves a value inward: down ≤ x ≤ up, both within one
        /// unit of the short mantissa's last bit, both SHORT_BITS wide (up may carry into
        /// the next power of two), and a value that fits is kept.
        #[test]
        fn outward_rounding_never_moves_inward(m in any::<i64>(), e in -60i32..60) {
            let x = Fx::new(i128::from(m), e);
            let (down, up) = (round(x, false), round(x, true));
            prop_assert!(!x.lt(down) && !up.lt(x), "{x:?} {down:?} {up:?}");
            let lsb = down.e;
            prop_assert_eq!(up.e, lsb);
            prop_assert!(up.m - down.m <= 1);
            let limit = 1i128 << (SHORT_BITS - 1);
            prop_assert!(-limit <= down.m && down.m < limit);
            prop_assert!(-limit <= up.m && up.m <= limit);
            if m.unsigned_abs() < 1 << (SHORT_BITS - 2) {
                prop_assert_eq!(down, x);
                prop_assert_eq!(up, x);
            }
            // Against f64 where f64 is exact.
            if m.unsigned_abs() < 1 << 52 {
                let (xf, step) = (x.to_f64(), 2f64.powi(lsb));
                prop_assert!(down.to_f64() <= xf && xf - down.to_f64() < step);
                prop_assert!(up.to_f64() >= xf && up.to_f64() - xf < step);
            }
        }

        /// The short adder: its rounded-down sum is `round(x.checked_add(y), false)` for any
        /// short floats (rounded either way), at near and far exponents.
        #[test]
        fn the_short_adder_rounds_the_exact_sum_down(
            a in any::<i64>(), ea in -60i32..60, ua in any::<bool>(),
            b in any::<i64>(), eb in -60i32..60, ub in any::<bool>(),
            shift in 0u32..64,
        ) {
            let x = round(Fx::new(i128::from(a >> shift), ea), ua);
            let y = round(Fx::new(i128::from(b), eb), ub);
            // Far apart, the exact sum overflows i128 (add_down does not).
            let Some(sum) = x.checked_add(y) else { return Ok(()); };
            let want = round(sum, false);
            let got = add_down(x, y);
            prop_assert!(!got.lt(want) && !want.lt(got), "{x:?} + {y:?}: {got:?} {want:?}");
        }

        /// The dropped parts' bound: every component's truncation error is below
        /// 2^dropped, and nothing is reported dropped when the block is exact.
        #[test]
        fn dropped_parts_bound_the_truncation_error(
            v in proptest::array::uniform3(float(-30, 30)),
            w in 8u32..=24,
        ) {
            let Some(b) = to_block(exact(v), w) else { return Ok(()); };
            let errs: Vec<f64> = v
                .iter()
                .zip(b.m)
                .map(|(c, m)| f64::from(*c) - m as f64 * 2f64.powi(b.lsb))
                .collect();
            match b.dropped {
                None => prop_assert!(errs.iter().all(|&e| e == 0.0)),
                Some(d) => {
                    prop_assert!(errs.iter().all(|&e| e < 2f64.powi(d)));
                    prop_assert!(d <= b.lsb);
                    // Tight: the largest error is at least half the bound, unless the
                    // window clamped it.
                    let top = errs.iter().cloned().fold(0.0, f64::max);
                    prop_assert!(top >= 2f64.powi(d - 1) || d == b.e - DROP_WINDOW);
                }
            }
        }

        /// The filter's value a·trunc(b × c) against the exact triple product: within the
        /// margin's filter terms (the margin less its fixed part, which is the fallback's and
        /// the translations'), and |value| + margin within QUOTIENT_RANGE·2^(E_a+E_b+E_c).
        #[test]
        fn filter_values_are_within_their_margin_terms(
            a in proptest::array::uniform3(float(-6, 6)),
            b in proptest::array::uniform3(float(-6, 6)),
            c in proptest::array::uniform3(float(-6, 6)),
            w in 8u32..=24,
        ) {
            let ws = widths(w);
            let (Some(ab), Some(bb), Some(cb)) = (
                to_block(exact(a), ws[1]),
                to_block(exact(b), ws[0]),
                to_block(exact(c), ws[2]),
            ) else { return Ok(()); };
            let xb = cross_block(&bb, &cb, ws[4]);
            // The cut is a valid block: every exact component in [−2^e, 2^e).
            for m in cross(&bb.m, &cb.m) {
                let x = Fx::new(m, bb.lsb + cb.lsb);
                prop_assert!(top(x) <= xb.e || m == 0);
            }
            // As det = e1·trunc(dir × e2): a in E1's place, b in Dir's, c in E2's.
            let value = DET;
            let filter = Fx::new(dot(&ab.m, &xb.m), ab.lsb + xb.lsb);
            let want = triple(exact(a), exact(b), exact(c));
            let err = filter.checked_add(Fx::new(-want.m, want.e)).unwrap();
            // The fallback's part (the fixed constant) is not the filter's: leave it out.
            let fixed = constant(constants().fixed, ab.e + bb.e + cb.e);
            // The value's last bit is 2^(ΣE − K), K fixed per kind and width.
            prop_assert_eq!(filter.e, ab.e + bb.e + cb.e - value_shift(w, value));
            let below = [ab, bb, cb, xb].map(|v| v.dropped.map(|d| v.e - d));
            let e = Fx::new(margin_units(w, value, below, 1.0).unwrap(), filter.e);
            let filter_terms = e.checked_add(Fx::new(-fixed.m, fixed.e)).unwrap();
            prop_assert!(!filter_terms.lt(Fx::new(err.m.abs(), err.e)), "{err:?} > {filter_terms:?}");
            let sum = ab.e + bb.e + cb.e;
            let range = Fx::new(QUOTIENT_RANGE as i128, sum);
            prop_assert!(Fx::new(filter.m.abs(), filter.e).checked_add(e).unwrap().lt(range));
        }

        /// The truncated cross product's own term: |a·(trunc(b × c) − b × c)| ≤ 3·2^(E_a+D_x).
        #[test]
        fn truncated_dots_are_within_their_term(
            a in proptest::array::uniform3(-(1i128 << 24)..1 << 24),
            x in proptest::array::uniform3(-(1i128 << 40)..1 << 40),
            w in 8u32..=24,
        ) {
            let Some(ab) = to_block(a.map(|m| Fx::new(m, -24)), w) else { return Ok(()); };
            let Some(xb) = to_block(x.map(|m| Fx::new(m, -40)), w) else { return Ok(()); };
            let full = Fx::new(dot(&ab.m, &x), ab.lsb - 40);
            let cut = Fx::new(dot(&ab.m, &xb.m), ab.lsb + xb.lsb);
            let err = cut.checked_add(Fx::new(-full.m, full.e)).unwrap();
            match xb.dropped {
                None => prop_assert_eq!(err.m, 0),
                Some(d) => prop_assert!(Fx::new(err.m.abs(), err.e).lt(Fx::new(3, ab.e + d)) || err.m == 0),
            }
        }
    }

    #[test]
    fn margins_shrink_with_the_width_and_the_dropped_bits() {
        let det = DET;
        // Everything dropped at a full step (each vector's own W − 1 below its block
        // exponent), in units of 2^ΣE: the old per-width constant, decreasing with W.
        let full = |w: u32| {
            let below = det.map(|v| Some(widths(w)[v as usize] as i32 - 1));
            let k = value_shift(w, det);
            Fx::new(margin_units(w, det, below, 1.0).unwrap(), -k).to_f64()
        };
        for w in 9..=24 {
            assert!(full(w) < full(w - 1));
        }
        // W = 18: 3√3·3·2^-17 ≈ 1.19e-4, the truncated p's 3·2^-16 ≈ 4.6e-5, the fixed
        // part ≈ 3.6e-6.
        assert!((1.66e-4..1.72e-4).contains(&full(18)), "{}", full(18));
        // Nothing dropped anywhere: the fixed part alone.
        let k = value_shift(18, det);
        let units = |scale: f64| margin_units(18, det, [None; 4], scale).unwrap();
        let m = Fx::new(units(1.0), -k).to_f64();
        assert!((3.0e-6..4.0e-6).contains(&m), "{m}");
        assert!(units(0.5) < units(1.0));
        // Rounded up to the value's last bit: at W = 8 (K = 13) the fixed part is below it
        // and still counts one unit.
        assert_eq!(value_shift(8, det), 13);
        assert_eq!(margin_units(8, det, [None; 4], 1.0), Some(1));
    }

    /// The margin as it was first written, from the blocks' absolute exponents and the
    /// value's last bit: the independent reference of [`margin_units`].
    fn margin_from_exponents(
        blocks: &[Block; 6],
        value: [Vector; 4],
        lsb: i32,
        margin_scale: f64,
    ) -> Option<i128> {
        let c = constants();
        let [a, b, cc, x] = value.map(|v| blocks[v as usize]);
        let sum = a.e + b.e + cc.e;
        let mut terms = vec![constant(c.fixed * margin_scale, sum)];
        for v in [a, b, cc] {
            if let Some(d) = v.dropped {
                terms.push(constant(c.dropped * margin_scale, sum - v.e + d));
            }
        }
        if let Some(d) = x.dropped {
            terms.push(constant(c.product * margin_scale, a.e + d));
        }
        terms.into_iter().try_fold(0i128, |acc, t| {
            let units = match t.e - lsb {
                up @ 0.. => Fx::new(t.m, 0).mantissa_at(-up)?,
                down => {
                    let k = (-down).min(127) as u32;
                    let fl = t.m >> k;
                    fl + i128::from(fl << k != t.m)
                }
            };
            acc.checked_add(units)
        })
    }

    proptest! {
        /// The margin from the width, the kind and the dropped distances equals the one from
        /// the blocks' absolute exponents, for blocks placed as the filter places them
        /// (lsb = e − W + 1, the cut's exponent E_b + E_c + 1) and each kind of value.
        #[test]
        fn margins_from_distances_equal_margins_from_exponents(
            w in 8u32..=24,
            kind in 0usize..4,
            e in proptest::array::uniform4(EXP_MIN..=EXP_MAX),
            below in proptest::array::uniform6(prop_oneof![
                1 => Just(None),
                1 => Just(Some(DROP_WINDOW)),
                4 => (0..=DROP_WINDOW).prop_map(Some),
            ]),
            scale in prop_oneof![Just(1.0), 0.01f64..1.0],
        ) {
            use Vector::{Dir, E1, E2, P, Q, S};
            let ws = widths(w);
            let value = [DET, N_U, N_V, N_T][kind];
            // dir, e1, e2, s at random; the cut cross products' exponents follow.
            let mut es = [e[0], e[1], e[2], e[3], 0, 0];
            es[P as usize] = es[Dir as usize] + es[E2 as usize] + CROSS_HEADROOM;
            es[Q as usize] = es[S as usize] + es[E1 as usize] + CROSS_HEADROOM;
            let blocks: [Block; 6] = std::array::from_fn(|v| {
                let lsb = es[v] - (ws[v] as i32 - 1);
                // A dropped part lies at or below the block's last bit.
                let below = below[v].map(|b| b.max(ws[v] as i32 - 1));
                Block { m: [0; 3], e: es[v], lsb, dropped: below.map(|b| es[v] - b) }
            });
            let [a, _, _, x] = value.map(|v| blocks[v as usize]);
            let want = margin_from_exponents(&blocks, value, a.lsb + x.lsb, scale);
            let below = value.map(|v| blocks[v as usize].dropped.map(|d| blocks[v as usize].e - d));
            prop_assert_eq!(margin_units(w, value, below, scale), want);
            prop_assert!(want.is_some());
        }
    }
}
