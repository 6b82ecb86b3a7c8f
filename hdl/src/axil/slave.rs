//! Vitis-HLS-compatible AXI4-Lite control slave (`s_axi_control` + `ap_ctrl_hs`).
//!
//! Bus behaviour ([`AxiLiteBus`], shared with the traversal unit's slave):
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

use super::bus::{mask, word, AxiLiteBus, WORD_BITS};
use crate::macros::dff_setup;
use crate::regmap::{self, ADDR_BITS, OPERAND_COUNT};

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
    bus: AxiLiteBus,
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
    w_mapped: Signal<Local, Bit>,
    w_readonly: Signal<Local, Bit>,
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
            bus: Default::default(),
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
            w_mapped: Default::default(),
            w_readonly: Default::default(),
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
            dff_setup!(self, clock, args[i], held[i]);
            self.operands[i].next = self.held[i].q.val();
        }
        clock!(self, clock, bus);
        self.bus.reset_n.next = self.reset_n.val();
        AxiLiteSlavePort::link(&mut self.axi, &mut self.bus.axi);
        self.interrupt.next = self.gie.q.val() & (self.isr.q.val() & self.ier.q.val()).any();
        // Launch copies the operands; `start` follows a cycle later, with them in place.
        self.launch.next = self.ap_start.q.val() & !self.busy.q.val();
        self.start.next = self.start_q.q.val();
        self.core_done.next = self.done.val() & self.busy.q.val();

        // Read channel: the bus answers `r_mux` the next cycle.
        self.r_mapped.next = false;
        self.r_mux.next = 0.into();
        if self.bus.read_word.val() == self.word_control.val() {
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
            if self.bus.read.val() {
                // Clear on read; a completion in this very cycle sets them again below.
                self.ap_done.d.next = false;
                self.ap_ready.d.next = false;
            }
        }
        if self.bus.read_word.val() == self.word_gie.val() {
            self.r_mapped.next = true;
            if self.gie.q.val() {
                self.r_mux.next = self.mask_gie.val();
            }
        }
        if self.bus.read_word.val() == self.word_ier.val() {
            self.r_mapped.next = true;
            for i in 0..2 {
                if self.ier.q.val().get_bit(i) {
                    self.r_mux.next = self.r_mux.val() | self.mask_interrupt[i].val();
                }
            }
        }
        if self.bus.read_word.val() == self.word_isr.val() {
            self.r_mapped.next = true;
            for i in 0..2 {
                if self.isr.q.val().get_bit(i) {
                    self.r_mux.next = self.r_mux.val() | self.mask_interrupt[i].val();
                }
            }
        }
        for i in 0..OPERAND_COUNT {
            if self.bus.read_word.val() == self.word_operand[i].val() {
                self.r_mapped.next = true;
                self.r_mux.next = self.args[i].q.val();
            }
        }
        if self.bus.read_word.val() == self.word_result.val() {
            self.r_mapped.next = true;
            if self.hit_q.q.val() {
                self.r_mux.next = self.mask_hit.val();
            }
        }
        if self.bus.read_word.val() == self.word_t.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.t_q.q.val();
        }
        if self.bus.read_word.val() == self.word_u.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.u_q.q.val();
        }
        if self.bus.read_word.val() == self.word_v.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.v_q.q.val();
        }
        if self.bus.read_word.val() == self.word_id.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.id.val();
        }
        if self.bus.read_word.val() == self.word_config.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.configuration.val();
        }
        self.bus.read_data.next = self.r_mux.val();
        self.bus.read_ok.next = self.r_mapped.val();

        // Write channel: the bus holds address and data until both are there.
        // The core's handshake clears ap_start; a write of ap_start = 1 below wins.
        if self.core_done.val() {
            self.ap_start.d.next = self.auto_restart.q.val();
        }
        self.isr_next.next = self.isr.q.val();
        self.w_mapped.next = false;
        self.w_readonly.next = false;
        if self.bus.write_word.val() == self.word_control.val() {
            self.w_mapped.next = true;
            if self.bus.write.val() & self.bus.write_byte0.val() {
                if self.bus.write_data.val().get_bit(0) {
                    self.ap_start.d.next = true;
                }
                self.auto_restart.d.next = self.bus.write_data.val().get_bit(7);
            }
        }
        if self.bus.write_word.val() == self.word_gie.val() {
            self.w_mapped.next = true;
            if self.bus.write.val() & self.bus.write_byte0.val() {
                self.gie.d.next = self.bus.write_data.val().get_bit(0);
            }
        }
        if self.bus.write_word.val() == self.word_ier.val() {
            self.w_mapped.next = true;
            if self.bus.write.val() & self.bus.write_byte0.val() {
                self.ier.d.next = self.bus.write_data.val().get_bits::<2>(0);
            }
        }
        if self.bus.write_word.val() == self.word_isr.val() {
            self.w_mapped.next = true;
            if self.bus.write.val() & self.bus.write_byte0.val() {
                self.isr_next.next =
                    self.isr_next.val() ^ self.bus.write_data.val().get_bits::<2>(0);
            }
        }
        for i in 0..OPERAND_COUNT {
            if self.bus.write_word.val() == self.word_operand[i].val() {
                self.w_mapped.next = true;
                if self.bus.write.val() {
                    self.args[i].d.next = (self.args[i].q.val() & !self.bus.write_mask.val())
                        | (self.bus.write_data.val() & self.bus.write_mask.val());
                }
            }
        }
        if (self.bus.write_word.val() == self.word_result.val())
            | (self.bus.write_word.val() == self.word_t.val())
            | (self.bus.write_word.val() == self.word_u.val())
            | (self.bus.write_word.val() == self.word_v.val())
            | (self.bus.write_word.val() == self.word_id.val())
            | (self.bus.write_word.val() == self.word_config.val())
        {
            self.w_mapped.next = true;
            self.w_readonly.next = true;
        }
        self.bus.write_ok.next = self.w_mapped.val() & !self.w_readonly.val();

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
