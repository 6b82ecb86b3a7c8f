//! Vitis-HLS-compatible AXI4-Lite control slave (`s_axi_control` + `ap_ctrl_hs`).
//!
//! Bus behaviour:
//! - Write address and write data are captured independently (either order or together);
//!   the register write happens once both are held and no response is pending, then `bvalid`
//!   rises. One write and one read are outstanding at most; `awready`/`wready` are high
//!   while the respective holding register is empty.
//! - A read is accepted whenever no read response is pending (`arready = !rvalid`); the
//!   data is registered, so `rvalid` rises the cycle after the address handshake.
//! - The low two address bits are ignored (word registers, byte strobes). `wstrb` lanes are
//!   honoured on the operand registers; the narrow control registers take byte lane 0.
//! - Responses: OKAY for mapped registers; SLVERR for unmapped offsets and for writes to a
//!   wholly read-only register (RESULT, T, U, V, ID, CONFIG), which change nothing — a driver
//!   bug should trap rather than pass silently. Reads of unmapped offsets return 0.
//!
//! Block control (`ap_ctrl_hs`, as the Vitis slave implements it):
//! - writing 1 to ap_start sets it (writing 0 does not clear it); while ap_start is set and
//!   the core is idle the slave copies the operand registers to the `operands` outputs (held
//!   there until the next start, so software may write the next operands while the core
//!   works), becomes busy and, one cycle later, pulses `start` for one cycle;
//! - the core's `done` pulse ends the busy period: it latches hit/t/u/v into the result
//!   registers, sets ap_done and ap_ready (both clear-on-read of the control register; the
//!   operands are consumed at completion, so ready coincides with done), clears ap_start
//!   unless auto_restart is set, and sets the ISR bits that IER enables;
//! - ap_idle = not busy;
//! - `interrupt = GIE & |(ISR & IER)`; writing 1 to an ISR bit toggles it; a set by a core
//!   event wins over a toggle in the same cycle, as does a set of ap_done over its read clear
//!   (the read then returns the old value, so no completion is lost).
//! - `reset_n` is a synchronous active-low reset (Vitis' `ap_rst_n`).
use rust_hdl::prelude::*;

use crate::regmap::{self, ADDR_BITS, OPERAND_COUNT};

/// Width of the word address (byte address without its two low bits).
const WORD_BITS: usize = ADDR_BITS - 2;

/// The AXI4-Lite port of the slave, named like Vitis' `s_axi_control_*` signals.
#[derive(LogicInterface, Default)]
pub struct AxiLiteSlavePort {
    pub awvalid: Signal<In, Bit>,
    pub awready: Signal<Out, Bit>,
    pub awaddr: Signal<In, Bits<ADDR_BITS>>,
    pub wvalid: Signal<In, Bit>,
    pub wready: Signal<Out, Bit>,
    pub wdata: Signal<In, Bits<32>>,
    pub wstrb: Signal<In, Bits<4>>,
    pub bvalid: Signal<Out, Bit>,
    pub bready: Signal<In, Bit>,
    pub bresp: Signal<Out, Bits<2>>,
    pub arvalid: Signal<In, Bit>,
    pub arready: Signal<Out, Bit>,
    pub araddr: Signal<In, Bits<ADDR_BITS>>,
    pub rvalid: Signal<Out, Bit>,
    pub rready: Signal<In, Bit>,
    pub rdata: Signal<Out, Bits<32>>,
    pub rresp: Signal<Out, Bits<2>>,
}

