//! The AXI4-Stream front end: feeds every lane one query per cycle and returns the results in
//! order through a result FIFO, plus the register-mode path into lane 0.
//!
//! Packet format (docs/stream.md): an input beat carries one [`IN_LANE_BITS`]-bit slot per
//! lane (lane i at `tdata[544·i +: 544]`): words 0–15 are the query in the register map's
//! operand order (fp32 bits: origin xyz, direction xyz, v0, v1, v2, t_min), word 16
//! ([`CTRL_WORD`]) is the lane's control word (bit 0 `valid`, bits 31:8 a 24-bit `tag`, bits
//! 7:1 ignored). An output beat carries one [`OUT_LANE_BITS`]-bit slot per
//! lane: word 0 flags (bit 0 `hit` (0 for an invalid lane), bit 1 `valid`, bits 31:8 the
//! `tag`), words 1–3 t, u, v (fp32 bits). Output beat k answers input beat k; `tlast` is
//! passed through.
//!
//! Back-pressure: the lanes cannot stall, so every accepted beat reserves a FIFO slot up front
//! (credit counting over `accepted − read`); `s_tready` falls only when [`FIFO_DEPTH`] beats
//! are in flight or buffered. The FIFO is one block-RAM deep (512 entries, the RAMB18
//! granularity), so with `latency + 2 < 512` the lanes run at one beat per cycle whenever
//! data is there and `m_tready` keeps up.
use rust_hdl::prelude::*;

use crate::defaults;

use crate::regmap::OPERAND_COUNT;

/// Where the control word is in a lane's input slot: after the query's operands.
pub const CTRL_WORD: usize = OPERAND_COUNT;
/// Bits of one lane's slot in an input beat (the query and the control word: 17 words).
pub const IN_LANE_BITS: usize = 32 * (CTRL_WORD + 1);
/// Bits of one lane's slot in an output beat (4 words).
pub const OUT_LANE_BITS: usize = 128;
/// Bits of the query inside a lane's input slot.
pub const QUERY_BITS: usize = 32 * OPERAND_COUNT;
// The kernel spells these values as literals (rust-hdl leaks named consts into Verilog).
const _: () = assert!(QUERY_BITS == 512 && FIFO_ADDR_BITS == 9);
/// Address bits of the result FIFO.
pub const FIFO_ADDR_BITS: usize = 9;
/// Entries of the result FIFO (beats in flight plus beats waiting for `m_tready`).
pub const FIFO_DEPTH: usize = 1 << FIFO_ADDR_BITS;
/// Pointer width: the FIFO address plus a wrap bit.
const PTR_BITS: usize = FIFO_ADDR_BITS + 1;
/// Bits of a lane's stored result: hit in bit 0, t, u, v from bit 1.
const RESULT_BITS: usize = 97;
/// Width of the latency counters (latencies up to 65535 cycles).
const TIMER_BITS: usize = 16;

/// Control word bits (word [`CTRL_WORD`] of an input slot, word 0 of an output slot).
pub const CTRL_VALID: u32 = 1 << 0;
pub const FLAG_HIT: u32 = 1 << 0;
pub const FLAG_VALID: u32 = 1 << 1;
pub const TAG_SHIFT: u32 = 8;
pub const TAG_BITS: u32 = 24;
/// Where the FIFO's side word keeps the beat's `tlast` (a bit the control word ignores).
const SIDE_TLAST: u32 = 1 << 1;

