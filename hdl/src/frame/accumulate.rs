//! The frame unit's per-pixel accumulator, one record a cycle: `hw_model::frame::accumulate`'s
//! `Accumulator::open` and `Accumulator::settle` on a tile's pixels, bit for bit.
//!
//! A record names a pixel slot (tile-local) and is either *open* (the pixel's primary ray goes
//! out: sums 0, one ray out) or *settle* (one shaded ray: its contributions' sum added per
//! channel, its spawned rays counted out, itself retired). A settle that leaves no ray out
//! finishes its pixel: the slot and `rgb8` of each channel's sum come out on a valid/ready
//! stream, in the order the records finished them; the slot may then be opened again.
//!
//! Each slot's three 48-bit sums and its count of rays out are one block-RAM word, read,
//! updated and written back at one record a cycle (II = 1):
//!
//! ```text
//! stage 0   the record in; the RAM reads its slot's word
//! stage 1   old word (or the word written at the edge the RAM read, forwarded) → new word,
//!           written to the RAM and held in registers
//! stage 2   a settle whose count reached 0: slot and rgb8 of the held sums into the queue
//! ```
//!
//! **The hazard.** The RAM reads at the edge where the record before writes, and reads the old
//! word: a record to the slot of the record just before takes that record's new word from the
//! registers that hold it (the slots are compared in stage 0, so stage 1's only logic is that
//! multiplexer, the 48-bit adders and the count's 19-bit adder). A record two or more behind
//! reads the RAM after the write. The adders are carry chains, not DSP48E1s: 3 × 48 bits is
//! 36 CARRY4 and a LUT a bit, while the frame unit's DSP48E1s go to its fp32 multipliers
//! (yosys: 46 CARRY4, no DSP48E1; the longest path is this stage's, the RAM's read data
//! through the multiplexer and an adder to its write data, 15 levels).
//!
//! **Widths, from the model** (`hw_model::frame::accumulate`, at [`FrameLimits::HW`]): a
//! settle's sum per channel is at most `max_contributions_per_ray` = 8 contributions of 28
//! bits, [`SETTLE_BITS`] = 31 signed; it spawns at most `max_spawned` = 8 rays,
//! [`SPAWNED_BITS`] = 4; a pixel has at most `max_outstanding` = 2^18 rays out (2^15 cast rays
//! at depth 15 under 8 lights each: shadow rays count), [`OUTSTANDING_BITS`] = 19; the sums
//! are [`SUM_BITS`] = 48 bits, which `max_sum` shows cannot overflow.
//!
//! **The tile.** [`PIXEL_SLOT_BITS`] = 10: a 32×32 tile (the software renderer's default
//! tile), 1,024 words of 3 × 48 + 19 = 163 bits, 10 RAMB18 halves as five 1K × 36 block RAMs.
//! Block RAM is the scarce resource of the XC7Z020 beside the traversal unit (its scene
//! memory takes most of the 280 halves); a 64×64 tile would take about 40.
//!
//! **Back-pressure.** The pipeline never stalls: every accepted record reserves a slot of an
//! 8-entry queue of finished pixels (a credit count), given back when the record leaves
//! stage 2 without finishing a pixel or when its pixel is taken; `record_ready` falls only
//! when [`QUEUE_DEPTH`] records are in flight or queued, so a finished pixel is never
//! dropped. A credit of a finishing record is out for [`latency`] cycles, fewer than the
//! queue's entries, so a consumer that is always ready never stalls the records.
//! `record_ready` and `pixel_valid` come from registers.
//!
//! No reset: an open writes its slot's whole word, so the RAM needs no initial contents; the
//! count, the queue and the valid bits start from the flip-flops' power-on zeros. A settle
//! to a slot with no ray out is the caller's error (the count wraps).

use hw_model::frame::accumulate::{
    max_contributions_per_ray, max_outstanding, max_spawned, Settle, CONTRIBUTION,
};
use hw_model::frame::FrameLimits;
use rust_hdl::prelude::*;
use thiserror::Error;

use super::raygen::QUEUE_LATENCY;
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::clock;

