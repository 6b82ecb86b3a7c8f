//! The shader core's instruction set: what a shading program is made of, and its 64-bit
//! instruction word (one table of fields, [`Instr::encode`] and [`Instr::decode`]).
//!
//! A program runs once per shaded ray as a *thread*: straight-line code from the entry point
//! of the ray's material (or the miss entry) to `End`, no branches. Conditions are
//! predicates: every instruction names one ([`Pred`]), and an instruction whose predicate is
//! false does nothing. The machine is 3 lanes wide, fp32 (`crate::fp32`, the hardware's
//! rounding): a register holds a [`Word3`], three 32-bit words, usually a vector or an RGB
//! colour; scalars live in lane x. Every source operand selects each lane's component
//! (a swizzle: `Src::broadcast(r, 0)` is r.xxx, how a scalar scales a vector and how a dot
//! product's partial sums meet), and can clear (`abs`) then flip (`neg`) each word's bit 31.
//!
//! At a thread's start: registers r0 = ray origin, r1 = ray direction, r2 = the ray's weight,
//! r3 = (t, u, v) of its hit, r4..r6 = the hit triangle's corner normals n0, n1, n2 (r3..r6
//! are zero for a miss); [`PAST_DEPTH`] is true when the ray's spawned cast rays would be
//! deeper than the scene's maximum depth. Other registers and predicates are unspecified
//! until written (the interpreter starts them at zero and false).
//!
//! Constants: one memory of [`CONSTANTS`] [`Word3`]s loaded with the scene. `Const(k)` reads
//! entry k; `MatConst(k)` reads entry `material · MATERIAL_STRIDE + k` of the thread's
//! material (the hit triangle's object), so one program serves every material of a kind.

use thiserror::Error;

/// A register's contents: three 32-bit words (x, y, z; r, g, b).
pub type Word3 = [u32; 3];

/// Registers per thread.
pub const REGISTERS: usize = 32;
/// Predicates per thread; p0 is always true.
pub const PREDICATES: usize = 8;
/// The predicate that is true when the ray's spawned reflection and refraction rays would be
/// deeper than the maximum depth (depth + 1 > max_depth): set by the core at a thread's start,
/// read-only.
pub const PAST_DEPTH: u8 = 1;
/// Entries of the constant memory.
pub const CONSTANTS: usize = 512;
/// Constant entries per material: `MatConst(k)`, k < `MATERIAL_STRIDE`.
pub const MATERIAL_STRIDE: usize = 4;
/// Instructions of the program memory.
pub const CODE: usize = 2048;

/// The register a thread's inputs arrive in.
pub mod input {
    pub const ORIGIN: u8 = 0;
    pub const DIRECTION: u8 = 1;
    pub const WEIGHT: u8 = 2;
    /// (t, u, v) of the hit.
    pub const TUV: u8 = 3;
    /// n0, n1, n2 are `NORMALS`, `NORMALS + 1`, `NORMALS + 2`.
    pub const NORMALS: u8 = 4;
}

/// Where a source operand is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Loc {
    /// A thread register, `< REGISTERS`.
    Reg(u8),
    /// Constant entry k (absolute), `< CONSTANTS`.
    Const(u16),
    /// Constant entry `material · MATERIAL_STRIDE + k`, `k < MATERIAL_STRIDE`.
    MatConst(u8),
}

/// A source operand: a location, each lane's component of it (0 = x, 1 = y, 2 = z), then
/// `abs` (bit 31 cleared) and `neg` (bit 31 flipped), in that order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Src {
    pub loc: Loc,
    pub swizzle: [u8; 3],
    pub abs: bool,
    pub neg: bool,
}

impl Src {
    /// The location as it is: x, y, z.
    pub fn of(loc: Loc) -> Src {
        Src {
            loc,
            swizzle: [0, 1, 2],
            abs: false,
            neg: false,
        }
    }

