//! Every child's slab interval from its three axes: `near` the largest entry code, `far` the
//! smallest of the exit codes and the node's far end (signed: −1 enters nothing). Each is one
//! level of comparisons side by side and a select, not a chain of two.
//!
//! Entries and exits are indexed `3·child + axis`.
//!
//! Cut points ([`SlabFold::CUTS`]): 0. the results.

use rust_hdl::prelude::*;

use super::{EntryCode, ExitCode};
use crate::pipe::{placement, Pipe};

#[derive(LogicBlock)]
pub struct SlabFold {
    pub clock: Signal<In, Clock>,
    pub entry: Vec<Signal<In, EntryCode>>,
    pub exit: Vec<Signal<In, ExitCode>>,
    /// The node's far end.
    pub far_end: Signal<In, ExitCode>,
    pub near: Vec<Signal<Out, EntryCode>>,
    pub far: Vec<Signal<Out, ExitCode>>,
    /// Per child: the exits and the far end with their sign bits flipped (unsigned order).
    ordered: Vec<Signal<Local, ExitCode>>,
    far_ordered: Signal<Local, ExitCode>,
    near_out: Vec<Pipe<EntryCode>>,
    far_out: Vec<Pipe<ExitCode>>,
    flip: Constant<ExitCode>,
}

impl SlabFold {
    pub const CUTS: usize = 1;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    /// The fold of `width` children.
    pub fn new(width: usize, stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            entry: crate::defaults(3 * width),
            exit: crate::defaults(3 * width),
            far_end: Default::default(),
            near: crate::defaults(width),
            far: crate::defaults(width),
            ordered: crate::defaults(3 * width),
            far_ordered: Default::default(),
            near_out: (0..width).map(|_| Pipe::new(cut[0])).collect(),
            far_out: (0..width).map(|_| Pipe::new(cut[0])).collect(),
            flip: Constant::new(0x8000.into()),
        }
    }
}

impl Logic for SlabFold {
    #[hdl_gen]
    fn update(&mut self) {
        self.far_ordered.next = self.far_end.val() ^ self.flip.val();
        for c in 0..self.near.len() {
            self.near_out[c].clock.next = self.clock.val();
            self.far_out[c].clock.next = self.clock.val();
            // The largest entry.
            if (self.entry[3 * c].val() >= self.entry[3 * c + 1].val())
                & (self.entry[3 * c].val() >= self.entry[3 * c + 2].val())
            {
                self.near_out[c].d.next = self.entry[3 * c].val();
            } else if self.entry[3 * c + 1].val() >= self.entry[3 * c + 2].val() {
                self.near_out[c].d.next = self.entry[3 * c + 1].val();
            } else {
                self.near_out[c].d.next = self.entry[3 * c + 2].val();
            }
            // The smallest of the exits and the far end: the first that is at most all
            // later ones (if an earlier one is not the smallest, a later one is smaller).
            self.ordered[3 * c].next = self.exit[3 * c].val() ^ self.flip.val();
            self.ordered[3 * c + 1].next = self.exit[3 * c + 1].val() ^ self.flip.val();
            self.ordered[3 * c + 2].next = self.exit[3 * c + 2].val() ^ self.flip.val();
            if (self.ordered[3 * c].val() <= self.ordered[3 * c + 1].val())
                & (self.ordered[3 * c].val() <= self.ordered[3 * c + 2].val())
                & (self.ordered[3 * c].val() <= self.far_ordered.val())
            {
                self.far_out[c].d.next = self.exit[3 * c].val();
            } else if (self.ordered[3 * c + 1].val() <= self.ordered[3 * c + 2].val())
                & (self.ordered[3 * c + 1].val() <= self.far_ordered.val())
            {
                self.far_out[c].d.next = self.exit[3 * c + 1].val();
            } else if self.ordered[3 * c + 2].val() <= self.far_ordered.val() {
                self.far_out[c].d.next = self.exit[3 * c + 2].val();
            } else {
                self.far_out[c].d.next = self.far_end.val();
            }
            self.near[c].next = self.near_out[c].q.val();
            self.far[c].next = self.far_out[c].q.val();
        }
    }
}
