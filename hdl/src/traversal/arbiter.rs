//! The slot scheduler: a round-robin arbiter that grants one of the ray slots requesting a
//! shared resource (the box port, the stack's read port, a Möller-Trumbore lane, the hit
//! output) each cycle.
//!
//! Requests and the grant are one-hot vectors of `S` slots (rust-hdl cannot size an index
//! from `S`). Priority starts at the slot after the last one granted, so every requesting
//! slot is granted within `S` cycles however the others request: no slot starves.

use rust_hdl::prelude::*;

/// `grant` is the first requesting slot after `last` (cyclically), or the first requesting
/// slot when none follows it; `last` becomes the grant at the clock edge.
#[derive(LogicBlock)]
pub struct RoundRobin<const S: usize> {
    pub clock: Signal<In, Clock>,
    pub request: Signal<In, Bits<S>>,
    /// One-hot, or 0 when nothing is requested.
    pub grant: Signal<Out, Bits<S>>,
    /// The last grant (one-hot; 0 before the first).
    last: DFF<Bits<S>>,
    one: Constant<Bits<S>>,
    /// Requests of the slots after the last grant.
    after: Signal<Local, Bits<S>>,
    /// The requests the grant is taken from.
    pool: Signal<Local, Bits<S>>,
}

impl<const S: usize> Default for RoundRobin<S> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            request: Default::default(),
            grant: Default::default(),
            last: Default::default(),
            one: Constant::new(1.into()),
            after: Default::default(),
            pool: Default::default(),
        }
    }
}

impl<const S: usize> Logic for RoundRobin<S> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, last);
        // The slots above the last grant: !(2·last − 1) (all slots while last is 0, whose
        // mask would be 0: the fallback below takes the whole request then).
        self.after.next = self.request.val() & !((self.last.q.val() << 1) - self.one.val());
        self.pool.next = self.request.val();
        if self.after.val().any() {
            self.pool.next = self.after.val();
        }
        // The lowest set bit: x & −x.
        self.grant.next = self.pool.val() & (!self.pool.val() + self.one.val());
        self.last.d.next = self.last.q.val();
        if self.request.val().any() {
            self.last.d.next = self.grant.val();
        }
    }
}
