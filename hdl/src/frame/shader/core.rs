//! The shader core: threads of shading programs interleaved on one datapath ([`super::alu`]),
//! one instruction issued a cycle, each thread bit for bit
//! `hw_model::frame::shader::interpret::run`.
//!
//! **A barrel.** [`threads`]`(depth)` = T threads take turns in round robin, T the loop
//! latency of an instruction: program read (1), operand read (1), operand register (1), the
//! datapath's [`alu::latency`], and the write back in the cycle of the thread's next turn. So
//! a thread's next instruction reads its registers after its previous one wrote them, and no
//! hazard logic is needed: T = 4 at depth 1, 8 at depth 5, 32 at full depth (the register
//! file of 32 threads × 32 registers fills a 1k-deep block RAM a lane). The trade: deeper
//! operators for the clock cost threads in flight (and their registers' block RAM), and a
//! single thread runs at one instruction in T cycles, so the core needs T shaded rays at once
//! to issue every cycle.
//!
//! ```text
//! S0  the thread's context (pc, predicates, …) → program memory address
//! S1  the instruction word: decode; register file, constant and record addresses
//! S2  operands: register or constant, swizzle, abs, neg; Push, End and Count act here
//! S3  operands registered into the datapath
//! WB  (T cycles after S0) the result into the register file, a predicate or the record
//! ```
//!
//! **Per thread.** The context (state, pc, the 8 predicates, material, the tag, the spawned
//! count) circulates with the thread's instruction, around a ring of T registers: the stages'
//! registers and a delay line beside the datapath; S2 advances pc (unless the instruction is
//! blocked), counts a push and ends a thread, WB writes a predicate. The 32 registers of 96
//! bits are block RAM at thread·32 + register, one RAM a lane (the write mask), two copies
//! for the two operands; the output record is a RAM a field and lane at the thread.
//!
//! **Shared.** Program memory (`isa::CODE` words), constant memory (`isa::CONSTANTS` × 96 bits,
//! two copies; `MatConst(k)` reads material · `MATERIAL_STRIDE` + k), loaded through the
//! load port between frames. The start carries its entry point (the engine's lookup of the
//! material's or the miss entry).
//!
//! **Streams.** A thread start (entry, material, r0..r6, past depth, the tag: pixel and
//! depth) waits until a free thread passes S0, which the loader claims; the loader writes
//! r0..r6 and clears the record in cycles whose write back writes nothing (at least the
//! claimed thread's own, so it never starves), then hands the thread its context at its
//! next turn and takes the start. Pushed rays and settle records leave through one register
//! each, valid/ready: a Push or End at S2 whose register is full and not being taken is
//! blocked (pc stays) and issues again at the thread's next turn, so nothing is dropped and
//! a stalled consumer stalls only the threads that have output for it.
//!
//! Counters: the three `isa::Counter`s, instructions issued (blocked ones not counted,
//! `End` counted as the interpreter counts it), cycles with a thread loading or running.
//!
//! No reset: every thread starts free (state 0), the loader idle and the counters zero from
//! the flip-flops' power-on zeros.

use hw_model::frame::shader::isa::{
    self, word, PushKind, Word3, CODE, CONSTANTS, MATERIAL_STRIDE, PAST_DEPTH, PREDICATES,
    REGISTERS,
};
use hw_model::frame::shader::{Instr, Program, ThreadInput};
use rust_hdl::prelude::*;
use thiserror::Error;

use super::alu::{self, Alu};
use super::{opcode_constant, OPCODE_BITS};
use crate::frame::accumulate::SPAWNED_BITS;
use crate::frame::raygen::PIXEL_BITS;
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::{clock, dff_setup};
use crate::mt::delay::Delay;
use hw_model::frame::shader::isa::OpKind;

type Word = Bits<32>;
type Lanes = Bits<96>;

/// Stages from a thread's turn to its operands in the datapath: program read, operand
/// read, operand register.
pub const ISSUE_STAGES: usize = 3;
/// Bits of a thread index.
pub const THREAD_BITS: usize = 5;
/// Bits of a program address, a register, a constant address, a material.
pub const PC_BITS: usize = 11;
const REGISTER_BITS: usize = 5;
const CONSTANT_BITS: usize = 9;
pub const MATERIAL_BITS: usize = 7;
/// Bits of the depth carried in a thread's tag.
pub const DEPTH_BITS: usize = 4;
/// Bits of a counter.
pub const COUNTER_BITS: usize = 32;
const _: () = {
    assert!(1 << PC_BITS == CODE && 1 << REGISTER_BITS == REGISTERS);
    assert!(1 << CONSTANT_BITS == CONSTANTS && MATERIAL_STRIDE == 4);
    assert!(1 << MATERIAL_BITS == CONSTANTS / MATERIAL_STRIDE && PREDICATES == 8);
    // The kernel's literal field widths.
    assert!(word::PRED.1 == 3 && word::MASK.1 == 3 && word::DEST.1 == 5);
    assert!(word::SRC_BITS == 19 && word::SRC_KIND.1 == 2 && word::SRC_INDEX.1 == 9);
    assert!(word::SRC_SWIZZLE.1 == 6 && word::SRC_ABS.1 == 1 && word::SRC_NEG.1 == 1);
    assert!(word::BITS <= 64);
};

/// The context's layout in a [`Context`] word: (lowest bit, width), the kernel's literals.
/// state 0..2 (0 free, 1 loading, 2 running), pc 2..13, predicates 13..21, material 21..28,
/// pixel 28..49, depth 49..53, spawned 53..57.
type Context = Bits<64>;
const _: () = assert!(
    2 + PC_BITS + PREDICATES + MATERIAL_BITS + PIXEL_BITS + DEPTH_BITS + SPAWNED_BITS == 57
);

/// Threads of the core at `depth`: its loop latency (at most `2^THREAD_BITS`, the count at
/// full depth: a test checks it).
pub fn threads(depth: usize) -> usize {
    ISSUE_STAGES + alu::latency(depth)
}

