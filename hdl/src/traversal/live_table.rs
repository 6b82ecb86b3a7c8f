//! The live-value table of a slot word kept in several banks, one per writer
//! ([`super::slot_banks`]): which writer wrote each slot's word last, so that a reader takes
//! that writer's bank.
//!
//! It is held as `⌈log2 writers⌉` bit vectors over the `S` slots in flip-flops (bit k of slot
//! s: bit k of the index of the writer that wrote slot s last, 0 before any write), and
//! addressed by one-hot slots, the schedulers' grants and the answers' decoded slots that
//! [`super::slots::SlotState`] has anyway: a write sets a slot's bits in one LUT a slot and
//! bit, a read is an AND-OR over the slots beside the banks' own address decoding.

use rust_hdl::prelude::*;

use crate::macros::dff_setup;

/// A writer's index into its word's banks (up to 8 writers).
pub type WriterIndex = Bits<3>;

/// Writers `w` write the slot `write_select[w]` (one-hot) when `write_enable[w]`, never two
/// the same slot in one cycle; `live[r]` is the index of the writer that wrote the slot
/// `read_select[r]` (one-hot) last, before this cycle's edge.
#[derive(LogicBlock)]
pub struct LiveTable<const S: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Vec<Signal<In, Bit>>,
    pub write_select: Vec<Signal<In, Bits<S>>>,
    pub read_select: Vec<Signal<In, Bits<S>>>,
    pub live: Vec<Signal<Out, WriterIndex>>,
    /// Bit k of the last writer's index, per slot.
    table: Vec<DFF<Bits<S>>>,
    writer_id: Vec<Constant<WriterIndex>>,
    /// Bit k alone.
    bit: Vec<Constant<WriterIndex>>,
    /// The slots written this cycle, and per bit those written by a writer whose index has it.
    written: Signal<Local, Bits<S>>,
    marked: Vec<Signal<Local, Bits<S>>>,
}

impl<const S: usize> LiveTable<S> {
    /// The table of `writers` writers (2 to 8) for `readers` readers.
    pub fn new(writers: usize, readers: usize) -> Self {
        assert!(
            (2..=1 << WriterIndex::BITS).contains(&writers),
            "{writers} writers: a live-value table has 2 to {}",
            1 << WriterIndex::BITS
        );
        let bits = (writers - 1).ilog2() as usize + 1;
        let c = |x: usize| Constant::new((x as u64).into());
        Self {
            clock: Default::default(),
            write_enable: crate::defaults(writers),
            write_select: crate::defaults(writers),
            read_select: crate::defaults(readers),
            live: crate::defaults(readers),
            table: crate::defaults(bits),
            writer_id: (0..writers).map(c).collect(),
            bit: (0..bits).map(|k| c(1 << k)).collect(),
            written: Default::default(),
            marked: crate::defaults(bits),
        }
    }
}

impl<const S: usize> Logic for LiveTable<S> {
    #[hdl_gen]
    fn update(&mut self) {
        self.written.next = 0.into();
        for w in 0..self.write_enable.len() {
            if self.write_enable[w].val() {
                self.written.next = self.written.val() | self.write_select[w].val();
            }
        }
        for k in 0..self.table.len() {
            dff_setup!(self, clock, table[k]);
            self.marked[k].next = 0.into();
            for w in 0..self.write_enable.len() {
                if self.write_enable[w].val() & (self.writer_id[w].val() & self.bit[k].val()).any()
                {
                    self.marked[k].next = self.marked[k].val() | self.write_select[w].val();
                }
            }
            self.table[k].d.next =
                (self.table[k].q.val() & !self.written.val()) | self.marked[k].val();
        }
        for r in 0..self.live.len() {
            self.live[r].next = 0.into();
            for k in 0..self.table.len() {
                if (self.table[k].q.val() & self.read_select[r].val()).any() {
                    self.live[r].next = self.live[r].val() | self.bit[k].val();
                }
            }
        }
    }
}