    /// Register r.
    pub fn reg(r: u8) -> Src {
        Src::of(Loc::Reg(r))
    }

    /// Component `lane` of `loc` in every lane (a scalar broadcast).
    pub fn broadcast(loc: Loc, lane: u8) -> Src {
        Src {
            swizzle: [lane; 3],
            ..Src::of(loc)
        }
    }

    pub fn negated(self) -> Src {
        Src {
            neg: !self.neg,
            ..self
        }
    }

    pub fn absolute(self) -> Src {
        Src { abs: true, ..self }
    }
}

/// The predicate an instruction executes under: `p[index] != invert`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Pred {
    pub index: u8,
    pub invert: bool,
}

impl Pred {
    pub const ALWAYS: Pred = Pred {
        index: 0,
        invert: false,
    };

    pub fn when(index: u8) -> Pred {
        Pred {
            index,
            invert: false,
        }
    }

    pub fn unless(index: u8) -> Pred {
        Pred {
            index,
            invert: true,
        }
    }
}

/// A field of the thread's output record, written by [`Op::Out`] and emitted by [`Op::Push`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    Origin,
    Direction,
    /// A cast ray's weight (fp32) or a shadow ray's contribution (three integers).
    Payload,
    /// A shadow ray's t_max, lane x (cast rays are pushed with `Fp32::MAX`).
    TMax,
}

impl Field {
    pub const ALL: [Field; 4] = [Field::Origin, Field::Direction, Field::Payload, Field::TMax];
}

/// What [`Op::Push`] emits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PushKind {
    /// A shadow ray: origin, direction, t_max, its contribution (payload).
    Shadow,
    /// A reflection ray of depth + 1: origin, direction, weight (payload).
    Reflection,
    /// A refraction ray of depth + 1.
    Refraction,
}

impl PushKind {
    pub const ALL: [PushKind; 3] = [PushKind::Shadow, PushKind::Reflection, PushKind::Refraction];
}

/// The core's event counters [`Op::Count`] increments.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Counter {
    /// A shadow ray not spawned: its contribution was zero.
    ZeroShadow,
    /// A reflection or refraction ray not traced: past the maximum depth.
    PastDepth,
    /// A glass hit with kr = 1: no refraction ray.
    TotalInternal,
}

impl Counter {
    pub const ALL: [Counter; 3] = [
        Counter::ZeroShadow,
        Counter::PastDepth,
        Counter::TotalInternal,
    ];
}

/// The operations. Lane-wise ones act on the lanes the write mask names; "x" ones compute
/// from lane x of their operands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// Does nothing.
    Nop,
    /// d = a.
    Mov { d: u8, a: Src },
    /// d = a + b, fp32.
    Add { d: u8, a: Src, b: Src },
    /// d = a · b, fp32.
    Mul { d: u8, a: Src, b: Src },
    /// d = `a.max(b)` (the reference's `std::max`: a < b ? b : a).
    Max { d: u8, a: Src, b: Src },
    /// d = `a.min(b)` (`std::min`: b < a ? b : a).
    Min { d: u8, a: Src, b: Src },
    /// Every lane of d = recip(a.x), correctly rounded.
    Recip { d: u8, a: Src },
    /// Every lane of d = sqrt(a.x), correctly rounded.
    Sqrt { d: u8, a: Src },
    /// d = each lane of a (fp32 steps, fl(255·c)) as a contribution: `Contribution::of_steps`,
    /// an integer in two's complement.
    Fix { d: u8, a: Src },
    /// d = a + b, 32-bit integers, wrapping.
    IAdd { d: u8, a: Src, b: Src },
    /// p[p] = a.x < b.x (fp32, false with a NaN).
    Lt { p: u8, a: Src, b: Src },
    /// p[p] = a.x ≤ b.x (fp32, false with a NaN).
    Le { p: u8, a: Src, b: Src },
    /// p[p] = some word of a (all three lanes) is not zero.
    Nz { p: u8, a: Src },
    /// The output record's field f = a.
    Out { f: Field, a: Src },
    /// Emit the output record as a ray of this kind (the thread's pixel; a cast ray's depth is
    /// the thread's + 1); the thread's spawned count + 1.
    Push { kind: PushKind },
    /// The counter + 1.
    Count { counter: Counter },
    /// The thread's settle record: its contributions' sum (a, three integers) and its spawned
    /// count; the thread ends.
    End { a: Src },
}