/// Shading programs' threads in, their pushed rays and settle records out.
#[derive(LogicBlock)]
pub struct ShaderCore {
    pub clock: Signal<In, Clock>,
    // The load port, between frames: program word or constant entry `load_address`.
    pub load_program: Signal<In, Bit>,
    pub load_constant: Signal<In, Bit>,
    pub load_address: Signal<In, Bits<PC_BITS>>,
    /// A program word in the low 64 bits, or a constant's three words.
    pub load_data: Signal<In, Lanes>,
    // Thread starts.
    pub start_valid: Signal<In, Bit>,
    pub start_ready: Signal<Out, Bit>,
    pub start_entry: Signal<In, Bits<PC_BITS>>,
    pub start_material: Signal<In, Bits<MATERIAL_BITS>>,
    pub start_registers: [Signal<In, Lanes>; 7],
    pub start_past_depth: Signal<In, Bit>,
    pub start_pixel: Signal<In, Bits<PIXEL_BITS>>,
    pub start_depth: Signal<In, Bits<DEPTH_BITS>>,
    // Pushed rays.
    pub ray_valid: Signal<Out, Bit>,
    pub ray_ready: Signal<In, Bit>,
    /// The kind's index in `PushKind::ALL`.
    pub ray_kind: Signal<Out, Bits<2>>,
    pub ray_pixel: Signal<Out, Bits<PIXEL_BITS>>,
    pub ray_depth: Signal<Out, Bits<DEPTH_BITS>>,
    pub ray_origin: Signal<Out, Lanes>,
    pub ray_direction: Signal<Out, Lanes>,
    pub ray_payload: Signal<Out, Lanes>,
    pub ray_t_max: Signal<Out, Word>,
    // Settle records.
    pub settle_valid: Signal<Out, Bit>,
    pub settle_ready: Signal<In, Bit>,
    pub settle_pixel: Signal<Out, Bits<PIXEL_BITS>>,
    pub settle_depth: Signal<Out, Bits<DEPTH_BITS>>,
    pub settle_sum: Signal<Out, Lanes>,
    pub settle_spawned: Signal<Out, Bits<SPAWNED_BITS>>,
    // Counters.
    pub counters: [Signal<Out, Bits<COUNTER_BITS>>; 3],
    pub instructions: Signal<Out, Bits<COUNTER_BITS>>,
    pub busy_cycles: Signal<Out, Bits<COUNTER_BITS>>,

    code: RAM<Bits<64>, PC_BITS>,
    constants_a: RAM<Lanes, CONSTANT_BITS>,
    constants_b: RAM<Lanes, CONSTANT_BITS>,
    registers_a: [RAM<Word, 10>; 3],
    registers_b: [RAM<Word, 10>; 3],
    record_origin: [RAM<Word, THREAD_BITS>; 3],
    record_direction: [RAM<Word, THREAD_BITS>; 3],
    record_payload: [RAM<Word, THREAD_BITS>; 3],
    record_t_max: RAM<Word, THREAD_BITS>,
    alu: Alu,
    /// The thread at S0 (round robin), and at S1 and S2.
    turn: DFF<Bits<THREAD_BITS>>,
    tid1: DFF<Bits<THREAD_BITS>>,
    tid2: DFF<Bits<THREAD_BITS>>,
    last_thread: Constant<Bits<THREAD_BITS>>,
    /// The ring of contexts: S1, S2, S3, then beside the datapath to WB.
    ctx1: DFF<Context>,
    ctx2: DFF<Context>,
    ctx3: DFF<Context>,
    ctx_wb: Delay<Context>,
    /// S2's instruction and whether its predicate holds.
    instr2: DFF<Bits<64>>,
    runs2: DFF<Bit>,
    /// The datapath's inputs (S3).
    alu_op: DFF<Bits<OPCODE_BITS>>,
    alu_a: [DFF<Word>; 3],
    alu_b: [DFF<Word>; 3],
    /// What WB writes, beside the datapath: a register, a predicate or a record field; the
    /// destination; the lanes.
    wb_register: Delay<Bit>,
    wb_predicate: Delay<Bit>,
    wb_record: Delay<Bit>,
    wb_dest: Delay<Bits<5>>,
    wb_mask: Delay<Bits<3>>,
    // The loader.
    loading: DFF<Bit>,
    loading_thread: DFF<Bits<THREAD_BITS>>,
    load_step: DFF<Bits<4>>,
    // Output registers.
    ray_full: DFF<Bit>,
    ray_kind_q: DFF<Bits<2>>,
    ray_pixel_q: DFF<Bits<PIXEL_BITS>>,
    ray_depth_q: DFF<Bits<DEPTH_BITS>>,
    ray_origin_q: DFF<Lanes>,
    ray_direction_q: DFF<Lanes>,
    ray_payload_q: DFF<Lanes>,
    ray_t_max_q: DFF<Word>,
    settle_full: DFF<Bit>,
    settle_pixel_q: DFF<Bits<PIXEL_BITS>>,
    settle_depth_q: DFF<Bits<DEPTH_BITS>>,
    settle_sum_q: DFF<Lanes>,
    settle_spawned_q: DFF<Bits<SPAWNED_BITS>>,
    counter_q: [DFF<Bits<COUNTER_BITS>>; 3],
    instructions_q: DFF<Bits<COUNTER_BITS>>,
    busy_q: DFF<Bits<COUNTER_BITS>>,
    /// Threads loading or running.
    live: DFF<Bits<6>>,
    // S0.
    ctx0: Signal<Local, Context>,
    claim: Signal<Local, Bit>,
    hand_over: Signal<Local, Bit>,
    // S1.
    instr1: Signal<Local, Bits<64>>,
    src1: [Signal<Local, Bits<19>>; 2],
    constant_address: [Signal<Local, Bits<CONSTANT_BITS>>; 2],
    register_address: [Signal<Local, Bits<10>>; 2],
    index1: [Signal<Local, Bits<CONSTANT_BITS>>; 2],
    kind1: [Signal<Local, Bits<2>>; 2],
    material_base: Signal<Local, Bits<CONSTANT_BITS>>,
    thread_base: Signal<Local, Bits<10>>,
    /// A register's and a material constant's bits of an operand's index.
    register_mask: Constant<Bits<CONSTANT_BITS>>,
    material_mask: Constant<Bits<CONSTANT_BITS>>,
    pred_index: Signal<Local, Bits<8>>,
    // S2.
    opcode2: Signal<Local, Bits<OPCODE_BITS>>,
    dest2: Signal<Local, Bits<5>>,
    src2: [Signal<Local, Bits<19>>; 2],
    fetched_a: Signal<Local, Lanes>,
    fetched_b: Signal<Local, Lanes>,
    operand_a: [Signal<Local, Word>; 3],
    operand_b: [Signal<Local, Word>; 3],
    running2: Signal<Local, Bit>,
    pushing: Signal<Local, Bit>,
    ending: Signal<Local, Bit>,
    blocked: Signal<Local, Bit>,
    ray_free: Signal<Local, Bit>,
    settle_free: Signal<Local, Bit>,
    ctx_next: Signal<Local, Context>,
    writes_register: Signal<Local, Bit>,
    writes_predicate: Signal<Local, Bit>,
    writes_record: Signal<Local, Bit>,
    live_next: Signal<Local, Bits<6>>,
    swizzle_a: Signal<Local, Bits<6>>,
    swizzle_b: Signal<Local, Bits<6>>,
    // WB.
    predicate_bit: Signal<Local, Bits<8>>,
    loader_writes: Signal<Local, Bit>,
    record_zero: Signal<Local, Bit>,
    // The instruction word's fields (`isa::word`): lowest bits.
    at_pred: Constant<Bits<8>>,
    at_invert: Constant<Bits<8>>,
    at_mask: Constant<Bits<8>>,
    at_dest: Constant<Bits<8>>,
    at_src_a: Constant<Bits<8>>,
    at_src_b: Constant<Bits<8>>,
    at_kind: Constant<Bits<8>>,
    at_index: Constant<Bits<8>>,
    at_swizzle: Constant<Bits<8>>,
    at_abs: Constant<Bits<8>>,
    at_neg: Constant<Bits<8>>,
    sign_bit: Constant<Word>,
    op_push: Constant<Bits<OPCODE_BITS>>,
    op_end: Constant<Bits<OPCODE_BITS>>,
    op_count: Constant<Bits<OPCODE_BITS>>,
    op_out: Constant<Bits<OPCODE_BITS>>,
    op_lt: Constant<Bits<OPCODE_BITS>>,
    op_le: Constant<Bits<OPCODE_BITS>>,
    op_nz: Constant<Bits<OPCODE_BITS>>,
    /// The operations that write a register.
    op_mov: Constant<Bits<OPCODE_BITS>>,
    op_add: Constant<Bits<OPCODE_BITS>>,
    op_mul: Constant<Bits<OPCODE_BITS>>,
    op_max: Constant<Bits<OPCODE_BITS>>,
    op_min: Constant<Bits<OPCODE_BITS>>,
    op_recip: Constant<Bits<OPCODE_BITS>>,
    op_sqrt: Constant<Bits<OPCODE_BITS>>,
    op_fix: Constant<Bits<OPCODE_BITS>>,
    op_iadd: Constant<Bits<OPCODE_BITS>>,
    one: Constant<Bits<8>>,
    past_depth_bit: Constant<Bits<8>>,
    // Context words: a loading thread, a running one (state), pc + 1, spawned + 1, the
    // state's bits.
    loading_context: Constant<Context>,
    running_context: Constant<Context>,
    pc_step: Constant<Context>,
    spawned_step: Constant<Context>,
    state_bits: Constant<Context>,
}

