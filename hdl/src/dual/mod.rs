//! The block-floating-point dual-precision filter (docs/precision.md, "The block-floating-point
//! filter"), one block per file, each bit for bit its `hw_model::dual::bfp` function.

pub mod translate;
