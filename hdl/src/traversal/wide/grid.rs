//! The node's grid in t: the exponent `E` that bounds every exit that matters (the model's
//! `extent`), and the shift `8 − U = 22 − E` onto the grid of the slab codes.
//!
//! Per axis the bound comes from exponents alone (docs/wide-nodes.md, step 2):
//! `max(exp(α) + 1, e + exp(inv) + 9, exp(pad_t) + 1) + 2`, in biased exponents
//! `max(α_b, e + inv_b + 8, pad_b) − 124`; an axis whose reciprocal is flushed or not finite,
//! or whose `α` or `pad_t` is not finite, bounds nothing. `E` is the smallest bound and the
//! entry's width exponent (unless that is [`WIDTH_UNBOUNDED`]); with none, the node is not
//! `bounded` and every child is entered.
//!
//! Values are compared as 11-bit two's complement numbers with the sign bit flipped
//! (unsigned order, [`Ordered`]), an absent bound being all ones (larger than any bound:
//! bounds stay within −512..=510). Each axis's bound is an [`AxisExtent`].
//!
//! Cut points ([`NodeGrid::CUTS`]): 0. after the per-axis bounds; 1. the results.

use rust_hdl::prelude::*;

use super::extent::{AxisExtent, Ordered};
use super::{Shift, WidthExp, Word};
use crate::pipe::{placement, Pipe};
use hw_model::traversal::wide::box_test::{CODE_BITS, FRAC_BITS, WIDTH_UNBOUNDED};

#[derive(LogicBlock)]
pub struct NodeGrid {
    pub clock: Signal<In, Clock>,
    /// `α = (p − o)·inv` per axis.
    pub alpha: [Signal<In, Word>; 3],
    pub inv_dir: [Signal<In, Word>; 3],
    pub pad_t: [Signal<In, Word>; 3],
    /// The node's grid exponents (i8).
    pub exp: [Signal<In, Bits<8>>; 3],
    /// The entry's width exponent.
    pub width: Signal<In, WidthExp>,
    /// `E` (two's complement), meaningful when `bounded`.
    pub extent: Signal<Out, Shift>,
    /// `22 − E`.
    pub shift: Signal<Out, Shift>,
    pub bounded: Signal<Out, Bit>,
    axes: [AxisExtent; 3],
    /// Cut 0: per axis, then the width.
    bound: [Pipe<Ordered>; 4],
    smallest: [Signal<Local, Ordered>; 3],
    extent_local: Signal<Local, Shift>,
    /// Cut 1.
    extent_out: Pipe<Shift>,
    shift_out: Pipe<Shift>,
    bounded_out: Pipe<Bit>,
    /// The flipped sign bit, and a negative width's sign extension.
    flip: Constant<Ordered>,
    width_sign: Constant<Ordered>,
    absent: Constant<Ordered>,
    unbounded: Constant<WidthExp>,
    /// `8 − U = FRAC_BITS + CODE_BITS − 2 − E`.
    shift_base: Constant<Shift>,
}

impl NodeGrid {
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            alpha: Default::default(),
            inv_dir: Default::default(),
            pad_t: Default::default(),
            exp: Default::default(),
            width: Default::default(),
            extent: Default::default(),
            shift: Default::default(),
            bounded: Default::default(),
            axes: Default::default(),
            bound: std::array::from_fn(|_| Pipe::new(cut[0])),
            smallest: Default::default(),
            extent_local: Default::default(),
            extent_out: Pipe::new(cut[1]),
            shift_out: Pipe::new(cut[1]),
            bounded_out: Pipe::new(cut[1]),
            flip: Constant::new(0x400.into()),
            width_sign: Constant::new(0x400.into()),
            absent: Constant::new(0x7FF.into()),
            unbounded: Constant::new((WIDTH_UNBOUNDED as u64).into()),
            shift_base: Constant::new(u64::from(FRAC_BITS + CODE_BITS - 2).into()),
        }
    }
}

impl Logic for NodeGrid {
    #[hdl_gen]
    fn update(&mut self) {
        for a in 0..3 {
            self.axes[a].alpha.next = self.alpha[a].val();
            self.axes[a].inv_dir.next = self.inv_dir[a].val();
            self.axes[a].pad_t.next = self.pad_t[a].val();
            self.axes[a].exp.next = self.exp[a].val();
            self.bound[a].clock.next = self.clock.val();
            self.bound[a].d.next = self.axes[a].bound.val();
        }
        self.bound[3].clock.next = self.clock.val();
        self.bound[3].d.next = bit_cast::<11, 10>(self.width.val()) ^ self.flip.val();
        if self.width.val().get_bit(9) {
            self.bound[3].d.next =
                (bit_cast::<11, 10>(self.width.val()) | self.width_sign.val()) ^ self.flip.val();
        }
        if self.width.val() == self.unbounded.val() {
            self.bound[3].d.next = self.absent.val();
        }
        // The smallest of four: two pairs, then their smaller.
        self.smallest[0].next = self.bound[0].q.val();
        if self.bound[1].q.val() < self.bound[0].q.val() {
            self.smallest[0].next = self.bound[1].q.val();
        }
        self.smallest[1].next = self.bound[2].q.val();
        if self.bound[3].q.val() < self.bound[2].q.val() {
            self.smallest[1].next = self.bound[3].q.val();
        }
        self.smallest[2].next = self.smallest[0].val();
        if self.smallest[1].val() < self.smallest[0].val() {
            self.smallest[2].next = self.smallest[1].val();
        }
        self.extent_local.next = self.smallest[2].val() ^ self.flip.val();
        self.extent_out.clock.next = self.clock.val();
        self.shift_out.clock.next = self.clock.val();
        self.bounded_out.clock.next = self.clock.val();
        self.extent_out.d.next = self.extent_local.val();
        self.shift_out.d.next = self.shift_base.val() - self.extent_local.val();
        self.bounded_out.d.next = self.smallest[2].val() != self.absent.val();
        self.extent.next = self.extent_out.q.val();
        self.shift.next = self.shift_out.q.val();
        self.bounded.next = self.bounded_out.q.val();
    }
}
