//! Each position's word from the slot ranked there (a multiplexer per position; the slot
//! at position `p` picks among the children's words), registered.
//!
//! Cut points ([`Select::CUTS`]): 0. the results.

use rust_hdl::prelude::*;

use super::Slot;
use crate::pipe::{placement, Pipe};

#[derive(LogicBlock)]
pub struct Select<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Per child.
    pub word: Vec<Signal<In, Bits<N>>>,
    /// Per position.
    pub slot: Vec<Signal<In, Slot>>,
    pub y: Vec<Signal<Out, Bits<N>>>,
    picked: Vec<Signal<Local, Bits<N>>>,
    y_out: Vec<Pipe<Bits<N>>>,
}

impl<const N: usize> Select<N> {
    pub const CUTS: usize = 1;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    /// The selection among `width` children.
    pub fn new(width: usize, stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            word: crate::defaults(width),
            slot: crate::defaults(width),
            y: crate::defaults(width),
            picked: crate::defaults(width),
            y_out: (0..width).map(|_| Pipe::new(cut[0])).collect(),
        }
    }
}

impl<const N: usize> Logic for Select<N> {
    #[hdl_gen]
    fn update(&mut self) {
        for p in 0..self.y.len() {
            self.y_out[p].clock.next = self.clock.val();
            // The slot is one of the children's: child 0 unless another matches.
            self.picked[p].next = self.word[0].val();
            for c in 1..self.word.len() {
                if self.slot[p].val() == c.to_bits() {
                    self.picked[p].next = self.word[c].val();
                }
            }
            self.y_out[p].d.next = self.picked[p].val();
            self.y[p].next = self.y_out[p].q.val();
        }
    }
}
