//! The frame engine's pixel slots (docs/frame.md "The frame engine (design)"): whether the
//! next pixel's accumulator slot is free, and each finished slot's pixel index on the pixel
//! stream. Pixel p's slot is p mod [`PIXEL_SLOTS`] (its low bits), so pixel p opens once
//! pixel p − `PIXEL_SLOTS` has left: the schedule model's `slot_free_at`.
//!
//! - **Parity tables**: `opened` (1,024 × 1 bit) toggled at an open, `finished` at a pixel's
//!   leaving; a slot is free when the two are equal, whatever frames came before (every
//!   pixel opened leaves before the frame ends), so neither needs a reset or initial
//!   contents. Each table has one writer; `finished` has two readers (the open side, the
//!   toggle's read) and is held twice.
//! - **The open side**: the tables read the slot of `pixel` (the pixel counter's next pixel,
//!   held until opened) and, in the cycle of an open, of the next pixel in order, so a pixel
//!   a cycle opens flowing; `pixel_ready` when the words read at the last edge are the
//!   slot's, no leaving toggled it at that edge, and the parities are equal. An open
//!   (`pixel_valid` and `pixel_ready`) writes the pixel's index into the index RAM.
//! - **The pixel stream**: the accumulator's finished pixels (slot, RGB8) in, valid/ready; a
//!   one-stage buffer reads the slot's pixel index (a stalled stage keeps its address) and
//!   shows (index, RGB8) until taken; the taking toggles `finished`, so the slot is free
//!   only once its index has left.

use rust_hdl::prelude::*;

use super::accumulate::{PIXEL_SLOTS, PIXEL_SLOT_BITS};
use super::raygen::PIXEL_BITS;
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::dff_setup;

type Slot = Bits<PIXEL_SLOT_BITS>;
type Pixel = Bits<PIXEL_BITS>;

/// The next pixel's slot free; finished slots in, pixels (index, RGB8) out.
#[derive(LogicBlock, Default)]
pub struct PixelSlots {
    pub clock: Signal<In, Clock>,
    /// The next pixel to open, held while `pixel_valid` until it opens; `pixel_ready`: its
    /// slot is free (whatever `pixel_valid` says).
    pub pixel_valid: Signal<In, Bit>,
    pub pixel_ready: Signal<Out, Bit>,
    pub pixel: Signal<In, Pixel>,
    // Finished pixels from the accumulator.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_slot: Signal<In, Slot>,
    pub in_rgb: [Signal<In, Bits<8>>; 3],
    // The pixel stream.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_index: Signal<Out, Pixel>,
    pub out_rgb: [Signal<Out, Bits<8>>; 3],
    opened: RAM<Bit, PIXEL_SLOT_BITS>,
    /// The leaving's copy (0) and the open side's (1).
    finished: [RAM<Bit, PIXEL_SLOT_BITS>; 2],
    index: RAM<Pixel, PIXEL_SLOT_BITS>,
    /// The open side's address read at the last edge, and whether no leaving wrote it there.
    read_slot: DFF<Slot>,
    fresh: DFF<Bit>,
    // The buffered finished pixel.
    valid: DFF<Bit>,
    slot: DFF<Slot>,
    rgb: [DFF<Bits<8>>; 3],
    next_slot: Signal<Local, Slot>,
    open: Signal<Local, Bit>,
    leave: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
}

