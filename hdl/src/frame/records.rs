//! The accumulator's three sources (docs/frame.md "The frame engine (design)"): an *open*
//! (a pixel accepted), a shadow ray's answer settled beside the shader core, and a thread's
//! settle record from the core, one record a cycle into [`super::accumulate::Accumulate`].
//!
//! - **The shadow settle**: a shadow answer's record is its contribution if unoccluded,
//!   zeros if occluded, no spawned ray: bit for bit `thread::shade` of a shadow ray. The
//!   contribution is the ray store's payload as the core pushes it, three 28-bit values each
//!   sign-extended to a 32-bit lane; a settle's sum is its low [`SETTLE_BITS`].
//! - **The arbiter**: the thread's settle first (a waiting one stalls its thread), then the
//!   shadow's (it frees no entry until it is taken), then the open. Each source is
//!   valid/ready and holds its record until taken; a source is taken only when the record
//!   register is free (empty, or its record taken by the accumulator this cycle), so the
//!   sources' `ready` follow `record_ready` in the same cycle (the accumulator's comes from a
//!   register). An open must reach the accumulator before its pixel's settles: the engine
//!   hands its pixel to ray generation in the cycle the open is taken.
//!
//! One register stage: a record taken is shown the next cycle. No reset: the register starts
//! empty from the flip-flops' power-on zero.

use hw_model::frame::accumulate::Settle;
use rust_hdl::prelude::*;

use super::accumulate::{Command, Record, PIXEL_SLOT_BITS, SETTLE_BITS, SPAWNED_BITS};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::dff_setup;

type Slot = Bits<PIXEL_SLOT_BITS>;
type Sum = Bits<SETTLE_BITS>;

/// Opens, shadow answers and thread settles in; accumulator records out.
#[derive(LogicBlock, Default)]
pub struct Records {
    pub clock: Signal<In, Clock>,
    pub open_valid: Signal<In, Bit>,
    pub open_ready: Signal<Out, Bit>,
    pub open_slot: Signal<In, Slot>,
    pub shadow_valid: Signal<In, Bit>,
    pub shadow_ready: Signal<Out, Bit>,
    pub shadow_slot: Signal<In, Slot>,
    pub shadow_occluded: Signal<In, Bit>,
    /// The contribution: three 28-bit values, each sign-extended to 32 bits.
    pub shadow_payload: Signal<In, Bits<96>>,
    pub settle_valid: Signal<In, Bit>,
    pub settle_ready: Signal<Out, Bit>,
    pub settle_slot: Signal<In, Slot>,
    pub settle_sum: [Signal<In, Sum>; 3],
    pub settle_spawned: Signal<In, Bits<SPAWNED_BITS>>,
    // The accumulator's record port.
    pub record_valid: Signal<Out, Bit>,
    pub record_ready: Signal<In, Bit>,
    pub slot: Signal<Out, Slot>,
    pub open: Signal<Out, Bit>,
    pub sum: [Signal<Out, Sum>; 3],
    pub spawned: Signal<Out, Bits<SPAWNED_BITS>>,
    valid: DFF<Bit>,
    at_slot: DFF<Slot>,
    is_open: DFF<Bit>,
    at_sum: [DFF<Sum>; 3],
    at_spawned: DFF<Bits<SPAWNED_BITS>>,
    /// The register is free for a record this cycle.
    free: Signal<Local, Bit>,
}

