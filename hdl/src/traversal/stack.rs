//! The ray slots' traversal stacks: one block RAM holds every slot's stack (slot `s` at
//! words `s·D … s·D + D − 1`), with a stack pointer per slot in flip-flops.
//!
//! A cycle takes one push and one pop, of different slots (a slot waits for each step's
//! answer, so it never pushes and pops at once). A pop answers one cycle later: the entry, or
//! `empty` when the stack had none (the ray's walk is over). A push onto a full stack is
//! dropped and raises the sticky `overflow` with the slot, which the unit reports as an error
//! (the model's `TraversalError::StackOverflow`); `clear` empties a slot's stack for its next
//! ray.
//!
//! rust-hdl cannot derive widths: `S` slots addressed by `SB` bits, stack pointers of `PB`
//! bits (depth < 2^PB), RAM addresses of `AB` bits (S·D ≤ 2^AB), entries of `W` bits.

use crate::macros::dff_setup;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct SlotStacks<
    const S: usize,
    const SB: usize,
    const PB: usize,
    const AB: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    pub push: Signal<In, Bit>,
    pub push_slot: Signal<In, Bits<SB>>,
    pub push_data: Signal<In, Bits<W>>,
    pub pop: Signal<In, Bit>,
    pub pop_slot: Signal<In, Bits<SB>>,
    /// A new ray in `clear_slot`: its stack is emptied (with no push or pop of that slot).
    pub clear: Signal<In, Bit>,
    pub clear_slot: Signal<In, Bits<SB>>,
    /// The cycle after a pop: its entry (`popped`), or `empty`.
    pub popped: Signal<Out, Bit>,
    pub empty: Signal<Out, Bit>,
    pub pop_data: Signal<Out, Bits<W>>,
    /// Sticky: a push found its slot's stack full (`overflow_slot`, the first such slot).
    pub overflow: Signal<Out, Bit>,
    pub overflow_slot: Signal<Out, Bits<SB>>,
    /// The cycle after a push found its slot's stack full (not sticky): that slot.
    pub dropped: Signal<Out, Bit>,
    pub dropped_slot: Signal<Out, Bits<SB>>,
    sp: Vec<DFF<Bits<PB>>>,
    base: Vec<Constant<Bits<AB>>>,
    slot_id: Vec<Constant<Bits<SB>>>,
    depth: Constant<Bits<PB>>,
    ram: RAM<Bits<W>, AB>,
    popped_reg: DFF<Bit>,
    empty_reg: DFF<Bit>,
    overflow_reg: DFF<Bit>,
    overflow_slot_reg: DFF<Bits<SB>>,
    dropped_reg: DFF<Bit>,
    dropped_slot_reg: DFF<Bits<SB>>,
    /// The pushing and the popping slot's stack pointer and RAM base.
    push_sp: Signal<Local, Bits<PB>>,
    push_base: Signal<Local, Bits<AB>>,
    pop_sp: Signal<Local, Bits<PB>>,
    pop_base: Signal<Local, Bits<AB>>,
    push_fits: Signal<Local, Bit>,
    pop_finds: Signal<Local, Bit>,
}

impl<const S: usize, const SB: usize, const PB: usize, const AB: usize, const W: usize>
    SlotStacks<S, SB, PB, AB, W>
{
    /// Stacks of `depth` entries.
    pub fn new(depth: usize) -> Self {
        assert!(S <= 1 << SB, "{S} slots need more than {SB} bits");
        assert!(
            depth > 0 && depth < 1 << PB,
            "depth {depth} needs more than {PB} bits"
        );
        assert!(
            S * depth <= 1 << AB,
            "{S}×{depth} entries need more than {AB} bits"
        );
        Self {
            clock: Default::default(),
            push: Default::default(),
            push_slot: Default::default(),
            push_data: Default::default(),
            pop: Default::default(),
            pop_slot: Default::default(),
            clear: Default::default(),
            clear_slot: Default::default(),
            popped: Default::default(),
            empty: Default::default(),
            pop_data: Default::default(),
            overflow: Default::default(),
            overflow_slot: Default::default(),
            dropped: Default::default(),
            dropped_slot: Default::default(),
            sp: (0..S).map(|_| Default::default()).collect(),
            base: (0..S)
                .map(|s| Constant::new(((s * depth) as u64).into()))
                .collect(),
            slot_id: (0..S).map(|s| Constant::new((s as u64).into())).collect(),
            depth: Constant::new((depth as u64).into()),
            ram: Default::default(),
            popped_reg: Default::default(),
            empty_reg: Default::default(),
            overflow_reg: Default::default(),
            overflow_slot_reg: Default::default(),
            dropped_reg: Default::default(),
            dropped_slot_reg: Default::default(),
            push_sp: Default::default(),
            push_base: Default::default(),
            pop_sp: Default::default(),
            pop_base: Default::default(),
            push_fits: Default::default(),
            pop_finds: Default::default(),
        }
    }
}