fn position(lo: u32) -> Constant<Bits<8>> {
    Constant::new(u64::from(lo).into())
}

impl ShaderCore {
    pub fn new(depth: usize) -> Self {
        let t = threads(depth);
        Self {
            clock: Default::default(),
            load_program: Default::default(),
            load_constant: Default::default(),
            load_address: Default::default(),
            load_data: Default::default(),
            start_valid: Default::default(),
            start_ready: Default::default(),
            start_entry: Default::default(),
            start_material: Default::default(),
            start_registers: Default::default(),
            start_past_depth: Default::default(),
            start_pixel: Default::default(),
            start_depth: Default::default(),
            ray_valid: Default::default(),
            ray_ready: Default::default(),
            ray_kind: Default::default(),
            ray_pixel: Default::default(),
            ray_depth: Default::default(),
            ray_origin: Default::default(),
            ray_direction: Default::default(),
            ray_payload: Default::default(),
            ray_t_max: Default::default(),
            settle_valid: Default::default(),
            settle_ready: Default::default(),
            settle_pixel: Default::default(),
            settle_depth: Default::default(),
            settle_sum: Default::default(),
            settle_spawned: Default::default(),
            counters: Default::default(),
            instructions: Default::default(),
            busy_cycles: Default::default(),
            code: Default::default(),
            constants_a: Default::default(),
            constants_b: Default::default(),
            registers_a: Default::default(),
            registers_b: Default::default(),
            record_origin: Default::default(),
            record_direction: Default::default(),
            record_payload: Default::default(),
            record_t_max: Default::default(),
            alu: Alu::new(depth),
            turn: Default::default(),
            tid1: Default::default(),
            tid2: Default::default(),
            last_thread: Constant::new((t as u64 - 1).into()),
            ctx1: Default::default(),
            ctx2: Default::default(),
            ctx3: Default::default(),
            ctx_wb: Delay::new(alu::latency(depth)),
            instr2: Default::default(),
            runs2: Default::default(),
            alu_op: Default::default(),
            alu_a: Default::default(),
            alu_b: Default::default(),
            wb_register: Delay::new(alu::latency(depth) + 1),
            wb_predicate: Delay::new(alu::latency(depth) + 1),
            wb_record: Delay::new(alu::latency(depth) + 1),
            wb_dest: Delay::new(alu::latency(depth) + 1),
            wb_mask: Delay::new(alu::latency(depth) + 1),
            loading: Default::default(),
            loading_thread: Default::default(),
            load_step: Default::default(),
            ray_full: Default::default(),
            ray_kind_q: Default::default(),
            ray_pixel_q: Default::default(),
            ray_depth_q: Default::default(),
            ray_origin_q: Default::default(),
            ray_direction_q: Default::default(),
            ray_payload_q: Default::default(),
            ray_t_max_q: Default::default(),
            settle_full: Default::default(),
            settle_pixel_q: Default::default(),
            settle_depth_q: Default::default(),
            settle_sum_q: Default::default(),
            settle_spawned_q: Default::default(),
            counter_q: Default::default(),
            instructions_q: Default::default(),
            busy_q: Default::default(),
            live: Default::default(),
            ctx0: Default::default(),
            claim: Default::default(),
            hand_over: Default::default(),
            instr1: Default::default(),
            src1: Default::default(),
            constant_address: Default::default(),
            register_address: Default::default(),
            index1: Default::default(),
            kind1: Default::default(),
            material_base: Default::default(),
            thread_base: Default::default(),
            register_mask: Constant::new((REGISTERS as u64 - 1).into()),
            material_mask: Constant::new((MATERIAL_STRIDE as u64 - 1).into()),
            pred_index: Default::default(),
            opcode2: Default::default(),
            dest2: Default::default(),
            src2: Default::default(),
            fetched_a: Default::default(),
            fetched_b: Default::default(),
            operand_a: Default::default(),
            operand_b: Default::default(),
            running2: Default::default(),
            pushing: Default::default(),
            ending: Default::default(),
            blocked: Default::default(),
            ray_free: Default::default(),
            settle_free: Default::default(),
            ctx_next: Default::default(),
            writes_register: Default::default(),
            writes_predicate: Default::default(),
            writes_record: Default::default(),
            live_next: Default::default(),
            swizzle_a: Default::default(),
            swizzle_b: Default::default(),
            predicate_bit: Default::default(),
            loader_writes: Default::default(),
            record_zero: Default::default(),
            at_pred: position(word::PRED.0),
            at_invert: position(word::PRED_INVERT.0),
            at_mask: position(word::MASK.0),
            at_dest: position(word::DEST.0),
            at_src_a: position(word::SRC_A),
            at_src_b: position(word::SRC_B),
            at_kind: position(word::SRC_KIND.0),
            at_index: position(word::SRC_INDEX.0),
            at_swizzle: position(word::SRC_SWIZZLE.0),
            at_abs: position(word::SRC_ABS.0),
            at_neg: position(word::SRC_NEG.0),
            sign_bit: Constant::new(0x8000_0000u64.into()),
            op_push: opcode_constant(OpKind::Push),
            op_end: opcode_constant(OpKind::End),
            op_count: opcode_constant(OpKind::Count),
            op_out: opcode_constant(OpKind::Out),
            op_lt: opcode_constant(OpKind::Lt),
            op_le: opcode_constant(OpKind::Le),
            op_nz: opcode_constant(OpKind::Nz),
            op_mov: opcode_constant(OpKind::Mov),
            op_add: opcode_constant(OpKind::Add),
            op_mul: opcode_constant(OpKind::Mul),
            op_max: opcode_constant(OpKind::Max),
            op_min: opcode_constant(OpKind::Min),
            op_recip: opcode_constant(OpKind::Recip),
            op_sqrt: opcode_constant(OpKind::Sqrt),
            op_fix: opcode_constant(OpKind::Fix),
            op_iadd: opcode_constant(OpKind::IAdd),
            one: Constant::new(1.into()),
            past_depth_bit: Constant::new((1u64 << PAST_DEPTH).into()),
            loading_context: Constant::new(1.into()),
            running_context: Constant::new(2.into()),
            pc_step: Constant::new((1u64 << 2).into()),
            spawned_step: Constant::new((1u64 << 53).into()),
            state_bits: Constant::new(3.into()),
        }
    }
}

