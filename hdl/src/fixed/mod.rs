//! Fixed-point operators over any ap_fixed<W, I> format: one operator a file, sharing the
//! quantisation (`round`) and overflow (`fit`) blocks. Semantics: the SPEC in
//! `hw_model::format` (two's complement; Trn/Rnd quantisation; Wrap/Sat overflow).
//!
//! The quantisation and overflow modes are `const bool` parameters (RND, SAT) of every
//! operator that can round or overflow; `fixed_format!` derives them from the format.

pub mod add;
pub mod convert;
pub mod division_row;
pub mod fit;
pub mod lt;
pub mod mul;
pub mod recip;
pub mod round;

pub use add::FixedAdd;
pub use convert::{FixedFromF32, FixedToF32};
pub use lt::FixedLt;
pub use mul::FixedMul;
pub use recip::FixedRecip;

/// `fixed_format!(name, W, I, Quant, Overflow)` defines `pub mod name` with the operator
/// types of ap_fixed<W, I> (`Quant`: Trn or Rnd, `Overflow`: Wrap or Sat, the variants of
/// `hw_model::Quant` / `hw_model::Overflow`), as `hw_model::hw_formats!` spells a format.
macro_rules! fixed_format {
    ($name:ident, $w:literal, $i:literal, $quant:ident, $overflow:ident) => {
        pub mod $name {
            use crate::fixed::*;
            /// Catalogue name of the format (`hw_model::HwFormat`).
            pub const NAME: &str = stringify!($name);
            pub const WIDTH: usize = $w;
            /// The MT lane converts fp32 inputs into fixed point and back (see `formats`).
            pub const RAW_FP32: bool = false;
            pub const FORMAT: hw_model::Format = hw_model::Format::Fixed {
                int: $i,
                frac: $w - $i,
                quant: hw_model::Quant::$quant,
                overflow: hw_model::Overflow::$overflow,
            };
            const RND: bool = matches!(hw_model::Quant::$quant, hw_model::Quant::Rnd);
            const SAT: bool = matches!(hw_model::Overflow::$overflow, hw_model::Overflow::Sat);
            /// The operators' widths (`crate::widths`).
            const WIDTHS: crate::widths::FixedWidths = crate::widths::FixedWidths::of($w, $i);
            pub type Add = FixedAdd<{ WIDTHS.word }, { WIDTHS.sum }, SAT, false>;
            pub type Sub = FixedAdd<{ WIDTHS.word }, { WIDTHS.sum }, SAT, true>;
            pub type Mul = FixedMul<{ WIDTHS.word }, { WIDTHS.frac }, { WIDTHS.product }, RND, SAT>;
            pub type Recip = FixedRecip<
                { WIDTHS.word },
                { WIDTHS.frac },
                { WIDTHS.quotient },
                { WIDTHS.signed_quotient },
                RND,
                SAT,
            >;
            pub type Lt = FixedLt<{ WIDTHS.word }>;
            pub type FromF32 = FixedFromF32<
                { WIDTHS.word },
                { WIDTHS.frac },
                { WIDTHS.from_f32_aligned },
                { WIDTHS.from_f32_magnitude },
                RND,
                SAT,
            >;
            pub type ToF32 =
                FixedToF32<{ WIDTHS.word }, { WIDTHS.frac }, { WIDTHS.to_f32_normalized }>;
            $crate::formats::operator_table!(fixed);
        }
    };
}
pub(crate) use fixed_format;
