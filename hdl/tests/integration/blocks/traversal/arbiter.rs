//! `hdl::traversal::arbiter`.

use hdl::traversal::arbiter::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

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
    // The unit's 32 slots: requests of a few slots too (the last slot granted, then none).
    run::<32>((0..2_000).map(|_| rng.gen_range(0..1u64 << 32) & rng.gen_range(0..1u64 << 32)));
    run::<32>((0..2_000).map(|_| 1 << rng.gen_range(0..32) | 1 << rng.gen_range(0..32)));
    // The wide unit's 64 slots: dense, sparse, and the top slot.
    run::<64>((0..2_000).map(|_| rng.gen::<u64>()));
    run::<64>((0..2_000).map(|_| 1 << rng.gen_range(0..64) | 1 << rng.gen_range(0..64)));
    run::<64>((0..200).map(|k| {
        if k % 3 == 0 {
            1 << 63
        } else {
            rng.gen::<u64>() & rng.gen::<u64>() & rng.gen::<u64>()
        }
    }));
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