impl Logic for ShaderCore {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, turn, tid1, tid2, ctx1, ctx2, ctx3, instr2, runs2);
        dff_setup!(self, clock, loading, loading_thread, load_step, live);
        dff_setup!(
            self,
            clock,
            ray_full,
            ray_kind_q,
            ray_pixel_q,
            ray_depth_q,
            ray_origin_q
        );
        dff_setup!(
            self,
            clock,
            ray_direction_q,
            ray_payload_q,
            ray_t_max_q,
            settle_full
        );
        dff_setup!(
            self,
            clock,
            settle_pixel_q,
            settle_depth_q,
            settle_sum_q,
            settle_spawned_q
        );
        dff_setup!(self, clock, instructions_q, busy_q);
        dff_setup!(self, clock, alu_op);
        clock!(
            self,
            clock,
            alu,
            ctx_wb,
            wb_register,
            wb_predicate,
            wb_record,
            wb_dest,
            wb_mask
        );
        self.code.read_clock.next = self.clock.val();
        self.code.write_clock.next = self.clock.val();
        self.constants_a.read_clock.next = self.clock.val();
        self.constants_a.write_clock.next = self.clock.val();
        self.constants_b.read_clock.next = self.clock.val();
        self.constants_b.write_clock.next = self.clock.val();
        self.record_t_max.read_clock.next = self.clock.val();
        self.record_t_max.write_clock.next = self.clock.val();
        for k in 0..3 {
            dff_setup!(self, clock, counter_q[k], alu_a[k], alu_b[k]);
            self.registers_a[k].read_clock.next = self.clock.val();
            self.registers_a[k].write_clock.next = self.clock.val();
            self.registers_b[k].read_clock.next = self.clock.val();
            self.registers_b[k].write_clock.next = self.clock.val();
            self.record_origin[k].read_clock.next = self.clock.val();
            self.record_origin[k].write_clock.next = self.clock.val();
            self.record_direction[k].read_clock.next = self.clock.val();
            self.record_direction[k].write_clock.next = self.clock.val();
            self.record_payload[k].read_clock.next = self.clock.val();
            self.record_payload[k].write_clock.next = self.clock.val();
        }

        // The load port.
        self.code.write_enable.next = self.load_program.val();
        self.code.write_address.next = self.load_address.val();
        self.code.write_data.next = bit_cast::<64, 96>(self.load_data.val());
        self.constants_a.write_enable.next = self.load_constant.val();
        self.constants_a.write_address.next =
            bit_cast::<CONSTANT_BITS, PC_BITS>(self.load_address.val());
        self.constants_a.write_data.next = self.load_data.val();
        self.constants_b.write_enable.next = self.load_constant.val();
        self.constants_b.write_address.next =
            bit_cast::<CONSTANT_BITS, PC_BITS>(self.load_address.val());
        self.constants_b.write_data.next = self.load_data.val();

        // WB: what the thread at WB writes (the datapath's result of its instruction).
        self.predicate_bit.next = self.one.val() << self.wb_dest.q.val();
        // The loader's steps 0..7 write r0..r6 and clear the record, in cycles whose write
        // back writes nothing; step 8 waits for the thread's turn.
        self.loader_writes.next = self.loading.q.val()
            & !self.load_step.q.val().get_bit(3)
            & !self.wb_register.q.val()
            & !self.wb_record.q.val();
        self.record_zero.next = self.loader_writes.val() & (self.load_step.q.val() == 7);
        for k in 0..3 {
            self.registers_a[k].write_address.next =
                (bit_cast::<10, THREAD_BITS>(self.turn.q.val()) << 5)
                    | bit_cast::<10, 5>(self.wb_dest.q.val());
            self.registers_a[k].write_data.next = self.alu.y[k].val();
            self.registers_a[k].write_enable.next =
                self.wb_register.q.val() & self.wb_mask.q.val().get_bit(k);
            self.record_origin[k].write_address.next = self.turn.q.val();
            self.record_direction[k].write_address.next = self.turn.q.val();
            self.record_payload[k].write_address.next = self.turn.q.val();
            self.record_origin[k].write_data.next = self.alu.y[k].val();
            self.record_direction[k].write_data.next = self.alu.y[k].val();
            self.record_payload[k].write_data.next = self.alu.y[k].val();
            self.record_origin[k].write_enable.next = self.wb_record.q.val()
                & self.wb_mask.q.val().get_bit(k)
                & (self.wb_dest.q.val() == 0);
            self.record_direction[k].write_enable.next = self.wb_record.q.val()
                & self.wb_mask.q.val().get_bit(k)
                & (self.wb_dest.q.val() == 1);
            self.record_payload[k].write_enable.next = self.wb_record.q.val()
                & self.wb_mask.q.val().get_bit(k)
                & (self.wb_dest.q.val() == 2);
            if self.loader_writes.val() & !self.record_zero.val() {
                self.registers_a[k].write_address.next =
                    (bit_cast::<10, THREAD_BITS>(self.loading_thread.q.val()) << 5)
                        | bit_cast::<10, 4>(self.load_step.q.val());
                self.registers_a[k].write_enable.next = true;
            }
            if self.record_zero.val() {
                self.record_origin[k].write_address.next = self.loading_thread.q.val();
                self.record_direction[k].write_address.next = self.loading_thread.q.val();
                self.record_payload[k].write_address.next = self.loading_thread.q.val();
                self.record_origin[k].write_data.next = 0.into();
                self.record_direction[k].write_data.next = 0.into();
                self.record_payload[k].write_data.next = 0.into();
                self.record_origin[k].write_enable.next = true;
                self.record_direction[k].write_enable.next = true;
                self.record_payload[k].write_enable.next = true;
            }
        }
        self.record_t_max.write_address.next = self.turn.q.val();
        self.record_t_max.write_data.next = self.alu.y[0].val();
        self.record_t_max.write_enable.next =
            self.wb_record.q.val() & self.wb_mask.q.val().get_bit(0) & (self.wb_dest.q.val() == 3);
        if self.record_zero.val() {
            self.record_t_max.write_address.next = self.loading_thread.q.val();
            self.record_t_max.write_data.next = 0.into();
            self.record_t_max.write_enable.next = true;
        }
        // The loader's register word, step k's start register.
        for r in 0..7 {
            if self.loader_writes.val() & (self.load_step.q.val() == r.to_bits()) {
                for k in 0..3 {
                    self.registers_a[k].write_data.next =
                        self.start_registers[r].val().get_bits::<32>(32 * k);
                }
            }
        }
        for k in 0..3 {
            self.registers_b[k].write_address.next = self.registers_a[k].write_address.val();
            self.registers_b[k].write_data.next = self.registers_a[k].write_data.val();
            self.registers_b[k].write_enable.next = self.registers_a[k].write_enable.val();
        }
        if self.loader_writes.val() {
            self.load_step.d.next = self.load_step.q.val() + 1;
        }

        // S0 (the same thread as WB): the context with WB's predicate, a start claimed or
        // handed over; its instruction fetched.
        self.ctx0.next = self.ctx_wb.q.val();
        if self.wb_predicate.q.val() {
            self.ctx0.next = self.ctx0.val() & !(bit_cast::<64, 8>(self.predicate_bit.val()) << 13);
            if self.alu.p.val() {
                self.ctx0.next =
                    self.ctx0.val() | (bit_cast::<64, 8>(self.predicate_bit.val()) << 13);
            }
        }
        self.claim.next = self.start_valid.val()
            & !self.loading.q.val()
            & (self.ctx0.val().get_bits::<2>(0) == 0);
        self.hand_over.next = self.loading.q.val()
            & (self.load_step.q.val() == 8)
            & (self.loading_thread.q.val() == self.turn.q.val());
        self.start_ready.next = self.hand_over.val();
        self.live_next.next = self.live.q.val();
        if self.claim.val() {
            self.ctx0.next = self.loading_context.val();
            self.loading.d.next = true;
            self.loading_thread.d.next = self.turn.q.val();
            self.load_step.d.next = 0.into();
            self.live_next.next = self.live_next.val() + 1;
        }
        if self.hand_over.val() {
            // Running at the entry: p0 true, p1 past depth, the others false.
            self.ctx0.next = self.running_context.val()
                | (bit_cast::<64, PC_BITS>(self.start_entry.val()) << 2)
                | (bit_cast::<64, 8>(self.one.val()) << 13)
                | (bit_cast::<64, MATERIAL_BITS>(self.start_material.val()) << 21)
                | (bit_cast::<64, PIXEL_BITS>(self.start_pixel.val()) << 28)
                | (bit_cast::<64, DEPTH_BITS>(self.start_depth.val()) << 49);
            if self.start_past_depth.val() {
                self.ctx0.next =
                    self.ctx0.val() | (bit_cast::<64, 8>(self.past_depth_bit.val()) << 13);
            }
            self.loading.d.next = false;
        }
        self.code.read_address.next = self.ctx0.val().get_bits::<PC_BITS>(2);
        self.ctx1.d.next = self.ctx0.val();
        self.tid1.d.next = self.turn.q.val();
        self.turn.d.next = self.turn.q.val() + 1;
        if self.turn.q.val() == self.last_thread.val() {
            self.turn.d.next = 0.into();
        }

        // S1: decode; operand and record addresses; the predicate.
        self.instr1.next = self.code.read_data.val();
        self.src1[0].next = bit_cast::<19, 64>(self.instr1.val() >> self.at_src_a.val());
        self.src1[1].next = bit_cast::<19, 64>(self.instr1.val() >> self.at_src_b.val());
        // Constant k, or the material's constant k; the register (`bit_cast` of an indexed
        // signal does not build inside a loop: a and b spelled out).
        self.index1[0].next =
            bit_cast::<CONSTANT_BITS, 19>(self.src1[0].val() >> self.at_index.val());
        self.index1[1].next =
            bit_cast::<CONSTANT_BITS, 19>(self.src1[1].val() >> self.at_index.val());
        self.kind1[0].next = bit_cast::<2, 19>(self.src1[0].val() >> self.at_kind.val());
        self.kind1[1].next = bit_cast::<2, 19>(self.src1[1].val() >> self.at_kind.val());
        self.material_base.next = bit_cast::<CONSTANT_BITS, MATERIAL_BITS>(
            self.ctx1.q.val().get_bits::<MATERIAL_BITS>(21),
        ) << 2;
        self.thread_base.next = bit_cast::<10, THREAD_BITS>(self.tid1.q.val()) << 5;
        self.register_address[0].next = self.thread_base.val()
            | bit_cast::<10, CONSTANT_BITS>(self.index1[0].val() & self.register_mask.val());
        self.register_address[1].next = self.thread_base.val()
            | bit_cast::<10, CONSTANT_BITS>(self.index1[1].val() & self.register_mask.val());
        for s in 0..2 {
            self.constant_address[s].next = self.index1[s].val();
            if self.kind1[s].val() == 2 {
                self.constant_address[s].next =
                    self.material_base.val() | (self.index1[s].val() & self.material_mask.val());
            }
        }
        self.constants_a.read_address.next = self.constant_address[0].val();
        self.constants_b.read_address.next = self.constant_address[1].val();
        for k in 0..3 {
            self.registers_a[k].read_address.next = self.register_address[0].val();
            self.registers_b[k].read_address.next = self.register_address[1].val();
            self.record_origin[k].read_address.next = self.tid1.q.val();
            self.record_direction[k].read_address.next = self.tid1.q.val();
            self.record_payload[k].read_address.next = self.tid1.q.val();
        }
        self.record_t_max.read_address.next = self.tid1.q.val();
        self.pred_index.next =
            self.one.val() << bit_cast::<3, 64>(self.instr1.val() >> self.at_pred.val());
        self.runs2.d.next = (self.ctx1.q.val().get_bits::<8>(13) & self.pred_index.val()).any()
            ^ bit_cast::<1, 64>(self.instr1.val() >> self.at_invert.val()).any();
        self.instr2.d.next = self.instr1.val();
        self.ctx2.d.next = self.ctx1.q.val();
        self.tid2.d.next = self.tid1.q.val();

        // S2: operands; Push, End, Count.
        self.opcode2.next = bit_cast::<OPCODE_BITS, 64>(self.instr2.q.val());
        self.dest2.next = bit_cast::<5, 64>(self.instr2.q.val() >> self.at_dest.val());
        self.src2[0].next = bit_cast::<19, 64>(self.instr2.q.val() >> self.at_src_a.val());
        self.src2[1].next = bit_cast::<19, 64>(self.instr2.q.val() >> self.at_src_b.val());
        self.fetched_a.next = self.constants_a.read_data.val();
        if bit_cast::<2, 19>(self.src2[0].val() >> self.at_kind.val()) == 0 {
            self.fetched_a.next = bit_cast::<96, 32>(self.registers_a[0].read_data.val())
                | (bit_cast::<96, 32>(self.registers_a[1].read_data.val()) << 32)
                | (bit_cast::<96, 32>(self.registers_a[2].read_data.val()) << 64);
        }
        self.fetched_b.next = self.constants_b.read_data.val();
        if bit_cast::<2, 19>(self.src2[1].val() >> self.at_kind.val()) == 0 {
            self.fetched_b.next = bit_cast::<96, 32>(self.registers_b[0].read_data.val())
                | (bit_cast::<96, 32>(self.registers_b[1].read_data.val()) << 32)
                | (bit_cast::<96, 32>(self.registers_b[2].read_data.val()) << 64);
        }
        self.swizzle_a.next = bit_cast::<6, 19>(self.src2[0].val() >> self.at_swizzle.val());
        self.swizzle_b.next = bit_cast::<6, 19>(self.src2[1].val() >> self.at_swizzle.val());
        for k in 0..3 {
            // Lane k: the component its swizzle names, then abs, then neg.
            self.operand_a[k].next = self.fetched_a.val().get_bits::<32>(0);
            if self.swizzle_a.val().get_bits::<2>(2 * k) == 1 {
                self.operand_a[k].next = self.fetched_a.val().get_bits::<32>(32);
            }
            if self.swizzle_a.val().get_bits::<2>(2 * k) == 2 {
                self.operand_a[k].next = self.fetched_a.val().get_bits::<32>(64);
            }
            if bit_cast::<1, 19>(self.src2[0].val() >> self.at_abs.val()).any() {
                self.operand_a[k].next = self.operand_a[k].val() & !self.sign_bit.val();
            }
            if bit_cast::<1, 19>(self.src2[0].val() >> self.at_neg.val()).any() {
                self.operand_a[k].next = self.operand_a[k].val() ^ self.sign_bit.val();
            }
            self.operand_b[k].next = self.fetched_b.val().get_bits::<32>(0);
            if self.swizzle_b.val().get_bits::<2>(2 * k) == 1 {
                self.operand_b[k].next = self.fetched_b.val().get_bits::<32>(32);
            }
            if self.swizzle_b.val().get_bits::<2>(2 * k) == 2 {
                self.operand_b[k].next = self.fetched_b.val().get_bits::<32>(64);
            }
            if bit_cast::<1, 19>(self.src2[1].val() >> self.at_abs.val()).any() {
                self.operand_b[k].next = self.operand_b[k].val() & !self.sign_bit.val();
            }
            if bit_cast::<1, 19>(self.src2[1].val() >> self.at_neg.val()).any() {
                self.operand_b[k].next = self.operand_b[k].val() ^ self.sign_bit.val();
            }
        }
        self.running2.next = self.ctx2.q.val().get_bits::<2>(0) == 2;
        self.pushing.next =
            self.running2.val() & self.runs2.q.val() & (self.opcode2.val() == self.op_push.val());
        self.ending.next =
            self.running2.val() & self.runs2.q.val() & (self.opcode2.val() == self.op_end.val());
        self.ray_free.next = !self.ray_full.q.val() | self.ray_ready.val();
        self.settle_free.next = !self.settle_full.q.val() | self.settle_ready.val();
        self.blocked.next = (self.pushing.val() & !self.ray_free.val())
            | (self.ending.val() & !self.settle_free.val());
        if self.ray_ready.val() {
            self.ray_full.d.next = false;
        }
        if self.settle_ready.val() {
            self.settle_full.d.next = false;
        }
        self.ctx_next.next = self.ctx2.q.val();
        if self.running2.val() & !self.blocked.val() {
            self.ctx_next.next = self.ctx2.q.val() + self.pc_step.val();
            self.instructions_q.d.next = self.instructions_q.q.val() + 1;
        }
        if self.pushing.val() & self.ray_free.val() {
            self.ray_full.d.next = true;
            self.ray_kind_q.d.next = bit_cast::<2, 5>(self.dest2.val());
            self.ray_pixel_q.d.next = self.ctx2.q.val().get_bits::<PIXEL_BITS>(28);
            self.ray_depth_q.d.next = self.ctx2.q.val().get_bits::<DEPTH_BITS>(49);
            self.ray_origin_q.d.next = bit_cast::<96, 32>(self.record_origin[0].read_data.val())
                | (bit_cast::<96, 32>(self.record_origin[1].read_data.val()) << 32)
                | (bit_cast::<96, 32>(self.record_origin[2].read_data.val()) << 64);
            self.ray_direction_q.d.next =
                bit_cast::<96, 32>(self.record_direction[0].read_data.val())
                    | (bit_cast::<96, 32>(self.record_direction[1].read_data.val()) << 32)
                    | (bit_cast::<96, 32>(self.record_direction[2].read_data.val()) << 64);
            self.ray_payload_q.d.next = bit_cast::<96, 32>(self.record_payload[0].read_data.val())
                | (bit_cast::<96, 32>(self.record_payload[1].read_data.val()) << 32)
                | (bit_cast::<96, 32>(self.record_payload[2].read_data.val()) << 64);
            self.ray_t_max_q.d.next = self.record_t_max.read_data.val();
            // The spawned count, bits 53..57.
            self.ctx_next.next = self.ctx_next.val() + self.spawned_step.val();
        }
        if self.ending.val() & self.settle_free.val() {
            self.settle_full.d.next = true;
            self.settle_pixel_q.d.next = self.ctx2.q.val().get_bits::<PIXEL_BITS>(28);
            self.settle_depth_q.d.next = self.ctx2.q.val().get_bits::<DEPTH_BITS>(49);
            self.settle_sum_q.d.next = bit_cast::<96, 32>(self.operand_a[0].val())
                | (bit_cast::<96, 32>(self.operand_a[1].val()) << 32)
                | (bit_cast::<96, 32>(self.operand_a[2].val()) << 64);
            self.settle_spawned_q.d.next = self.ctx2.q.val().get_bits::<SPAWNED_BITS>(53);
            // Free.
            self.ctx_next.next = self.ctx_next.val() & !self.state_bits.val();
            self.live_next.next = self.live_next.val() - 1;
        }
        self.live.d.next = self.live_next.val();
        if self.live.q.val().any() {
            self.busy_q.d.next = self.busy_q.q.val() + 1;
        }
        for c in 0..3 {
            if self.running2.val()
                & self.runs2.q.val()
                & (self.opcode2.val() == self.op_count.val())
                & (self.dest2.val() == c.to_bits())
            {
                self.counter_q[c].d.next = self.counter_q[c].q.val() + 1;
            }
        }
        self.ctx3.d.next = self.ctx_next.val();

        // S3: the datapath's operands; what WB writes, beside it.
        self.writes_predicate.next = (self.opcode2.val() == self.op_lt.val())
            | (self.opcode2.val() == self.op_le.val())
            | (self.opcode2.val() == self.op_nz.val());
        self.writes_record.next = self.opcode2.val() == self.op_out.val();
        self.writes_register.next = (self.opcode2.val() == self.op_mov.val())
            | (self.opcode2.val() == self.op_add.val())
            | (self.opcode2.val() == self.op_mul.val())
            | (self.opcode2.val() == self.op_max.val())
            | (self.opcode2.val() == self.op_min.val())
            | (self.opcode2.val() == self.op_recip.val())
            | (self.opcode2.val() == self.op_sqrt.val())
            | (self.opcode2.val() == self.op_fix.val())
            | (self.opcode2.val() == self.op_iadd.val());
        self.wb_register.d.next =
            self.running2.val() & self.runs2.q.val() & self.writes_register.val();
        self.wb_predicate.d.next =
            self.running2.val() & self.runs2.q.val() & self.writes_predicate.val();
        self.wb_record.d.next = self.running2.val() & self.runs2.q.val() & self.writes_record.val();
        self.wb_dest.d.next = self.dest2.val();
        self.wb_mask.d.next = bit_cast::<3, 64>(self.instr2.q.val() >> self.at_mask.val());
        self.alu_op.d.next = self.opcode2.val();
        self.alu.op.next = self.alu_op.q.val();
        for k in 0..3 {
            self.alu_a[k].d.next = self.operand_a[k].val();
            self.alu_b[k].d.next = self.operand_b[k].val();
            self.alu.a[k].next = self.alu_a[k].q.val();
            self.alu.b[k].next = self.alu_b[k].q.val();
        }
        self.ctx_wb.d.next = self.ctx3.q.val();

        // Outputs.
        self.ray_valid.next = self.ray_full.q.val();
        self.ray_kind.next = self.ray_kind_q.q.val();
        self.ray_pixel.next = self.ray_pixel_q.q.val();
        self.ray_depth.next = self.ray_depth_q.q.val();
        self.ray_origin.next = self.ray_origin_q.q.val();
        self.ray_direction.next = self.ray_direction_q.q.val();
        self.ray_payload.next = self.ray_payload_q.q.val();
        self.ray_t_max.next = self.ray_t_max_q.q.val();
        self.settle_valid.next = self.settle_full.q.val();
        self.settle_pixel.next = self.settle_pixel_q.q.val();
        self.settle_depth.next = self.settle_depth_q.q.val();
        self.settle_sum.next = self.settle_sum_q.q.val();
        self.settle_spawned.next = self.settle_spawned_q.q.val();
        for c in 0..3 {
            self.counters[c].next = self.counter_q[c].q.val();
        }
        self.instructions.next = self.instructions_q.q.val();
        self.busy_cycles.next = self.busy_q.q.val();
    }
}

