//! fp32 as the hardware computes with it ([`crate::Format::FP32`]: round to nearest even,
//! subnormals flushed, correctly rounded reciprocal and square root), as a scalar type with
//! operators, and 3-vectors of it in the reference renderer's operation order
//! (`sw_renderer::math::V3`): what the frame's shading is written in.
//!
//! Every operation here is one hardware operator: `+`, `−`, `×`, [`Fp32::recip`],
//! [`Fp32::sqrt`], comparisons and sign changes. There is no division: `a / b` is written
//! `a × recip(b)` (two roundings) where a formula needs it.

use std::ops::{Add, Mul, Neg, Sub};

use crate::float::FloatFormat;
use crate::format::Arith;

const F32: FloatFormat = FloatFormat::F32;

/// An fp32 value: its bits. Equality is bit equality (NaN == NaN, −0 ≠ +0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Fp32(u32);

impl Fp32 {
    pub const ZERO: Fp32 = Fp32(0);
    pub const ONE: Fp32 = Fp32(0x3f80_0000);
    /// The largest finite value (the reference's `kInfinity`, an unbounded ray's `t_max`).
    pub const MAX: Fp32 = Fp32(0x7f7f_ffff);

    /// `x` as the hardware reads it: a subnormal is ±0, a NaN the canonical NaN.
    #[inline]
    pub fn new(x: f32) -> Fp32 {
        Fp32(F32.convert_from(F32, x.to_bits() as u64) as u32)
    }

    #[inline]
    pub fn from_bits(bits: u32) -> Fp32 {
        Fp32::new(f32::from_bits(bits))
    }

    #[inline]
    pub fn bits(self) -> u32 {
        self.0
    }

    #[inline]
    pub fn f32(self) -> f32 {
        f32::from_bits(self.0)
    }

    /// The exact value of a small integer (≤ 2^24).
    #[inline]
    pub fn of_int(i: u32) -> Fp32 {
        debug_assert!(i <= 1 << 24);
        Fp32::new(i as f32)
    }

    /// Correctly rounded 1/x.
    #[inline]
    pub fn recip(self) -> Fp32 {
        Fp32(F32.recip(self.0 as u64) as u32)
    }

    /// Correctly rounded √x (NaN below zero; √−0 = −0).
    #[inline]
    pub fn sqrt(self) -> Fp32 {
        Fp32(F32.sqrt(self.0 as u64) as u32)
    }

    /// `self < o` as real numbers (false with a NaN).
    #[inline]
    pub fn lt(self, o: Fp32) -> bool {
        F32.lt(self.0 as u64, o.0 as u64)
    }

    /// `self <= o` as real numbers (false with a NaN; −0 equals +0).
    #[inline]
    pub fn le(self, o: Fp32) -> bool {
        !o.lt(self) && !self.is_nan() && !o.is_nan()
    }

    #[inline]
    pub fn is_nan(self) -> bool {
        F32.is_nan(self.0 as u64)
    }

    /// Finite: neither infinite nor NaN.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.0 & 0x7f80_0000 != 0x7f80_0000
    }

    /// The sign bit cleared.
    #[inline]
    pub fn abs(self) -> Fp32 {
        Fp32(self.0 & 0x7fff_ffff)
    }

    /// `std::max(a, b)`: `a < b ? b : a` (so `max(0, NaN)` is 0, as in the reference).
    #[inline]
    pub fn max(self, b: Fp32) -> Fp32 {
        if self.lt(b) {
            b
        } else {
            self
        }
    }

    /// `std::min(a, b)`: `b < a ? b : a`.
    #[inline]
    pub fn min(self, b: Fp32) -> Fp32 {
        if b.lt(self) {
            b
        } else {
            self
        }
    }

    /// The reference's `clamp(lo, hi, v) = max(lo, min(hi, v))`.
    #[inline]
    pub fn clamp(self, lo: Fp32, hi: Fp32) -> Fp32 {
        lo.max(hi.min(self))
    }

    /// `x^n` for an integer `n` by square-and-multiply from the exponent's leading bit:
    /// r = x; for each lower bit, r = r·r, then r = r·x if the bit is set (x^0 = 1). For n = 10
    /// (0b1010): x, x², x⁴·x, x¹⁰; at most 2·(bits of n − 1) multiplies.
    pub fn powi(self, n: u32) -> Fp32 {
        if n == 0 {
            return Fp32::ONE;
        }
        let mut r = self;
        for bit in (0..31 - n.leading_zeros()).rev() {
            r = r * r;
            if n >> bit & 1 == 1 {
                r = r * self;
            }
        }
        r
    }
}

impl Add for Fp32 {
    type Output = Fp32;
    #[inline]
    fn add(self, o: Fp32) -> Fp32 {
        Fp32(F32.add(self.0 as u64, o.0 as u64) as u32)
    }
}

