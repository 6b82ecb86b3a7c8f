//! The slot scheduler: a round-robin arbiter that grants one of the ray slots requesting a
//! shared resource (the box port, the stack's read port, a Möller-Trumbore lane, the hit
//! output) each cycle.
//!
//! Requests and the grant are one-hot vectors of `S` slots (rust-hdl cannot size an index
//! from `S`). Priority starts at the slot after the last one granted, so every requesting
//! slot is granted within `S` cycles however the others request: no slot starves.

use rust_hdl::prelude::*;

/// `grant` is the first requesting slot after the last grant (cyclically), or the first
/// requesting slot when none follows it.
///
/// For the clock: the slots after the last grant are kept as a registered mask, not derived
/// from the last grant, so that a grant is one carry chain (`x & −x`, the lowest set bit, of
/// the masked and of the plain requests side by side) and a multiplexer from the registers;
/// the next mask, `x ^ −x` (the bits above the lowest set bit), comes off the same chains.
#[derive(LogicBlock)]
pub struct RoundRobin<const S: usize> {
    pub clock: Signal<In, Clock>,
    pub request: Signal<In, Bits<S>>,
    /// One-hot, or 0 when nothing is requested.
    pub grant: Signal<Out, Bits<S>>,
    /// The slots after the last grant (0 before the first: none, so every slot).
    after_last: DFF<Bits<S>>,
    one: Constant<Bits<S>>,
    /// The requests of the slots after the last grant.
    after: Signal<Local, Bits<S>>,
    /// −after and −request (two's complement).
    after_neg: Signal<Local, Bits<S>>,
    request_neg: Signal<Local, Bits<S>>,
}

impl<const S: usize> Default for RoundRobin<S> {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            request: Default::default(),
            grant: Default::default(),
            after_last: Default::default(),
            one: Constant::new(1.into()),
            after: Default::default(),
            after_neg: Default::default(),
            request_neg: Default::default(),
        }
    }
}

impl<const S: usize> Logic for RoundRobin<S> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, after_last);
        self.after.next = self.request.val() & self.after_last.q.val();
        self.after_neg.next = !self.after.val() + self.one.val();
        self.request_neg.next = !self.request.val() + self.one.val();
        // The lowest set bit of the requests after the last grant, else of all requests.
        self.grant.next = self.request.val() & self.request_neg.val();
        if self.after.val().any() {
            self.grant.next = self.after.val() & self.after_neg.val();
        }
        // The slots above the grant (none above the last slot).
        self.after_last.d.next = self.after_last.q.val();
        if self.after.val().any() {
            self.after_last.d.next = self.after.val() ^ self.after_neg.val();
        } else if self.request.val().any() {
            self.after_last.d.next = self.request.val() ^ self.request_neg.val();
        }
    }
}