impl<const S: usize, const SB: usize, const PB: usize, const AB: usize, const W: usize> Logic
    for SlotStacks<S, SB, PB, AB, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();
        clock!(
            self,
            clock,
            popped_reg,
            empty_reg,
            overflow_reg,
            overflow_slot_reg,
            dropped_reg,
            dropped_slot_reg
        );
        // The two slots' pointers and bases (one-of-S selects).
        self.push_sp.next = 0.into();
        self.push_base.next = 0.into();
        self.pop_sp.next = 0.into();
        self.pop_base.next = 0.into();
        for i in 0..S {
            dff_setup!(self, clock, sp[i]);
            if self.push_slot.val() == self.slot_id[i].val() {
                self.push_sp.next = self.sp[i].q.val();
                self.push_base.next = self.base[i].val();
            }
            if self.pop_slot.val() == self.slot_id[i].val() {
                self.pop_sp.next = self.sp[i].q.val();
                self.pop_base.next = self.base[i].val();
            }
        }
        self.push_fits.next = self.push_sp.val() != self.depth.val();
        self.pop_finds.next = self.pop_sp.val().any();
        // Push: write at base + sp, then sp + 1.
        self.ram.write_enable.next = self.push.val() & self.push_fits.val();
        self.ram.write_address.next = self.push_base.val() + bit_cast::<AB, PB>(self.push_sp.val());
        self.ram.write_data.next = self.push_data.val();
        // Pop: read at base + sp − 1 (the RAM answers next cycle), then sp − 1.
        self.ram.read_address.next =
            self.pop_base.val() + bit_cast::<AB, PB>(self.pop_sp.val()) - 1;
        for i in 0..S {
            if self.push.val()
                & self.push_fits.val()
                & (self.push_slot.val() == self.slot_id[i].val())
            {
                self.sp[i].d.next = self.sp[i].q.val() + 1;
            }
            if self.pop.val()
                & self.pop_finds.val()
                & (self.pop_slot.val() == self.slot_id[i].val())
            {
                self.sp[i].d.next = self.sp[i].q.val() - 1;
            }
            if self.clear.val() & (self.clear_slot.val() == self.slot_id[i].val()) {
                self.sp[i].d.next = 0.into();
            }
        }
        self.popped_reg.d.next = self.pop.val() & self.pop_finds.val();
        self.empty_reg.d.next = self.pop.val() & !self.pop_finds.val();
        self.popped.next = self.popped_reg.q.val();
        self.empty.next = self.empty_reg.q.val();
        self.pop_data.next = self.ram.read_data.val();
        self.overflow_reg.d.next = self.overflow_reg.q.val();
        self.overflow_slot_reg.d.next = self.overflow_slot_reg.q.val();
        if self.push.val() & !self.push_fits.val() & !self.overflow_reg.q.val() {
            self.overflow_reg.d.next = true;
            self.overflow_slot_reg.d.next = self.push_slot.val();
        }
        self.dropped_reg.d.next = self.push.val() & !self.push_fits.val();
        self.dropped_slot_reg.d.next = self.push_slot.val();
        self.dropped.next = self.dropped_reg.q.val();
        self.dropped_slot.next = self.dropped_slot_reg.q.val();
        self.overflow.next = self.overflow_reg.q.val();
        self.overflow_slot.next = self.overflow_slot_reg.q.val();
    }
}