/// A word through the load port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Load {
    Program { address: u16, word: u64 },
    Constant { address: u16, value: Word3 },
}

/// A program the core's memories do not hold.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum LoadError {
    #[error("a program of {len} instructions: the program memory holds {CODE}")]
    Code { len: usize },
    #[error("{len} constants: the constant memory holds {CONSTANTS}")]
    Constants { len: usize },
    #[error(transparent)]
    Isa(#[from] isa::IsaError),
}

/// The load port's words for `program`: its code, then every constant entry (zero past the
/// program's, as the interpreter reads them).
pub fn loads(program: &Program) -> Result<Vec<Load>, LoadError> {
    if program.code.len() > CODE {
        return Err(LoadError::Code {
            len: program.code.len(),
        });
    }
    if program.constants.len() > CONSTANTS {
        return Err(LoadError::Constants {
            len: program.constants.len(),
        });
    }
    let mut words = Vec::new();
    for (address, instr) in program.code.iter().enumerate() {
        words.push(Load::Program {
            address: address as u16,
            word: Instr::encode(*instr)?,
        });
    }
    for address in 0..CONSTANTS {
        words.push(Load::Constant {
            address: address as u16,
            value: program.constants.get(address).copied().unwrap_or([0; 3]),
        });
    }
    Ok(words)
}