#[derive(LogicBlock)]
pub struct StreamFrontEnd {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active low.
    pub reset_n: Signal<In, Bit>,
    // AXI4-Stream slave (queries), one slot per lane.
    pub s_tdata: Vec<Signal<In, Bits<IN_LANE_BITS>>>,
    pub s_tvalid: Signal<In, Bit>,
    pub s_tready: Signal<Out, Bit>,
    pub s_tlast: Signal<In, Bit>,
    // AXI4-Stream master (results), one slot per lane.
    pub m_tdata: Vec<Signal<Out, Bits<OUT_LANE_BITS>>>,
    pub m_tvalid: Signal<Out, Bit>,
    pub m_tready: Signal<In, Bit>,
    pub m_tlast: Signal<Out, Bit>,
    // Register mode (the AXI4-Lite slave's core side): one test on lane 0.
    pub reg_start: Signal<In, Bit>,
    pub reg_operands: [Signal<In, Bits<32>>; OPERAND_COUNT],
    /// One-cycle pulse: lane 0's outputs are the register-mode test's result.
    pub reg_done: Signal<Out, Bit>,
    // Lanes.
    pub lane_valid_in: Vec<Signal<Out, Bit>>,
    pub lane_query: Vec<Signal<Out, Bits<QUERY_BITS>>>,
    /// Lane 0's `valid_out` (the lanes run in lockstep).
    pub lane_valid_out: Signal<In, Bit>,
    pub lane_hit: Vec<Signal<In, Bit>>,
    pub lane_t: Vec<Signal<In, Bits<32>>>,
    pub lane_u: Vec<Signal<In, Bits<32>>>,
    pub lane_v: Vec<Signal<In, Bits<32>>>,
    // FIFO: slot `acc` is reserved at accept, filled at `res`, read at `rd`.
    side_ram: Vec<RAM<Bits<32>, FIFO_ADDR_BITS>>,
    result_ram: Vec<RAM<Bits<RESULT_BITS>, FIFO_ADDR_BITS>>,
    acc_ptr: DFF<Bits<PTR_BITS>>,
    res_ptr: DFF<Bits<PTR_BITS>>,
    rd_ptr: DFF<Bits<PTR_BITS>>,
    head_valid: DFF<Bit>,
    /// Cycles left until the lanes hold no query from before reset.
    warm: DFF<Bits<TIMER_BITS>>,
    reg_pending: DFF<Bit>,
    reg_timer: DFF<Bits<TIMER_BITS>>,
    latency: Constant<Bits<TIMER_BITS>>,
    ctrl_keep: Constant<Bits<32>>,
    tag_mask: Constant<Bits<32>>,
    flag_valid: Constant<Bits<32>>,
    flag_hit: Constant<Bits<32>>,
    side_tlast: Constant<Bits<32>>,
    result_hit: Constant<Bits<RESULT_BITS>>,
    // Combinational helpers.
    ready: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
    stream_result: Signal<Local, Bit>,
    pop: Signal<Local, Bit>,
    rd_next: Signal<Local, Bits<PTR_BITS>>,
    in_flight: Signal<Local, Bits<PTR_BITS>>,
    reg_active: Signal<Local, Bit>,
    reg_now: Signal<Local, Bits<TIMER_BITS>>,
    reg_query: Signal<Local, Bits<QUERY_BITS>>,
    side_in: Signal<Local, Bits<32>>,
    result_in: Signal<Local, Bits<RESULT_BITS>>,
    result_out: Signal<Local, Bits<RESULT_BITS>>,
    word: Signal<Local, Bits<32>>,
    flags: Signal<Local, Bits<32>>,
}

