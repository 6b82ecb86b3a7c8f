//! Float operators over any (exp, man) format: one operator a file, sharing the unpacking and
//! rounding blocks. Semantics: the SPEC in `hw_model::format` (RNE, FTZ, canonical NaN).

pub mod add;
pub mod convert;
pub mod leading_zeros;
pub mod lt;
pub mod mul;
pub mod recip;
pub mod round;
pub mod sqrt;
pub mod sqrt_row;
pub mod unpack;

pub use add::FloatAdd;
pub use convert::{FloatFromF32, FloatToF32};
pub use lt::FloatLt;
pub use mul::FloatMul;
pub use recip::FloatRecip;
pub use sqrt::FloatSqrt;
