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

/// The stack port's block over its stacks (the binary port's [`SlotStacks`], the wide port's
/// `BankedStacks`): the registered grant, the pop and its skip test, the overflow report, the same
/// for both; each says its push (`push` fields, `push_into_stacks`, `push_slot` the pushing slot,
/// whose ray id the overflow report reads), its step (`step` fields, `popped_link` decoding the
/// popped word) and its `constants`. A macro rather than a shared sub-block, which would change the
/// binary unit's Verilog; `self` and `#[hdl_gen]` come from the caller (macro hygiene: the
/// attribute's `connect` takes the caller's `self`), as do the statements that use `self`.
macro_rules! stack_port_block {
    (
        $pound:tt $hdl_gen:tt
        $this:ident,
        $port:ident<$($g:ident),*>,
        stacks: $stacks:ty,
        push: { $($push:tt)* },
        step: { $($step:tt)* },
        constants: { $($constants:tt)* },
        push_into_stacks: { $($push_into_stacks:tt)* },
        popped_link: { $($popped_link:tt)* },
        push_slot: { $($push_slot:tt)* },
    ) => {
        #[derive(LogicBlock)]
        pub struct $port<$(const $g: usize),*> {
            pub clock: Signal<In, Clock>,
            pub reset_n: Signal<In, Bit>,
            pub grant: PopGrant<SB>,
            $($push)*
            /// A new ray: its slot's stack is emptied; its id is kept for the overflow report.
            pub entered: Entered<SB>,
            $($step)*
            pub overflow: Signal<Out, Bit>,
            pub overflow_ray: Signal<Out, Bits<32>>,
            stacks: $stacks,
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
            $($constants)*
        }

        impl<$(const $g: usize),*> Logic for $port<$($g),*> {
            $pound $hdl_gen
            fn update(&mut $this) {
                clock!($this, clock, stacks);
                dff_setup!(
                    $this,
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
                $this.ids.read_clock.next = $this.clock.val();
                $this.ids.write_clock.next = $this.clock.val();
                $($push_into_stacks)*
                $this.stacks.clear.next = $this.entered.valid.val();
                $this.stacks.clear_slot.next = $this.entered.slot.val();

                // The registered grant pops; the entry arrives the next cycle.
                $this.granted.d.next = $this.grant.valid.val();
                $this.granted_slot.d.next = $this.grant.slot.val();
                $this.granted_t_hi.d.next = $this.grant.t_hi.val();
                $this.stacks.pop.next = $this.granted.q.val();
                $this.stacks.pop_slot.next = $this.granted_slot.q.val();
                $this.valid.d.next = $this.granted.q.val();
                $this.slot.d.next = $this.granted_slot.q.val();
                $this.t_hi.d.next = $this.granted_t_hi.q.val();
                $this.step.valid.next = $this.valid.q.val();
                $this.step.slot.next = $this.slot.q.val();
                $($popped_link)*
                $this.beyond.a.next = $this.t_hi.q.val();
                $this.beyond.b.next = $this.step.entry.val();
                $this.step.pop.next = $this.stacks.popped.val() & $this.beyond.lt.val();
                $this.step.enter.next = $this.stacks.popped.val() & !$this.beyond.lt.val();

                // A dropped push: the first one's ray id, sticky until a reset.
                $this.ids.write_enable.next = $this.entered.valid.val();
                $this.ids.write_address.next = $this.entered.slot.val();
                $this.ids.write_data.next = $this.entered.id.val();
                $this.ids.read_address.next = $($push_slot)*;
                if $this.stacks.dropped.val() & !$this.overflow_q.q.val() {
                    $this.overflow_q.d.next = true;
                    $this.overflow_ray_q.d.next = $this.ids.read_data.val();
                }
                if !$this.reset_n.val() {
                    $this.overflow_q.d.next = false;
                }
                $this.overflow.next = $this.overflow_q.q.val();
                $this.overflow_ray.next = $this.overflow_ray_q.q.val();
            }
        }
    };
}
pub(crate) use stack_port_block;

/// The struct literal of a stack port (`stack_port_block!`'s): the shared fields' values, then
/// the port's own (`own`: its push, step, stacks and constants).
macro_rules! stack_port_new {
    ({ $($own:tt)* }) => {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            grant: Default::default(),
            entered: Default::default(),
            step: Default::default(),
            overflow: Default::default(),
            overflow_ray: Default::default(),
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
            $($own)*
        }
    };
}
pub(crate) use stack_port_new;

stack_port_block! {
    #[hdl_gen]
    self,
    StackPort<S, SB, PB, AB, W, LF, LC>,
    stacks: SlotStacks<S, SB, PB, AB, W>,
    push: { pub push: PushSink<SB, W>, },
    step: { pub step: LinkStep<SB, LF, LC>, },
    constants: {
        /// A stack entry: the distance in bits 0–31, the count at 32, the first at `at_first`.
        at_first: Constant<Bits<8>>,
    },
    push_into_stacks: {
        self.stacks.push.next = self.push.valid.val();
        self.stacks.push_slot.next = self.push.slot.val();
        self.stacks.push_data.next = self.push.data.val();
    },
    popped_link: {
        self.step.first.next = bit_cast::<LF, W>(self.stacks.pop_data.val() >> self.at_first.val());
        self.step.count.next = bit_cast::<LC, W>(self.stacks.pop_data.val() >> 32);
        self.step.entry.next = bit_cast::<32, W>(self.stacks.pop_data.val());
    },
    push_slot: { self.push.slot.val() },
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
        stack_port_new!({
            push: Default::default(),
            stacks: SlotStacks::new(depth),
            at_first: Constant::new(((LC + 32) as u64).into()),
        })
    }
}
