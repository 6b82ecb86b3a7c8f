//! The block-floating-point dual-precision filter (docs/precision.md, "The block-floating-point
//! filter"), one block per file, each bit for bit its `hw_model::dual::bfp` function; and the
//! Plücker filter ("The Plücker filter"; `align_add`, `edge_value`, `plucker` its datapath,
//! `s_bound`, `plucker_margin`, and `plucker_filter` the whole lane with bfp's `decide`), bit
//! for bit `hw_model::dual::plucker`.

pub mod add_down;
pub mod align_add;
pub mod bit_length;
pub mod cross_block;
pub mod decide;
pub mod dot;
pub mod edge_value;
pub mod filter;
pub mod margin;
pub mod pair;
pub mod plucker;
pub mod plucker_filter;
pub mod plucker_margin;
pub mod plucker_operands;
pub mod pow2_lt;
pub mod round;
pub mod s_bound;
pub mod short_lt;
pub mod sign_decide;
pub mod slot;
pub mod slot_filter;
pub mod to_block;
pub mod translate;

/// The mantissa width W the filter is built at: bfp18/fp32, the width docs/precision.md
/// measures and costs (`hw_model::dual::bfp::widths` gives each vector's from it).
pub const WIDTH: u32 = 18;
