//! IEEE-like floats with round-to-nearest-even and flush-to-zero, by exact integer arithmetic.
//!
//! Every operation forms the exact result as `sig × 2^e` (plus a sticky flag for the one
//! inexact case, the reciprocal's quotient) and rounds it once in [`FloatFormat::round_pack`].
//! No host float operation is used: host f32/f64 are what the tests compare against.

/// The layout of one float format: `exp` exponent bits, `man` fraction bits.
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

/// Alignment distance above which the smaller addend is replaced by one unit at this distance:
/// the big significand (≤ 53 bits) shifted this far still fits a u128 with a carry bit, and
/// the rounding position lies ≥ 70 bits above, so `big ± 1` rounds exactly like `big ± tiny`.
const ALIGN_CAP: u32 = 74;

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
    #[inline]
    pub fn round_pack(self, sign: bool, sig: u128, e: i32, sticky: bool) -> u64 {
        debug_assert!(sig != 0);
        let n = 128 - sig.leading_zeros() as i32;
        let p = self.man as i32 + 1;
        let (mut keep, mut e) = if n > p {
            let sh = (n - p) as u32;
            let keep = (sig >> sh) as u64;
            let rem = sig & ((1u128 << sh) - 1);
            let half = 1u128 << (sh - 1);
            let up = rem > half || (rem == half && (sticky || keep & 1 == 1));
            (keep + up as u64, e + sh as i32)
        } else {
            debug_assert!(!sticky, "an inexact value needs more bits than the format keeps");
            ((sig as u64) << (p - n), e - (p - n))
        };
        if keep >> p != 0 {
            keep >>= 1;
            e += 1;
        }
        let biased = e + self.man as i32 + self.bias();
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
            Unpacked::Finite { sign, sig, e } => self.round_pack(sign, sig as u128, e, false),
        }
    }

    #[inline]
    pub fn add(self, a: u64, b: u64) -> u64 {
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
            (Finite { sign: sa, sig: ma, e: ea }, Finite { sign: sb, sig: mb, e: eb }) => {
                // `big` has the larger exponent; align it down onto the smaller one's scale.
                let (sbig, mbig, ebig, ssm, msm, esm) =
                    if ea >= eb { (sa, ma, ea, sb, mb, eb) } else { (sb, mb, eb, sa, ma, ea) };
                let d = (ebig - esm) as u32;
                let (big, small, e) = if d > ALIGN_CAP {
                    ((mbig as u128) << ALIGN_CAP, 1u128, ebig - ALIGN_CAP as i32)
                } else {
                    ((mbig as u128) << d, msm as u128, esm)
                };
                if sbig == ssm {
                    self.round_pack(sbig, big + small, e, false)
                } else if big > small {
                    self.round_pack(sbig, big - small, e, false)
                } else if small > big {
                    self.round_pack(ssm, small - big, e, false)
                } else {
                    self.zero(false)
                }
            }
        }
    }

    #[inline]
    pub fn neg(self, a: u64) -> u64 {
        a ^ self.sign_bit()
    }

    #[inline]
    pub fn sub(self, a: u64, b: u64) -> u64 {
        self.add(a, self.neg(b))
    }

    #[inline]
    pub fn mul(self, a: u64, b: u64) -> u64 {
        use Unpacked::*;
        match (self.unpack(a), self.unpack(b)) {
            (Nan, _) | (_, Nan) | (Inf(_), Zero(_)) | (Zero(_), Inf(_)) => self.nan(),
            (Inf(sa), Inf(sb) | Finite { sign: sb, .. }) | (Finite { sign: sa, .. }, Inf(sb)) => {
                self.inf(sa != sb)
            }
            (Zero(sa), Zero(sb) | Finite { sign: sb, .. }) | (Finite { sign: sa, .. }, Zero(sb)) => {
                self.zero(sa != sb)
            }
            (Finite { sign: sa, sig: ma, e: ea }, Finite { sign: sb, sig: mb, e: eb }) => {
                self.round_pack(sa != sb, ma as u128 * mb as u128, ea + eb, false)
            }
        }
    }

    /// Correctly rounded 1/a: the quotient 2^K / sig carries ≥ man + 3 bits, the remainder
    /// becomes the sticky flag.
    #[inline]
    pub fn recip(self, a: u64) -> u64 {
        match self.unpack(a) {
            Unpacked::Nan => self.nan(),
            Unpacked::Inf(s) => self.zero(s),
            Unpacked::Zero(s) => self.inf(s),
            Unpacked::Finite { sign, sig, e } => {
                let k = 2 * self.man + 3;
                let (q, r) = if k < 64 {
                    let num = 1u64 << k;
                    ((num / sig) as u128, num % sig)
                } else {
                    let num = 1u128 << k;
                    (num / sig as u128, (num % sig as u128) as u64)
                };
                self.round_pack(sign, q, -(k as i32) - e, r != 0)
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

    #[inline]
    pub fn lt(self, a: u64, b: u64) -> bool {
        match (self.order_key(a), self.order_key(b)) {
            (Some(ka), Some(kb)) => ka < kb,
            _ => false,
        }
    }

    #[inline]
    pub fn is_nan(self, a: u64) -> bool {
        self.exp_field(a) == self.exp_ones() && a & self.frac_mask() != 0
    }
}