impl StreamFrontEnd {
    /// A front end for `lanes` lanes whose results appear `latency` cycles after their queries.
    pub fn new(lanes: usize, latency: usize) -> Self {
        assert!(lanes >= 1, "at least one lane");
        assert!(
            latency < 1 << TIMER_BITS,
            "latency {latency} exceeds the counters"
        );
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            s_tdata: defaults(lanes),
            s_tvalid: Default::default(),
            s_tready: Default::default(),
            s_tlast: Default::default(),
            m_tdata: defaults(lanes),
            m_tvalid: Default::default(),
            m_tready: Default::default(),
            m_tlast: Default::default(),
            reg_start: Default::default(),
            reg_operands: Default::default(),
            reg_done: Default::default(),
            lane_valid_in: defaults(lanes),
            lane_query: defaults(lanes),
            lane_valid_out: Default::default(),
            lane_hit: defaults(lanes),
            lane_t: defaults(lanes),
            lane_u: defaults(lanes),
            lane_v: defaults(lanes),
            side_ram: defaults(lanes),
            result_ram: defaults(lanes),
            acc_ptr: Default::default(),
            res_ptr: Default::default(),
            rd_ptr: Default::default(),
            head_valid: Default::default(),
            warm: Default::default(),
            reg_pending: Default::default(),
            reg_timer: Default::default(),
            latency: Constant::new((latency as u64).into()),
            ctrl_keep: Constant::new(((u32::MAX << TAG_SHIFT | CTRL_VALID) as u64).into()),
            tag_mask: Constant::new(((u32::MAX << TAG_SHIFT) as u64).into()),
            flag_valid: Constant::new((FLAG_VALID as u64).into()),
            flag_hit: Constant::new((FLAG_HIT as u64).into()),
            side_tlast: Constant::new((SIDE_TLAST as u64).into()),
            result_hit: Constant::new(1u64.into()),
            ready: Default::default(),
            accept: Default::default(),
            stream_result: Default::default(),
            pop: Default::default(),
            rd_next: Default::default(),
            in_flight: Default::default(),
            reg_active: Default::default(),
            reg_now: Default::default(),
            reg_query: Default::default(),
            side_in: Default::default(),
            result_in: Default::default(),
            result_out: Default::default(),
            word: Default::default(),
            flags: Default::default(),
        }
    }
}

