//! The catalogue's float formats as rust-hdl operator types: one module a format, each
//! holding the same names (`Add`, `Sub`, `Mul`, `Recip`, `Lt`, `FromF32`, `ToF32`, `WIDTH`,
//! `FORMAT`, `NAME`) so pipelines can be written over `formats::<name>`.
//!
//! rust-hdl cannot compute widths from generic parameters, so every derived width is a
//! parameter of the operator; `float_format!` computes them from (exp, man) once.

/// Per-format `max_stages(op)` and `rtl(op, stages)` over the module's operator types:
/// every format module (float or fixed) invokes it after defining them.
macro_rules! operator_table {
    () => {
        /// Maximum pipeline stages of `op` in this format.
        pub fn max_stages(op: $crate::operator::Op) -> usize {
            use $crate::operator::{Op, Operator};
            match op {
                Op::Add => <Add as Operator>::max_stages(),
                Op::Sub => <Sub as Operator>::max_stages(),
                Op::Mul => <Mul as Operator>::max_stages(),
                Op::Recip => <Recip as Operator>::max_stages(),
                Op::Lt => <Lt as Operator>::max_stages(),
                Op::FromF32 => <FromF32 as Operator>::max_stages(),
                Op::ToF32 => <ToF32 as Operator>::max_stages(),
            }
        }

        /// Verilog and port widths of `op` in this format with `stages` registers.
        pub fn rtl(
            op: $crate::operator::Op,
            stages: usize,
        ) -> Result<$crate::verilog::OperatorRtl, $crate::operator::OperatorError> {
            use $crate::operator::Op;
            use $crate::verilog::operator_verilog;
            let max = max_stages(op);
            if stages > max {
                return Err($crate::operator::OperatorError::TooManyStages {
                    format: NAME.to_string(),
                    op,
                    stages,
                    max,
                });
            }
            Ok(match op {
                Op::Add => operator_verilog::<Add>(stages),
                Op::Sub => operator_verilog::<Sub>(stages),
                Op::Mul => operator_verilog::<Mul>(stages),
                Op::Recip => operator_verilog::<Recip>(stages),
                Op::Lt => operator_verilog::<Lt>(stages),
                Op::FromF32 => operator_verilog::<FromF32>(stages),
                Op::ToF32 => operator_verilog::<ToF32>(stages),
            })
        }

        // The MT lane over these operators (`MtLane`, `mt_lane_verilog`).
        $crate::mt::mt_lane!();
    };
}
pub(crate) use operator_table;

/// `float_format!(name, exp = E, man = M)` defines `pub mod name` with the operator types.
macro_rules! float_format {
    ($name:ident, exp = $e:literal, man = $m:literal) => {
        pub mod $name {
            use crate::float::*;
            /// Catalogue name of the format (`hw_model::catalogue::lookup`).
            pub const NAME: &str = stringify!($name);
            pub const WIDTH: usize = 1 + $e + $m;
            pub const FORMAT: hw_model::Format = hw_model::Format::Float { exp: $e, man: $m };
            /// fp32 itself: converting an fp32 word only flushes a subnormal to ±0 and makes a
            /// NaN canonical, which every operator does to its inputs anyway, and every
            /// operator's result is already such a word (SPEC in `hw_model::format`), so the MT
            /// lane feeds the words to its operators and its results out unconverted (no
            /// from_f32 or to_f32 stage).
            pub const RAW_FP32: bool = $e == 8 && $m == 23;
            // Width parameters, in the order the operators take them (see their docs):
            // W = 1+E+M, S = M+1, X = E+2 (signed exponent), A = M+4, A1 = M+5.
            pub type Add = FloatAdd<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $e + 2 }, { $m + 4 }, { $m + 5 }, false>;
            pub type Sub = FloatAdd<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $e + 2 }, { $m + 4 }, { $m + 5 }, true>;
            pub type Mul = FloatMul<$e, $m, { 1 + $e + $m }, { $m + 1 }, { 2 * $m + 2 }, { $e + 2 }>;
            // Recip: the table and product widths of `float::recip` (its docs).
            pub type Recip = FloatRecip<$e, $m, { 1 + $e + $m }, { $m + 1 }, { $e + 2 },
                { recip::index_bits($m) }, { recip::d_bits($m) }, { recip::y_bits($m) },
                { recip::b_bits($m) }, { recip::c_bits($m) }, { 2 * recip::d_bits($m) },
                { recip::square_bits($m) }, { recip::b_bits($m) + recip::d_bits($m) },
                { recip::c_bits($m) + recip::square_bits($m) }, { 2 * $m + 2 }>;
            pub type Lt = FloatLt<$e, $m, { 1 + $e + $m }, { $m + 1 }>;
            // FromF32: X = 10, the signed range of fp32's exponent.
            pub type FromF32 = FloatFromF32<$e, $m, { 1 + $e + $m }, { $m + 1 }, 10>;
            pub type ToF32 = FloatToF32<$e, $m, { 1 + $e + $m }, { $m + 1 }>;
            $crate::formats::operator_table!();
        }
    };
}