impl Logic for Records {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid, at_slot, is_open, at_spawned);
        for k in 0..3 {
            dff_setup!(self, clock, at_sum[k]);
        }
        self.free.next = !self.valid.q.val() | self.record_ready.val();
        self.settle_ready.next = self.free.val();
        self.shadow_ready.next = self.free.val() & !self.settle_valid.val();
        self.open_ready.next =
            self.free.val() & !self.settle_valid.val() & !self.shadow_valid.val();
        if self.free.val() {
            self.valid.d.next =
                self.settle_valid.val() | self.shadow_valid.val() | self.open_valid.val();
            self.is_open.d.next = false;
            self.at_spawned.d.next = 0.into();
            if self.settle_valid.val() {
                self.at_slot.d.next = self.settle_slot.val();
                self.at_spawned.d.next = self.settle_spawned.val();
            } else if self.shadow_valid.val() {
                self.at_slot.d.next = self.shadow_slot.val();
            } else {
                self.at_slot.d.next = self.open_slot.val();
                self.is_open.d.next = true;
            }
        }
        for k in 0..3 {
            if self.free.val() {
                self.at_sum[k].d.next = 0.into();
                if self.settle_valid.val() {
                    self.at_sum[k].d.next = self.settle_sum[k].val();
                } else if self.shadow_valid.val() & !self.shadow_occluded.val() {
                    self.at_sum[k].d.next =
                        self.shadow_payload.val().get_bits::<SETTLE_BITS>(32 * k);
                }
            }
            self.sum[k].next = self.at_sum[k].q.val();
        }
        self.record_valid.next = self.valid.q.val();
        self.slot.next = self.at_slot.q.val();
        self.open.next = self.is_open.q.val();
        self.spawned.next = self.at_spawned.q.val();
    }
}

/// A shadow ray's answer as the block takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadowAnswer {
    pub slot: usize,
    pub occluded: bool,
    /// The contribution's words as the ray store holds them (the core's push payload).
    pub payload: [u32; 3],
}

/// One cycle's inputs: each source's record offered, and the accumulator's `record_ready`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RecordsInput {
    pub open: Option<usize>,
    pub shadow: Option<ShadowAnswer>,
    pub settle: Option<(usize, Settle)>,
    pub record_ready: bool,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RecordsOutput {
    pub open_ready: bool,
    pub shadow_ready: bool,
    pub settle_ready: bool,
    pub record: Option<Record>,
}

impl Stepped for Records {
    type Input = RecordsInput;
    type Output = RecordsOutput;

    fn idle() -> RecordsInput {
        RecordsInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &RecordsInput) {
        self.open_valid.next = input.open.is_some();
        self.open_slot.next = (input.open.unwrap_or(0) as u64).into();
        let shadow = input.shadow.unwrap_or(ShadowAnswer {
            slot: 0,
            occluded: false,
            payload: [0; 3],
        });
        self.shadow_valid.next = input.shadow.is_some();
        self.shadow_slot.next = (shadow.slot as u64).into();
        self.shadow_occluded.next = shadow.occluded;
        self.shadow_payload.next = shadow
            .payload
            .iter()
            .rev()
            .fold(Bits::<96>::default(), |a, &w| {
                (a << 32) | Bits::<96>::from(u64::from(w))
            });
        let (slot, settle) = input.settle.unwrap_or_default();
        self.settle_valid.next = input.settle.is_some();
        self.settle_slot.next = (slot as u64).into();
        for (port, sum) in self.settle_sum.iter_mut().zip(settle.sum) {
            port.next = (sum as u64 & ((1 << SETTLE_BITS) - 1)).into();
        }
        self.settle_spawned.next = u64::from(settle.spawned).into();
        self.record_ready.next = input.record_ready;
    }

    fn observe(&self) -> RecordsOutput {
        let command = if self.open.val() {
            Command::Open
        } else {
            let sum = std::array::from_fn(|k| {
                let v = self.sum[k].val().to_u64();
                // Sign-extend the settle's bits.
                ((v << (64 - SETTLE_BITS)) as i64) >> (64 - SETTLE_BITS)
            });
            Command::Settle(Settle {
                sum,
                spawned: self.spawned.val().to_u64() as u32,
            })
        };
        let slot = self.slot.val().index();
        RecordsOutput {
            open_ready: self.open_ready.val(),
            shadow_ready: self.shadow_ready.val(),
            settle_ready: self.settle_ready.val(),
            record: self.record_valid.val().then(|| {
                Record::new(slot, command).expect("the block's record fits the accumulator")
            }),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_records(
    drive: impl FnMut(Option<&RecordsOutput>) -> Option<RecordsInput> + Send + 'static,
) -> Vec<(RecordsInput, RecordsOutput)> {
    simulate_driven(Records::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn records_verilog() -> String {
    built_verilog(Records::default)
}