/// A thread start: the interpreter's input and the tag the core passes through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Start {
    pub input: ThreadInput,
    pub pixel: u32,
    pub depth: u32,
}

/// A start the core's ports do not carry.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum StartError {
    #[error("entry point {entry}: the program memory holds {CODE} instructions")]
    Entry { entry: u16 },
    #[error("material {material}: the constant memory holds {} materials", 1 << MATERIAL_BITS)]
    Material { material: u32 },
    #[error("pixel {pixel} does not fit the tag's {PIXEL_BITS} bits")]
    Pixel { pixel: u32 },
    #[error("depth {depth} does not fit the tag's {DEPTH_BITS} bits")]
    Depth { depth: u32 },
}

impl Start {
    pub fn new(input: ThreadInput, pixel: u32, depth: u32) -> Result<Start, StartError> {
        if input.entry as usize >= CODE {
            return Err(StartError::Entry { entry: input.entry });
        }
        if input.material >= 1 << MATERIAL_BITS {
            return Err(StartError::Material {
                material: input.material,
            });
        }
        if pixel >= 1 << PIXEL_BITS {
            return Err(StartError::Pixel { pixel });
        }
        if depth >= 1 << DEPTH_BITS {
            return Err(StartError::Depth { depth });
        }
        Ok(Start {
            input,
            pixel,
            depth,
        })
    }
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CoreInput {
    pub load: Option<Load>,
    pub start: Option<Start>,
    pub ray_ready: bool,
    pub settle_ready: bool,
}

/// A pushed ray: the interpreter's, and the thread's tag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayOut {
    pub pushed: hw_model::frame::shader::Pushed,
    pub pixel: u32,
    pub depth: u32,
}