#[derive(LogicBlock)]
pub struct AxiLiteSlave {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active low (`ap_rst_n`).
    pub reset_n: Signal<In, Bit>,
    pub axi: AxiLiteSlavePort,
    pub interrupt: Signal<Out, Bit>,
    // Core side.
    /// One-cycle pulse: the core must take `operands` and begin.
    pub start: Signal<Out, Bit>,
    /// Operands in [`regmap::OPERANDS`] order, stable from `start` until the next `start`.
    pub operands: [Signal<Out, Bits<32>>; OPERAND_COUNT],
    /// One-cycle pulse: `hit`, `t`, `u`, `v` are valid.
    pub done: Signal<In, Bit>,
    pub hit: Signal<In, Bit>,
    pub t: Signal<In, Bits<32>>,
    pub u: Signal<In, Bits<32>>,
    pub v: Signal<In, Bits<32>>,
    /// Constant inputs read through the ID and CONFIG registers.
    pub id: Signal<In, Bits<32>>,
    pub configuration: Signal<In, Bits<32>>,
    // Write channel.
    aw_full: DFF<Bit>,
    aw_word: DFF<Bits<WORD_BITS>>,
    w_full: DFF<Bit>,
    w_data: DFF<Bits<32>>,
    w_strb: DFF<Bits<4>>,
    b_valid: DFF<Bit>,
    b_resp: DFF<Bits<2>>,
    // Read channel.
    r_valid: DFF<Bit>,
    r_data: DFF<Bits<32>>,
    r_resp: DFF<Bits<2>>,
    // Registers of the map.
    ap_start: DFF<Bit>,
    ap_done: DFF<Bit>,
    ap_ready: DFF<Bit>,
    auto_restart: DFF<Bit>,
    busy: DFF<Bit>,
    start_q: DFF<Bit>,
    gie: DFF<Bit>,
    ier: DFF<Bits<2>>,
    isr: DFF<Bits<2>>,
    args: [DFF<Bits<32>>; OPERAND_COUNT],
    held: [DFF<Bits<32>>; OPERAND_COUNT],
    hit_q: DFF<Bit>,
    t_q: DFF<Bits<32>>,
    u_q: DFF<Bits<32>>,
    v_q: DFF<Bits<32>>,
    // Combinational helpers.
    write_now: Signal<Local, Bit>,
    w_mapped: Signal<Local, Bit>,
    w_readonly: Signal<Local, Bit>,
    w_mask: Signal<Local, Bits<32>>,
    read_now: Signal<Local, Bit>,
    r_word: Signal<Local, Bits<WORD_BITS>>,
    r_mapped: Signal<Local, Bit>,
    r_mux: Signal<Local, Bits<32>>,
    launch: Signal<Local, Bit>,
    core_done: Signal<Local, Bit>,
    isr_next: Signal<Local, Bits<2>>,
    // Word addresses of the registers, from the register map.
    word_control: Constant<Bits<WORD_BITS>>,
    word_gie: Constant<Bits<WORD_BITS>>,
    word_ier: Constant<Bits<WORD_BITS>>,
    word_isr: Constant<Bits<WORD_BITS>>,
    word_operand: [Constant<Bits<WORD_BITS>>; OPERAND_COUNT],
    word_result: Constant<Bits<WORD_BITS>>,
    word_t: Constant<Bits<WORD_BITS>>,
    word_u: Constant<Bits<WORD_BITS>>,
    word_v: Constant<Bits<WORD_BITS>>,
    word_id: Constant<Bits<WORD_BITS>>,
    word_config: Constant<Bits<WORD_BITS>>,
    /// Bit mask of each byte lane, for `wstrb`.
    lane_mask: [Constant<Bits<32>>; 4],
    resp_okay: Constant<Bits<2>>,
    resp_slverr: Constant<Bits<2>>,
    // Bits of the control, GIE, IER/ISR and RESULT registers, from the register map.
    mask_ap_start: Constant<Bits<32>>,
    mask_ap_done: Constant<Bits<32>>,
    mask_ap_idle: Constant<Bits<32>>,
    mask_ap_ready: Constant<Bits<32>>,
    mask_auto_restart: Constant<Bits<32>>,
    mask_gie: Constant<Bits<32>>,
    mask_hit: Constant<Bits<32>>,
    mask_interrupt: [Constant<Bits<32>>; 2],
    no_interrupts: Constant<Bits<2>>,
}

fn word(offset: usize) -> Constant<Bits<WORD_BITS>> {
    Constant::new((offset as u64 >> 2).into())
}

fn mask(bits: u32) -> Constant<Bits<32>> {
    Constant::new((bits as u64).into())
}

