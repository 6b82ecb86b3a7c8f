//! The shader core's datapath: an operation (its opcode) and two 3-lane fp32 operands, already
//! swizzled, abs'd and negated, in every cycle; the 3-lane result and the predicate bit out
//! exactly [`latency`]`(depth)` cycles later, whatever the operation, so results retire in
//! issue order through one write port. Per operation (`hw_model::frame::shader::interpret`):
//!
//! ```text
//! t = 0          Mov, Out, End: a     IAdd: a + b (wrapping)     Nz: a ≠ 0 (any lane)
//! t_lt           Max: lt(a, b) ? b : a    Min: lt(b, a) ? b : a   (per lane)
//!                Lt: lt(a.x, b.x)     Le: !lt(b.x, a.x), no NaN
//! t_fix          Fix: FixedFromF32 of each lane (the contribution conversion's), sign-extended
//! t_mul          Mul (3 lanes)
//! t_add          Add (3 lanes)
//! t_recip        Recip (lane x, broadcast)
//! t_sqrt         Sqrt (lane x, broadcast) = latency
//! ```
//!
//! Each operator has `min(depth, its max_stages())` registers (as in [`crate::frame::raygen`]);
//! the times are in that order at every depth because the operators' `max_stages()` are. The
//! result so far, the predicate and the opcode travel down one chain of delay lines from
//! t = 0 to the latency; at each operator's time the chain takes its output if the opcode is
//! the operator's. A comparison serves Max, Min, Lt and Le: its inputs are swapped for Min and
//! Le; the word Max or Min picks is read as the model reads operands (`Fp32::from_bits`:
//! subnormals flush to ±0, NaNs become canonical) by fp32's `ToF32` without registers.

use rust_hdl::prelude::*;

use super::{opcode_constant, OPCODE_BITS};
use crate::float::unpack::Unpack;
use crate::formats::fp32::{self, Add, Lt, Mul, Recip, Sqrt, ToF32};
use crate::frame::contribution::{ToFixed, CONTRIBUTION_BITS};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::operator::Op;
use hw_model::frame::shader::isa::OpKind;

type Word = Bits<32>;
type Lanes = Bits<96>;
/// fp32's fields for the NaN test of `Le`.
type Fp32Unpack = Unpack<8, 23, 32, 24>;

/// When each operator's result is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AluSchedule {
    pub t_lt: usize,
    pub t_fix: usize,
    pub t_mul: usize,
    pub t_add: usize,
    pub t_recip: usize,
    pub t_sqrt: usize,
    /// Operands in to result out, every operation.
    pub latency: usize,
}

impl AluSchedule {
    pub fn new(depth: usize) -> Self {
        let at = |op| depth.min(fp32::max_stages(op));
        let t_sqrt = at(Op::Sqrt);
        AluSchedule {
            t_lt: at(Op::Lt),
            t_fix: depth.min(ToFixed::max_stages()),
            t_mul: at(Op::Mul),
            t_add: at(Op::Add),
            t_recip: at(Op::Recip),
            t_sqrt,
            latency: t_sqrt,
        }
    }

    /// The chain's delay lines: 0 to t_lt, t_lt to t_fix, …, t_recip to t_sqrt.
    fn segments(&self) -> [usize; 6] {
        let t = [
            0,
            self.t_lt,
            self.t_fix,
            self.t_mul,
            self.t_add,
            self.t_recip,
            self.t_sqrt,
        ];
        std::array::from_fn(|k| t[k + 1] - t[k])
    }
}

/// Cycles from the operands in to the result out, every operation: the one source of it.
pub fn latency(depth: usize) -> usize {
    AluSchedule::new(depth).latency
}

/// The depth from which every operator has all its registers.
pub fn full_depth() -> usize {
    [Op::Add, Op::Mul, Op::Recip, Op::Lt, Op::Sqrt]
        .into_iter()
        .map(fp32::max_stages)
        .chain([ToFixed::max_stages()])
        .max()
        .unwrap_or(0)
}

