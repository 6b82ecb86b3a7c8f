//! Two's-complement fixed point as ap_fixed<W, I>: exact result, then quantise, then overflow.

use crate::float::{FloatFormat, Unpacked};
use crate::format::{Arith, Overflow, Quant};

/// The layout of one fixed-point format: `int` integer bits (sign included), `frac` fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FixedFormat {
    pub int: u32,
    pub frac: u32,
    pub quant: Quant,
    pub overflow: Overflow,
}

/// Right shifts beyond this leave only the sign of a float-sized significand (< 2^53).
const SHIFT_CAP: u32 = 100;

impl FixedFormat {
    #[inline]
    fn width(self) -> u32 {
        self.int + self.frac
    }
    #[inline]
    fn mask(self) -> u64 {
        u64::MAX >> (64 - self.width())
    }
    #[inline]
    fn min(self) -> i64 {
        i64::MIN >> (64 - self.width())
    }
    #[inline]
    fn max(self) -> i64 {
        i64::MAX >> (64 - self.width())
    }

    /// The signed value (in units of 2^-frac) of the low `width` bits.
    #[inline]
    pub fn value(self, bits: u64) -> i64 {
        let unused = 64 - self.width();
        ((bits << unused) as i64) >> unused
    }

    /// Brings an exact integer (units of 2^-frac) into range: low W bits, or clamped.
    #[inline]
    fn fit(self, v: i128) -> u64 {
        let v = match self.overflow {
            Overflow::Wrap => v as u64,
            Overflow::Sat => v.clamp(self.min() as i128, self.max() as i128) as u64,
        };
        v & self.mask()
    }

    /// Quantises `floor(x) + rem/div` (0 ≤ rem < div) to an integer: Trn keeps the floor,
    /// Rnd adds one when the fraction is ≥ 1/2 (ties toward +∞).
    #[inline]
    fn quantise(self, floor: i128, rem: u128, div: u128) -> i128 {
        match self.quant {
            Quant::Trn => floor,
            Quant::Rnd => floor + (rem >= div - rem) as i128,
        }
    }

    /// `x / 2^sh` quantised.
    #[inline]
    fn quantise_shift(self, x: i128, sh: u32) -> i128 {
        if sh == 0 {
            return x;
        }
        let floor = x >> sh;
        let rem = (x - (floor << sh)) as u128;
        self.quantise(floor, rem, 1u128 << sh)
    }
}

impl Arith for FixedFormat {
    #[inline]
    fn add(self, a: u64, b: u64) -> u64 {
        self.fit(self.value(a) as i128 + self.value(b) as i128)
    }
    #[inline]
    fn sub(self, a: u64, b: u64) -> u64 {
        self.fit(self.value(a) as i128 - self.value(b) as i128)
    }
    #[inline]
    fn neg(self, a: u64) -> u64 {
        self.fit(-(self.value(a) as i128))
    }
    #[inline]
    fn mul(self, a: u64, b: u64) -> u64 {
        let product = self.value(a) as i128 * self.value(b) as i128;
        self.fit(self.quantise_shift(product, self.frac))
    }
    /// 1/x = 2^(2·frac) / X in units of 2^-frac; recip(0) = max.
    #[inline]
    fn recip(self, a: u64) -> u64 {
        let x = self.value(a) as i128;
        if x == 0 {
            return self.max() as u64 & self.mask();
        }
        // floor(N / x) with a positive divisor: N/x = (−N)/(−x).
        let (num, div) = if x > 0 {
            (1i128 << (2 * self.frac), x)
        } else {
            (-(1i128 << (2 * self.frac)), -x)
        };
        let floor = num.div_euclid(div);
        let rem = num.rem_euclid(div) as u128;
        self.fit(self.quantise(floor, rem, div as u128))
    }
    #[inline]
    fn lt(self, a: u64, b: u64) -> bool {
        self.value(a) < self.value(b)
    }
    /// From a float: NaN → 0, ±Inf → max/min, subnormals (flushed) → 0, else quantised and fitted.
    fn convert_in(self, src: FloatFormat, bits: u64) -> u64 {
        match src.unpack(bits) {
            Unpacked::Nan | Unpacked::Zero(_) => 0,
            Unpacked::Inf(s) => (if s { self.min() } else { self.max() }) as u64 & self.mask(),
            Unpacked::Finite { sign, sig, e } => {
                let signed = if sign { -(sig as i128) } else { sig as i128 };
                let k = e + self.frac as i32;
                if k >= 0 {
                    // Above 2^64 units the low W bits are all zero (Wrap) or the value clamps (Sat).
                    let shifted = if k > 64 {
                        signed.signum() << 64
                    } else {
                        signed << k
                    };
                    self.fit(shifted)
                } else {
                    let sh = (-k as u32).min(SHIFT_CAP);
                    self.fit(self.quantise_shift(signed, sh))
                }
            }
        }
    }
    /// To a float: the exact value rounded once (RNE) into `dst`.
    fn convert_out(self, dst: FloatFormat, bits: u64) -> u64 {
        let x = self.value(bits);
        if x == 0 {
            return dst.zero(false);
        }
        dst.round_pack(x < 0, x.unsigned_abs() as u128, -(self.frac as i32), false)
    }

    #[inline]
    fn is_nan(self, _a: u64) -> bool {
        false
    }
}