impl Default for AxiLiteSlave {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            axi: Default::default(),
            interrupt: Default::default(),
            start: Default::default(),
            operands: Default::default(),
            done: Default::default(),
            hit: Default::default(),
            t: Default::default(),
            u: Default::default(),
            v: Default::default(),
            id: Default::default(),
            configuration: Default::default(),
            aw_full: Default::default(),
            aw_word: Default::default(),
            w_full: Default::default(),
            w_data: Default::default(),
            w_strb: Default::default(),
            b_valid: Default::default(),
            b_resp: Default::default(),
            r_valid: Default::default(),
            r_data: Default::default(),
            r_resp: Default::default(),
            ap_start: Default::default(),
            ap_done: Default::default(),
            ap_ready: Default::default(),
            auto_restart: Default::default(),
            busy: Default::default(),
            start_q: Default::default(),
            gie: Default::default(),
            ier: Default::default(),
            isr: Default::default(),
            args: Default::default(),
            held: Default::default(),
            hit_q: Default::default(),
            t_q: Default::default(),
            u_q: Default::default(),
            v_q: Default::default(),
            write_now: Default::default(),
            w_mapped: Default::default(),
            w_readonly: Default::default(),
            w_mask: Default::default(),
            read_now: Default::default(),
            r_word: Default::default(),
            r_mapped: Default::default(),
            r_mux: Default::default(),
            launch: Default::default(),
            core_done: Default::default(),
            isr_next: Default::default(),
            word_control: word(regmap::CONTROL),
            word_gie: word(regmap::GIE),
            word_ier: word(regmap::IER),
            word_isr: word(regmap::ISR),
            word_operand: regmap::OPERANDS.map(word),
            word_result: word(regmap::RESULT),
            word_t: word(regmap::T),
            word_u: word(regmap::U),
            word_v: word(regmap::V),
            word_id: word(regmap::ID),
            word_config: word(regmap::CONFIG),
            lane_mask: [0, 1, 2, 3].map(|lane| Constant::new((0xFFu64 << (8 * lane)).into())),
            resp_okay: Constant::new((regmap::RESP_OKAY as u64).into()),
            resp_slverr: Constant::new((regmap::RESP_SLVERR as u64).into()),
            mask_ap_start: mask(regmap::AP_START),
            mask_ap_done: mask(regmap::AP_DONE),
            mask_ap_idle: mask(regmap::AP_IDLE),
            mask_ap_ready: mask(regmap::AP_READY),
            mask_auto_restart: mask(regmap::AUTO_RESTART),
            mask_gie: mask(regmap::GIE_ENABLE),
            mask_hit: mask(regmap::RESULT_HIT),
            mask_interrupt: [mask(regmap::INT_DONE), mask(regmap::INT_READY)],
            no_interrupts: Constant::new(0u64.into()),
        }
    }
}

