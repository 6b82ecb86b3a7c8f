//! The stack port: the slots' stacks ([`SlotStacks`], one push and one pop a cycle) behind
//! the pop scheduler's grant. The grant is registered first (for the clock: the scheduler's
//! pick and the granted slot's words fill the grant's cycle, the stack pointer's select and
//! the stack RAM's address the next), then the stack is read; a pop answers [`LATENCY`]
//! cycles after its grant with a [`LinkStep`]: the popped entry entered, or popped again when
//! it was entered beyond the slot's far end `t_hi`, or the end of the walk when the stack is
//! empty. A push onto a full stack is dropped and
//! reported once, sticky, with its ray's id (`overflow`, `overflow_ray`; the model's
//! `TraversalError::StackOverflow`).
//!
//! rust-hdl cannot derive widths: `S` slots of `SB` bits, stack pointers of `PB` bits, stack
//! RAM addresses of `AB` bits, entries of `W` = LF + LC + 32 bits (see [`SlotStacks`]).

use rust_hdl::prelude::*;

use super::hit_update::F32Order;
use super::slot_ports::{Entered, LinkStep, PopGrant, PushSink};
use super::stack::SlotStacks;
use super::timing::MEMORY_READ;

/// Cycles from a pop's grant to its step: the grant's register, then the stack read (the
/// step's comparison with the far end is combinational).
pub const LATENCY: usize = 1 + MEMORY_READ;

#[derive(LogicBlock)]
pub struct StackPort<
    const S: usize,
    const SB: usize,
    const PB: usize,
    const AB: usize,
    const W: usize,
    const LF: usize,
    const LC: usize,
> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub grant: PopGrant<SB>,
    pub push: PushSink<SB, W>,
    /// A new ray: its slot's stack is emptied; its id is kept for the overflow report.
    pub entered: Entered<SB>,
    pub step: LinkStep<SB, LF, LC>,
    pub overflow: Signal<Out, Bit>,
    pub overflow_ray: Signal<Out, Bits<32>>,
    stacks: SlotStacks<S, SB, PB, AB, W>,
    /// The grant, registered.
    granted: DFF<Bit>,
    granted_slot: DFF<Bits<SB>>,
    granted_t_hi: DFF<Bits<32>>,
    /// The granted slot, registered beside the stack read.
    valid: DFF<Bit>,
    slot: DFF<Bits<SB>>,
    t_hi: DFF<Bits<32>>,
    /// lt(t_hi, entry distance) of the popped entry: entered beyond the far end.
    beyond: F32Order,
    /// The slots' ray ids, read with every push (ready when the stack reports a drop).
    ids: RAM<Bits<32>, SB>,
    overflow_q: DFF<Bit>,
    overflow_ray_q: DFF<Bits<32>>,
    /// A stack entry: the distance in bits 0–31, the count at 32, the first at `at_first`.
    at_first: Constant<Bits<8>>,
}

impl<
        const S: usize,
        const SB: usize,
        const PB: usize,
        const AB: usize,
        const W: usize,
        const LF: usize,
        const LC: usize,
    > StackPort<S, SB, PB, AB, W, LF, LC>
{
    /// Stacks of `depth` entries.
    pub fn new(depth: usize) -> Self {
        assert_eq!(W, LF + LC + 32, "a stack entry is a link and a distance");
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            grant: Default::default(),
            push: Default::default(),
            entered: Default::default(),
            step: Default::default(),
            overflow: Default::default(),
            overflow_ray: Default::default(),
            stacks: SlotStacks::new(depth),
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
            at_first: Constant::new(((LC + 32) as u64).into()),
        }
    }
}

impl<
        const S: usize,
        const SB: usize,
        const PB: usize,
        const AB: usize,
        const W: usize,
        const LF: usize,
        const LC: usize,
    > Logic for StackPort<S, SB, PB, AB, W, LF, LC>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, stacks);
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
        self.stacks.push.next = self.push.valid.val();
        self.stacks.push_slot.next = self.push.slot.val();
        self.stacks.push_data.next = self.push.data.val();
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
        self.step.count.next = bit_cast::<LC, W>(self.stacks.pop_data.val() >> 32);
        self.step.entry.next = bit_cast::<32, W>(self.stacks.pop_data.val());
        self.beyond.a.next = self.t_hi.q.val();
        self.beyond.b.next = self.step.entry.val();
        self.step.pop.next = self.stacks.popped.val() & self.beyond.lt.val();
        self.step.enter.next = self.stacks.popped.val() & !self.beyond.lt.val();

        // A dropped push: the first one's ray id, sticky until a reset.
        self.ids.write_enable.next = self.entered.valid.val();
        self.ids.write_address.next = self.entered.slot.val();
        self.ids.write_data.next = self.entered.id.val();
        self.ids.read_address.next = self.push.slot.val();
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
