//! A FIFO of ray ids whose `valid` comes from a register: the frame engine's queues of ids
//! (the free lists of [`super::ray_ids`], the trace queues, the waiting queue; docs/frame.md
//! "The frame engine (design)"). Every queue of ids holds at most [`IDS`]: an id is in at
//! most one of them, so none overflows.
//!
//! rust-hdl's FIFO shows a word [`SHOW_LATENCY`] cycles after its write; the block counts the
//! words shown (a write counted when its FIFO shows it, `arrived`), and a read takes the head
//! while `valid`. The count, not the FIFO's `empty`, drives `valid`: a read driven from
//! `empty` is a loop through the FIFO's one `always` block in Verilator's view. No reset: the
//! count starts from the flip-flops' power-on zero.

use rust_hdl::prelude::*;

use super::raygen::QUEUE_LATENCY;
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::{clock, dff_setup};
use crate::mt::delay::Delay;

/// Bits of a ray id: a ray-store entry's address.
pub const ID_BITS: usize = 9;
/// Ray-store entries (`hw_model::frame::schedule::DEFAULT_RAY_STORE`).
pub const IDS: usize = 1 << ID_BITS;
/// Bits of a count of ids (0 to `IDS`).
pub const COUNT_BITS: usize = ID_BITS + 1;
/// Cycles from a write to its id shown: rust-hdl's FIFO shows a word two cycles after its
/// write.
pub const SHOW_LATENCY: usize = QUEUE_LATENCY;
const _: () = assert!(
    IDS == hw_model::frame::schedule::DEFAULT_RAY_STORE && COUNT_BITS == 10 && SHOW_LATENCY == 2
);

pub type Id = Bits<ID_BITS>;
pub type Count = Bits<COUNT_BITS>;
type Fifo = SynchronousFIFO<Id, ID_BITS, COUNT_BITS, 1>;

/// Ids in when `write`; the head shown while `valid`, taken by `read`.
#[derive(LogicBlock)]
pub struct IdQueue {
    pub clock: Signal<In, Clock>,
    pub write: Signal<In, Bit>,
    pub data_in: Signal<In, Id>,
    pub valid: Signal<Out, Bit>,
    pub head: Signal<Out, Id>,
    /// Takes the head (only while `valid`).
    pub read: Signal<In, Bit>,
    /// A write shown from the next cycle on.
    pub arrived: Signal<Out, Bit>,
    fifo: Fifo,
    /// A write, until its FIFO shows it.
    arriving: Delay<Bit>,
    /// Ids shown.
    shown: DFF<Count>,
}

impl Default for IdQueue {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            write: Default::default(),
            data_in: Default::default(),
            valid: Default::default(),
            head: Default::default(),
            read: Default::default(),
            arrived: Default::default(),
            fifo: Default::default(),
            arriving: Delay::new(SHOW_LATENCY - 1),
            shown: Default::default(),
        }
    }
}

impl Logic for IdQueue {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, fifo, arriving);
        dff_setup!(self, clock, shown);
        self.fifo.write.next = self.write.val();
        self.fifo.data_in.next = self.data_in.val();
        self.fifo.read.next = self.read.val();
        self.arriving.d.next = self.write.val();
        self.arrived.next = self.arriving.q.val();
        if self.arriving.q.val() & !self.read.val() {
            self.shown.d.next = self.shown.q.val() + 1;
        }
        if !self.arriving.q.val() & self.read.val() {
            self.shown.d.next = self.shown.q.val() - 1;
        }
        self.valid.next = self.shown.q.val().any();
        self.head.next = self.fifo.data_out.val();
    }
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IdQueueInput {
    pub write: Option<usize>,
    pub read: bool,
}

impl Stepped for IdQueue {
    type Input = IdQueueInput;
    /// The head shown.
    type Output = Option<usize>;

    fn idle() -> IdQueueInput {
        IdQueueInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &IdQueueInput) {
        self.write.next = input.write.is_some();
        self.data_in.next = (input.write.unwrap_or(0) as u64).into();
        self.read.next = input.read;
    }

    fn observe(&self) -> Option<usize> {
        self.valid.val().then(|| self.head.val().index())
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_id_queue(
    drive: impl FnMut(Option<&Option<usize>>) -> Option<IdQueueInput> + Send + 'static,
) -> Vec<(IdQueueInput, Option<usize>)> {
    simulate_driven(IdQueue::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn id_queue_verilog() -> String {
    built_verilog(IdQueue::default)
}