/// Address bits of a pixel slot: a 32×32 tile.
pub const PIXEL_SLOT_BITS: usize = 10;
/// Pixel slots: a tile's pixels.
pub const PIXEL_SLOTS: usize = 1 << PIXEL_SLOT_BITS;
/// Bits of a pixel's sum per channel (the model's `SUM_BITS`).
pub const SUM_BITS: usize = hw_model::frame::accumulate::SUM_BITS as usize;
/// Bits of a settle record's sum per channel, two's complement.
pub const SETTLE_BITS: usize = 31;
/// Bits of a settle record's spawned count.
pub const SPAWNED_BITS: usize = 4;
/// Bits of a pixel's count of rays out.
pub const OUTSTANDING_BITS: usize = 19;

/// The largest |sum| of one settle record: its contributions at the format's extreme.
const MAX_SETTLE: u64 =
    max_contributions_per_ray(&FrameLimits::HW) << (CONTRIBUTION.width() - 1) as u64;
/// Each width is the least that holds its bound.
const fn least_bits(max: u64) -> usize {
    (u64::BITS - max.leading_zeros()) as usize
}
const _: () = {
    // −MAX_SETTLE is the most negative sum, so it needs one bit fewer than +MAX_SETTLE.
    assert!(SETTLE_BITS == least_bits(MAX_SETTLE - 1) + 1);
    assert!(SPAWNED_BITS == least_bits(max_spawned(&FrameLimits::HW) as u64));
    assert!(OUTSTANDING_BITS == least_bits(max_outstanding(&FrameLimits::HW)));
    assert!(SUM_BITS == 48);
};

/// A slot's RAM word: the three sums from bit 0, the count of rays out above them.
const WORD_BITS: usize = 3 * SUM_BITS + OUTSTANDING_BITS;
/// A finished pixel in the queue: its slot, then red, green and blue from bit 10.
const FINISHED_BITS: usize = PIXEL_SLOT_BITS + 24;
/// Address bits of the queue of finished pixels.
pub const QUEUE_ADDR_BITS: usize = 3;
/// Records the block holds in its pipeline and its queue together.
pub const QUEUE_DEPTH: usize = 1 << QUEUE_ADDR_BITS;
/// Width of the credit count (0 to `QUEUE_DEPTH`).
const PENDING_BITS: usize = QUEUE_ADDR_BITS + 1;
/// Stages from a record's acceptance to its finished pixel written into the queue.
const STAGES: usize = 2;
// The kernel spells the word's and the queue entry's fields, the settle's sign bit, the top
// bit of the credit count and the sum's bits as literals.
const _: () = assert!(
    WORD_BITS == 163
        && FINISHED_BITS == 34
        && SETTLE_BITS == 31
        && PENDING_BITS == 4
        && hw_model::frame::accumulate::FRACTION_BITS == 16
);

/// Cycles from an accepted record to its finished pixel at the outputs, the queue empty:
/// the one source of it.
pub const fn latency() -> usize {
    STAGES + QUEUE_LATENCY
}
const _: () = assert!(
    latency() < QUEUE_DEPTH,
    "a record a cycle needs more credits"
);

type SlotRam = RAM<Bits<WORD_BITS>, PIXEL_SLOT_BITS>;
/// The queue of finished pixels (rust-hdl's FIFO: `data_out` shows the head while not
/// `empty`).
type FinishedQueue = SynchronousFIFO<Bits<FINISHED_BITS>, QUEUE_ADDR_BITS, PENDING_BITS, 1>;