impl Logic for AxiLiteSlave {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            aw_full,
            aw_word,
            w_full,
            w_data,
            w_strb,
            b_valid,
            b_resp,
            r_valid,
            r_data,
            r_resp,
            ap_start,
            ap_done,
            ap_ready,
            auto_restart,
            busy,
            start_q,
            gie,
            ier,
            isr,
            hit_q,
            t_q,
            u_q,
            v_q
        );
        for i in 0..OPERAND_COUNT {
            self.args[i].clock.next = self.clock.val();
            self.args[i].d.next = self.args[i].q.val();
            self.held[i].clock.next = self.clock.val();
            self.held[i].d.next = self.held[i].q.val();
            self.operands[i].next = self.held[i].q.val();
        }
        self.axi.awready.next = !self.aw_full.q.val();
        self.axi.wready.next = !self.w_full.q.val();
        self.axi.bvalid.next = self.b_valid.q.val();
        self.axi.bresp.next = self.b_resp.q.val();
        self.axi.arready.next = !self.r_valid.q.val();
        self.axi.rvalid.next = self.r_valid.q.val();
        self.axi.rdata.next = self.r_data.q.val();
        self.axi.rresp.next = self.r_resp.q.val();
        self.interrupt.next = self.gie.q.val() & (self.isr.q.val() & self.ier.q.val()).any();
        // Launch copies the operands; `start` follows a cycle later, with them in place.
        self.launch.next = self.ap_start.q.val() & !self.busy.q.val();
        self.start.next = self.start_q.q.val();
        self.core_done.next = self.done.val() & self.busy.q.val();

        // Read channel: decode the address on the handshake, answer the next cycle.
        if self.r_valid.q.val() & self.axi.rready.val() {
            self.r_valid.d.next = false;
        }
        self.read_now.next = self.axi.arvalid.val() & !self.r_valid.q.val();
        self.r_word.next = self.axi.araddr.val().get_bits::<WORD_BITS>(2);
        self.r_mapped.next = false;
        self.r_mux.next = 0.into();
        if self.r_word.val() == self.word_control.val() {
            self.r_mapped.next = true;
            if self.ap_start.q.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_ap_start.val();
            }
            if self.ap_done.q.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_ap_done.val();
            }
            if !self.busy.q.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_ap_idle.val();
            }
            if self.ap_ready.q.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_ap_ready.val();
            }
            if self.auto_restart.q.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_auto_restart.val();
            }
            if self.read_now.val() {
                // Clear on read; a completion in this very cycle sets them again below.
                self.ap_done.d.next = false;
                self.ap_ready.d.next = false;
            }
        }
        if self.r_word.val() == self.word_gie.val() {
            self.r_mapped.next = true;
            if self.gie.q.val() {
                self.r_mux.next = self.mask_gie.val();
            }
        }
        if self.r_word.val() == self.word_ier.val() {
            self.r_mapped.next = true;
            for i in 0..2 {
                if self.ier.q.val().get_bit(i) {
                    self.r_mux.next = self.r_mux.val() | self.mask_interrupt[i].val();
                }
            }
        }
        if self.r_word.val() == self.word_isr.val() {
            self.r_mapped.next = true;
            for i in 0..2 {
                if self.isr.q.val().get_bit(i) {
                    self.r_mux.next = self.r_mux.val() | self.mask_interrupt[i].val();
                }
            }
        }
        for i in 0..OPERAND_COUNT {
            if self.r_word.val() == self.word_operand[i].val() {
                self.r_mapped.next = true;
                self.r_mux.next = self.args[i].q.val();
            }
        }
        if self.r_word.val() == self.word_result.val() {
            self.r_mapped.next = true;
            if self.hit_q.q.val() {
                self.r_mux.next = self.mask_hit.val();
            }
        }
        if self.r_word.val() == self.word_t.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.t_q.q.val();
        }
        if self.r_word.val() == self.word_u.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.u_q.q.val();
        }
        if self.r_word.val() == self.word_v.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.v_q.q.val();
        }
        if self.r_word.val() == self.word_id.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.id.val();
        }
        if self.r_word.val() == self.word_config.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.configuration.val();
        }
        if self.read_now.val() {
            self.r_valid.d.next = true;
            self.r_data.d.next = self.r_mux.val();
            if self.r_mapped.val() {
                self.r_resp.d.next = self.resp_okay.val();
            } else {
                self.r_resp.d.next = self.resp_slverr.val();
            }
        }

        // Write channel: hold address and data until both are there, then write.
        if self.axi.awvalid.val() & !self.aw_full.q.val() {
            self.aw_full.d.next = true;
            self.aw_word.d.next = self.axi.awaddr.val().get_bits::<WORD_BITS>(2);
        }
        if self.axi.wvalid.val() & !self.w_full.q.val() {
            self.w_full.d.next = true;
            self.w_data.d.next = self.axi.wdata.val();
            self.w_strb.d.next = self.axi.wstrb.val();
        }
        if self.b_valid.q.val() & self.axi.bready.val() {
            self.b_valid.d.next = false;
        }
        self.write_now.next = self.aw_full.q.val() & self.w_full.q.val() & !self.b_valid.q.val();
        self.w_mask.next = 0.into();
        for i in 0..4 {
            if self.w_strb.q.val().get_bit(i) {
                self.w_mask.next = self.w_mask.val() | self.lane_mask[i].val();
            }
        }
        // The core's handshake clears ap_start; a write of ap_start = 1 below wins.
        if self.core_done.val() {
            self.ap_start.d.next = self.auto_restart.q.val();
        }
        self.isr_next.next = self.isr.q.val();
        self.w_mapped.next = false;
        self.w_readonly.next = false;
        if self.aw_word.q.val() == self.word_control.val() {
            self.w_mapped.next = true;
            if self.write_now.val() & self.w_strb.q.val().get_bit(0) {
                if self.w_data.q.val().get_bit(0) {
                    self.ap_start.d.next = true;
                }
                self.auto_restart.d.next = self.w_data.q.val().get_bit(7);
            }
        }
        if self.aw_word.q.val() == self.word_gie.val() {
            self.w_mapped.next = true;
            if self.write_now.val() & self.w_strb.q.val().get_bit(0) {
                self.gie.d.next = self.w_data.q.val().get_bit(0);
            }
        }
        if self.aw_word.q.val() == self.word_ier.val() {
            self.w_mapped.next = true;
            if self.write_now.val() & self.w_strb.q.val().get_bit(0) {
                self.ier.d.next = self.w_data.q.val().get_bits::<2>(0);
            }
        }
        if self.aw_word.q.val() == self.word_isr.val() {
            self.w_mapped.next = true;
            if self.write_now.val() & self.w_strb.q.val().get_bit(0) {
                self.isr_next.next = self.isr_next.val() ^ self.w_data.q.val().get_bits::<2>(0);
            }
        }
        for i in 0..OPERAND_COUNT {
            if self.aw_word.q.val() == self.word_operand[i].val() {
                self.w_mapped.next = true;
                if self.write_now.val() {
                    self.args[i].d.next = (self.args[i].q.val() & !self.w_mask.val())
                        | (self.w_data.q.val() & self.w_mask.val());
                }
            }
        }
        if (self.aw_word.q.val() == self.word_result.val())
            | (self.aw_word.q.val() == self.word_t.val())
            | (self.aw_word.q.val() == self.word_u.val())
            | (self.aw_word.q.val() == self.word_v.val())
            | (self.aw_word.q.val() == self.word_id.val())
            | (self.aw_word.q.val() == self.word_config.val())
        {
            self.w_mapped.next = true;
            self.w_readonly.next = true;
        }
        if self.write_now.val() {
            self.aw_full.d.next = false;
            self.w_full.d.next = false;
            self.b_valid.d.next = true;
            if self.w_mapped.val() & !self.w_readonly.val() {
                self.b_resp.d.next = self.resp_okay.val();
            } else {
                self.b_resp.d.next = self.resp_slverr.val();
            }
        }

        // Core handshake.
        self.start_q.d.next = self.launch.val();
        if self.launch.val() {
            self.busy.d.next = true;
            for i in 0..OPERAND_COUNT {
                self.held[i].d.next = self.args[i].q.val();
            }
        }
        if self.core_done.val() {
            self.busy.d.next = false;
            self.ap_done.d.next = true;
            self.ap_ready.d.next = true;
            self.isr_next.next = self.isr_next.val() | self.ier.q.val();
            self.hit_q.d.next = self.hit.val();
            self.t_q.d.next = self.t.val();
            self.u_q.d.next = self.u.val();
            self.v_q.d.next = self.v.val();
        }
        self.isr.d.next = self.isr_next.val();

        if !self.reset_n.val() {
            self.aw_full.d.next = false;
            self.w_full.d.next = false;
            self.b_valid.d.next = false;
            self.r_valid.d.next = false;
            self.ap_start.d.next = false;
            self.ap_done.d.next = false;
            self.ap_ready.d.next = false;
            self.auto_restart.d.next = false;
            self.busy.d.next = false;
            self.start_q.d.next = false;
            self.gie.d.next = false;
            self.ier.d.next = self.no_interrupts.val();
            self.isr.d.next = self.no_interrupts.val();
            self.hit_q.d.next = false;
            self.t_q.d.next = 0.into();
            self.u_q.d.next = 0.into();
            self.v_q.d.next = 0.into();
            for i in 0..OPERAND_COUNT {
                self.args[i].d.next = 0.into();
                self.held[i].d.next = 0.into();
            }
        }
    }
}
