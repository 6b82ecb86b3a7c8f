//! The frame engine's waiting queue (docs/frame.md "The frame engine (design)"): the ids of
//! answered cast rays waiting for a thread. Its head goes to the thread start; a start that
//! cannot go yet (the start decision at the thread start's output) comes back to the tail,
//! so every waiting ray is looked at in turn and the escape pixel's deepest ray reaches the
//! head. One [`IdQueue`] with one write a cycle: a deferred start's id (always taken), else
//! an answer's (`answer_ready` is low in a cycle with a deferred start).

use rust_hdl::prelude::*;

use super::id_queue::{Id, IdQueue};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::clock;

/// Answered ids and deferred starts in; the head out.
#[derive(LogicBlock, Default)]
pub struct WaitingQueue {
    pub clock: Signal<In, Clock>,
    pub answer_valid: Signal<In, Bit>,
    pub answer_ready: Signal<Out, Bit>,
    pub answer_id: Signal<In, Id>,
    /// A start that cannot go: its id back to the tail.
    pub deferred: Signal<In, Bit>,
    pub deferred_id: Signal<In, Id>,
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub out_id: Signal<Out, Id>,
    queue: IdQueue,
}

impl Logic for WaitingQueue {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, queue);
        self.answer_ready.next = !self.deferred.val();
        self.queue.write.next = self.deferred.val() | self.answer_valid.val();
        self.queue.data_in.next = self.answer_id.val();
        if self.deferred.val() {
            self.queue.data_in.next = self.deferred_id.val();
        }
        self.out_valid.next = self.queue.valid.val();
        self.out_id.next = self.queue.head.val();
        self.queue.read.next = self.out_ready.val() & self.queue.valid.val();
    }
}

/// One cycle's inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WaitingInput {
    pub answer: Option<usize>,
    pub deferred: Option<usize>,
    pub out_ready: bool,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WaitingOutput {
    pub answer_ready: bool,
    pub head: Option<usize>,
}

impl Stepped for WaitingQueue {
    type Input = WaitingInput;
    type Output = WaitingOutput;

    fn idle() -> WaitingInput {
        WaitingInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &WaitingInput) {
        self.answer_valid.next = input.answer.is_some();
        self.answer_id.next = (input.answer.unwrap_or(0) as u64).into();
        self.deferred.next = input.deferred.is_some();
        self.deferred_id.next = (input.deferred.unwrap_or(0) as u64).into();
        self.out_ready.next = input.out_ready;
    }

    fn observe(&self) -> WaitingOutput {
        WaitingOutput {
            answer_ready: self.answer_ready.val(),
            head: self.out_valid.val().then(|| self.out_id.val().index()),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_waiting_queue(
    drive: impl FnMut(Option<&WaitingOutput>) -> Option<WaitingInput> + Send + 'static,
) -> Vec<(WaitingInput, WaitingOutput)> {
    simulate_driven(WaitingQueue::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn waiting_queue_verilog() -> String {
    built_verilog(WaitingQueue::default)
}
