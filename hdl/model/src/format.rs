//! The number formats and the operator set every format provides.
//!
//! SPEC (shared by the model, the rust-hdl operators and the MT pipeline):
//! Float { exp: E, man: M }: 1 sign bit, E exponent bits (bias 2^(E-1)-1), M fraction bits,
//!   IEEE-754 layout. Rounding: round to nearest, ties to even. Subnormals are flushed to
//!   zero on input (an operand whose exponent field is 0 is ±0, sign kept) and on output
//!   (tininess after rounding: the exact result is rounded to M+1 significant bits with an
//!   unbounded exponent; if that exponent is below the minimum normal exponent the result is
//!   ±0 with the exact result's sign). Overflow gives ±Inf. Any NaN operand, Inf−Inf, 0×Inf
//!   give the canonical NaN (sign 0, exponent all ones, fraction MSB only). recip(±0) = ±Inf,
//!   recip(±Inf) = ±0; recip is correctly rounded. Signed zeros follow IEEE (x + −x = +0).
//! Fixed { int: I, frac: F, quant, overflow }: W = I + F bits two's complement, I includes
//!   the sign bit (like ap_fixed<W, I>). Results are computed exactly, then quantised to F
//!   fraction bits (Trn: toward −∞; Rnd: to nearest, ties toward +∞), then brought into range
//!   (Wrap: keep the low W bits; Sat: clamp to [min, max]). recip(0) = max. From fp32: NaN →
//!   0, ±Inf → max/min (saturated whatever the overflow mode). To fp32: round to nearest even.
//! lt(a, b): a < b as real numbers; false if either is NaN; −0 == +0.
//!
//! See `float.rs` / `fixed.rs` for the implementations.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Quantisation (rounding) mode of a fixed-point format, as ap_fixed's AP_TRN / AP_RND.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Quant {
    /// Truncate toward minus infinity (AP_TRN).
    Trn,
    /// Round to nearest, ties toward plus infinity (AP_RND).
    Rnd,
}

/// Overflow mode of a fixed-point format, as ap_fixed's AP_WRAP / AP_SAT.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Overflow {
    Wrap,
    Sat,
}

/// A number format of the hardware datapath.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Format {
    Float { exp: u32, man: u32 },
    Fixed { int: u32, frac: u32, quant: Quant, overflow: Overflow },
}

#[derive(Debug, Error, PartialEq, Eq)]
pub enum FormatError {
    #[error("unknown format `{0}`; `rtfpga formats` lists the catalogue")]
    Unknown(String),
    #[error("impossible format `{name}`: {why}")]
    Impossible { name: String, why: String },
}