impl Sub for Fp32 {
    type Output = Fp32;
    #[inline]
    fn sub(self, o: Fp32) -> Fp32 {
        Fp32(F32.sub(self.0 as u64, o.0 as u64) as u32)
    }
}

impl Mul for Fp32 {
    type Output = Fp32;
    #[inline]
    fn mul(self, o: Fp32) -> Fp32 {
        Fp32(F32.mul(self.0 as u64, o.0 as u64) as u32)
    }
}

impl Neg for Fp32 {
    type Output = Fp32;
    /// The sign bit flipped (a wire swap).
    #[inline]
    fn neg(self) -> Fp32 {
        Fp32(self.0 ^ 0x8000_0000)
    }
}

/// A 3-vector (a point, a direction, an RGB colour) of [`Fp32`], with the reference's
/// operation order: dot products summed left to right, component-wise products.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vec3 {
    pub x: Fp32,
    pub y: Fp32,
    pub z: Fp32,
}

impl Vec3 {
    pub const ZERO: Vec3 = Vec3 {
        x: Fp32::ZERO,
        y: Fp32::ZERO,
        z: Fp32::ZERO,
    };

    pub fn new(x: Fp32, y: Fp32, z: Fp32) -> Vec3 {
        Vec3 { x, y, z }
    }

    /// Every component read by [`Fp32::new`].
    pub fn of(v: [f32; 3]) -> Vec3 {
        Vec3::new(Fp32::new(v[0]), Fp32::new(v[1]), Fp32::new(v[2]))
    }

    pub fn to_f32(self) -> [f32; 3] {
        [self.x.f32(), self.y.f32(), self.z.f32()]
    }

    pub fn components(self) -> [Fp32; 3] {
        [self.x, self.y, self.z]
    }

    /// `x·x' + y·y'`, then `+ z·z'`.
    #[inline]
    pub fn dot(self, o: Vec3) -> Fp32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Component-wise product.
    #[inline]
    pub fn mul_v(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }

    /// Every component times `s`.
    #[inline]
    pub fn scale(self, s: Fp32) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }

    /// n = x² + y² + z² (as [`Vec3::dot`]); if n > 0 every component times
    /// recip(sqrt(n)), else the vector unchanged (as the reference's `normalize`).
    #[inline]
    pub fn normalized(self) -> Vec3 {
        let n = self.dot(self);
        if Fp32::ZERO.lt(n) {
            self.scale(n.sqrt().recip())
        } else {
            self
        }
    }

    /// `I − N·(2·(I·N))`, given `I·N` (computed once where a formula uses it twice).
    #[inline]
    pub fn reflect_with(self, n: Vec3, i_dot_n: Fp32) -> Vec3 {
        self - n.scale(Fp32::new(2.0) * i_dot_n)
    }

    pub fn all_finite(self) -> bool {
        self.components().iter().all(|c| c.is_finite())
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline]
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline]
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powi_is_square_and_multiply_in_fp32() {
        let x = Fp32::new(0.9);
        assert_eq!(x.powi(0), Fp32::ONE);
        assert_eq!(x.powi(1), x);
        // 10 = 0b1010: x, x², x⁵ = x⁴·x, x¹⁰ = x⁵·x⁵; each product rounded as f32 does.
        let (x2, x4) = (0.9f32 * 0.9, (0.9f32 * 0.9) * (0.9 * 0.9));
        let x5 = x4 * 0.9;
        assert_eq!(x.powi(10).f32(), x5 * x5);
        assert_eq!(x.powi(2).f32(), x2);
        assert!((x.powi(20).f32() - 0.9f32.powi(20)).abs() < 1e-6);
        assert_eq!(Fp32::ZERO.powi(10), Fp32::ZERO);
    }

    #[test]
    fn max_min_keep_the_std_semantics() {
        let nan = Fp32::new(f32::NAN);
        assert_eq!(Fp32::ZERO.max(nan), Fp32::ZERO);
        assert!(nan.max(Fp32::ONE).is_nan());
        assert_eq!(nan.clamp(Fp32::ZERO, Fp32::ONE), Fp32::ONE);
        assert_eq!(Fp32::new(-2.0).clamp(Fp32::ZERO, Fp32::ONE), Fp32::ZERO);
    }

    #[test]
    fn normalise_leaves_a_zero_vector_and_scales_by_the_reciprocal_root() {
        assert_eq!(Vec3::ZERO.normalized(), Vec3::ZERO);
        let v = Vec3::of([3.0, 0.0, 4.0]).normalized();
        // recip(sqrt(25)) = recip(5) = 0.2 rounded once; 3·0.2 and 4·0.2 rounded once.
        assert_eq!(v.to_f32(), [3.0 * 0.2f32, 0.0, 4.0 * 0.2f32]);
        assert_eq!(Fp32::new(1e-40), Fp32::ZERO, "subnormals read as zero");
    }
}
