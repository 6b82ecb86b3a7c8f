//! The frame engine's trace queues (docs/frame.md "The frame engine (design)"): the ids of
//! rays waiting for the traversal unit, spawned rays (a thread's pushes) before primary ones,
//! as the schedule model feeds its unit, so that pixels in flight finish before new ones
//! start. Two [`IdQueue`]s; an id enters one of them at most once a cycle each (a push and a
//! primary ray together are fine); the head is the spawned queue's while it shows one, else
//! the primary queue's, taken by `out_ready`.

use rust_hdl::prelude::*;

use super::id_queue::{Id, IdQueue};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::clock;

/// Spawned and primary ids in; the next id for the traversal unit out.
#[derive(LogicBlock, Default)]
pub struct TraceQueues {
    pub clock: Signal<In, Clock>,
    pub spawned: Signal<In, Bit>,
    pub spawned_id: Signal<In, Id>,
    pub primary: Signal<In, Bit>,
    pub primary_id: Signal<In, Id>,
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_id: Signal<Out, Id>,
    /// The spawned queue (0) and the primary queue (1).
    queues: [IdQueue; 2],
}

impl Logic for TraceQueues {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..2 {
            clock!(self, clock, queues[k]);
        }
        self.queues[0].write.next = self.spawned.val();
        self.queues[0].data_in.next = self.spawned_id.val();
        self.queues[1].write.next = self.primary.val();
        self.queues[1].data_in.next = self.primary_id.val();
        self.out_valid.next = self.queues[0].valid.val() | self.queues[1].valid.val();
        self.out_id.next = self.queues[1].head.val();
        self.queues[0].read.next = false;
        self.queues[1].read.next = false;
        if self.queues[0].valid.val() {
            self.out_id.next = self.queues[0].head.val();
            self.queues[0].read.next = self.out_ready.val();
        } else {
            self.queues[1].read.next = self.out_ready.val() & self.queues[1].valid.val();
        }
    }
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceInput {
    pub spawned: Option<usize>,
    pub primary: Option<usize>,
    pub out_ready: bool,
}

impl Stepped for TraceQueues {
    type Input = TraceInput;
    /// The id shown.
    type Output = Option<usize>;

    fn idle() -> TraceInput {
        TraceInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &TraceInput) {
        self.spawned.next = input.spawned.is_some();
        self.spawned_id.next = (input.spawned.unwrap_or(0) as u64).into();
        self.primary.next = input.primary.is_some();
        self.primary_id.next = (input.primary.unwrap_or(0) as u64).into();
        self.out_ready.next = input.out_ready;
    }

    fn observe(&self) -> Option<usize> {
        self.out_valid.val().then(|| self.out_id.val().index())
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_trace_queues(
    drive: impl FnMut(Option<&Option<usize>>) -> Option<TraceInput> + Send + 'static,
) -> Vec<(TraceInput, Option<usize>)> {
    simulate_driven(TraceQueues::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn trace_queues_verilog() -> String {
    built_verilog(TraceQueues::default)
}
