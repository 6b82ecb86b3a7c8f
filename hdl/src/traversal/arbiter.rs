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
        self.last.clock.next = self.clock.val();
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// The reference: the first requesting slot after `last` cyclically.
    fn reference(request: u64, last: Option<usize>, slots: usize) -> Option<usize> {
        let start = last.map_or(0, |l| l + 1);
        (0..slots)
            .map(|k| (start + k) % slots)
            .find(|&k| request >> k & 1 == 1)
    }

    fn run<const S: usize>(requests: impl Iterator<Item = u64>) -> Vec<Option<usize>> {
        let mut uut = RoundRobin::<S>::default();
        uut.connect_all();
        let mut grants = Vec::new();
        let mut last = None;
        for request in requests {
            uut.request.next = request.into();
            uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut uut, 100));
            let grant = uut.grant.val().to_u64();
            let want = reference(request, last, S);
            assert_eq!(
                grant,
                want.map_or(0, |k| 1 << k),
                "request {request:#b}, last {last:?}"
            );
            last = want.or(last);
            grants.push(want);
            uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut uut, 100));
        }
        grants
    }

    #[test]
    fn grants_follow_the_reference_on_random_requests() {
        let mut rng = StdRng::seed_from_u64(5);
        run::<5>((0..2_000).map(|_| rng.gen_range(0..32)));
        run::<16>((0..2_000).map(|_| rng.gen_range(0..1 << 16) & rng.gen_range(0..1 << 16)));
    }

    #[test]
    fn every_requesting_slot_is_served_within_s_cycles() {
        // Slot 2 requests throughout; the others too: 2 is granted every 8th cycle.
        let grants = run::<8>(std::iter::repeat_n(0xFF, 40));
        assert_eq!(grants.iter().filter(|g| **g == Some(2)).count(), 5);
        assert_eq!(grants[..8].to_vec(), (0..8).map(Some).collect::<Vec<_>>());
        // Nothing requested: no grant, and the priority is kept.
        let grants = run::<4>([0b0100, 0, 0b0101].into_iter());
        assert_eq!(grants, vec![Some(2), None, Some(0)]);
    }
}