/// One instruction: an operation, the predicate it runs under and the lanes it writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Instr {
    pub op: Op,
    pub pred: Pred,
    /// Lanes of the destination register or field written (bit 0 = x).
    pub mask: u8,
}

impl Instr {
    /// Always executed, all three lanes written.
    pub fn new(op: Op) -> Instr {
        Instr {
            op,
            pred: Pred::ALWAYS,
            mask: 0b111,
        }
    }

    pub fn when(self, pred: Pred) -> Instr {
        Instr { pred, ..self }
    }

    pub fn lanes(self, mask: u8) -> Instr {
        Instr { mask, ..self }
    }
}

/// An instruction or instruction word the machine does not have.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum IsaError {
    #[error("instruction word {word:#018x}: opcode {opcode} is not an operation")]
    Opcode { word: u64, opcode: u64 },
    #[error("instruction word {word:#018x}: {what} {value} is out of range (at most {max})")]
    Field {
        word: u64,
        what: &'static str,
        value: u64,
        max: u64,
    },
    #[error("{instr:?}: predicate {p} is read-only (p0 is always true, p1 the past-depth flag); compares write p2 to p7")]
    ReadOnlyPredicate { instr: Instr, p: u8 },
    #[error("{instr:?}: {what} {value} is out of range (at most {max})")]
    Operand {
        instr: Instr,
        what: &'static str,
        value: u64,
        max: u64,
    },
}

/// The instruction word, one place: each field's (lowest bit, width).
pub mod word {
    /// The operation ([`super::Op`] in declaration order, 0 = `Nop`).
    pub const OPCODE: (u32, u32) = (0, 5);
    /// Predicate index, then its invert bit.
    pub const PRED: (u32, u32) = (5, 3);
    pub const PRED_INVERT: (u32, u32) = (8, 1);
    /// Write mask, bit 0 = lane x.
    pub const MASK: (u32, u32) = (9, 3);
    /// Destination: a register, a predicate, a field, a push kind or a counter (the list's
    /// index in its `ALL`).
    pub const DEST: (u32, u32) = (12, 5);
    /// Source operands a and b, each [`SRC_BITS`] wide.
    pub const SRC_A: u32 = 17;
    pub const SRC_B: u32 = 17 + SRC_BITS;
    /// Within an operand: location kind (0 register, 1 constant, 2 material constant),
    /// index, the three lanes' components, abs, neg.
    pub const SRC_KIND: (u32, u32) = (0, 2);
    pub const SRC_INDEX: (u32, u32) = (2, 9);
    pub const SRC_SWIZZLE: (u32, u32) = (11, 6);
    pub const SRC_ABS: (u32, u32) = (17, 1);
    pub const SRC_NEG: (u32, u32) = (18, 1);
    pub const SRC_BITS: u32 = 19;
    /// Bits used (the rest are zero).
    pub const BITS: u32 = SRC_B + SRC_BITS;
}

fn put(w: &mut u64, (lo, width): (u32, u32), v: u64) {
    debug_assert!(v < 1 << width);
    *w |= v << lo;
}

fn get(w: u64, (lo, width): (u32, u32)) -> u64 {
    (w >> lo) & ((1 << width) - 1)
}

const NO_SRC: Src = Src {
    loc: Loc::Reg(0),
    swizzle: [0, 1, 2],
    abs: false,
    neg: false,
};

