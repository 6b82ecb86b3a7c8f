//! Bit-accurate software model of the accelerator's arithmetic.
//!
//! A [`Format`] is either a float `(exp, man)` or a fixed-point `(int, frac)` format; values
//! travel as raw bit patterns in a `u64` (low `width()` bits). Every operator here is the
//! reference the rust-hdl operators and the Verilated hardware are checked against bit for
//! bit. No rust-hdl in this crate, so the renderer can use it cheaply.

pub mod catalogue;
mod fixed;
mod float;
pub mod format;
pub mod mt;
pub mod traversal;

pub use catalogue::{catalogue, lookup, HwFormat, NamedFormat};
pub use format::{Format, FormatError, Overflow, Quant};
pub use mt::{mt_model, MtQuery, MtResult};
