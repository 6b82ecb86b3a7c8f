//! IEEE-like floats with round-to-nearest-even and flush-to-zero, by exact integer arithmetic.
//!
//! Every operation forms the exact result as `sig × 2^e` (plus a sticky flag for the one
//! inexact case, the reciprocal's quotient) and rounds it once in [`FloatFormat::round_pack`].
//! Exact sums and products are formed in u64 when the format is narrow enough, else u128.
//! No host float operation is used: host f32/f64 are what the tests compare against.

/// The layout of one float format: `exp` exponent bits, `man` fraction bits.
use std::ops::{Add, BitAnd, Shl, Shr, Sub};

use crate::format::Arith;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FloatFormat {
    pub exp: u32,
    pub man: u32,
}

/// An operand after flushing subnormals: the exact value is `sig × 2^e`, `sig` has `man + 1` bits.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Unpacked {
    Nan,
    Inf(bool),
    Zero(bool),
    Finite { sign: bool, sig: u64, e: i32 },
}

/// The unsigned integers exact results are formed in: u64 whenever the format is narrow
/// enough (the common, fast case), u128 for the widest formats.
pub(crate) trait Wide:
    Copy
    + Ord
    + From<u64>
    + Shl<u32, Output = Self>
    + Shr<u32, Output = Self>
    + Add<Output = Self>
    + Sub<Output = Self>
    + BitAnd<Output = Self>
{
    const BITS: u32;
    const ONE: Self;
    fn leading_zeros(self) -> u32;
    fn low_u64(self) -> u64;
}

impl Wide for u64 {
    const BITS: u32 = 64;
    const ONE: Self = 1;
    #[inline]
    fn leading_zeros(self) -> u32 {
        u64::leading_zeros(self)
    }
    #[inline]
    fn low_u64(self) -> u64 {
        self
    }
}

impl Wide for u128 {
    const BITS: u32 = 128;
    const ONE: Self = 1;
    #[inline]
    fn leading_zeros(self) -> u32 {
        u128::leading_zeros(self)
    }
    #[inline]
    fn low_u64(self) -> u64 {
        self as u64
    }
}

impl FloatFormat {
    pub const F32: FloatFormat = FloatFormat { exp: 8, man: 23 };
    pub const F64: FloatFormat = FloatFormat { exp: 11, man: 52 };

    #[inline]
    fn exp_ones(self) -> u64 {
        (1u64 << self.exp) - 1
    }
    #[inline]
    fn bias(self) -> i32 {
        (1i32 << (self.exp - 1)) - 1
    }
    #[inline]
    fn frac_mask(self) -> u64 {
        (1u64 << self.man) - 1
    }
    #[inline]
    fn sign_bit(self) -> u64 {
        1u64 << (self.exp + self.man)
    }
    #[inline]
    fn exp_field(self, bits: u64) -> u64 {
        (bits >> self.man) & self.exp_ones()
    }

    #[inline]
    pub fn zero(self, sign: bool) -> u64 {
        if sign {
            self.sign_bit()
        } else {
            0
        }
    }
    #[inline]
    pub fn inf(self, sign: bool) -> u64 {
        self.zero(sign) | (self.exp_ones() << self.man)
    }
    /// The canonical NaN: sign 0, exponent all ones, fraction MSB only.
    #[inline]
    pub fn nan(self) -> u64 {
        (self.exp_ones() << self.man) | (1u64 << (self.man - 1))
    }

    #[inline]
    pub fn unpack(self, bits: u64) -> Unpacked {
        let sign = bits & self.sign_bit() != 0;
        let ef = self.exp_field(bits);
        let frac = bits & self.frac_mask();
        if ef == self.exp_ones() {
            if frac != 0 {
                Unpacked::Nan
            } else {
                Unpacked::Inf(sign)
            }
        } else if ef == 0 {
            Unpacked::Zero(sign)
        } else {
            Unpacked::Finite {
                sign,
                sig: frac | (1u64 << self.man),
                e: ef as i32 - self.bias() - self.man as i32,
            }
        }
    }

