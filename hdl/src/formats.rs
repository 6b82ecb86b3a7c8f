//! The catalogue's formats as rust-hdl operator types: one module a format of
//! `hw_model::hw_formats!`, each holding the same names (`Add`, `Sub`, `Mul`, `Recip`, `Lt`,
//! `FromF32`, `ToF32`, `WIDTH`, `FORMAT`, `NAME`) so pipelines can be written over
//! `formats::<name>`, and entry points ([`rtl`], [`max_stages`], [`raw_fp32`]) that take a
//! [`HwFormat`].
//!
//! rust-hdl cannot compute widths from generic parameters, so every derived width is a
//! parameter of the operator; `float_format!` computes them from (exp, man) once, the fixed
//! point ones come from `crate::fixed::fixed_format!`.

use hw_model::HwFormat;

use crate::operator::{Op, OperatorError};
use crate::verilog::OperatorRtl;

/// Per-format `max_stages(op)` and `rtl(op, stages)` over the module's operator types:
/// every format module (float or fixed) invokes it after defining them.
macro_rules! operator_table {
    () => {
        /// The format as the rest of the toolkit names it.
        pub const HW: hw_model::HwFormat = hw_model::HwFormat::named(NAME);

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
            /// Catalogue name of the format (`hw_model::HwFormat`).
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

/// `format_modules!` over the `hw_model::hw_formats!` list: a module a format, and their
/// entry points in catalogue order ([`HwFormat::code`] indexes it).
macro_rules! format_modules {
    ($($name:ident: $kind:ident($($arg:tt),*), $description:literal;)*) => {
        $(format_module!($name, $kind($($arg),*));)*

        /// Every format module's entry points, in catalogue order ([`HwFormat::code`]
        /// indexes it).
        pub static TABLE: &[FormatOps] = &[$(FormatOps {
            name: $name::NAME,
            raw_fp32: $name::RAW_FP32,
            max_stages: $name::max_stages,
            rtl: $name::rtl,
        }),*];
    };
}

macro_rules! format_module {
    ($name:ident, float($e:literal, $m:literal)) => {
        float_format!($name, exp = $e, man = $m);
    };
    ($name:ident, fixed($w:literal, $i:literal, $quant:ident, $overflow:ident)) => {
        crate::fixed::fixed_format!($name, $w, $i, $quant, $overflow);
    };
}

/// What a format module offers, for dispatch on a [`HwFormat`].
pub struct FormatOps {
    /// The module's name, its format's catalogue name.
    pub name: &'static str,
    raw_fp32: bool,
    max_stages: fn(Op) -> usize,
    rtl: fn(Op, usize) -> Result<OperatorRtl, OperatorError>,
}

hw_model::hw_formats!(format_modules);

fn ops(format: HwFormat) -> &'static FormatOps {
    let ops = &TABLE[usize::from(format.code())];
    debug_assert_eq!(ops.name, format.name(), "TABLE is in catalogue order");
    ops
}

/// Verilog of `op` in `format` with `stages` pipeline registers.
pub fn rtl(format: HwFormat, op: Op, stages: usize) -> Result<OperatorRtl, OperatorError> {
    (ops(format).rtl)(op, stages)
}

/// Whether the MT lane of `format` takes and gives fp32 words unconverted (`RAW_FP32`).
pub fn raw_fp32(format: HwFormat) -> bool {
    ops(format).raw_fp32
}

/// Maximum pipeline stages of `op` in `format`.
pub fn max_stages(format: HwFormat, op: Op) -> usize {
    (ops(format).max_stages)(op)
}
