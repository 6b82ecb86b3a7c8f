//! `hdl::traversal::stack` and `hdl::traversal::stack_port`.

use hdl::traversal::stack::*;
use hdl::traversal::stack_port::{StackPort, LATENCY};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

type Stacks = SlotStacks<6, 3, 3, 6, 16>;

/// Random pushes, pops and clears of different slots each cycle against `Vec` stacks.
#[test]
fn pushes_and_pops_follow_a_stack_per_slot() {
    const DEPTH: usize = 5;
    let mut uut = Stacks::new(DEPTH);
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(11);
    let mut stacks = vec![Vec::<u64>::new(); 6];
    // What the last cycle's pop must answer: Some(entry) or None (empty).
    let mut expect: Option<Option<u64>> = None;
    // The slot whose push the last cycle dropped.
    let mut dropped: Option<u64> = None;
    let (mut pops, mut empties, mut overflowed, mut drops) = (0, 0, None, 0);
    for cycle in 0..5_000 {
        let push_slot = rng.gen_range(0..6usize);
        let pop_slot = (push_slot + rng.gen_range(1..6)) % 6;
        let push = rng.gen_bool(0.5);
        let pop = rng.gen_bool(0.45);
        let clear = rng.gen_bool(0.02);
        let clear_slot = (0..6).find(|&s| s != push_slot && s != pop_slot).unwrap();
        let data: u64 = rng.gen_range(0..1 << 16);
        uut.push.next = push;
        uut.push_slot.next = (push_slot as u64).into();
        uut.push_data.next = data.into();
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
        if push {
            if stacks[push_slot].len() < DEPTH {
                stacks[push_slot].push(data);
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
    assert!(pops > 500 && empties > 100 && overflowed.is_some() && drops > 10);
}

/// 4 slots of 4 entries; links of 4 + 4 bits.
type Port = StackPort<4, 2, 3, 4, 40, 4, 4>;

/// One clock cycle: the inputs set before it are registered at its rising edge.
fn tick(uut: &mut Port) {
    uut.clock.next = Clock { clk: true };
    assert!(simulate(uut, 100));
    uut.clock.next = Clock { clk: false };
    assert!(simulate(uut, 100));
}

/// The port's step for a pop granted at cycle 0: the cycle it arrives and its (enter, pop,
/// first, count, entry).
fn pop_step(uut: &mut Port, slot: u64, t_hi: f32) -> (usize, (bool, bool, u64, u64, u32)) {
    uut.grant.valid.next = true;
    uut.grant.slot.next = slot.into();
    uut.grant.t_hi.next = u64::from(t_hi.to_bits()).into();
    assert!(simulate(uut, 100));
    for cycle in 0..10 {
        tick(uut);
        uut.grant.valid.next = false;
        assert!(simulate(uut, 100));
        if uut.step.valid.val() {
            assert_eq!(uut.step.slot.val().to_u64(), slot);
            let step = (
                uut.step.enter.val(),
                uut.step.pop.val(),
                uut.step.first.val().to_u64(),
                uut.step.count.val().to_u64(),
                uut.step.entry.val().to_u64() as u32,
            );
            return (cycle + 1, step);
        }
    }
    panic!("no step for the pop of slot {slot}");
}

/// A pop answers `LATENCY` cycles after its grant (the figure the schedule model times pops
/// with): the entry entered within the far end, popped again beyond it, the end when empty.
#[test]
fn a_pop_answers_latency_cycles_after_its_grant() {
    let mut uut = Port::new(4);
    uut.connect_all();
    uut.reset_n.next = true;
    uut.clock.next = Clock { clk: false };
    assert!(simulate(&mut uut, 100));
    // Slot 2 pushes two entries (first 5, count 0, at 1.5; first 9, count 3, at 4.0).
    for (first, count, entry) in [(5u64, 0u64, 1.5f32), (9, 3, 4.0)] {
        uut.push.valid.next = true;
        uut.push.slot.next = 2.into();
        uut.push.data.next = (u64::from(entry.to_bits()) | count << 32 | first << 36).into();
        tick(&mut uut);
    }
    uut.push.valid.next = false;
    let steps = [
        pop_step(&mut uut, 2, 3.0),
        pop_step(&mut uut, 2, 3.0),
        pop_step(&mut uut, 2, 3.0),
    ];
    for (cycles, _) in steps {
        assert_eq!(cycles, LATENCY);
    }
    // Beyond the far end (4.0 > 3.0): popped again; within: entered; then empty: the end.
    assert_eq!(steps[0].1, (false, true, 9, 3, 4.0f32.to_bits()));
    assert_eq!(steps[1].1, (true, false, 5, 0, 1.5f32.to_bits()));
    assert_eq!((steps[2].1 .0, steps[2].1 .1), (false, false));
}