/// One operation a cycle: `op` (an opcode of `isa::word::OPCODE`) on `a` and `b`; `y` and `p`
/// [`latency`]`(depth)` cycles later. Opcodes without a result (Nop, Push, Count) give a.
#[derive(LogicBlock)]
pub struct Alu {
    pub clock: Signal<In, Clock>,
    pub op: Signal<In, Bits<OPCODE_BITS>>,
    pub a: [Signal<In, Word>; 3],
    pub b: [Signal<In, Word>; 3],
    pub y: [Signal<Out, Word>; 3],
    pub p: Signal<Out, Bit>,
    add: [Add; 3],
    mul: [Mul; 3],
    lt: [Lt; 3],
    fix: [ToFixed; 3],
    recip: Recip,
    sqrt: Sqrt,
    /// The operands at t_lt, for Max and Min to pick from and Le's NaN test.
    a_at_lt: [Delay<Word>; 3],
    b_at_lt: [Delay<Word>; 3],
    nan_a: Fp32Unpack,
    nan_b: Fp32Unpack,
    /// The result so far, the predicate and the opcode, from each operator's time to the next.
    chain_y: [Delay<Lanes>; 6],
    chain_p: [Delay<Bit>; 6],
    chain_op: [Delay<Bits<OPCODE_BITS>>; 6],
    /// Max's or Min's pick, as `Fp32::from_bits` reads it (subnormals ±0, NaNs canonical).
    canonical: [ToF32; 3],
    /// The result at t = 0, and at each operator's time (`v[s]` into `chain_y[s]`).
    start: [Signal<Local, Word>; 3],
    v: [Signal<Local, Lanes>; 6],
    /// Fix's contributions, and sign-extended.
    fixed: [Signal<Local, Word>; 3],
    extended: [Signal<Local, Word>; 3],
    /// Min and Le compare b with a.
    swap: Signal<Local, Bit>,
    op_iadd: Constant<Bits<OPCODE_BITS>>,
    op_max: Constant<Bits<OPCODE_BITS>>,
    op_min: Constant<Bits<OPCODE_BITS>>,
    op_lt: Constant<Bits<OPCODE_BITS>>,
    op_le: Constant<Bits<OPCODE_BITS>>,
    op_fix: Constant<Bits<OPCODE_BITS>>,
    op_mul: Constant<Bits<OPCODE_BITS>>,
    op_add: Constant<Bits<OPCODE_BITS>>,
    op_recip: Constant<Bits<OPCODE_BITS>>,
    op_sqrt: Constant<Bits<OPCODE_BITS>>,
    /// A contribution's sign bit, and the bits above it its sign extension sets.
    fix_sign: Constant<Word>,
    fix_extension: Constant<Word>,
}

impl Alu {
    pub fn new(depth: usize) -> Self {
        let s = AluSchedule::new(depth);
        let seg = s.segments();
        let at = |op| depth.min(fp32::max_stages(op));
        Self {
            clock: Default::default(),
            op: Default::default(),
            a: Default::default(),
            b: Default::default(),
            y: Default::default(),
            p: Default::default(),
            add: std::array::from_fn(|_| Add::new(at(Op::Add))),
            mul: std::array::from_fn(|_| Mul::new(at(Op::Mul))),
            lt: std::array::from_fn(|_| Lt::new(at(Op::Lt))),
            fix: std::array::from_fn(|_| ToFixed::new(s.t_fix)),
            recip: Recip::new(at(Op::Recip)),
            sqrt: Sqrt::new(at(Op::Sqrt)),
            a_at_lt: Delay::lines(s.t_lt),
            b_at_lt: Delay::lines(s.t_lt),
            nan_a: Default::default(),
            nan_b: Default::default(),
            chain_y: seg.map(Delay::new),
            chain_p: seg.map(Delay::new),
            chain_op: seg.map(Delay::new),
            canonical: std::array::from_fn(|_| ToF32::new(0)),
            start: Default::default(),
            v: Default::default(),
            fixed: Default::default(),
            extended: Default::default(),
            swap: Default::default(),
            op_iadd: opcode_constant(OpKind::IAdd),
            op_max: opcode_constant(OpKind::Max),
            op_min: opcode_constant(OpKind::Min),
            op_lt: opcode_constant(OpKind::Lt),
            op_le: opcode_constant(OpKind::Le),
            op_fix: opcode_constant(OpKind::Fix),
            op_mul: opcode_constant(OpKind::Mul),
            op_add: opcode_constant(OpKind::Add),
            op_recip: opcode_constant(OpKind::Recip),
            op_sqrt: opcode_constant(OpKind::Sqrt),
            fix_sign: Constant::new((1u64 << (CONTRIBUTION_BITS - 1)).into()),
            fix_extension: Constant::new(
                (0xffff_ffffu64 & !((1u64 << CONTRIBUTION_BITS) - 1)).into(),
            ),
        }
    }
}

