//! Runs one thread of a shading program, instruction by instruction: the semantics of
//! [`super::isa`] that the shader core equals bit for bit (it only interleaves threads).

use thiserror::Error;

use super::isa::{
    Counter, Field, Instr, Loc, Op, PushKind, Src, Word3, CODE, CONSTANTS, MATERIAL_STRIDE,
    PAST_DEPTH, PREDICATES, REGISTERS,
};
use crate::fp32::Fp32;
use crate::frame::accumulate::Contribution;

/// A loaded shading program: code, constants and the entry points.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub code: Vec<Instr>,
    /// `CONSTANTS` entries at most; reads past the end are zero.
    pub constants: Vec<Word3>,
    /// Entry point of each material (object) index.
    pub material_entry: Vec<u16>,
    /// Entry point of a cast ray that missed.
    pub miss_entry: u16,
}

/// The rays a thread may push, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pushes {
    pub shadow: usize,
    /// Reflection and refraction rays.
    pub cast: usize,
}

impl Pushes {
    pub fn total(self) -> usize {
        self.shadow + self.cast
    }
}

impl Program {
    /// The rays a thread entering at `entry` may push: the `Push` instructions from `entry`
    /// to its `End`, executed or not (what the frame unit reserves ray-store entries for
    /// when the thread starts).
    pub fn pushes_from(&self, entry: u16) -> Pushes {
        let code = self.code.get(entry as usize..).unwrap_or_default();
        let mut pushes = Pushes::default();
        for i in code.iter().take_while(|i| !matches!(i.op, Op::End { .. })) {
            match i.op {
                Op::Push {
                    kind: PushKind::Shadow,
                } => pushes.shadow += 1,
                Op::Push { .. } => pushes.cast += 1,
                _ => {}
            }
        }
        pushes
    }
}

/// What a thread starts with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ThreadInput {
    pub entry: u16,
    /// The hit triangle's object (selects `MatConst`); 0 for a miss.
    pub material: u32,
    /// r0..r6 (`isa::input`).
    pub registers: [Word3; 7],
    pub past_depth: bool,
}

/// A ray [`Op::Push`] emitted: the output record's fields at the push.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pushed {
    pub kind: PushKind,
    pub origin: Word3,
    pub direction: Word3,
    pub payload: Word3,
    pub t_max: u32,
}

/// What a thread did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ThreadOutput {
    pub pushed: Vec<Pushed>,
    /// The settle record's sum ([`Op::End`]'s operand as three integers).
    pub sum: [i32; 3],
    /// `Counter::ALL`'s order.
    pub counters: [u32; 3],
    /// Instructions issued, `End` included (executed or not: the core spends a cycle on each).
    pub instructions: u32,
}

#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum RunError {
    #[error("the thread ran past the end of the program at {pc} ({len} instructions) without End")]
    NoEnd { pc: usize, len: usize },
    #[error("entry point {entry} is outside the program ({len} instructions)")]
    Entry { entry: u16, len: usize },
    #[error("material {material} has no constants (the memory holds {CONSTANTS} entries)")]
    Material { material: u32 },
}

/// The machine's state for one thread.
struct Thread<'a> {
    program: &'a Program,
    material: u32,
    regs: [Word3; REGISTERS],
    preds: [bool; PREDICATES],
    record: [Word3; 4],
}

impl Thread<'_> {
    fn read(&self, s: Src) -> Word3 {
        let word = match s.loc {
            Loc::Reg(r) => self.regs[r as usize],
            Loc::Const(k) => self.constant(k as usize),
            Loc::MatConst(k) => {
                self.constant(self.material as usize * MATERIAL_STRIDE + k as usize)
            }
        };
        s.swizzle.map(|c| {
            let w = word[c as usize];
            let w = if s.abs { w & 0x7fff_ffff } else { w };
            if s.neg {
                w ^ 0x8000_0000
            } else {
                w
            }
        })
    }

    fn constant(&self, k: usize) -> Word3 {
        self.program.constants.get(k).copied().unwrap_or([0; 3])
    }

    fn write(&mut self, d: u8, mask: u8, value: Word3) {
        for (lane, v) in value.into_iter().enumerate() {
            if mask >> lane & 1 == 1 {
                self.regs[d as usize][lane] = v;
            }
        }
    }
}