impl Logic for PixelSlots {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, read_slot, fresh, valid, slot);
        for k in 0..3 {
            dff_setup!(self, clock, rgb[k]);
        }
        self.opened.read_clock.next = self.clock.val();
        self.opened.write_clock.next = self.clock.val();
        self.index.read_clock.next = self.clock.val();
        self.index.write_clock.next = self.clock.val();
        for k in 0..2 {
            self.finished[k].read_clock.next = self.clock.val();
            self.finished[k].write_clock.next = self.clock.val();
        }

        // The pixel stream: a finished pixel taken when the buffer is free; its index read.
        self.leave.next = self.valid.q.val() & self.out_ready.val();
        self.in_ready.next = !self.valid.q.val() | self.out_ready.val();
        self.accept.next = self.in_valid.val() & self.in_ready.val();
        self.valid.d.next = self.accept.val() | (self.valid.q.val() & !self.out_ready.val());
        self.index.read_address.next = self.slot.q.val();
        self.finished[0].read_address.next = self.slot.q.val();
        if self.accept.val() {
            self.slot.d.next = self.in_slot.val();
            self.index.read_address.next = self.in_slot.val();
            self.finished[0].read_address.next = self.in_slot.val();
        }
        for k in 0..3 {
            if self.accept.val() {
                self.rgb[k].d.next = self.in_rgb[k].val();
            }
            self.out_rgb[k].next = self.rgb[k].q.val();
        }
        self.out_valid.next = self.valid.q.val();
        self.out_index.next = self.index.read_data.val();
        // The leaving toggles its slot's `finished` in both copies.
        for k in 0..2 {
            self.finished[k].write_enable.next = self.leave.val();
            self.finished[k].write_address.next = self.slot.q.val();
            self.finished[k].write_data.next = !self.finished[0].read_data.val();
        }

        // The open side: this pixel's slot, or in an open's cycle the next pixel's.
        self.pixel_ready.next = self.fresh.q.val()
            & (self.read_slot.q.val() == self.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0))
            & (self.opened.read_data.val() == self.finished[1].read_data.val());
        self.open.next = self.pixel_valid.val() & self.pixel_ready.val();
        self.next_slot.next = self.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        if self.open.val() {
            self.next_slot.next = self.next_slot.val() + 1;
        }
        self.opened.read_address.next = self.next_slot.val();
        self.finished[1].read_address.next = self.next_slot.val();
        self.read_slot.d.next = self.next_slot.val();
        self.fresh.d.next = !(self.leave.val() & (self.slot.q.val() == self.next_slot.val()));
        self.opened.write_enable.next = self.open.val();
        self.opened.write_address.next = self.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.opened.write_data.next = !self.opened.read_data.val();
        self.index.write_enable.next = self.open.val();
        self.index.write_address.next = self.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.index.write_data.next = self.pixel.val();
    }
}

const _: () = assert!(PIXEL_SLOTS == 1 << PIXEL_SLOT_BITS);

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlotsInput {
    /// The next pixel offered.
    pub pixel: Option<u32>,
    /// A finished pixel offered: its slot and colour.
    pub finished: Option<(usize, [u8; 3])>,
    pub out_ready: bool,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlotsOutput {
    pub pixel_ready: bool,
    pub in_ready: bool,
    /// The pixel shown: its index and colour.
    pub pixel: Option<(u32, [u8; 3])>,
}

impl Stepped for PixelSlots {
    type Input = SlotsInput;
    type Output = SlotsOutput;

    fn idle() -> SlotsInput {
        SlotsInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &SlotsInput) {
        self.pixel_valid.next = input.pixel.is_some();
        self.pixel.next = u64::from(input.pixel.unwrap_or(0)).into();
        let (slot, rgb) = input.finished.unwrap_or_default();
        self.in_valid.next = input.finished.is_some();
        self.in_slot.next = (slot as u64).into();
        for (port, c) in self.in_rgb.iter_mut().zip(rgb) {
            port.next = u64::from(c).into();
        }
        self.out_ready.next = input.out_ready;
    }

    fn observe(&self) -> SlotsOutput {
        SlotsOutput {
            pixel_ready: self.pixel_ready.val(),
            in_ready: self.in_ready.val(),
            pixel: self.out_valid.val().then(|| {
                (
                    self.out_index.val().to_u64() as u32,
                    std::array::from_fn(|k| self.out_rgb[k].val().to_u64() as u8),
                )
            }),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_pixel_slots(
    drive: impl FnMut(Option<&SlotsOutput>) -> Option<SlotsInput> + Send + 'static,
) -> Vec<(SlotsInput, SlotsOutput)> {
    simulate_driven(PixelSlots::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn pixel_slots_verilog() -> String {
    built_verilog(PixelSlots::default)
}