impl Logic for Alu {
    #[hdl_gen]
    fn update(&mut self) {
        // The operators, on every cycle's operands.
        clock!(self, clock, recip, sqrt);
        self.recip.a.next = self.a[0].val();
        self.sqrt.a.next = self.a[0].val();
        self.swap.next = (self.op.val() == self.op_min.val()) | (self.op.val() == self.op_le.val());
        for k in 0..3 {
            clock!(self, clock, add[k], mul[k], lt[k], fix[k], canonical[k]);
            clock!(self, clock, a_at_lt[k], b_at_lt[k]);
            self.add[k].a.next = self.a[k].val();
            self.add[k].b.next = self.b[k].val();
            self.mul[k].a.next = self.a[k].val();
            self.mul[k].b.next = self.b[k].val();
            self.fix[k].a.next = self.a[k].val();
            self.lt[k].a.next = self.a[k].val();
            self.lt[k].b.next = self.b[k].val();
            if self.swap.val() {
                self.lt[k].a.next = self.b[k].val();
                self.lt[k].b.next = self.a[k].val();
            }
            self.a_at_lt[k].d.next = self.a[k].val();
            self.b_at_lt[k].d.next = self.b[k].val();
        }
        for s in 0..6 {
            clock!(self, clock, chain_y[s], chain_p[s], chain_op[s]);
        }
        for s in 1..6 {
            self.chain_op[s].d.next = self.chain_op[s - 1].q.val();
        }
        for s in 2..6 {
            self.chain_p[s].d.next = self.chain_p[s - 1].q.val();
        }

        // t = 0: a, IAdd, Nz.
        for k in 0..3 {
            self.start[k].next = self.a[k].val();
            if self.op.val() == self.op_iadd.val() {
                self.start[k].next = self.a[k].val() + self.b[k].val();
            }
        }
        self.v[0].next = bit_cast::<96, 32>(self.start[0].val())
            | (bit_cast::<96, 32>(self.start[1].val()) << 32)
            | (bit_cast::<96, 32>(self.start[2].val()) << 64);
        self.chain_y[0].d.next = self.v[0].val();
        self.chain_p[0].d.next = (self.a[0].val() | self.a[1].val() | self.a[2].val()).any();
        self.chain_op[0].d.next = self.op.val();

        // t_lt: Max, Min (the word picked, as the model reads it: `Fp32::from_bits`), Lt, Le.
        for k in 0..3 {
            self.canonical[k].a.next = self.a_at_lt[k].q.val();
            if self.lt[k].y.val() {
                self.canonical[k].a.next = self.b_at_lt[k].q.val();
            }
        }
        self.nan_a.x.next = self.a_at_lt[0].q.val();
        self.nan_b.x.next = self.b_at_lt[0].q.val();
        self.v[1].next = self.chain_y[0].q.val();
        if (self.chain_op[0].q.val() == self.op_max.val())
            | (self.chain_op[0].q.val() == self.op_min.val())
        {
            self.v[1].next = bit_cast::<96, 32>(self.canonical[0].y.val())
                | (bit_cast::<96, 32>(self.canonical[1].y.val()) << 32)
                | (bit_cast::<96, 32>(self.canonical[2].y.val()) << 64);
        }
        self.chain_p[1].d.next = self.chain_p[0].q.val();
        if self.chain_op[0].q.val() == self.op_lt.val() {
            self.chain_p[1].d.next = self.lt[0].y.val();
        }
        if self.chain_op[0].q.val() == self.op_le.val() {
            self.chain_p[1].d.next =
                !self.lt[0].y.val() & !self.nan_a.nan.val() & !self.nan_b.nan.val();
        }
        self.chain_y[1].d.next = self.v[1].val();

        // t_fix: Fix, the contribution sign-extended to 32 bits (`bit_cast` of an indexed
        // signal does not build inside a loop).
        self.fixed[0].next = bit_cast::<32, CONTRIBUTION_BITS>(self.fix[0].y.val());
        self.fixed[1].next = bit_cast::<32, CONTRIBUTION_BITS>(self.fix[1].y.val());
        self.fixed[2].next = bit_cast::<32, CONTRIBUTION_BITS>(self.fix[2].y.val());
        for k in 0..3 {
            self.extended[k].next = self.fixed[k].val();
            if (self.fixed[k].val() & self.fix_sign.val()).any() {
                self.extended[k].next = self.fixed[k].val() | self.fix_extension.val();
            }
        }
        self.v[2].next = self.chain_y[1].q.val();
        if self.chain_op[1].q.val() == self.op_fix.val() {
            self.v[2].next = bit_cast::<96, 32>(self.extended[0].val())
                | (bit_cast::<96, 32>(self.extended[1].val()) << 32)
                | (bit_cast::<96, 32>(self.extended[2].val()) << 64);
        }
        self.chain_y[2].d.next = self.v[2].val();

        // t_mul: Mul.
        self.v[3].next = self.chain_y[2].q.val();
        if self.chain_op[2].q.val() == self.op_mul.val() {
            self.v[3].next = bit_cast::<96, 32>(self.mul[0].y.val())
                | (bit_cast::<96, 32>(self.mul[1].y.val()) << 32)
                | (bit_cast::<96, 32>(self.mul[2].y.val()) << 64);
        }
        self.chain_y[3].d.next = self.v[3].val();

        // t_add: Add.
        self.v[4].next = self.chain_y[3].q.val();
        if self.chain_op[3].q.val() == self.op_add.val() {
            self.v[4].next = bit_cast::<96, 32>(self.add[0].y.val())
                | (bit_cast::<96, 32>(self.add[1].y.val()) << 32)
                | (bit_cast::<96, 32>(self.add[2].y.val()) << 64);
        }
        self.chain_y[4].d.next = self.v[4].val();

        // t_recip: Recip, broadcast.
        self.v[5].next = self.chain_y[4].q.val();
        if self.chain_op[4].q.val() == self.op_recip.val() {
            self.v[5].next = bit_cast::<96, 32>(self.recip.y.val())
                | (bit_cast::<96, 32>(self.recip.y.val()) << 32)
                | (bit_cast::<96, 32>(self.recip.y.val()) << 64);
        }
        self.chain_y[5].d.next = self.v[5].val();

        // t_sqrt: Sqrt, broadcast; the result.
        for k in 0..3 {
            self.y[k].next = self.chain_y[5].q.val().get_bits::<32>(32 * k);
            if self.chain_op[5].q.val() == self.op_sqrt.val() {
                self.y[k].next = self.sqrt.y.val();
            }
        }
        self.p.next = self.chain_p[5].q.val();
    }
}

