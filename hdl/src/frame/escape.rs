//! The frame engine's escape pixel (docs/frame.md "The frame engine", "Why it cannot
//! deadlock"): one designated pixel, kept until it finishes, and its cast rays in flight
//! counted by depth, so the engine knows its deepest: the one ray that may start a thread
//! below the escape reserve. The model's part is `frame::schedule`'s `cast_depths` of a
//! pixel slot and its deepest depth in flight.
//!
//! - **Designation**: while none is designated, `candidate_slot` (the waiting queue head's
//!   pixel) becomes the escape pixel; a finish of its slot ends it.
//! - **Census**: its rays already in flight are counted by reading the ray store's tags once,
//!   entry 0 to [`IDS`] − 1, an entry a cycle (`scan_address` out; `scan_cast`, `scan_slot`,
//!   `scan_depth` in, the tag RAM's word for the address of the cycle before). An event
//!   (a cast ray entering the store, or leaving it at its thread's start) is the ray store's
//!   write at the end of its cycle, which the tag RAM's read at the same edge does not see:
//!   so an event counts at once if its entry is at or below the address read this cycle, and
//!   is left to the census if above.
//! - **Out**: `escape_valid` once the census is done; the slot; `deepest`, the highest depth
//!   with a ray in flight, and `in_flight` (any).
//!
//! Counts are [`COUNT_BITS`] wide: a depth's rays are at most the store's entries.

use rust_hdl::prelude::*;

use super::accumulate::PIXEL_SLOT_BITS;
use super::ray_ids::{IDS, ID_BITS};
use super::shader::core::DEPTH_BITS;
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::dff_setup;

/// Depths a ray's tag holds.
pub const DEPTHS: usize = 1 << DEPTH_BITS;
/// Bits of a count of rays (0 to `IDS`).
pub const COUNT_BITS: usize = ID_BITS + 1;
/// Cycles from a candidate designated to `escape_valid`: the census reads every entry, a
/// cycle each, then counts the last word and shows the counts.
pub const CENSUS_CYCLES: usize = IDS + 2;
// The kernel spells the scan pointer's top bit (`ID_BITS`) and the depth's width as literals.
const _: () = assert!(ID_BITS == 9 && DEPTH_BITS == 4 && DEPTHS == 16);

type Slot = Bits<PIXEL_SLOT_BITS>;
type Id = Bits<ID_BITS>;
type Depth = Bits<DEPTH_BITS>;

/// The escape pixel and its cast rays in flight by depth.
#[derive(LogicBlock)]
pub struct EscapePixel {
    pub clock: Signal<In, Clock>,
    /// A cast ray enters the ray store (generated or pushed).
    pub enter: Signal<In, Bit>,
    pub enter_slot: Signal<In, Slot>,
    pub enter_depth: Signal<In, Depth>,
    pub enter_id: Signal<In, Id>,
    /// A cast ray leaves it (its thread starts).
    pub leave: Signal<In, Bit>,
    pub leave_slot: Signal<In, Slot>,
    pub leave_depth: Signal<In, Depth>,
    pub leave_id: Signal<In, Id>,
    /// A pixel finished.
    pub finish: Signal<In, Bit>,
    pub finish_slot: Signal<In, Slot>,
    /// The pixel to designate when none is.
    pub candidate: Signal<In, Bit>,
    pub candidate_slot: Signal<In, Slot>,
    /// The census: the tag read, and the word read for the address of the cycle before.
    pub scan_address: Signal<Out, Id>,
    pub scan_cast: Signal<In, Bit>,
    pub scan_slot: Signal<In, Slot>,
    pub scan_depth: Signal<In, Depth>,
    pub escape_valid: Signal<Out, Bit>,
    pub escape_slot: Signal<Out, Slot>,
    pub deepest: Signal<Out, Depth>,
    pub in_flight: Signal<Out, Bit>,
    /// A pixel is designated.
    designated: DFF<Bit>,
    slot: DFF<Slot>,
    /// The next address the census reads (bit 9: all read).
    pointer: DFF<Bits<COUNT_BITS>>,
    /// The census read an address at the last edge; its word is in.
    reading: DFF<Bit>,
    counts: [DFF<Bits<COUNT_BITS>>; DEPTHS],
    one: Constant<Bits<DEPTHS>>,
    /// One-hot depths of this cycle's census word, entering and leaving ray.
    scanned: Signal<Local, Bits<DEPTHS>>,
    entering: Signal<Local, Bits<DEPTHS>>,
    leaving: Signal<Local, Bits<DEPTHS>>,
    /// Events at entries the census has read (or reads at this edge).
    live_enter: Signal<Local, Bit>,
    live_leave: Signal<Local, Bit>,
    census_done: Signal<Local, Bit>,
    ends: Signal<Local, Bit>,
    /// The census reads at this edge; the counts while they are updated.
    read_now: Signal<Local, Bit>,
    count_next: [Signal<Local, Bits<COUNT_BITS>>; DEPTHS],
}