fn lanes(a: Word3, b: Word3, f: impl Fn(Fp32, Fp32) -> Fp32) -> Word3 {
    [0, 1, 2].map(|i| f(Fp32::from_bits(a[i]), Fp32::from_bits(b[i])).bits())
}

fn x(w: Word3) -> Fp32 {
    Fp32::from_bits(w[0])
}

/// Runs a thread from `input.entry` to its `End`.
pub fn run(program: &Program, input: &ThreadInput) -> Result<ThreadOutput, RunError> {
    let len = program.code.len();
    if input.entry as usize >= len {
        return Err(RunError::Entry {
            entry: input.entry,
            len,
        });
    }
    if (input.material as usize + 1) * MATERIAL_STRIDE > CONSTANTS {
        return Err(RunError::Material {
            material: input.material,
        });
    }
    let mut t = Thread {
        program,
        material: input.material,
        regs: [[0; 3]; REGISTERS],
        preds: [false; PREDICATES],
        record: [[0; 3]; 4],
    };
    t.regs[..7].copy_from_slice(&input.registers);
    t.preds[0] = true;
    t.preds[PAST_DEPTH as usize] = input.past_depth;
    let mut out = ThreadOutput::default();
    let mut pc = input.entry as usize;
    loop {
        let Some(&instr) = program.code.get(pc).filter(|_| pc < CODE) else {
            return Err(RunError::NoEnd { pc, len });
        };
        pc += 1;
        out.instructions += 1;
        let runs = t.preds[instr.pred.index as usize] != instr.pred.invert;
        if !runs {
            continue;
        }
        let mask = instr.mask;
        match instr.op {
            Op::Nop => {}
            Op::Mov { d, a } => t.write(d, mask, t.read(a)),
            Op::Add { d, a, b } => t.write(d, mask, lanes(t.read(a), t.read(b), |a, b| a + b)),
            Op::Mul { d, a, b } => t.write(d, mask, lanes(t.read(a), t.read(b), |a, b| a * b)),
            Op::Max { d, a, b } => t.write(d, mask, lanes(t.read(a), t.read(b), Fp32::max)),
            Op::Min { d, a, b } => t.write(d, mask, lanes(t.read(a), t.read(b), Fp32::min)),
            Op::Recip { d, a } => t.write(d, mask, [x(t.read(a)).recip().bits(); 3]),
            Op::Sqrt { d, a } => t.write(d, mask, [x(t.read(a)).sqrt().bits(); 3]),
            Op::Fix { d, a } => {
                let v = t
                    .read(a)
                    .map(|w| Contribution::of_steps(Fp32::from_bits(w)) as u32);
                t.write(d, mask, v)
            }
            Op::IAdd { d, a, b } => {
                let (a, b) = (t.read(a), t.read(b));
                t.write(d, mask, [0, 1, 2].map(|i| a[i].wrapping_add(b[i])))
            }
            Op::Lt { p, a, b } => t.preds[p as usize] = x(t.read(a)).lt(x(t.read(b))),
            Op::Le { p, a, b } => t.preds[p as usize] = x(t.read(a)).le(x(t.read(b))),
            Op::Nz { p, a } => t.preds[p as usize] = t.read(a) != [0; 3],
            Op::Out { f, a } => {
                let value = t.read(a);
                let field = &mut t.record[Field::ALL.iter().position(|&g| g == f).unwrap()];
                for (lane, v) in value.into_iter().enumerate() {
                    if mask >> lane & 1 == 1 {
                        field[lane] = v;
                    }
                }
            }
            Op::Push { kind } => {
                let [origin, direction, payload, t_max] = t.record;
                out.pushed.push(Pushed {
                    kind,
                    origin,
                    direction,
                    payload,
                    t_max: t_max[0],
                });
            }
            Op::Count { counter } => {
                out.counters[Counter::ALL.iter().position(|&c| c == counter).unwrap()] += 1
            }
            Op::End { a } => {
                out.sum = t.read(a).map(|w| w as i32);
                return Ok(out);
            }
        }
    }
}