/// Records in when `record_valid` and `record_ready`; finished pixels out, each shown from
/// `pixel_valid` until `pixel_ready` takes it.
#[derive(LogicBlock)]
pub struct Accumulate {
    pub clock: Signal<In, Clock>,
    // Records in.
    pub record_valid: Signal<In, Bit>,
    pub record_ready: Signal<Out, Bit>,
    pub slot: Signal<In, Bits<PIXEL_SLOT_BITS>>,
    /// 1: open; 0: settle (`sum` and `spawned`).
    pub open: Signal<In, Bit>,
    /// Per channel, two's complement.
    pub sum: [Signal<In, Bits<SETTLE_BITS>>; 3],
    pub spawned: Signal<In, Bits<SPAWNED_BITS>>,
    // Finished pixels out.
    pub pixel_valid: Signal<Out, Bit>,
    pub pixel_ready: Signal<In, Bit>,
    pub pixel_slot: Signal<Out, Bits<PIXEL_SLOT_BITS>>,
    pub rgb: [Signal<Out, Bits<8>>; 3],
    words: SlotRam,
    /// Stage 1: the record, and whether the RAM missed the word of its slot written at the
    /// edge it read.
    valid: DFF<Bit>,
    is_open: DFF<Bit>,
    at_slot: DFF<Bits<PIXEL_SLOT_BITS>>,
    add: [DFF<Bits<SETTLE_BITS>>; 3],
    spawned_at: DFF<Bits<SPAWNED_BITS>>,
    forward: DFF<Bit>,
    /// Stage 2: the word stage 1 wrote, and its slot.
    written_valid: DFF<Bit>,
    written_slot: DFF<Bits<PIXEL_SLOT_BITS>>,
    written_sum: [DFF<Bits<SUM_BITS>>; 3],
    written_count: DFF<Bits<OUTSTANDING_BITS>>,
    queue: FinishedQueue,
    pending: DFF<Bits<PENDING_BITS>>,
    /// Ones above a settle's bits: its sign extended to a sum's.
    sign_fill: Constant<Bits<SUM_BITS>>,
    /// Stage 1's slot word before and after the record.
    old_sum: [Signal<Local, Bits<SUM_BITS>>; 3],
    old_count: Signal<Local, Bits<OUTSTANDING_BITS>>,
    extended: [Signal<Local, Bits<SUM_BITS>>; 3],
    new_sum: [Signal<Local, Bits<SUM_BITS>>; 3],
    new_count: Signal<Local, Bits<OUTSTANDING_BITS>>,
    /// Stage 2's pixel in 8 bits per channel.
    channel: [Signal<Local, Bits<8>>; 3],
    finished: Signal<Local, Bit>,
    /// The credit count while it is updated.
    count: Signal<Local, Bits<PENDING_BITS>>,
    accept: Signal<Local, Bit>,
    take: Signal<Local, Bit>,
}

impl Default for Accumulate {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            record_valid: Default::default(),
            record_ready: Default::default(),
            slot: Default::default(),
            open: Default::default(),
            sum: Default::default(),
            spawned: Default::default(),
            pixel_valid: Default::default(),
            pixel_ready: Default::default(),
            pixel_slot: Default::default(),
            rgb: Default::default(),
            words: Default::default(),
            valid: Default::default(),
            is_open: Default::default(),
            at_slot: Default::default(),
            add: Default::default(),
            spawned_at: Default::default(),
            forward: Default::default(),
            written_valid: Default::default(),
            written_slot: Default::default(),
            written_sum: Default::default(),
            written_count: Default::default(),
            queue: Default::default(),
            pending: Default::default(),
            sign_fill: Constant::new(((1u64 << SUM_BITS) - (1 << SETTLE_BITS)).into()),
            old_sum: Default::default(),
            old_count: Default::default(),
            extended: Default::default(),
            new_sum: Default::default(),
            new_count: Default::default(),
            channel: Default::default(),
            finished: Default::default(),
            count: Default::default(),
            accept: Default::default(),
            take: Default::default(),
        }
    }
}