/// A settle record.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SettleOut {
    pub pixel: u32,
    pub depth: u32,
    pub sum: [i32; 3],
    pub spawned: u32,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoreOutput {
    pub start_ready: bool,
    pub ray: Option<RayOut>,
    pub settle: Option<SettleOut>,
    /// `Counter::ALL`'s order.
    pub counters: [u32; 3],
    pub instructions: u32,
    pub busy_cycles: u32,
}

fn lanes(w: Word3) -> Lanes {
    Lanes::from(u64::from(w[0]))
        | (Lanes::from(u64::from(w[1])) << 32)
        | (Lanes::from(u64::from(w[2])) << 64)
}

fn words(l: Lanes) -> Word3 {
    let v = l.to_u128();
    [0, 1, 2].map(|k| (v >> (32 * k)) as u32)
}

impl Stepped for ShaderCore {
    type Input = CoreInput;
    type Output = CoreOutput;

    fn idle() -> CoreInput {
        CoreInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &CoreInput) {
        self.load_program.next = matches!(input.load, Some(Load::Program { .. }));
        self.load_constant.next = matches!(input.load, Some(Load::Constant { .. }));
        let (address, data) = match input.load {
            Some(Load::Program { address, word }) => (address, Lanes::from(word)),
            Some(Load::Constant { address, value }) => (address, lanes(value)),
            None => (0, Lanes::default()),
        };
        self.load_address.next = u64::from(address).into();
        self.load_data.next = data;
        self.start_valid.next = input.start.is_some();
        let start = input.start.unwrap_or(Start {
            input: ThreadInput {
                entry: 0,
                material: 0,
                registers: [[0; 3]; 7],
                past_depth: false,
            },
            pixel: 0,
            depth: 0,
        });
        self.start_entry.next = u64::from(start.input.entry).into();
        self.start_material.next = u64::from(start.input.material).into();
        for (port, &r) in self.start_registers.iter_mut().zip(&start.input.registers) {
            port.next = lanes(r);
        }
        self.start_past_depth.next = start.input.past_depth;
        self.start_pixel.next = u64::from(start.pixel).into();
        self.start_depth.next = u64::from(start.depth).into();
        self.ray_ready.next = input.ray_ready;
        self.settle_ready.next = input.settle_ready;
    }