/// The operations by opcode, the one table of them: an [`Op`]'s opcode is its kind's
/// position here (`Nop` = 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OpKind {
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

impl OpKind {
    /// Every kind, in opcode order.
    pub const ALL: [OpKind; 17] = [
        OpKind::Nop,
        OpKind::Mov,
        OpKind::Add,
        OpKind::Mul,
        OpKind::Max,
        OpKind::Min,
        OpKind::Recip,
        OpKind::Sqrt,
        OpKind::Fix,
        OpKind::IAdd,
        OpKind::Lt,
        OpKind::Le,
        OpKind::Nz,
        OpKind::Out,
        OpKind::Push,
        OpKind::Count,
        OpKind::End,
    ];

    pub fn opcode(self) -> u64 {
        self as u64
    }

    pub fn of_opcode(opcode: u64) -> Option<OpKind> {
        usize::try_from(opcode)
            .ok()
            .and_then(|i| OpKind::ALL.get(i).copied())
    }
}

/// A destination field beyond the list it indexes (an output field, a push kind, a
/// counter): what it names and the largest index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DestOutOfRange {
    pub what: &'static str,
    pub max: u64,
}

impl Op {
    pub fn kind(self) -> OpKind {
        match self {
            Op::Nop => OpKind::Nop,
            Op::Mov { .. } => OpKind::Mov,
            Op::Add { .. } => OpKind::Add,
            Op::Mul { .. } => OpKind::Mul,
            Op::Max { .. } => OpKind::Max,
            Op::Min { .. } => OpKind::Min,
            Op::Recip { .. } => OpKind::Recip,
            Op::Sqrt { .. } => OpKind::Sqrt,
            Op::Fix { .. } => OpKind::Fix,
            Op::IAdd { .. } => OpKind::IAdd,
            Op::Lt { .. } => OpKind::Lt,
            Op::Le { .. } => OpKind::Le,
            Op::Nz { .. } => OpKind::Nz,
            Op::Out { .. } => OpKind::Out,
            Op::Push { .. } => OpKind::Push,
            Op::Count { .. } => OpKind::Count,
            Op::End { .. } => OpKind::End,
        }
    }

    /// The operation of `kind` with destination field `dest` (a register or predicate as
    /// given, truncated to 8 bits; an index into the field, push-kind or counter list) and
    /// the operands it reads of `a`, `b`: [`Op::kind`] and the encoded fields inverted. Only
    /// list indices are checked here; [`Instr::check`] checks the rest.
    pub fn from_fields(kind: OpKind, dest: u64, a: Src, b: Src) -> Result<Op, DestOutOfRange> {
        fn pick<T: Copy>(all: &[T], dest: u64, what: &'static str) -> Result<T, DestOutOfRange> {
            usize::try_from(dest)
                .ok()
                .and_then(|i| all.get(i).copied())
                .ok_or(DestOutOfRange {
                    what,
                    max: all.len() as u64 - 1,
                })
        }
        let d = dest as u8;
        Ok(match kind {
            OpKind::Nop => Op::Nop,
            OpKind::Mov => Op::Mov { d, a },
            OpKind::Add => Op::Add { d, a, b },
            OpKind::Mul => Op::Mul { d, a, b },
            OpKind::Max => Op::Max { d, a, b },
            OpKind::Min => Op::Min { d, a, b },
            OpKind::Recip => Op::Recip { d, a },
            OpKind::Sqrt => Op::Sqrt { d, a },
            OpKind::Fix => Op::Fix { d, a },
            OpKind::IAdd => Op::IAdd { d, a, b },
            OpKind::Lt => Op::Lt { p: d, a, b },
            OpKind::Le => Op::Le { p: d, a, b },
            OpKind::Nz => Op::Nz { p: d, a },
            OpKind::Out => Op::Out {
                f: pick(&Field::ALL, dest, "output field")?,
                a,
            },
            OpKind::Push => Op::Push {
                kind: pick(&PushKind::ALL, dest, "push kind")?,
            },
            OpKind::Count => Op::Count {
                counter: pick(&Counter::ALL, dest, "counter")?,
            },
            OpKind::End => Op::End { a },
        })
    }