    /// Rounds the exact value `±(sig + δ) × 2^e` (δ ∈ (0, 1) if `sticky`, else 0; `sig` ≠ 0)
    /// to `man + 1` significant bits, ties to even, with an unbounded exponent; then
    /// overflows to ±Inf or flushes to ±0 (the flush-after-rounding rule of the SPEC).
    /// Branch-free up to the range checks: the renderer's operands round up or down at random.
    #[inline]
    pub fn round_pack<W: Wide>(self, sign: bool, sig: W, e: i32, sticky: bool) -> u64 {
        debug_assert!(sig != W::from(0));
        let lz = sig.leading_zeros();
        let norm = sig << lz; // leading one at the top bit
        let p = self.man + 1;
        let keep = (norm >> (W::BITS - p)).low_u64();
        let rem = norm << p; // the dropped bits, left-aligned: a half ulp is the top bit alone
        let half = W::ONE << (W::BITS - 1);
        let up = (rem > half) | ((rem == half) & (sticky | (keep & 1 == 1)));
        let keep = keep + up as u64;
        let carry = (keep >> p) as u32; // rounded up to 2^p
        let keep = keep >> carry;
        // keep's unit is 2^(e + BITS − lz − p + carry); its leading bit sits `man` above.
        let biased = e + W::BITS as i32 - lz as i32 - p as i32
            + carry as i32
            + self.man as i32
            + self.bias();
        if biased >= self.exp_ones() as i32 {
            self.inf(sign)
        } else if biased <= 0 {
            self.zero(sign)
        } else {
            self.zero(sign) | ((biased as u64) << self.man) | (keep & self.frac_mask())
        }
    }

    /// Converts `bits` of format `from` to this format (one rounding, FTZ on both sides).
    #[inline]
    pub fn convert_from(self, from: FloatFormat, bits: u64) -> u64 {
        match from.unpack(bits) {
            Unpacked::Nan => self.nan(),
            Unpacked::Inf(s) => self.inf(s),
            Unpacked::Zero(s) => self.zero(s),
            Unpacked::Finite { sign, sig, e } => self.round_pack(sign, sig, e, false),
        }
    }

    /// Sign, significand and unbiased exponent (value = sig × 2^(e − man)) of a finite nonzero operand.
    #[inline]
    fn parts(self, bits: u64) -> (bool, u64, i32) {
        let ef = self.exp_field(bits);
        (
            bits & self.sign_bit() != 0,
            (bits & self.frac_mask()) | (1u64 << self.man),
            ef as i32 - self.bias(),
        )
    }

    /// The exact sum of finite nonzero `x`, `y` with |x| ≥ |y|, rounded once.
    /// Alignment stops at `man + 3` bits: a smaller addend further down is below a quarter
    /// of the rounding unit of `x << (man + 3)` and lies strictly between two rounding
    /// boundaries next to it, so replacing it by one unit at that scale rounds identically
    /// and no sticky bit is needed. Needs (man + 1) + (man + 3) + 1 bits of `W`.
    #[inline]
    fn add_ordered<W: Wide>(self, x: u64, y: u64) -> u64 {
        let ((sx, mx, ex), (sy, my, ey)) = (self.parts(x), self.parts(y));
        let cap = self.man + 3;
        let d = (ex - ey) as u32;
        let shift = d.min(cap);
        let big = W::from(mx) << shift;
        let small = W::from(if d > cap { 1 } else { my });
        let sum = if sx == sy { big + small } else { big - small };
        if sum == W::from(0) {
            return self.zero(false); // x + (−x) = +0
        }
        // `parts` gives value = sig × 2^(e − man), so the unit of `sum` is 2^(ex − shift − man).
        self.round_pack(sx, sum, ex - shift as i32 - self.man as i32, false)
    }

    /// Correctly rounded √a (RNE, FTZ): √±0 = ±0, √+Inf = +Inf, a NaN or a value below zero
    /// gives the canonical NaN. The exact root of `sig × 2^e` is formed as the integer square
    /// root of `sig` shifted left by an even-making amount to `2·man + 6` or `2·man + 7` bits:
    /// `man + 3` or more root bits, its remainder the sticky flag: one rounding of root +
    /// sticky is the correct one (and a square root is never exactly halfway between two
    /// floats). Formats up to 28 fraction bits (the root then fits a u64).
    #[inline]
    pub fn sqrt(self, a: u64) -> u64 {
        match self.unpack(a) {
            Unpacked::Nan | Unpacked::Inf(true) | Unpacked::Finite { sign: true, .. } => self.nan(),
            Unpacked::Inf(false) => a,
            Unpacked::Zero(s) => self.zero(s),
            Unpacked::Finite { sig, e, .. } => {
                let mut shift = self.man + 5;
                if (e - shift as i32) % 2 != 0 {
                    shift += 1;
                }
                debug_assert!(
                    2 * self.man + 7 <= 64,
                    "sqrt's root fits a u64 up to man = 28"
                );
                let x = sig << shift;
                let root = x.isqrt();
                self.round_pack(false, root, (e - shift as i32) / 2, root * root != x)
            }
        }
    }

