//! The AXI4-Lite bus protocol of a register slave, without its registers: what
//! `axil::slave` (the accelerator's map) and `traversal::unit_axil` (the unit's) share.
//!
//! - Write address and write data are captured independently (either order or together);
//!   the write happens once both are held and no response is pending (`write` pulses with
//!   `write_word`, `write_data`, `write_mask` and `write_byte0` stable), then `bvalid` rises
//!   with OKAY if the owner answers `write_ok`, else SLVERR. One write and one read are
//!   outstanding at most; `awready`/`wready` are high while the holding register is empty.
//! - A read is accepted whenever no read response is pending (`arready = !rvalid`): `read`
//!   pulses in that cycle with `read_word` (combinational from `araddr`), the owner answers
//!   `read_data` and `read_ok` in the same cycle, registered, so `rvalid` rises the next
//!   cycle (SLVERR without `read_ok`).
//! - The low two address bits are ignored (word registers, byte strobes).
//! - `reset_n` is synchronous, active low.
use rust_hdl::prelude::*;

use super::AxiLiteSlavePort;
use crate::regmap::{self, ADDR_BITS};

/// Width of the word address (byte address without its two low bits).
pub const WORD_BITS: usize = ADDR_BITS - 2;

/// The word address of a register's byte offset, as a constant.
pub fn word(offset: usize) -> Constant<Bits<WORD_BITS>> {
    Constant::new((offset as u64 >> 2).into())
}

/// A 32-bit mask constant (a register's bits).
pub fn mask(bits: u32) -> Constant<Bits<32>> {
    Constant::new(u64::from(bits).into())
}

#[derive(LogicBlock)]
pub struct AxiLiteBus {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub axi: AxiLiteSlavePort,
    /// A read is accepted this cycle; `read_word` is its word address (valid with `read`,
    /// but decoded every cycle so the owner's read mux may be combinational).
    pub read: Signal<Out, Bit>,
    pub read_word: Signal<Out, Bits<WORD_BITS>>,
    pub read_data: Signal<In, Bits<32>>,
    pub read_ok: Signal<In, Bit>,
    /// The held write happens this cycle.
    pub write: Signal<Out, Bit>,
    /// The held write's word address, data, the strobes' bit mask and whether byte lane 0
    /// is written (for narrow registers; valid while held, so the owner may decode before
    /// `write`).
    pub write_word: Signal<Out, Bits<WORD_BITS>>,
    pub write_data: Signal<Out, Bits<32>>,
    pub write_mask: Signal<Out, Bits<32>>,
    pub write_byte0: Signal<Out, Bit>,
    pub write_ok: Signal<In, Bit>,
    aw_full: DFF<Bit>,
    aw_word: DFF<Bits<WORD_BITS>>,
    w_full: DFF<Bit>,
    w_data: DFF<Bits<32>>,
    w_strb: DFF<Bits<4>>,
    b_valid: DFF<Bit>,
    b_resp: DFF<Bits<2>>,
    r_valid: DFF<Bit>,
    r_data: DFF<Bits<32>>,
    r_resp: DFF<Bits<2>>,
    w_mask: Signal<Local, Bits<32>>,
    /// Bit mask of each byte lane, for `wstrb`.
    lane_mask: [Constant<Bits<32>>; 4],
    resp_okay: Constant<Bits<2>>,
    resp_slverr: Constant<Bits<2>>,
}

impl Default for AxiLiteBus {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            axi: Default::default(),
            read: Default::default(),
            read_word: Default::default(),
            read_data: Default::default(),
            read_ok: Default::default(),
            write: Default::default(),
            write_word: Default::default(),
            write_data: Default::default(),
            write_mask: Default::default(),
            write_byte0: Default::default(),
            write_ok: Default::default(),
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
            w_mask: Default::default(),
            lane_mask: [0, 1, 2, 3].map(|lane| mask(0xFF << (8 * lane))),
            resp_okay: Constant::new(u64::from(regmap::RESP_OKAY).into()),
            resp_slverr: Constant::new(u64::from(regmap::RESP_SLVERR).into()),
        }
    }
}

impl Logic for AxiLiteBus {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, aw_full, aw_word, w_full, w_data, w_strb, b_valid, b_resp, r_valid,
            r_data, r_resp
        );
        self.axi.awready.next = !self.aw_full.q.val();
        self.axi.wready.next = !self.w_full.q.val();
        self.axi.bvalid.next = self.b_valid.q.val();
        self.axi.bresp.next = self.b_resp.q.val();
        self.axi.arready.next = !self.r_valid.q.val();
        self.axi.rvalid.next = self.r_valid.q.val();
        self.axi.rdata.next = self.r_data.q.val();
        self.axi.rresp.next = self.r_resp.q.val();

        // Read channel: decode the address on the handshake, answer the next cycle.
        if self.r_valid.q.val() & self.axi.rready.val() {
            self.r_valid.d.next = false;
        }
        self.read.next = self.axi.arvalid.val() & !self.r_valid.q.val();
        self.read_word.next = self.axi.araddr.val().get_bits::<WORD_BITS>(2);
        if self.axi.arvalid.val() & !self.r_valid.q.val() {
            self.r_valid.d.next = true;
            self.r_data.d.next = self.read_data.val();
            if self.read_ok.val() {
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
        self.write.next = self.aw_full.q.val() & self.w_full.q.val() & !self.b_valid.q.val();
        self.write_word.next = self.aw_word.q.val();
        self.write_data.next = self.w_data.q.val();
        self.write_byte0.next = self.w_strb.q.val().get_bit(0);
        self.w_mask.next = 0.into();
        for i in 0..4 {
            if self.w_strb.q.val().get_bit(i) {
                self.w_mask.next = self.w_mask.val() | self.lane_mask[i].val();
            }
        }
        self.write_mask.next = self.w_mask.val();
        if self.aw_full.q.val() & self.w_full.q.val() & !self.b_valid.q.val() {
            self.aw_full.d.next = false;
            self.w_full.d.next = false;
            self.b_valid.d.next = true;
            if self.write_ok.val() {
                self.b_resp.d.next = self.resp_okay.val();
            } else {
                self.b_resp.d.next = self.resp_slverr.val();
            }
        }

        if !self.reset_n.val() {
            self.aw_full.d.next = false;
            self.w_full.d.next = false;
            self.b_valid.d.next = false;
            self.r_valid.d.next = false;
        }
    }
}