    /// The register it writes, if any.
    pub fn written_register(self) -> Option<u8> {
        match self {
            Op::Mov { d, .. }
            | Op::Add { d, .. }
            | Op::Mul { d, .. }
            | Op::Max { d, .. }
            | Op::Min { d, .. }
            | Op::Recip { d, .. }
            | Op::Sqrt { d, .. }
            | Op::Fix { d, .. }
            | Op::IAdd { d, .. } => Some(d),
            _ => None,
        }
    }

    /// (destination field, a, b) as encoded; unused ones zero.
    fn fields(self) -> (u64, Src, Src) {
        match self {
            Op::Nop => (0, NO_SRC, NO_SRC),
            Op::Mov { d, a } | Op::Recip { d, a } | Op::Sqrt { d, a } | Op::Fix { d, a } => {
                (d.into(), a, NO_SRC)
            }
            Op::Add { d, a, b }
            | Op::Mul { d, a, b }
            | Op::Max { d, a, b }
            | Op::Min { d, a, b }
            | Op::IAdd { d, a, b } => (d.into(), a, b),
            Op::Lt { p, a, b } | Op::Le { p, a, b } => (p.into(), a, b),
            Op::Nz { p, a } => (p.into(), a, NO_SRC),
            Op::Out { f, a } => (index_of(&Field::ALL, f), a, NO_SRC),
            Op::Push { kind } => (index_of(&PushKind::ALL, kind), NO_SRC, NO_SRC),
            Op::Count { counter } => (index_of(&Counter::ALL, counter), NO_SRC, NO_SRC),
            Op::End { a } => (0, a, NO_SRC),
        }
    }
}

fn index_of<T: PartialEq>(all: &[T], x: T) -> u64 {
    all.iter().position(|y| *y == x).unwrap() as u64
}

impl Src {
    fn check(self, instr: Instr) -> Result<(), IsaError> {
        let (what, value, max) = match self.loc {
            Loc::Reg(r) => ("register", r as u64, REGISTERS as u64 - 1),
            Loc::Const(k) => ("constant", k as u64, CONSTANTS as u64 - 1),
            Loc::MatConst(k) => ("material constant", k as u64, MATERIAL_STRIDE as u64 - 1),
        };
        if value > max {
            return Err(IsaError::Operand {
                instr,
                what,
                value,
                max,
            });
        }
        if let Some(&c) = self.swizzle.iter().find(|&&c| c > 2) {
            return Err(IsaError::Operand {
                instr,
                what: "swizzle component",
                value: c.into(),
                max: 2,
            });
        }
        Ok(())
    }

    fn encode(self) -> u64 {
        let (kind, index) = match self.loc {
            Loc::Reg(r) => (0, r as u64),
            Loc::Const(k) => (1, k as u64),
            Loc::MatConst(k) => (2, k as u64),
        };
        let mut w = 0;
        put(&mut w, word::SRC_KIND, kind);
        put(&mut w, word::SRC_INDEX, index);
        let swizzle = self.swizzle.iter().rev().fold(0, |s, &c| s << 2 | c as u64);
        put(&mut w, word::SRC_SWIZZLE, swizzle);
        put(&mut w, word::SRC_ABS, self.abs.into());
        put(&mut w, word::SRC_NEG, self.neg.into());
        w
    }