    /// An order-preserving integer key; `None` for NaN. Flushed subnormals and both zeros map to 0.
    #[inline]
    fn order_key(self, a: u64) -> Option<i64> {
        let ef = self.exp_field(a);
        if ef == self.exp_ones() && a & self.frac_mask() != 0 {
            return None;
        }
        if ef == 0 {
            return Some(0);
        }
        let mag = (a & !self.sign_bit()) as i64;
        Some(if a & self.sign_bit() != 0 { -mag } else { mag })
    }
}

impl Arith for FloatFormat {
    #[inline]
    fn add(self, a: u64, b: u64) -> u64 {
        use Unpacked::*;
        match (self.unpack(a), self.unpack(b)) {
            (Nan, _) | (_, Nan) => self.nan(),
            (Inf(sa), Inf(sb)) => {
                if sa == sb {
                    self.inf(sa)
                } else {
                    self.nan()
                }
            }
            (Inf(s), _) | (_, Inf(s)) => self.inf(s),
            (Zero(sa), Zero(sb)) => self.zero(sa && sb),
            (Zero(_), Finite { .. }) => b,
            (Finite { .. }, Zero(_)) => a,
            (Finite { .. }, Finite { .. }) => {
                // Order by magnitude: the aligned difference is then never negative.
                let magnitude = !self.sign_bit();
                let (x, y) = if a & magnitude >= b & magnitude {
                    (a, b)
                } else {
                    (b, a)
                };
                if 2 * self.man + 5 <= 64 {
                    self.add_ordered::<u64>(x, y)
                } else {
                    self.add_ordered::<u128>(x, y)
                }
            }
        }
    }
    #[inline]
    fn neg(self, a: u64) -> u64 {
        a ^ self.sign_bit()
    }
    #[inline]
    fn sub(self, a: u64, b: u64) -> u64 {
        self.add(a, self.neg(b))
    }
    #[inline]
    fn mul(self, a: u64, b: u64) -> u64 {
        use Unpacked::*;
        match (self.unpack(a), self.unpack(b)) {
            (Nan, _) | (_, Nan) | (Inf(_), Zero(_)) | (Zero(_), Inf(_)) => self.nan(),
            (Inf(sa), Inf(sb) | Finite { sign: sb, .. }) | (Finite { sign: sa, .. }, Inf(sb)) => {
                self.inf(sa != sb)
            }
            (Zero(sa), Zero(sb) | Finite { sign: sb, .. })
            | (Finite { sign: sa, .. }, Zero(sb)) => self.zero(sa != sb),
            (
                Finite {
                    sign: sa,
                    sig: ma,
                    e: ea,
                },
                Finite {
                    sign: sb,
                    sig: mb,
                    e: eb,
                },
            ) => {
                if self.man < 32 {
                    self.round_pack(sa != sb, ma * mb, ea + eb, false)
                } else {
                    self.round_pack(sa != sb, ma as u128 * mb as u128, ea + eb, false)
                }
            }
        }
    }
    /// Correctly rounded 1/a: the quotient 2^K / sig carries man + 3 or man + 4 bits (so it
    /// fits a u64), the remainder becomes the sticky flag.
    #[inline]
    fn recip(self, a: u64) -> u64 {
        match self.unpack(a) {
            Unpacked::Nan => self.nan(),
            Unpacked::Inf(s) => self.zero(s),
            Unpacked::Zero(s) => self.inf(s),
            Unpacked::Finite { sign, sig, e } => {
                let k = 2 * self.man + 3;
                debug_assert!(sig >> self.man == 1);
                let (q, r) = if k < 64 {
                    let num = 1u64 << k;
                    (num / sig, num % sig)
                } else {
                    let num = 1u128 << k;
                    ((num / sig as u128) as u64, (num % sig as u128) as u64)
                };
                self.round_pack(sign, q, -(k as i32) - e, r != 0)
            }
        }
    }
    #[inline]
    fn lt(self, a: u64, b: u64) -> bool {
        match (self.order_key(a), self.order_key(b)) {
            (Some(ka), Some(kb)) => ka < kb,
            _ => false,
        }
    }
    #[inline]
    fn is_nan(self, a: u64) -> bool {
        self.exp_field(a) == self.exp_ones() && a & self.frac_mask() != 0
    }

    #[inline]
    fn convert_in(self, src: FloatFormat, bits: u64) -> u64 {
        self.convert_from(src, bits)
    }
    #[inline]
    fn convert_out(self, dst: FloatFormat, bits: u64) -> u64 {
        dst.convert_from(self, bits)
    }
}