impl Logic for Accumulate {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, valid, is_open, at_slot, spawned_at, forward);
        clock!(
            self,
            clock,
            written_valid,
            written_slot,
            written_count,
            queue,
            pending
        );
        self.words.read_clock.next = self.clock.val();
        self.words.write_clock.next = self.clock.val();

        // Stage 0: a record in, its slot's word read.
        self.record_ready.next = !self.pending.q.val().get_bit(3);
        self.accept.next = self.record_valid.val() & self.record_ready.val();
        self.valid.d.next = self.accept.val();
        self.is_open.d.next = self.open.val();
        self.at_slot.d.next = self.slot.val();
        self.spawned_at.d.next = self.spawned.val();
        self.words.read_address.next = self.slot.val();
        self.forward.d.next = self.valid.q.val() & (self.slot.val() == self.at_slot.q.val());

        // Stage 1: the word updated and written.
        self.old_count.next = self.words.read_data.val().get_bits::<OUTSTANDING_BITS>(144);
        if self.forward.q.val() {
            self.old_count.next = self.written_count.q.val();
        }
        self.new_count.next = self.old_count.val()
            + bit_cast::<OUTSTANDING_BITS, SPAWNED_BITS>(self.spawned_at.q.val())
            - 1;
        if self.is_open.q.val() {
            self.new_count.next = 1.into();
        }
        // (`bit_cast` of an indexed signal takes a literal index: hdl_gen evaluates it.)
        self.extended[0].next = bit_cast::<SUM_BITS, SETTLE_BITS>(self.add[0].q.val());
        self.extended[1].next = bit_cast::<SUM_BITS, SETTLE_BITS>(self.add[1].q.val());
        self.extended[2].next = bit_cast::<SUM_BITS, SETTLE_BITS>(self.add[2].q.val());
        for k in 0..3 {
            clock!(self, clock, add[k], written_sum[k]);
            self.add[k].d.next = self.sum[k].val();
            self.old_sum[k].next = self.words.read_data.val().get_bits::<SUM_BITS>(48 * k);
            if self.forward.q.val() {
                self.old_sum[k].next = self.written_sum[k].q.val();
            }
            if self.add[k].q.val().get_bit(30) {
                self.extended[k].next = self.extended[k].val() | self.sign_fill.val();
            }
            self.new_sum[k].next = self.old_sum[k].val() + self.extended[k].val();
            if self.is_open.q.val() {
                self.new_sum[k].next = 0.into();
            }
            self.written_sum[k].d.next = self.new_sum[k].val();
        }
        self.words.write_data.next = bit_cast::<WORD_BITS, SUM_BITS>(self.new_sum[0].val())
            | (bit_cast::<WORD_BITS, SUM_BITS>(self.new_sum[1].val()) << 48)
            | (bit_cast::<WORD_BITS, SUM_BITS>(self.new_sum[2].val()) << 96)
            | (bit_cast::<WORD_BITS, OUTSTANDING_BITS>(self.new_count.val()) << 144);
        self.words.write_enable.next = self.valid.q.val();
        self.words.write_address.next = self.at_slot.q.val();
        self.written_valid.d.next = self.valid.q.val();
        self.written_slot.d.next = self.at_slot.q.val();
        self.written_count.d.next = self.new_count.val();

        // Stage 2: a count at 0 (only a settle's: an open's is 1) finishes the pixel:
        // rgb8 = clamp(sum >> 16, 0, 255) per channel into the queue.
        self.finished.next = self.written_valid.q.val() & !self.written_count.q.val().any();
        for k in 0..3 {
            self.channel[k].next = self.written_sum[k].q.val().get_bits::<8>(16);
            if self.written_sum[k].q.val().get_bits::<23>(24).any() {
                self.channel[k].next = 255.into();
            }
            if self.written_sum[k].q.val().get_bit(47) {
                self.channel[k].next = 0.into();
            }
        }
        self.queue.write.next = self.finished.val();
        self.queue.data_in.next =
            bit_cast::<FINISHED_BITS, PIXEL_SLOT_BITS>(self.written_slot.q.val())
                | (bit_cast::<FINISHED_BITS, 8>(self.channel[0].val()) << 10)
                | (bit_cast::<FINISHED_BITS, 8>(self.channel[1].val()) << 18)
                | (bit_cast::<FINISHED_BITS, 8>(self.channel[2].val()) << 26);

        // Finished pixels out: the queue's head.
        self.pixel_valid.next = !self.queue.empty.val();
        self.take.next = self.pixel_ready.val() & !self.queue.empty.val();
        // The queue ignores a read while empty (driving `read` from `empty` would be a loop
        // through the queue's one `always` block in Verilator's view).
        self.queue.read.next = self.pixel_ready.val();
        self.pixel_slot.next = self.queue.data_out.val().get_bits::<PIXEL_SLOT_BITS>(0);
        for k in 0..3 {
            self.rgb[k].next = self.queue.data_out.val().get_bits::<8>(10 + 8 * k);
        }

        // Credits: one per record accepted, back when it leaves stage 2 without finishing a
        // pixel or when its pixel is taken.
        self.count.next = self.pending.q.val();
        if self.accept.val() {
            self.count.next = self.count.val() + 1;
        }
        if self.written_valid.q.val() & !self.finished.val() {
            self.count.next = self.count.val() - 1;
        }
        if self.take.val() {
            self.count.next = self.count.val() - 1;
        }
        self.pending.d.next = self.count.val();
    }
}

