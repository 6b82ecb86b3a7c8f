//! The reference renderer's vector and matrix arithmetic, operation for operation.
//!
//! Every function here evaluates in exactly the order and precision the thesis' C++
//! (scratchapixel's `geometry.h`) did, because golden images must match bit for bit: plain
//! `f32` operations (Rust never fuses them), dot products summed left to right, and the two
//! places where C++ silently went through `double` (see `normalized`). Comparison helpers
//! mirror `std::min`/`std::max`, whose NaN and signed-zero behaviour differs from `f32::min`.

use std::ops::{Add, Mul, Neg, Sub};

use glam::Vec3;

use crate::scene::Mat44;

/// A 3-vector of `f32` with the reference's operations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V3 {
    pub x: f32,
    pub y: f32,
    pub z: f32,
}

impl V3 {
    pub const ZERO: V3 = V3 {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };

    pub const fn new(x: f32, y: f32, z: f32) -> V3 {
        V3 { x, y, z }
    }

    pub const fn from_array(a: [f32; 3]) -> V3 {
        V3 {
            x: a[0],
            y: a[1],
            z: a[2],
        }
    }

    pub const fn to_array(self) -> [f32; 3] {
        [self.x, self.y, self.z]
    }

    /// `x·x' + y·y'` then `+ z·z'`.
    #[inline]
    pub fn dot(self, o: V3) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// `(a.y·b.z − a.z·b.y, a.z·b.x − a.x·b.z, a.x·b.y − a.y·b.x)`.
    #[inline]
    pub fn cross(self, o: V3) -> V3 {
        V3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// Component-wise product.
    #[inline]
    pub fn mul_v(self, o: V3) -> V3 {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }

    /// Component-wise quotient by a scalar (`x / r`, not `x · (1/r)`).
    #[inline]
    pub fn div_s(self, r: f32) -> V3 {
        V3::new(self.x / r, self.y / r, self.z / r)
    }

    /// The reference's `normalize()`: n = x²+y²+z² in float; if n > 0, every component is
    /// multiplied by `float(1.0 / sqrt(double(n)))` (the C++ called the double `sqrt`).
    /// A zero or NaN length leaves the vector unchanged, as in C++.
    #[inline]
    pub fn normalized(self) -> V3 {
        let n = self.dot(self);
        if n > 0.0 {
            let factor = (1.0 / f64::from(n).sqrt()) as f32;
            self * factor
        } else {
            self
        }
    }
}

impl From<Vec3> for V3 {
    fn from(v: Vec3) -> V3 {
        V3::new(v.x, v.y, v.z)
    }
}

impl Add for V3 {
    type Output = V3;
    #[inline]
    fn add(self, o: V3) -> V3 {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for V3 {
    type Output = V3;
    #[inline]
    fn sub(self, o: V3) -> V3 {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for V3 {
    type Output = V3;
    #[inline]
    fn neg(self) -> V3 {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f32> for V3 {
    type Output = V3;
    #[inline]
    fn mul(self, r: f32) -> V3 {
        V3::new(self.x * r, self.y * r, self.z * r)
    }
}

/// `std::min(a, b)`: `b < a ? b : a`.
#[inline]
pub fn cpp_min(a: f32, b: f32) -> f32 {
    if b < a {
        b
    } else {
        a
    }
}

/// `std::max(a, b)`: `a < b ? b : a`.
#[inline]
pub fn cpp_max(a: f32, b: f32) -> f32 {
    if a < b {
        b
    } else {
        a
    }
}

/// The reference's `clamp(lo, hi, v) = std::max(lo, std::min(hi, v))` (NaN becomes `hi`).
#[inline]
pub fn clamp(lo: f32, hi: f32, v: f32) -> f32 {
    cpp_max(lo, cpp_min(hi, v))
}

/// `multVecMatrix`: the row vector (p, 1) times `m`, then divided by w.
pub fn mult_point(m: &Mat44, p: V3) -> V3 {
    let x = &m.0;
    let a = p.x * x[0][0] + p.y * x[1][0] + p.z * x[2][0] + x[3][0];
    let b = p.x * x[0][1] + p.y * x[1][1] + p.z * x[2][1] + x[3][1];
    let c = p.x * x[0][2] + p.y * x[1][2] + p.z * x[2][2] + x[3][2];
    let w = p.x * x[0][3] + p.y * x[1][3] + p.z * x[2][3] + x[3][3];
    V3::new(a / w, b / w, c / w)
}

/// `multDirMatrix`: the row vector (d, 0) times `m`, no translation, no divide.
pub fn mult_dir(m: &Mat44, d: V3) -> V3 {
    let x = &m.0;
    V3::new(
        d.x * x[0][0] + d.y * x[1][0] + d.z * x[2][0],
        d.x * x[0][1] + d.y * x[1][1] + d.z * x[2][1],
        d.x * x[0][2] + d.y * x[1][2] + d.z * x[2][2],
    )
}

pub fn transpose(m: &Mat44) -> Mat44 {
    let mut t = [[0.0f32; 4]; 4];
    for (i, row) in t.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = m.0[j][i];
        }
    }
    Mat44(t)
}

/// `Matrix44::inverse()`: Gauss-Jordan elimination with partial pivoting in `f32`, in the
/// reference's loop order. A singular matrix yields the identity, as the C++ returned.
pub fn inverse(m: &Mat44) -> Mat44 {
    let mut t = m.0;
    let mut s = Mat44::IDENTITY.0;

    // Forward elimination.
    for i in 0..3 {
        let mut pivot = i;
        let mut pivot_size = t[i][i].abs();
        for (j, row) in t.iter().enumerate().skip(i + 1) {
            let tmp = row[i].abs();
            if tmp > pivot_size {
                pivot = j;
                pivot_size = tmp;
            }
        }
        if pivot_size == 0.0 {
            return Mat44::IDENTITY;
        }
        if pivot != i {
            t.swap(i, pivot);
            s.swap(i, pivot);
        }
        for j in i + 1..4 {
            let f = t[j][i] / t[i][i];
            for k in 0..4 {
                t[j][k] -= f * t[i][k];
                s[j][k] -= f * s[i][k];
            }
        }
    }

    // Backward substitution.
    for i in (0..4).rev() {
        let f = t[i][i];
        if f == 0.0 {
            return Mat44::IDENTITY;
        }
        for j in 0..4 {
            t[i][j] /= f;
            s[i][j] /= f;
        }
        for j in 0..i {
            let f = t[j][i];
            for k in 0..4 {
                t[j][k] -= f * t[i][k];
                s[j][k] -= f * s[i][k];
            }
        }
    }
    Mat44(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mat_mul(a: &Mat44, b: &Mat44) -> [[f32; 4]; 4] {
        [0, 1, 2, 3].map(|i| [0, 1, 2, 3].map(|j| (0..4).map(|k| a.0[i][k] * b.0[k][j]).sum()))
    }

    #[test]
    fn inverse_times_matrix_is_identity() {
        // A rotation, scale and translation that needs pivoting (zero on the diagonal).
        let m = Mat44([
            [0.0, 2.0, 0.0, 0.0],
            [-3.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.5, 0.0],
            [4.0, -5.0, 6.0, 1.0],
        ]);
        let p = mat_mul(&m, &inverse(&m));
        for (i, row) in p.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-6, "({i},{j}) = {v}");
            }
        }
    }

    #[test]
    fn singular_matrix_inverts_to_identity() {
        let m = Mat44([
            [1.0, 2.0, 3.0, 0.0],
            [2.0, 4.0, 6.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]);
        assert_eq!(inverse(&m), Mat44::IDENTITY);
    }

    #[test]
    fn point_transform_divides_by_w_and_direction_ignores_translation() {
        let mut m = Mat44::IDENTITY;
        m.0[3] = [1.0, 2.0, 3.0, 2.0];
        assert_eq!(
            mult_point(&m, V3::new(1.0, 1.0, 1.0)),
            V3::new(1.0, 1.5, 2.0)
        );
        assert_eq!(mult_dir(&m, V3::new(1.0, 1.0, 1.0)), V3::new(1.0, 1.0, 1.0));
    }

    #[test]
    fn normalise_goes_through_double_reciprocal_square_root() {
        // Over many vectors the double route must differ somewhere from an all-float 1/sqrt,
        // and always equal the explicit formula.
        let mut differs = 0;
        for i in 1..2000u32 {
            let v = V3::new(i as f32 * 0.37, 1.0 + i as f32 * 0.011, -(i as f32).sqrt());
            let n = v.dot(v);
            let f = (1.0f64 / (n as f64).sqrt()) as f32;
            let got = v.normalized();
            assert_eq!(got, V3::new(v.x * f, v.y * f, v.z * f));
            if got != v * (1.0 / n.sqrt()) {
                differs += 1;
            }
        }
        assert!(differs > 0);
        assert_eq!(V3::ZERO.normalized(), V3::ZERO);
    }

    #[test]
    fn cpp_min_max_keep_the_std_semantics() {
        assert_eq!(cpp_max(0.0, f32::NAN), 0.0);
        assert!(cpp_max(f32::NAN, 1.0).is_nan());
        assert_eq!(clamp(0.0, 1.0, f32::NAN), 1.0);
        assert_eq!(clamp(0.0, 1.0, -2.0), 0.0);
        assert_eq!(clamp(0.0, 1.0, 0.25), 0.25);
        assert_eq!(cpp_max(0.0, -0.0).to_bits(), 0.0f32.to_bits());
    }
}
