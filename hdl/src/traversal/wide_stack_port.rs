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
use super::wide::Count;
use super::wide_box_port::ENTRY_BITS;
use crate::macros::dff_setup;

pub use super::stack_port::LATENCY;

#[derive(LogicBlock)]
pub struct WideStackPort<
    const S: usize,
    const SB: usize,
    const PB: usize,
    const RB: usize,
    const W: usize,
    const LF: usize,
> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub grant: PopGrant<SB>,
    /// The box port's push: `push_count` entries of `push_slot` (`BankedStacks`' order).
    pub push_count: Signal<In, Count>,
    pub push_slot: Signal<In, Bits<SB>>,
    pub push_data: Vec<Signal<In, Bits<W>>>,
    /// A new ray: its slot's stack is emptied; its id is kept for the overflow report.
    pub entered: Entered<SB>,
    pub step: LinkStep<SB, LF, WIDE_COUNT_BITS>,
    /// The popped entry word (t0, width exponent), beside the step.
    pub step_entry: Signal<Out, Bits<ENTRY_BITS>>,
    pub overflow: Signal<Out, Bit>,
    pub overflow_ray: Signal<Out, Bits<32>>,
    stacks: BankedStacks<S, SB, PB, RB, W>,
    granted: DFF<Bit>,
    granted_slot: DFF<Bits<SB>>,
    granted_t_hi: DFF<Bits<32>>,
    valid: DFF<Bit>,
    slot: DFF<Bits<SB>>,
    t_hi: DFF<Bits<32>>,
    /// lt(t_hi, t0) of the popped entry: entered beyond the far end.
    beyond: F32Order,
    ids: RAM<Bits<32>, SB>,
    overflow_q: DFF<Bit>,
    overflow_ray_q: DFF<Bits<32>>,
    at_first: Constant<Bits<8>>,
    at_count: Constant<Bits<8>>,
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
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            grant: Default::default(),
            push_count: Default::default(),
            push_slot: Default::default(),
            push_data: crate::defaults(width - 1),
            entered: Default::default(),
            step: Default::default(),
            step_entry: Default::default(),
            overflow: Default::default(),
            overflow_ray: Default::default(),
            stacks: BankedStacks::new(width, depth),
            granted: Default::default(),
            granted_slot: Default::default(),
            granted_t_hi: Default::default(),
            valid: Default::default(),
            slot: Default::default(),
            t_hi: Default::default(),
            beyond: Default::default(),
            ids: Default::default(),
            overflow_q: Default::default(),
            overflow_ray_q: Default::default(),
            at_first: Constant::new((ENTRY_BITS as u64).into()),
            at_count: Constant::new(((ENTRY_BITS + LF) as u64).into()),
        }
    }
}

impl<
        const S: usize,
        const SB: usize,
        const PB: usize,
        const RB: usize,
        const W: usize,
        const LF: usize,
    > Logic for WideStackPort<S, SB, PB, RB, W, LF>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.stacks.clock.next = self.clock.val();
        dff_setup!(
            self,
            clock,
            granted,
            granted_slot,
            granted_t_hi,
            valid,
            slot,
            t_hi,
            overflow_q,
            overflow_ray_q
        );
        self.ids.read_clock.next = self.clock.val();
        self.ids.write_clock.next = self.clock.val();
        self.stacks.push_count.next = self.push_count.val();
        self.stacks.push_slot.next = self.push_slot.val();
        for j in 0..self.push_data.len() {
            self.stacks.push_data[j].next = self.push_data[j].val();
        }
        self.stacks.clear.next = self.entered.valid.val();
        self.stacks.clear_slot.next = self.entered.slot.val();

        // The registered grant pops; the entry arrives the next cycle.
        self.granted.d.next = self.grant.valid.val();
        self.granted_slot.d.next = self.grant.slot.val();
        self.granted_t_hi.d.next = self.grant.t_hi.val();
        self.stacks.pop.next = self.granted.q.val();
        self.stacks.pop_slot.next = self.granted_slot.q.val();
        self.valid.d.next = self.granted.q.val();
        self.slot.d.next = self.granted_slot.q.val();
        self.t_hi.d.next = self.granted_t_hi.q.val();
        self.step.valid.next = self.valid.q.val();
        self.step.slot.next = self.slot.q.val();
        self.step.first.next = bit_cast::<LF, W>(self.stacks.pop_data.val() >> self.at_first.val());
        self.step.count.next = bit_cast::<4, W>(self.stacks.pop_data.val() >> self.at_count.val());
        self.step.entry.next = bit_cast::<32, W>(self.stacks.pop_data.val());
        self.step_entry.next = bit_cast::<ENTRY_BITS, W>(self.stacks.pop_data.val());
        self.beyond.a.next = self.t_hi.q.val();
        self.beyond.b.next = self.step.entry.val();
        self.step.pop.next = self.stacks.popped.val() & self.beyond.lt.val();
        self.step.enter.next = self.stacks.popped.val() & !self.beyond.lt.val();

        // A dropped push: the first one's ray id, sticky until a reset.
        self.ids.write_enable.next = self.entered.valid.val();
        self.ids.write_address.next = self.entered.slot.val();
        self.ids.write_data.next = self.entered.id.val();
        self.ids.read_address.next = self.push_slot.val();
        if self.stacks.dropped.val() & !self.overflow_q.q.val() {
            self.overflow_q.d.next = true;
            self.overflow_ray_q.d.next = self.ids.read_data.val();
        }
        if !self.reset_n.val() {
            self.overflow_q.d.next = false;
        }
        self.overflow.next = self.overflow_q.q.val();
        self.overflow_ray.next = self.overflow_ray_q.q.val();
    }
}