    fn decode(full: u64, w: u64) -> Result<Src, IsaError> {
        let index = get(w, word::SRC_INDEX);
        let loc = match get(w, word::SRC_KIND) {
            0 => Loc::Reg(index as u8),
            1 => Loc::Const(index as u16),
            2 => Loc::MatConst(index as u8),
            kind => {
                return Err(IsaError::Field {
                    word: full,
                    what: "operand kind",
                    value: kind,
                    max: 2,
                })
            }
        };
        let swizzle = get(w, word::SRC_SWIZZLE);
        Ok(Src {
            loc,
            swizzle: [0, 1, 2].map(|lane| (swizzle >> (2 * lane) & 3) as u8),
            abs: get(w, word::SRC_ABS) == 1,
            neg: get(w, word::SRC_NEG) == 1,
        })
    }
}

impl Instr {
    /// Every register, predicate, constant and swizzle within the machine's sizes; p0 and
    /// [`PAST_DEPTH`] are never written.
    pub fn check(self) -> Result<(), IsaError> {
        let err = |what, value: u64, max: u64| {
            Err(IsaError::Operand {
                instr: self,
                what,
                value,
                max,
            })
        };
        if self.pred.index as usize >= PREDICATES {
            return err("predicate", self.pred.index.into(), PREDICATES as u64 - 1);
        }
        if self.mask > 0b111 {
            return err("write mask", self.mask.into(), 0b111);
        }
        let (dest, a, b) = self.op.fields();
        if let Op::Lt { .. } | Op::Le { .. } | Op::Nz { .. } = self.op {
            if dest >= PREDICATES as u64 {
                return err("written predicate", dest, PREDICATES as u64 - 1);
            }
            if dest <= PAST_DEPTH as u64 {
                return Err(IsaError::ReadOnlyPredicate {
                    instr: self,
                    p: dest as u8,
                });
            }
        }
        if let Some(d) = self.op.written_register() {
            if d as usize >= REGISTERS {
                return err("register", d.into(), REGISTERS as u64 - 1);
            }
        }
        a.check(self)?;
        b.check(self)
    }

    /// The instruction word ([`word`]); an instruction outside the machine is an error.
    pub fn encode(self) -> Result<u64, IsaError> {
        self.check()?;
        let (dest, a, b) = self.op.fields();
        let mut w = 0;
        put(&mut w, word::OPCODE, self.op.kind().opcode());
        put(&mut w, word::PRED, self.pred.index.into());
        put(&mut w, word::PRED_INVERT, self.pred.invert.into());
        put(&mut w, word::MASK, self.mask.into());
        put(&mut w, word::DEST, dest);
        w |= a.encode() << word::SRC_A;
        w |= b.encode() << word::SRC_B;
        Ok(w)
    }

    /// The instruction of a word [`Instr::encode`] made; any other word is an error naming
    /// the field.
    pub fn decode(w: u64) -> Result<Instr, IsaError> {
        if w >> word::BITS != 0 {
            return Err(IsaError::Field {
                word: w,
                what: "unused bits",
                value: w >> word::BITS,
                max: 0,
            });
        }
        let dest = get(w, word::DEST);
        let a = Src::decode(w, get(w, (word::SRC_A, word::SRC_BITS)))?;
        let b = Src::decode(w, get(w, (word::SRC_B, word::SRC_BITS)))?;
        let opcode = get(w, word::OPCODE);
        let kind = OpKind::of_opcode(opcode).ok_or(IsaError::Opcode { word: w, opcode })?;
        let op = Op::from_fields(kind, dest, a, b).map_err(|e| IsaError::Field {
            word: w,
            what: e.what,
            value: dest,
            max: e.max,
        })?;
        let instr = Instr {
            op,
            pred: Pred {
                index: get(w, word::PRED) as u8,
                invert: get(w, word::PRED_INVERT) == 1,
            },
            mask: get(w, word::MASK) as u8,
        };
        instr.check()?;
        // Fields an operation does not use must be zero, so that a word has one meaning.
        if instr.encode()? != w {
            return Err(IsaError::Field {
                word: w,
                what: "bits the operation does not use",
                value: w ^ instr.encode()?,
                max: 0,
            });
        }
        Ok(instr)
    }
}