    fn observe(&self) -> CoreOutput {
        let ray = self.ray_valid.val().then(|| RayOut {
            pushed: hw_model::frame::shader::Pushed {
                kind: PushKind::ALL[self.ray_kind.val().index() % PushKind::ALL.len()],
                origin: words(self.ray_origin.val()),
                direction: words(self.ray_direction.val()),
                payload: words(self.ray_payload.val()),
                t_max: self.ray_t_max.val().to_u64() as u32,
            },
            pixel: self.ray_pixel.val().to_u64() as u32,
            depth: self.ray_depth.val().to_u64() as u32,
        });
        let settle = self.settle_valid.val().then(|| SettleOut {
            pixel: self.settle_pixel.val().to_u64() as u32,
            depth: self.settle_depth.val().to_u64() as u32,
            sum: words(self.settle_sum.val()).map(|w| w as i32),
            spawned: self.settle_spawned.val().to_u64() as u32,
        });
        CoreOutput {
            start_ready: self.start_ready.val(),
            ray,
            settle,
            counters: std::array::from_fn(|c| self.counters[c].val().to_u64() as u32),
            instructions: self.instructions.val().to_u64() as u32,
            busy_cycles: self.busy_cycles.val().to_u64() as u32,
        }
    }
}

/// Runs a freshly built core at `depth` in rust-hdl's simulator, the inputs of each cycle
/// chosen by `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_core(
    depth: usize,
    drive: impl FnMut(Option<&CoreOutput>) -> Option<CoreInput> + Send + 'static,
) -> Vec<(CoreInput, CoreOutput)> {
    simulate_driven(move || ShaderCore::new(depth), drive)
}

/// Verilog of the core at `depth`, top module `top`.
pub fn core_verilog(depth: usize) -> String {
    built_verilog(move || ShaderCore::new(depth))
}