/// One cycle's operation: an opcode and the operands' words.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AluInput {
    pub op: u64,
    pub a: [u32; 3],
    pub b: [u32; 3],
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AluOutput {
    pub y: [u32; 3],
    pub p: bool,
}

impl Stepped for Alu {
    type Input = AluInput;
    type Output = AluOutput;

    fn idle() -> AluInput {
        AluInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &AluInput) {
        self.op.next = input.op.into();
        for k in 0..3 {
            self.a[k].next = u64::from(input.a[k]).into();
            self.b[k].next = u64::from(input.b[k]).into();
        }
    }

    fn observe(&self) -> AluOutput {
        AluOutput {
            y: std::array::from_fn(|k| self.y[k].val().to_u64() as u32),
            p: self.p.val(),
        }
    }
}

/// Runs a freshly built datapath at `depth` in rust-hdl's simulator, one input a cycle, and
/// returns what the outputs show in every cycle (`inputs.len() + flush` of them).
pub fn simulate_alu(depth: usize, inputs: &[AluInput], flush: usize) -> Vec<AluOutput> {
    simulate_cycles(move || Alu::new(depth), inputs, flush)
}

/// Verilog of the datapath at `depth`, top module `top`.
pub fn alu_verilog(depth: usize) -> String {
    built_verilog(move || Alu::new(depth))
}
