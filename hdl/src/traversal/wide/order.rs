//! The entered children, nearest first: each child's rank among the entered ones by
//! `(near, slot)` (the model's sort key), the number of children before it (one comparison
//! per pair side by side, counted by [`Ones`]), then for each position the slot ranked there. Children that are not entered rank after all that
//! are; the positions from `entered` on are not meaningful.
//!
//! When the node's grid is unknown every child below `children` is entered, in slot order.
//!
//! Cut points ([`NearestFirst::CUTS`]): 0. after the ranks and the count; 1. the positions.

use rust_hdl::prelude::*;

use super::ones::Ones;
use super::{Count, EntryCode, ExitCode, Slot, SlotBits};
use crate::pipe::{placement, Pipe};

#[derive(LogicBlock)]
pub struct NearestFirst {
    pub clock: Signal<In, Clock>,
    pub near: Vec<Signal<In, EntryCode>>,
    pub far: Vec<Signal<In, ExitCode>>,
    /// The node's children: slots from here on are empty.
    pub children: Signal<In, Count>,
    pub unknown: Signal<In, Bit>,
    /// The slot at each position.
    pub slot: Vec<Signal<Out, Slot>>,
    pub entered: Signal<Out, Count>,
    enters: Vec<Signal<Local, Bit>>,
    /// The entered children, and per child those before it (bit per slot).
    entered_bits: Signal<Local, SlotBits>,
    before: Vec<Signal<Local, SlotBits>>,
    count_ones: Ones,
    rank_ones: Vec<Ones>,
    /// Cut 0.
    rank: Vec<Pipe<Count>>,
    count: Pipe<Count>,
    children_0: Pipe<Count>,
    unknown_0: Pipe<Bit>,
    slot_sum: Vec<Signal<Local, Slot>>,
    /// Cut 1.
    slot_out: Vec<Pipe<Slot>>,
    entered_out: Pipe<Count>,
}

impl NearestFirst {
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    /// The order of `width` children.
    pub fn new(width: usize, stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            near: crate::defaults(width),
            far: crate::defaults(width),
            children: Default::default(),
            unknown: Default::default(),
            slot: crate::defaults(width),
            entered: Default::default(),
            enters: crate::defaults(width),
            entered_bits: Default::default(),
            before: crate::defaults(width),
            count_ones: Default::default(),
            rank_ones: (0..width).map(|_| Ones::default()).collect(),
            rank: (0..width).map(|_| Pipe::new(cut[0])).collect(),
            count: Pipe::new(cut[0]),
            children_0: Pipe::new(cut[0]),
            unknown_0: Pipe::new(cut[0]),
            slot_sum: crate::defaults(width),
            slot_out: (0..width).map(|_| Pipe::new(cut[1])).collect(),
            entered_out: Pipe::new(cut[1]),
        }
    }
}

impl Logic for NearestFirst {
    #[hdl_gen]
    fn update(&mut self) {
        self.count.clock.next = self.clock.val();
        self.children_0.clock.next = self.clock.val();
        self.unknown_0.clock.next = self.clock.val();
        self.entered_out.clock.next = self.clock.val();
        // Entered: a slot of the node, far ≥ 0 and near ≤ far.
        self.entered_bits.next = 0.into();
        for c in 0..self.near.len() {
            // A far end is at most CODE_LIMIT, below 2^15.
            self.enters[c].next = !self.far[c].val().get_bit(15)
                & (self.near[c].val() <= self.far[c].val().get_bits::<15>(0))
                & (self.children.val() > c.to_bits());
            self.entered_bits.next = self.entered_bits.val().replace_bit(c, self.enters[c].val());
        }
        self.count_ones.x.next = self.entered_bits.val();
        self.count.d.next = self.count_ones.count.val();
        // d comes before c: entered, and c is not or is farther (a tie goes to the lower
        // slot).
        for c in 0..self.near.len() {
            self.rank[c].clock.next = self.clock.val();
            self.before[c].next = 0.into();
            for d in 0..self.near.len() {
                if d < c {
                    self.before[c].next = self.before[c].val().replace_bit(
                        d,
                        self.enters[d].val()
                            & (!self.enters[c].val() | (self.near[d].val() <= self.near[c].val())),
                    );
                }
                if c < d {
                    self.before[c].next = self.before[c].val().replace_bit(
                        d,
                        self.enters[d].val()
                            & (!self.enters[c].val() | (self.near[d].val() < self.near[c].val())),
                    );
                }
            }
            self.rank_ones[c].x.next = self.before[c].val();
            self.rank[c].d.next = self.rank_ones[c].count.val();
        }
        self.children_0.d.next = self.children.val();
        self.unknown_0.d.next = self.unknown.val();
        // The slot of each position: the one child ranked there.
        for p in 0..self.slot.len() {
            self.slot_out[p].clock.next = self.clock.val();
            self.slot_sum[p].next = 0.into();
            for c in 0..self.near.len() {
                if self.rank[c].q.val() == p.to_bits() {
                    self.slot_sum[p].next = self.slot_sum[p].val() | c.to_bits();
                }
            }
            self.slot_out[p].d.next = self.slot_sum[p].val();
            if self.unknown_0.q.val() {
                self.slot_out[p].d.next = p.to_bits();
            }
            self.slot[p].next = self.slot_out[p].q.val();
        }
        self.entered_out.d.next = self.count.q.val();
        if self.unknown_0.q.val() {
            self.entered_out.d.next = self.children_0.q.val();
        }
        self.entered.next = self.entered_out.q.val();
    }
}
