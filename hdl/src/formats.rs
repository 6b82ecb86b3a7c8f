//! The catalogue's float formats as rust-hdl operator types: one module a format, each
//! holding the same names (`Add`, `Sub`, `Mul`, `Recip`, `Lt`, `FromF32`, `ToF32`, `WIDTH`,
//! `FORMAT`, `NAME`) so pipelines can be written over `formats::<name>`.
//!
//! rust-hdl cannot compute widths from generic parameters, so every derived width is a
//! parameter of the operator; `float_format!` computes them from (exp, man) once.

/// `float_format!(name, exp = E, man = M)` defines `pub mod name` with the operator types.
macro_rules! float_format {
    ($name:ident, exp = $e:literal, man = $m:literal) => {
        pub mod $name {
            use crate::float::*;
            /// Catalogue name of the format (`hw_model::catalogue::lookup`).
            pub const NAME: &str = stringify!($name);
            pub const WIDTH: usize = 1 + $e + $m;
            pub const FORMAT: hw_model::Format = hw_model::Format::Float { exp: $e, man: $m };
            // Width parameters, in the order the operators take them (see their docs):
            // W = 1+E+M, S = M+1, S1 = M+2, X = E+2 (signed exponent), A = M+4, A1 = M+5.
            pub type Add = FloatAdd<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $m + 2 }, { $e + 2 }, { $m + 4 }, { $m + 5 }, false>;
            pub type Sub = FloatAdd<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $m + 2 }, { $e + 2 }, { $m + 4 }, { $m + 5 }, true>;
            pub type Mul = FloatMul<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $m + 2 }, { 2 * $m + 2 }, { $e + 2 }>;
            // Recip: R = M+2 (remainder), Q = M+3 (quotient bits).
            pub type Recip = FloatRecip<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $m + 2 }, { $e + 2 }, { $m + 2 }, { $m + 3 }>;
            pub type Lt = FloatLt<$e, $m, { 1 + $e + $m }, { $m + 1 }>;
            // FromF32: X = 10, the signed range of fp32's exponent.
            pub type FromF32 = FloatFromF32<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $m + 2 }, 10>;
            pub type ToF32 = FloatToF32<$e, $m, { 1 + $e + $m }, { $m + 1 }>;
        }
    };
}

float_format!(fp32, exp = 8, man = 23);
float_format!(fp24, exp = 8, man = 15);
float_format!(bf16, exp = 8, man = 7);
float_format!(fp16, exp = 5, man = 10);