impl Default for EscapePixel {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            enter: Default::default(),
            enter_slot: Default::default(),
            enter_depth: Default::default(),
            enter_id: Default::default(),
            leave: Default::default(),
            leave_slot: Default::default(),
            leave_depth: Default::default(),
            leave_id: Default::default(),
            finish: Default::default(),
            finish_slot: Default::default(),
            candidate: Default::default(),
            candidate_slot: Default::default(),
            scan_address: Default::default(),
            scan_cast: Default::default(),
            scan_slot: Default::default(),
            scan_depth: Default::default(),
            escape_valid: Default::default(),
            escape_slot: Default::default(),
            deepest: Default::default(),
            in_flight: Default::default(),
            designated: Default::default(),
            slot: Default::default(),
            pointer: Default::default(),
            reading: Default::default(),
            counts: Default::default(),
            one: Constant::new(1.into()),
            scanned: Default::default(),
            entering: Default::default(),
            leaving: Default::default(),
            live_enter: Default::default(),
            live_leave: Default::default(),
            census_done: Default::default(),
            ends: Default::default(),
            read_now: Default::default(),
            count_next: Default::default(),
        }
    }
}

impl Logic for EscapePixel {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, designated, slot, pointer, reading);
        for k in 0..DEPTHS {
            dff_setup!(self, clock, counts[k]);
        }

        // The census: the address read at this edge, and the word read at the last.
        self.census_done.next = self.pointer.q.val().get_bit(9) & !self.reading.q.val();
        self.scan_address.next = self.pointer.q.val().get_bits::<ID_BITS>(0);
        self.read_now.next = self.designated.q.val() & !self.pointer.q.val().get_bit(9);
        if self.read_now.val() {
            self.pointer.d.next = self.pointer.q.val() + 1;
        }
        self.scanned.next = 0.into();
        if self.reading.q.val() & self.scan_cast.val() & (self.scan_slot.val() == self.slot.q.val())
        {
            self.scanned.next = self.one.val() << self.scan_depth.val();
        }

        // Events of the designated pixel at entries the census has read.
        self.live_enter.next = self.enter.val()
            & self.designated.q.val()
            & (self.enter_slot.val() == self.slot.q.val())
            & (self.pointer.q.val().get_bit(9)
                | (self.pointer.q.val().get_bits::<ID_BITS>(0) >= self.enter_id.val()));
        self.live_leave.next = self.leave.val()
            & self.designated.q.val()
            & (self.leave_slot.val() == self.slot.q.val())
            & (self.pointer.q.val().get_bit(9)
                | (self.pointer.q.val().get_bits::<ID_BITS>(0) >= self.leave_id.val()));
        self.entering.next = 0.into();
        if self.live_enter.val() {
            self.entering.next = self.one.val() << self.enter_depth.val();
        }
        self.leaving.next = 0.into();
        if self.live_leave.val() {
            self.leaving.next = self.one.val() << self.leave_depth.val();
        }

        // The counts; the deepest depth with a ray in flight.
        self.deepest.next = 0.into();
        self.in_flight.next = false;
        for k in 0..DEPTHS {
            self.count_next[k].next = self.counts[k].q.val();
            if self.scanned.val().get_bit(k) {
                self.count_next[k].next = self.count_next[k].val() + 1;
            }
            if self.entering.val().get_bit(k) {
                self.count_next[k].next = self.count_next[k].val() + 1;
            }
            if self.leaving.val().get_bit(k) {
                self.count_next[k].next = self.count_next[k].val() - 1;
            }
            self.counts[k].d.next = self.count_next[k].val();
            if self.counts[k].q.val().any() {
                self.deepest.next = k.to_bits();
                self.in_flight.next = true;
            }
        }
        self.escape_valid.next = self.designated.q.val() & self.census_done.val();
        self.escape_slot.next = self.slot.q.val();

        // A finish ends the designation; a candidate starts one and its census.
        self.ends.next = self.designated.q.val()
            & self.finish.val()
            & (self.finish_slot.val() == self.slot.q.val());
        self.reading.d.next = self.read_now.val();
        if self.ends.val() {
            self.designated.d.next = false;
            self.reading.d.next = false;
        }
        if !self.designated.q.val() & self.candidate.val() {
            self.designated.d.next = true;
            self.slot.d.next = self.candidate_slot.val();
            self.pointer.d.next = 0.into();
        }
        if self.ends.val() | !self.designated.q.val() {
            for k in 0..DEPTHS {
                self.counts[k].d.next = 0.into();
            }
        }
    }
}

