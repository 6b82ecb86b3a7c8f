//! The shader core: shading programs (`hw_model::frame::shader`) run on a time-shared fp32
//! datapath, bit for bit `hw_model::frame::shader::interpret::run` for every thread.
//!
//! - [`alu`]: the datapath, an operation on two 3-lane operands a cycle, every operation
//!   retiring after the same latency.
//! - [`core`]: T threads in a barrel on the datapath, one instruction issued a cycle;
//!   thread starts in, pushed rays and settle records out.
//!
//! The instruction word's fields come from `isa::word`, the one table of them; the opcodes
//! from `isa::OpKind`.

pub mod alu;
pub mod core;

use hw_model::frame::shader::isa::{word, OpKind};
use rust_hdl::prelude::*;

/// Bits of an opcode (`isa::word::OPCODE`).
pub const OPCODE_BITS: usize = 5;
const _: () = assert!(word::OPCODE.1 as usize == OPCODE_BITS);

/// `kind`'s opcode as a constant of the kernel.
pub(crate) fn opcode_constant(kind: OpKind) -> Constant<Bits<OPCODE_BITS>> {
    Constant::new(kind.opcode().into())
}
