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
//! Refinements where the text above was silent (added by the model, same meaning elsewhere):
//! - Operators assume a format that passed `validate()`. Bits above `width()` in an operand
//!   must be 0; results always have them 0.
//! - Float neg flips the sign bit and nothing else (NaN, Inf and zero patterns included), as
//!   a wire swap does; fixed neg is the exact −x, then the overflow mode (−min wraps to min or
//!   saturates to max).
//! - Float from/to fp32 is one RNE rounding with the same rules as an operation: a subnormal
//!   fp32 input is ±0, a result below the minimum normal after rounding is ±0, NaN gives the
//!   target's canonical NaN (fp32: 0x7FC0_0000).
//! - Fixed from fp32: a subnormal fp32 input is flushed to 0 like every other fp32 input;
//!   finite values are quantised with the format's mode, then brought into range with its
//!   overflow mode (only ±Inf always saturates). recip: the exact 1/x quantised, then fitted.
//! - lt on floats: a subnormal operand is ±0, so it equals zero.
//!
//! See `float.rs` / `fixed.rs` for the implementations.

use std::fmt;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::fixed::FixedFormat;
use crate::float::FloatFormat;

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
    Float {
        exp: u32,
        man: u32,
    },
    Fixed {
        int: u32,
        frac: u32,
        quant: Quant,
        overflow: Overflow,
    },
}

#[derive(Debug, Error, PartialEq, Eq)]
pub enum FormatError {
    #[error(
        "unknown format `{0}`: expected a catalogue name ({}; `rtfpga formats`) or a generic spelling such as e8m14 or fx<24,8>",
        crate::catalogue::names()
    )]
    Unknown(String),
    #[error("impossible format `{name}`: {why}")]
    Impossible { name: String, why: String },
    #[error(
        "format `{name}` has no hardware operators; the hardware formats are {} (`rtfpga formats`)",
        crate::catalogue::names()
    )]
    NoHardware { name: String },
}

impl std::str::FromStr for Format {
    type Err = FormatError;

    /// [`crate::lookup`]: a catalogue name or a generic spelling.
    fn from_str(s: &str) -> Result<Self, FormatError> {
        crate::lookup(s)
    }
}

impl Format {
    /// fp32 as the hardware computes it (round to nearest even, subnormals flushed).
    pub const FP32: Format = Format::Float { exp: 8, man: 23 };

    /// Total bits of a value.
    #[inline]
    pub const fn width(&self) -> u32 {
        match *self {
            Format::Float { exp, man } => 1 + exp + man,
            Format::Fixed { int, frac, .. } => int + frac,
        }
    }

    /// Rejects formats no operator can implement.
    pub fn validate(&self) -> Result<(), FormatError> {
        let why = match *self {
            Format::Float { exp, .. } if !(2..=11).contains(&exp) => {
                format!("{exp} exponent bits; a float needs 2 to 11")
            }
            Format::Float { man, .. } if !(1..=52).contains(&man) => {
                format!("{man} fraction bits; a float needs 1 to 52")
            }
            Format::Fixed { int: 0, .. } => "0 integer bits; the sign needs at least 1".to_string(),
            Format::Fixed { int, frac, .. } if !(2..=64).contains(&(int as u64 + frac as u64)) => {
                format!(
                    "{} bits in total; a fixed-point format needs 2 to 64",
                    int as u64 + frac as u64
                )
            }
            _ => return Ok(()),
        };
        Err(FormatError::Impossible {
            name: self.to_string(),
            why,
        })
    }