/// A ray's tag: its pixel slot and depth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tag {
    pub slot: usize,
    pub depth: usize,
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EscapeInput {
    /// A cast ray entering the store at an id.
    pub enter: Option<(usize, Tag)>,
    /// A cast ray leaving it.
    pub leave: Option<(usize, Tag)>,
    pub finish: Option<usize>,
    pub candidate: Option<usize>,
    /// The tag RAM's word for the address of the cycle before: a cast ray's tag or none.
    pub scanned: Option<Tag>,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EscapeOutput {
    pub scan_address: usize,
    /// The escape pixel's slot, its deepest depth in flight if any, once its census is done.
    pub escape: Option<(usize, Option<usize>)>,
}

impl Stepped for EscapePixel {
    type Input = EscapeInput;
    type Output = EscapeOutput;

    fn idle() -> EscapeInput {
        EscapeInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &EscapeInput) {
        let (enter_id, enter) = input.enter.unwrap_or_default();
        self.enter.next = input.enter.is_some();
        self.enter_id.next = (enter_id as u64).into();
        self.enter_slot.next = (enter.slot as u64).into();
        self.enter_depth.next = (enter.depth as u64).into();
        let (leave_id, leave) = input.leave.unwrap_or_default();
        self.leave.next = input.leave.is_some();
        self.leave_id.next = (leave_id as u64).into();
        self.leave_slot.next = (leave.slot as u64).into();
        self.leave_depth.next = (leave.depth as u64).into();
        self.finish.next = input.finish.is_some();
        self.finish_slot.next = (input.finish.unwrap_or(0) as u64).into();
        self.candidate.next = input.candidate.is_some();
        self.candidate_slot.next = (input.candidate.unwrap_or(0) as u64).into();
        let scanned = input.scanned.unwrap_or_default();
        self.scan_cast.next = input.scanned.is_some();
        self.scan_slot.next = (scanned.slot as u64).into();
        self.scan_depth.next = (scanned.depth as u64).into();
    }

    fn observe(&self) -> EscapeOutput {
        EscapeOutput {
            scan_address: self.scan_address.val().index(),
            escape: self.escape_valid.val().then(|| {
                (
                    self.escape_slot.val().index(),
                    self.in_flight.val().then(|| self.deepest.val().index()),
                )
            }),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_escape(
    drive: impl FnMut(Option<&EscapeOutput>) -> Option<EscapeInput> + Send + 'static,
) -> Vec<(EscapeInput, EscapeOutput)> {
    simulate_driven(EscapePixel::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn escape_verilog() -> String {
    built_verilog(EscapePixel::default)
}
