//! The stack port for wide nodes: [`StackPort`](super::stack_port::StackPort)'s pop, skip
//! and overflow report over the banked stacks ([`BankedStacks`]), which take a wide node's
//! pushes (up to K − 1 entries) in one cycle. A stack entry is a link and where the walk
//! enters it (t0, width exponent); the pop's skip compares the slot's far end with t0 (`t_hi <
//! t0`: popped again), as the binary port compares the popped distance. The answer
//! ([`LinkStep`], `step_entry` the popped entry word) comes [`LATENCY`] cycles after the
//! grant, as the binary port's.
//!
//! rust-hdl cannot derive widths: `S` slots of `SB` bits, stack pointers of `PB` bits, bank
//! addresses of `RB` bits (see [`BankedStacks`]), entries of `W` bits (the entry word in bits
//! 0–41, the link of `LF` + 4 bits above), `LF` a link's first.

use rust_hdl::prelude::*;

use super::banked_stack::BankedStacks;
use super::hit_update::F32Order;
use super::scene_records::WIDE_COUNT_BITS;
use super::slot_ports::{Entered, LinkStep, PopGrant};
use super::stack_port::{stack_port_block, stack_port_new};
use super::wide::Count;
use super::wide_box_port::ENTRY_BITS;
use crate::macros::dff_setup;

pub use super::stack_port::LATENCY;

stack_port_block! {
    #[hdl_gen]
    self,
    WideStackPort<S, SB, PB, RB, W, LF>,
    stacks: BankedStacks<S, SB, PB, RB, W>,
    push: {
        /// The box port's push: `push_count` entries of `push_slot` (`BankedStacks`' order).
        pub push_count: Signal<In, Count>,
        pub push_slot: Signal<In, Bits<SB>>,
        pub push_data: Vec<Signal<In, Bits<W>>>,
    },
    step: {
        pub step: LinkStep<SB, LF, WIDE_COUNT_BITS>,
        /// The popped entry word (t0, width exponent), beside the step.
        pub step_entry: Signal<Out, Bits<ENTRY_BITS>>,
    },
    constants: {
        /// A stack entry: the entry word in bits 0–41, the link's first at `at_first`, its
        /// count at `at_count`.
        at_first: Constant<Bits<8>>,
        at_count: Constant<Bits<8>>,
    },
    push_into_stacks: {
        self.stacks.push_count.next = self.push_count.val();
        self.stacks.push_slot.next = self.push_slot.val();
        for j in 0..self.push_data.len() {
            self.stacks.push_data[j].next = self.push_data[j].val();
        }
    },
    popped_link: {
        self.step.first.next = bit_cast::<LF, W>(self.stacks.pop_data.val() >> self.at_first.val());
        self.step.count.next = bit_cast::<4, W>(self.stacks.pop_data.val() >> self.at_count.val());
        self.step.entry.next = bit_cast::<32, W>(self.stacks.pop_data.val());
        self.step_entry.next = bit_cast::<ENTRY_BITS, W>(self.stacks.pop_data.val());
    },
    push_slot: { self.push_slot.val() },
}

impl<
        const S: usize,
        const SB: usize,
        const PB: usize,
        const RB: usize,
        const W: usize,
        const LF: usize,
    > WideStackPort<S, SB, PB, RB, W, LF>
{
    /// Stacks of `depth` entries for nodes of `width` children.
    pub fn new(width: usize, depth: usize) -> Self {
        assert_eq!(
            W,
            ENTRY_BITS + LF + WIDE_COUNT_BITS,
            "a stack entry is an entry word and a link"
        );
        stack_port_new!({
            push_count: Default::default(),
            push_slot: Default::default(),
            push_data: crate::defaults(width - 1),
            step_entry: Default::default(),
            stacks: BankedStacks::new(width, depth),
            at_first: Constant::new((ENTRY_BITS as u64).into()),
            at_count: Constant::new(((ENTRY_BITS + LF) as u64).into()),
        })
    }
}