impl Logic for StreamFrontEnd {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            acc_ptr,
            res_ptr,
            rd_ptr,
            head_valid,
            warm,
            reg_pending,
            reg_timer
        );

        // Register mode: lane 0 takes the slave's operands on `reg_start`; the result is at
        // lane 0's outputs exactly `latency` cycles later.
        // Operand k goes to bits 32k.. of the query: shift each in at the top (480 =
        // QUERY_BITS - 32), moving the earlier ones down.
        self.reg_query.next = 0.into();
        for k in 0..OPERAND_COUNT {
            self.word.next = self.reg_operands[k].val();
            self.reg_query.next =
                (self.reg_query.val() >> 32) | (bit_cast::<QUERY_BITS, 32>(self.word.val()) << 480);
        }
        self.reg_active.next = self.reg_pending.q.val() | self.reg_start.val();
        self.reg_now.next = self.reg_timer.q.val();
        if self.reg_start.val() {
            self.reg_now.next = self.latency.val();
        }
        self.reg_done.next = self.reg_active.val() & (self.reg_now.val() == 0);
        self.reg_pending.d.next = self.reg_active.val() & !self.reg_done.val();
        if self.reg_now.val() != 0 {
            self.reg_timer.d.next = self.reg_now.val() - 1;
        }

        // Input side: a beat is taken when a FIFO slot is free for its results (bit 9 =
        // FIFO_ADDR_BITS: 512 slots taken); never in the cycle a register-mode test enters lane 0.
        self.in_flight.next = self.acc_ptr.q.val() - self.rd_ptr.q.val();
        self.ready.next = self.reset_n.val()
            & (self.warm.q.val() == 0)
            & !self.in_flight.val().get_bit(9)
            & !self.reg_start.val();
        self.s_tready.next = self.ready.val();
        self.accept.next = self.ready.val() & self.s_tvalid.val();
        if self.accept.val() {
            self.acc_ptr.d.next = self.acc_ptr.q.val() + 1;
        }
        if self.warm.q.val() != 0 {
            self.warm.d.next = self.warm.q.val() - 1;
        }

        // Results of stream beats arrive in order on lane 0's valid_out (the register-mode
        // result is told apart by its timer); each fills the oldest reserved slot. Once warm,
        // a lane's valid_out comes only from an accepted beat or `reg_start`, so no pointer
        // test is needed: at latency 0 the result arrives in its beat's accept cycle, before
        // `acc_ptr` counts it, and testing `accept` here would close a combinational loop
        // through `lane_valid_in` in Verilator's view.
        self.stream_result.next =
            self.lane_valid_out.val() & !self.reg_done.val() & (self.warm.q.val() == 0);
        if self.stream_result.val() {
            self.res_ptr.d.next = self.res_ptr.q.val() + 1;
        }

        // Output side: the RAM is read one cycle ahead (address = next head), so the head
        // entry is on the RAM outputs while m_tvalid is high and stays there until taken.
        self.pop.next = self.head_valid.q.val() & self.m_tready.val();
        self.rd_next.next = self.rd_ptr.q.val();
        if self.pop.val() {
            self.rd_next.next = self.rd_ptr.q.val() + 1;
        }
        self.rd_ptr.d.next = self.rd_next.val();
        self.head_valid.d.next = self.res_ptr.q.val() != self.rd_next.val();
        self.m_tvalid.next = self.head_valid.q.val();
        self.m_tlast.next = self.side_ram[0].read_data.val().get_bit(1);

        for i in 0..self.lane_valid_in.len() {
            self.lane_valid_in[i].next = self.accept.val();
            self.lane_query[i].next = self.s_tdata[i].val().get_bits::<QUERY_BITS>(0);

            self.side_ram[i].write_clock.next = self.clock.val();
            self.side_ram[i].read_clock.next = self.clock.val();
            self.side_ram[i].write_enable.next = self.accept.val();
            self.side_ram[i].write_address.next =
                self.acc_ptr.q.val().get_bits::<FIFO_ADDR_BITS>(0);
            // The control word (bits 512.. = QUERY_BITS) keeps valid and tag; bit 1 carries
            // this beat's tlast.
            self.side_in.next = self.s_tdata[i].val().get_bits::<32>(512) & self.ctrl_keep.val();
            if self.s_tlast.val() {
                self.side_in.next = self.side_in.val() | self.side_tlast.val();
            }
            self.side_ram[i].write_data.next = self.side_in.val();
            self.side_ram[i].read_address.next = self.rd_next.val().get_bits::<FIFO_ADDR_BITS>(0);

            self.result_ram[i].write_clock.next = self.clock.val();
            self.result_ram[i].read_clock.next = self.clock.val();
            self.result_ram[i].write_enable.next = self.stream_result.val();
            self.result_ram[i].write_address.next =
                self.res_ptr.q.val().get_bits::<FIFO_ADDR_BITS>(0);
            self.word.next = self.lane_v[i].val();
            self.result_in.next = bit_cast::<RESULT_BITS, 32>(self.word.val());
            self.word.next = self.lane_u[i].val();
            self.result_in.next =
                (self.result_in.val() << 32) | bit_cast::<RESULT_BITS, 32>(self.word.val());
            self.word.next = self.lane_t[i].val();
            self.result_in.next =
                (self.result_in.val() << 32) | bit_cast::<RESULT_BITS, 32>(self.word.val());
            self.result_in.next = self.result_in.val() << 1;
            if self.lane_hit[i].val() {
                self.result_in.next = self.result_in.val() | self.result_hit.val();
            }
            self.result_ram[i].write_data.next = self.result_in.val();
            self.result_ram[i].read_address.next = self.rd_next.val().get_bits::<FIFO_ADDR_BITS>(0);

            self.flags.next = self.side_ram[i].read_data.val() & self.tag_mask.val();
            if self.side_ram[i].read_data.val().get_bit(0) {
                self.flags.next = self.flags.val() | self.flag_valid.val();
                if self.result_ram[i].read_data.val().get_bit(0) {
                    self.flags.next = self.flags.val() | self.flag_hit.val();
                }
            }
            self.result_out.next = self.result_ram[i].read_data.val();
            self.m_tdata[i].next = bit_cast::<OUT_LANE_BITS, 32>(self.flags.val())
                | (bit_cast::<OUT_LANE_BITS, RESULT_BITS>(self.result_out.val() >> 1) << 32);
        }
        // Lane 0 also serves register mode.
        if self.reg_start.val() {
            self.lane_valid_in[0].next = true;
            self.lane_query[0].next = self.reg_query.val();
        }

        if !self.reset_n.val() {
            self.acc_ptr.d.next = 0.into();
            self.res_ptr.d.next = 0.into();
            self.rd_ptr.d.next = 0.into();
            self.head_valid.d.next = false;
            self.warm.d.next = self.latency.val();
            self.reg_pending.d.next = false;
            self.reg_timer.d.next = 0.into();
        }
    }
}
