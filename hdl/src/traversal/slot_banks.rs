//! A slot word that several ports write in one cycle and several read, in LUT RAM: one bank
//! ([`LutRam`]) per writer and reader, the word of a slot read from the bank of the writer
//! that wrote it last ([`super::live_table::LiveTable`], the "live-value table").
//!
//! A LUT RAM has one write port, so each writer has banks of its own; a reader reads every
//! writer's bank at its slot and takes the live one. A read port of its own per reader costs
//! no more than a shared multi-port bank: a RAM64M is 3 bits of one read port or 1 bit of
//! three, a RAM32M 6 bits of one or 2 of three. Reads are asynchronous and writes land at the
//! edge, as with the flip-flop words they replace: a word read at a grant and written at the
//! edge reads the old word all cycle.
//!
//! The banks sit in one flat list (bank `w · readers + r`: writer w's copy for reader r) and
//! are wired by comparing constant indices, which synthesis folds away: rust-hdl's generator
//! mis-names a port indexed twice (`banks[w].read[r]`).

use rust_hdl::prelude::*;

use super::live_table::WriterIndex;
use super::lut_ram::LutRam;

/// A reader's index among a word's readers (up to 8).
type ReaderIndex = Bits<3>;

/// The `W`-bit words of up to `2^SB` slots, written by `writers` ports (`write_data[w]` into
/// slot `write_slot[w]` when `write_enable[w]`) and read by `readers` (`read_data[r]`, the
/// word of slot `read_slot[r]` last written by writer `live[r]`, the live-value table's
/// answer for that slot).
#[derive(LogicBlock)]
pub struct SlotBanks<const SB: usize, const W: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Vec<Signal<In, Bit>>,
    pub write_slot: Vec<Signal<In, Bits<SB>>>,
    pub write_data: Vec<Signal<In, Bits<W>>>,
    pub read_slot: Vec<Signal<In, Bits<SB>>>,
    pub live: Vec<Signal<In, WriterIndex>>,
    pub read_data: Vec<Signal<Out, Bits<W>>>,
    banks: Vec<LutRam<W, SB>>,
    /// Each bank's writer and reader; each writer's and reader's index.
    bank_writer: Vec<Constant<WriterIndex>>,
    bank_reader: Vec<Constant<ReaderIndex>>,
    writer_id: Vec<Constant<WriterIndex>>,
    reader_id: Vec<Constant<ReaderIndex>>,
}

impl<const SB: usize, const W: usize> SlotBanks<SB, W> {
    /// The banks of `writers` writers (1 to 8) for `readers` readers (0 to 8; none: no banks).
    pub fn new(writers: usize, readers: usize) -> Self {
        assert!(
            (1..=1 << WriterIndex::BITS).contains(&writers) && readers <= 1 << ReaderIndex::BITS,
            "{writers} writers, {readers} readers: slot banks have 1 to 8 writers, 0 to 8 readers"
        );
        let c = |x: usize| Constant::new((x as u64).into());
        let banks = writers * readers;
        Self {
            clock: Default::default(),
            write_enable: crate::defaults(writers),
            write_slot: crate::defaults(writers),
            write_data: crate::defaults(writers),
            read_slot: crate::defaults(readers),
            live: crate::defaults(readers),
            read_data: crate::defaults(readers),
            banks: crate::defaults(banks),
            bank_writer: (0..banks).map(|b| c(b / readers)).collect(),
            bank_reader: (0..banks).map(|b| c(b % readers)).collect(),
            // None without banks: nothing reads them (and Verilator flags an unused constant).
            writer_id: (0..writers.min(banks)).map(c).collect(),
            reader_id: (0..readers).map(c).collect(),
        }
    }
}

impl<const SB: usize, const W: usize> Logic for SlotBanks<SB, W> {
    #[hdl_gen]
    fn update(&mut self) {
        for b in 0..self.banks.len() {
            self.banks[b].clock.next = self.clock.val();
            self.banks[b].write_enable.next = false;
            self.banks[b].write_address.next = 0.into();
            self.banks[b].write_data.next = 0.into();
            for w in 0..self.write_enable.len() {
                if self.bank_writer[b].val() == self.writer_id[w].val() {
                    self.banks[b].write_enable.next = self.write_enable[w].val();
                    self.banks[b].write_address.next = self.write_slot[w].val();
                    self.banks[b].write_data.next = self.write_data[w].val();
                }
            }
            self.banks[b].read_address.next = 0.into();
            for r in 0..self.read_slot.len() {
                if self.bank_reader[b].val() == self.reader_id[r].val() {
                    self.banks[b].read_address.next = self.read_slot[r].val();
                }
            }
        }
        for r in 0..self.read_data.len() {
            self.read_data[r].next = 0.into();
            for b in 0..self.banks.len() {
                if (self.bank_reader[b].val() == self.reader_id[r].val())
                    & (self.bank_writer[b].val() == self.live[r].val())
                {
                    self.read_data[r].next = self.banks[b].read_data.val();
                }
            }
        }
    }
}
