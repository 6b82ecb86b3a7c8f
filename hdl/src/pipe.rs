//! A pipeline stage that is a register or a wire, chosen when the operator is built.
//!
//! Every operator has a list of cut points (the places where a register does the most
//! good, listed in its docs) and is built with `new(stages)`: [`placement`] spreads the
//! `stages` registers evenly over the cut points, and each cut point is a set of [`Pipe`]s
//! built with `Pipe::new(registered)`. An unregistered pipe is a wire; its flip-flop drives
//! nothing and synthesis removes it. The latency of an operator is exactly `stages` cycles.

use rust_hdl::prelude::*;

/// One signal crossing one cut point: `q` is `d` delayed by one clock, or `d` itself.
#[derive(LogicBlock)]
pub struct Pipe<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    flop: DFF<T>,
    registered: Constant<Bit>,
}

impl<T: Synth> Pipe<T> {
    pub fn new(registered: bool) -> Self {
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            flop: Default::default(),
            registered: Constant::new(registered),
        }
    }
}

impl<T: Synth> Logic for Pipe<T> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, flop);
        self.flop.d.next = self.d.val();
        if self.registered.val() {
            self.q.next = self.flop.q.val();
        } else {
            self.q.next = self.d.val();
        }
    }
}

/// Which of `cuts` cut points get a register when an operator has `stages` of them:
/// register k sits at cut floor((2k+1)·cuts / 2·stages), i.e. the registers are spread
/// evenly and centred (1 register of 3 cuts → the middle one).
///
/// Panics if `stages > cuts`: an operator's `new` documents its `max_stages()`.
pub fn placement(stages: usize, cuts: usize) -> Vec<bool> {
    assert!(
        stages <= cuts,
        "{stages} pipeline stages requested but the operator has only {cuts} cut points"
    );
    let mut enabled = vec![false; cuts];
    for k in 0..stages {
        enabled[(2 * k + 1) * cuts / (2 * stages)] = true;
    }
    enabled
}

/// `n` pipes, one per cut point of a chain, registered as `placement` says.
pub fn chain<T: Synth>(enabled: &[bool]) -> Vec<Pipe<T>> {
    enabled.iter().map(|&r| Pipe::new(r)).collect()
}