float_format!(fp32, exp = 8, man = 23);
float_format!(fp24, exp = 8, man = 15);
float_format!(bf16, exp = 8, man = 7);
float_format!(fp16, exp = 5, man = 10);

// The fixed-point formats (`fixed_format!` is in `crate::fixed`).
crate::fixed::fixed_format!(fx16_10, int = 10, frac = 6, Trn, Wrap);
crate::fixed::fixed_format!(fx16_10_rnd_sat, int = 10, frac = 6, Rnd, Sat);
crate::fixed::fixed_format!(fx16_13, int = 13, frac = 3, Trn, Wrap);
crate::fixed::fixed_format!(fx16_13_rnd_sat, int = 13, frac = 3, Rnd, Sat);
crate::fixed::fixed_format!(fx21_12, int = 12, frac = 9, Trn, Wrap);
crate::fixed::fixed_format!(fx21_12_rnd_sat, int = 12, frac = 9, Rnd, Sat);
crate::fixed::fixed_format!(fx25_10, int = 10, frac = 15, Trn, Wrap);
crate::fixed::fixed_format!(fx25_10_rnd_sat, int = 10, frac = 15, Rnd, Sat);
crate::fixed::fixed_format!(fx32_16, int = 16, frac = 16, Trn, Wrap);
crate::fixed::fixed_format!(fx32_16_rnd_sat, int = 16, frac = 16, Rnd, Sat);
crate::fixed::fixed_format!(fx32_20, int = 20, frac = 12, Trn, Wrap);
crate::fixed::fixed_format!(fx32_20_rnd_sat, int = 20, frac = 12, Rnd, Sat);

/// Calls `$callback!(fp32, fp24, …)` with every catalogue format that has rust-hdl
/// operators: the one list that the dispatch below and the accelerator tops expand.
macro_rules! with_formats {
    ($callback:ident) => {
        $callback!(
            fp32,
            fp24,
            bf16,
            fp16,
            fx16_10,
            fx16_10_rnd_sat,
            fx16_13,
            fx16_13_rnd_sat,
            fx21_12,
            fx21_12_rnd_sat,
            fx25_10,
            fx25_10_rnd_sat,
            fx32_16,
            fx32_16_rnd_sat,
            fx32_20,
            fx32_20_rnd_sat,
        );
    };
}
pub(crate) use with_formats;

macro_rules! dispatch {
    ($($name:ident),* $(,)?) => {
        /// Names of the formats that have rust-hdl operators.
        pub const NAMES: &[&str] = &[$($name::NAME),*];

        /// Verilog of `op` in the catalogue format `format` with `stages` pipeline registers.
        pub fn rtl(format: &str, op: crate::operator::Op, stages: usize) -> Result<crate::verilog::OperatorRtl, crate::operator::OperatorError> {
            match format {
                $($name::NAME => $name::rtl(op, stages),)*
                _ => Err(crate::operator::OperatorError::UnknownFormat(format.to_string())),
            }
        }

        /// Whether the MT lane of `format` takes and gives fp32 words unconverted (`RAW_FP32`).
        pub fn raw_fp32(format: &str) -> Result<bool, crate::operator::OperatorError> {
            match format {
                $($name::NAME => Ok($name::RAW_FP32),)*
                _ => Err(crate::operator::OperatorError::UnknownFormat(format.to_string())),
            }
        }

        /// Maximum pipeline stages of `op` in the catalogue format `format`.
        pub fn max_stages(format: &str, op: crate::operator::Op) -> Result<usize, crate::operator::OperatorError> {
            Ok(match format {
                $($name::NAME => $name::max_stages(op),)*
                _ => return Err(crate::operator::OperatorError::UnknownFormat(format.to_string())),
            })
        }
    };
}

with_formats!(dispatch);

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    /// Specials and edges of fp32, mixed into the random operands.
    const EDGES: [u32; 10] = [
        0,
        0x8000_0000,
        1,
        0x007f_ffff,
        0x0080_0000,
        0x3f80_0000,
        0x7f7f_ffff,
        0x7f80_0000,
        0xff80_0000,
        0xffc0_0001,
    ];

    fn operand() -> impl Strategy<Value = u32> {
        prop_oneof![any::<u32>(), proptest::sample::select(&EDGES[..])]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        /// `RAW_FP32` rests on this: every result of fp32's operators is its own fp32 word
        /// (no subnormal, a NaN only as the canonical one), so to_f32 would change nothing.
        #[test]
        fn fp32_operator_results_are_their_own_fp32_words(a in operand(), b in operand()) {
            let f = super::fp32::FORMAT;
            let (a, b) = (u64::from(a), u64::from(b));
            for r in [f.add(a, b), f.sub(a, b), f.mul(a, b), f.recip(a)] {
                prop_assert_eq!(u64::from(f.to_f32(r).to_bits()), r, "{:#x} {:#x}", a, b);
            }
        }
    }
}
