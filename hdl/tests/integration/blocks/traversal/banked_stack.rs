//! `hdl::traversal::banked_stack`.

use hdl::traversal::banked_stack::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

/// 6 slots, pointers of 5 bits, bank rows of 5 bits, 16-bit entries.
type Stacks = BankedStacks<6, 3, 5, 5, 16>;

/// Random multi-pushes, pops and clears of different slots each cycle against `Vec` stacks,
/// with `banks` banks and a depth that is not a multiple of them.
fn follows_a_stack_per_slot(banks: usize, depth: usize, seed: u64) {
    let mut uut = Stacks::new(banks, depth);
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(seed);
    let mut stacks = vec![Vec::<u64>::new(); 6];
    // What the last cycle's pop must answer: Some(entry) or None (empty).
    let mut expect: Option<Option<u64>> = None;
    // The slot whose push the last cycle dropped.
    let mut dropped: Option<u64> = None;
    let (mut pops, mut empties, mut overflowed, mut drops, mut wide) = (0, 0, None, 0, 0);
    for cycle in 0..6_000 {
        let push_slot = rng.gen_range(0..6usize);
        let pop_slot = (push_slot + rng.gen_range(1..6)) % 6;
        // Pushes of every count, pops slightly more often than entries arrive.
        let count = if rng.gen_bool(0.3) {
            rng.gen_range(1..banks)
        } else {
            0
        };
        let pop = rng.gen_bool(0.6);
        let clear = rng.gen_bool(0.01);
        let clear_slot = (0..6).find(|&s| s != push_slot && s != pop_slot).unwrap();
        let data: Vec<u64> = (0..banks - 1).map(|_| rng.gen_range(0..1 << 16)).collect();
        uut.push_count.next = (count as u64).into();
        uut.push_slot.next = (push_slot as u64).into();
        for (port, d) in uut.push_data.iter_mut().zip(&data) {
            port.next = (*d).into();
        }
        uut.pop.next = pop;
        uut.pop_slot.next = (pop_slot as u64).into();
        uut.clear.next = clear;
        uut.clear_slot.next = (clear_slot as u64).into();
        uut.clock.next = Clock { clk: false };
        assert!(simulate(&mut uut, 100));
        if let Some(want) = expect.take() {
            match want {
                Some(entry) => {
                    assert!(uut.popped.val() && !uut.empty.val(), "cycle {cycle}");
                    assert_eq!(uut.pop_data.val().to_u64(), entry, "cycle {cycle}");
                }
                None => assert!(uut.empty.val() && !uut.popped.val(), "cycle {cycle}"),
            }
        } else {
            assert!(!uut.popped.val() && !uut.empty.val(), "cycle {cycle}");
        }
        assert_eq!(uut.overflow.val(), overflowed.is_some());
        if let Some(slot) = overflowed {
            assert_eq!(uut.overflow_slot.val().to_u64(), slot);
        }
        assert_eq!(uut.dropped.val(), dropped.is_some(), "cycle {cycle}");
        if let Some(slot) = dropped.take() {
            assert_eq!(uut.dropped_slot.val().to_u64(), slot, "cycle {cycle}");
        }
        if count > 0 {
            let stack = &mut stacks[push_slot];
            if stack.len() + count <= depth {
                // data[0] is popped first: pushed last.
                stack.extend(data[..count].iter().rev());
                wide += usize::from(count > 1);
            } else {
                overflowed.get_or_insert(push_slot as u64);
                dropped = Some(push_slot as u64);
                drops += 1;
            }
        }
        if pop {
            let entry = stacks[pop_slot].pop();
            pops += usize::from(entry.is_some());
            empties += usize::from(entry.is_none());
            expect = Some(entry);
        }
        if clear {
            stacks[clear_slot].clear();
        }
        uut.clock.next = Clock { clk: true };
        assert!(simulate(&mut uut, 100));
    }
    assert!(
        pops > 500
            && empties > 100
            && overflowed.is_some()
            && drops > 10
            && (banks == 2 || wide > 300),
        "{pops} pops, {empties} empty, {drops} dropped, {wide} multi-pushes"
    );
}

#[test]
fn four_banks_follow_a_stack_per_slot() {
    follows_a_stack_per_slot(4, 11, 21);
}

#[test]
fn eight_banks_follow_a_stack_per_slot() {
    follows_a_stack_per_slot(8, 9, 22);
}

#[test]
fn two_banks_follow_a_stack_per_slot() {
    follows_a_stack_per_slot(2, 3, 23);
}