/// A record the block rejects: its fields do not fit the block's.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum RecordError {
    #[error("pixel slot {slot}: the accumulator has slots 0 to {}", PIXEL_SLOTS - 1)]
    Slot { slot: usize },
    #[error(
        "a settle's sum {sum} (channel {channel}) is beyond the {SETTLE_BITS}-bit sum of {} \
         contributions",
        max_contributions_per_ray(&FrameLimits::HW)
    )]
    Sum { channel: usize, sum: i64 },
    #[error(
        "a settle spawning {spawned} rays: a shaded ray spawns at most {}",
        max_spawned(&FrameLimits::HW)
    )]
    Spawned { spawned: u32 },
}

/// What a record does to its slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Open,
    Settle(Settle),
}

/// A record the block takes: built by [`Record::new`], which checks that it fits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Record {
    slot: usize,
    command: Command,
}

impl Record {
    pub fn new(slot: usize, command: Command) -> Result<Record, RecordError> {
        if slot >= PIXEL_SLOTS {
            return Err(RecordError::Slot { slot });
        }
        if let Command::Settle(s) = command {
            let limit = 1i64 << (SETTLE_BITS - 1);
            if let Some(channel) = (0..3).find(|&k| !(-limit..limit).contains(&s.sum[k])) {
                return Err(RecordError::Sum {
                    channel,
                    sum: s.sum[channel],
                });
            }
            if s.spawned > max_spawned(&FrameLimits::HW) {
                return Err(RecordError::Spawned { spawned: s.spawned });
            }
        }
        Ok(Record { slot, command })
    }

    pub fn slot(&self) -> usize {
        self.slot
    }

    pub fn command(&self) -> Command {
        self.command
    }
}

/// One cycle's inputs: a record if valid, and the consumer's ready.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccumulateInput {
    pub record: Option<Record>,
    pub pixel_ready: bool,
}

/// A finished pixel: its slot and its 8-bit colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Finished {
    pub slot: usize,
    pub rgb: [u8; 3],
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccumulateOutput {
    pub record_ready: bool,
    /// The pixel shown while `pixel_valid`.
    pub pixel: Option<Finished>,
}

impl Stepped for Accumulate {
    type Input = AccumulateInput;
    type Output = AccumulateOutput;

    fn idle() -> AccumulateInput {
        AccumulateInput {
            record: None,
            pixel_ready: false,
        }
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &AccumulateInput) {
        let settle = match input.record.map(|r| r.command) {
            Some(Command::Settle(s)) => s,
            _ => Settle::default(),
        };
        self.record_valid.next = input.record.is_some();
        self.slot.next = (input.record.map_or(0, |r| r.slot) as u64).into();
        self.open.next = matches!(input.record.map(|r| r.command), Some(Command::Open));
        for (port, sum) in self.sum.iter_mut().zip(settle.sum) {
            port.next = (sum as u64 & ((1 << SETTLE_BITS) - 1)).into();
        }
        self.spawned.next = u64::from(settle.spawned).into();
        self.pixel_ready.next = input.pixel_ready;
    }

    fn observe(&self) -> AccumulateOutput {
        AccumulateOutput {
            record_ready: self.record_ready.val(),
            pixel: self.pixel_valid.val().then(|| Finished {
                slot: self.pixel_slot.val().to_u64() as usize,
                rgb: std::array::from_fn(|k| self.rgb[k].val().to_u64() as u8),
            }),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_accumulate(
    drive: impl FnMut(Option<&AccumulateOutput>) -> Option<AccumulateInput> + Send + 'static,
) -> Vec<(AccumulateInput, AccumulateOutput)> {
    simulate_driven(Accumulate::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn accumulate_verilog() -> String {
    built_verilog(Accumulate::default)
}