    #[inline]
    pub fn from_f32(&self, x: f32) -> u64 {
        with_arith!(self, f => f.convert_in_f32(x))
    }
    #[inline]
    pub fn to_f32(&self, bits: u64) -> f32 {
        with_arith!(self, f => f.convert_out_f32(bits))
    }
    /// From f64 (FTZ on input, one rounding): for tests and constants.
    pub fn from_f64(&self, x: f64) -> u64 {
        with_arith!(self, f => f.convert_in(FloatFormat::F64, x.to_bits()))
    }
    /// To f64: exact for every valid format.
    pub fn to_f64(&self, bits: u64) -> f64 {
        f64::from_bits(with_arith!(self, f => f.convert_out(FloatFormat::F64, bits)))
    }
    #[inline]
    pub fn add(&self, a: u64, b: u64) -> u64 {
        with_arith!(self, f => f.add(a, b))
    }
    #[inline]
    pub fn sub(&self, a: u64, b: u64) -> u64 {
        with_arith!(self, f => f.sub(a, b))
    }
    #[inline]
    pub fn mul(&self, a: u64, b: u64) -> u64 {
        with_arith!(self, f => f.mul(a, b))
    }
    #[inline]
    pub fn recip(&self, a: u64) -> u64 {
        with_arith!(self, f => f.recip(a))
    }
    /// Correctly rounded square root (`FloatFormat::sqrt`: the frame unit's normalisation);
    /// `None` in a fixed-point format, which has no square root.
    #[inline]
    pub fn sqrt(&self, a: u64) -> Option<u64> {
        match self.kind() {
            Kind::Float(f) => Some(f.sqrt(a)),
            Kind::Fixed(_) => None,
        }
    }
    #[inline]
    pub fn neg(&self, a: u64) -> u64 {
        with_arith!(self, f => f.neg(a))
    }
    #[inline]
    pub fn lt(&self, a: u64, b: u64) -> bool {
        with_arith!(self, f => f.lt(a, b))
    }
    #[inline]
    pub fn is_nan(&self, a: u64) -> bool {
        with_arith!(self, f => f.is_nan(a))
    }

    #[inline]
    pub(crate) fn kind(&self) -> Kind {
        match *self {
            Format::Float { exp, man } => Kind::Float(FloatFormat { exp, man }),
            Format::Fixed {
                int,
                frac,
                quant,
                overflow,
            } => Kind::Fixed(FixedFormat {
                int,
                frac,
                quant,
                overflow,
            }),
        }
    }
}

/// The operator set every kind of format implements (the SPEC above), on raw bits. Generic
/// code over it (the MT datapath) is compiled once per kind, without per-operation dispatch.
pub(crate) trait Arith: Copy {
    fn add(self, a: u64, b: u64) -> u64;
    fn sub(self, a: u64, b: u64) -> u64;
    fn mul(self, a: u64, b: u64) -> u64;
    fn recip(self, a: u64) -> u64;
    fn neg(self, a: u64) -> u64;
    fn lt(self, a: u64, b: u64) -> bool;
    fn is_nan(self, a: u64) -> bool;
    /// From a float format's bits, with the conversion rules of the SPEC.
    fn convert_in(self, src: FloatFormat, bits: u64) -> u64;
    /// To a float format's bits, one RNE rounding.
    fn convert_out(self, dst: FloatFormat, bits: u64) -> u64;

    #[inline]
    fn convert_in_f32(self, x: f32) -> u64 {
        self.convert_in(FloatFormat::F32, x.to_bits() as u64)
    }
    #[inline]
    fn convert_out_f32(self, bits: u64) -> f32 {
        f32::from_bits(self.convert_out(FloatFormat::F32, bits) as u32)
    }
}

/// Runs `$body` with `$f` bound to the [`Arith`] implementation of a [`Format`].
macro_rules! with_arith {
    ($format:expr, $f:ident => $body:expr) => {
        match $format.kind() {
            $crate::format::Kind::Float($f) => $body,
            $crate::format::Kind::Fixed($f) => $body,
        }
    };
}
pub(crate) use with_arith;

/// The implementation behind a [`Format`].
pub(crate) enum Kind {
    Float(FloatFormat),
    Fixed(FixedFormat),
}

/// The generic spelling `lookup` accepts: `e8m23`, `fx<16,10>`, `fx<16,10>_rnd_sat`.
impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Format::Float { exp, man } => write!(f, "e{exp}m{man}"),
            Format::Fixed {
                int,
                frac,
                quant,
                overflow,
            } => {
                write!(f, "fx<{},{}>", int as u64 + frac as u64, int)?;
                if quant == Quant::Rnd {
                    f.write_str("_rnd")?;
                }
                if overflow == Overflow::Sat {
                    f.write_str("_sat")?;
                }
                Ok(())
            }
        }
    }
}
