//! The catalogue's formats as rust-hdl operator types: one module a format of
//! `hw_model::hw_formats!`, each holding the same names (`Add`, `Sub`, `Mul`, `Recip`, `Lt`, (float) `Sqrt`,
//! `FromF32`, `ToF32`, `WIDTH`, `FORMAT`, `NAME`) so pipelines can be written over
//! `formats::<name>`, and entry points ([`rtl`], [`max_stages`], [`raw_fp32`]) that take a
//! [`HwFormat`].
//!
//! rust-hdl cannot compute widths from generic parameters, so every derived width is a
//! parameter of the operator ([`crate::widths`] says why and names each); `float_format!`
//! fills them from [`FloatWidths::of`](crate::widths::FloatWidths::of), the fixed point ones
//! `crate::fixed::fixed_format!` from [`FixedWidths::of`](crate::widths::FixedWidths::of).

use hw_model::HwFormat;

use crate::operator::{Op, OperatorError};
use crate::verilog::OperatorRtl;

/// Per-format `max_stages(op)` and `rtl(op, stages)` over the module's operator types:
/// every format module invokes it after defining them, a float format with `float` (it has
/// `Sqrt`), a fixed-point one with `fixed` (it has none: `max_stages(Op::Sqrt)` is 0 and
/// `rtl(Op::Sqrt, _)` the error [`OperatorError::NotInFormat`]).
macro_rules! operator_table {
    (@sqrt_max float) => { <Sqrt as $crate::operator::Operator>::max_stages() };
    (@sqrt_max fixed) => { 0 };
    (@sqrt_missing float, $op:ident) => { None };
    (@sqrt_missing fixed, $op:ident) => {
        ($op == $crate::operator::Op::Sqrt).then(|| $crate::operator::OperatorError::NotInFormat {
            format: NAME.to_string(),
            op: $op,
        })
    };
    (@sqrt_rtl float, $stages:ident) => { $crate::verilog::operator_verilog::<Sqrt>($stages) };
    (@sqrt_rtl fixed, $stages:ident) => { unreachable!("refused above: no fixed-point square root") };
    ($kind:ident) => {
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
                Op::Sqrt => $crate::formats::operator_table!(@sqrt_max $kind),
            }
        }

        /// Verilog and port widths of `op` in this format with `stages` registers.
        pub fn rtl(
            op: $crate::operator::Op,
            stages: usize,
        ) -> Result<$crate::verilog::OperatorRtl, $crate::operator::OperatorError> {
            use $crate::operator::Op;
            use $crate::verilog::operator_verilog;
            if let Some(missing) = $crate::formats::operator_table!(@sqrt_missing $kind, op) {
                return Err(missing);
            }
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
                Op::Sqrt => $crate::formats::operator_table!(@sqrt_rtl $kind, stages),
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
            /// The operators' widths (`crate::widths`).
            const WIDTHS: crate::widths::FloatWidths = crate::widths::FloatWidths::of($e, $m);
            const RECIP: crate::widths::RecipWidths = WIDTHS.recip;
            const SQRT: crate::widths::SqrtWidths = WIDTHS.sqrt;
            pub type Add = FloatAdd<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, { WIDTHS.exponent }, { WIDTHS.aligned }, { WIDTHS.sum }, false>;
            pub type Sub = FloatAdd<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, { WIDTHS.exponent }, { WIDTHS.aligned }, { WIDTHS.sum }, true>;
            pub type Mul = FloatMul<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, { WIDTHS.product }, { WIDTHS.exponent }>;
            pub type Recip = FloatRecip<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, { WIDTHS.exponent },
                { RECIP.index }, { RECIP.d }, { RECIP.y }, { RECIP.b }, { RECIP.c }, { RECIP.d_squared },
                { RECIP.d_squared_kept }, { RECIP.b_product }, { RECIP.c_product }, { RECIP.rounding_product }>;
            pub type Sqrt = FloatSqrt<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, { WIDTHS.exponent },
                { SQRT.root }, { SQRT.remainder }, { SQRT.radicand }>;
            pub type Lt = FloatLt<$e, $m, { WIDTHS.word }, { WIDTHS.significand }>;
            // FromF32: X = 10, the signed range of fp32's exponent.
            pub type FromF32 = FloatFromF32<$e, $m, { WIDTHS.word }, { WIDTHS.significand }, 10>;
            pub type ToF32 = FloatToF32<$e, $m, { WIDTHS.word }, { WIDTHS.significand }>;
            $crate::formats::operator_table!(float);
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
