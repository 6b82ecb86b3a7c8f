//! The shader core: shading programs (`hw_model::frame::shader`) run on a time-shared fp32
//! datapath, bit for bit `hw_model::frame::shader::interpret::run` for every thread.
//!
//! - [`alu`]: the datapath, an operation on two 3-lane operands a cycle, every operation
//!   retiring after the same latency.
//! - [`core`]: T threads in a barrel on the datapath, one instruction issued a cycle;
//!   thread starts in, pushed rays and settle records out.
//!
//! The instruction word's fields come from `isa::word`, the one table of them; the opcodes
//! from the model's encoder ([`opcode`]).

pub mod alu;
pub mod core;

use hw_model::frame::shader::isa::{word, Counter, Field, Instr, Op, PushKind, Src};
use rust_hdl::prelude::*;

/// Bits of an opcode (`isa::word::OPCODE`).
pub const OPCODE_BITS: usize = 5;
const _: () = assert!(word::OPCODE.1 as usize == OPCODE_BITS);

/// The operations the hardware tells apart, one of each kind (operands do not matter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Nop,
    Mov,
    Add,
    Mul,
    Max,
    Min,
    Recip,
    Sqrt,
    Fix,
    IAdd,
    Lt,
    Le,
    Nz,
    Out,
    Push,
    Count,
    End,
}

impl Kind {
    /// An operation of this kind.
    pub fn sample(self) -> Op {
        let (d, a, b) = (2, Src::reg(0), Src::reg(1));
        match self {
            Kind::Nop => Op::Nop,
            Kind::Mov => Op::Mov { d, a },
            Kind::Add => Op::Add { d, a, b },
            Kind::Mul => Op::Mul { d, a, b },
            Kind::Max => Op::Max { d, a, b },
            Kind::Min => Op::Min { d, a, b },
            Kind::Recip => Op::Recip { d, a },
            Kind::Sqrt => Op::Sqrt { d, a },
            Kind::Fix => Op::Fix { d, a },
            Kind::IAdd => Op::IAdd { d, a, b },
            Kind::Lt => Op::Lt { p: d, a, b },
            Kind::Le => Op::Le { p: d, a, b },
            Kind::Nz => Op::Nz { p: d, a },
            Kind::Out => Op::Out {
                f: Field::Origin,
                a,
            },
            Kind::Push => Op::Push {
                kind: PushKind::Shadow,
            },
            Kind::Count => Op::Count {
                counter: Counter::ZeroShadow,
            },
            Kind::End => Op::End { a },
        }
    }
}

/// The opcode of operations of `kind` in the instruction word, as the model encodes it.
pub fn opcode(kind: Kind) -> u64 {
    let w = Instr::new(kind.sample())
        .encode()
        .expect("every sample operation is within the machine");
    field(w, word::OPCODE)
}

/// A field (lowest bit, width) of an instruction word.
pub(crate) fn field(w: u64, (lo, width): (u32, u32)) -> u64 {
    (w >> lo) & ((1 << width) - 1)
}

/// [`opcode`] as a constant of the kernel.
pub(crate) fn opcode_constant(kind: Kind) -> Constant<Bits<OPCODE_BITS>> {
    Constant::new(opcode(kind).into())
}
