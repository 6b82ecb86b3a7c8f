//! The ray slots' traversal stacks for wide nodes: a box test of a `K`-wide node pushes up to
//! `K − 1` entries in one cycle, so a slot's stack is spread over `K` banks (entry `i` of a
//! stack in bank `i mod K`, row `i / K`), each a block RAM with one write and one read port.
//! The entries of one push sit at consecutive indices, so each lands in a different bank.
//!
//! A cycle takes one push (of 0 to `K − 1` entries) and one pop, of different slots (a slot
//! waits for each step's answer, so it never pushes and pops at once). `push_data[j]` is the
//! entry popped `j`-th of the push (`push_data[0]` on top): the wide box stage's entered
//! children from the second nearest on, so that they pop nearest first. A pop answers one
//! cycle later: the entry, or `empty` when the stack had none (the ray's walk is over). A
//! push that does not fit whole is dropped whole and raises the sticky `overflow` with the
//! slot, which the unit reports as an error (as the model's `TraversalError::StackOverflow`
//! for a node whose entries do not fit); `clear` empties a slot's stack for its next ray.
//!
//! rust-hdl cannot derive widths: `S` slots addressed by `SB` bits, stack pointers of `PB`
//! bits (depth + K − 1 < 2^PB), bank addresses of `RB` bits (S·⌈D/K⌉ ≤ 2^RB), entries of
//! `W` bits; `K` (a power of two, 2 to 8) and the depth are [`BankedStacks::new`]'s.

use crate::macros::dff_setup;
use rust_hdl::prelude::*;

/// Bits of a push's entry count (up to 7 for 8-wide nodes).
pub type PushCount = Bits<4>;

#[derive(LogicBlock)]
pub struct BankedStacks<
    const S: usize,
    const SB: usize,
    const PB: usize,
    const RB: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Entries pushed onto `push_slot`'s stack (0: no push), `push_data[0 .. push_count]`.
    pub push_count: Signal<In, PushCount>,
    pub push_slot: Signal<In, Bits<SB>>,
    /// `K − 1` entries; entry `j` is popped `j`-th.
    pub push_data: Vec<Signal<In, Bits<W>>>,
    pub pop: Signal<In, Bit>,
    pub pop_slot: Signal<In, Bits<SB>>,
    /// A new ray in `clear_slot`: its stack is emptied (with no push or pop of that slot).
    pub clear: Signal<In, Bit>,
    pub clear_slot: Signal<In, Bits<SB>>,
    /// The cycle after a pop: its entry (`popped`), or `empty`.
    pub popped: Signal<Out, Bit>,
    pub empty: Signal<Out, Bit>,
    pub pop_data: Signal<Out, Bits<W>>,
    /// Sticky: a push did not fit its slot's stack (`overflow_slot`, the first such slot).
    pub overflow: Signal<Out, Bit>,
    pub overflow_slot: Signal<Out, Bits<SB>>,
    /// The cycle after a push did not fit (not sticky): that slot.
    pub dropped: Signal<Out, Bit>,
    pub dropped_slot: Signal<Out, Bits<SB>>,
    sp: Vec<DFF<Bits<PB>>>,
    /// Slot `s`'s first row in every bank.
    base: Vec<Constant<Bits<RB>>>,
    slot_id: Vec<Constant<Bits<SB>>>,
    depth: Constant<Bits<PB>>,
    banks: Vec<RAM<Bits<W>, RB>>,
    /// Bank `b`'s index, `K − 1` (an index's bank bits) and `log2 K` (its row's shift), in
    /// bank address bits (`bit_cast` cannot take a loop index, so the per-bank arithmetic
    /// is in one width).
    bank_id: Vec<Constant<Bits<RB>>>,
    bank_mask: Constant<Bits<RB>>,
    bank_shift: Constant<Bits<RB>>,
    /// The positions `j` of a push's entries after the first (`position[j − 1]` is `j`).
    position: Vec<Constant<Bits<RB>>>,
    /// The bank the last cycle's pop read.
    pop_bank: DFF<Bits<RB>>,
    popped_reg: DFF<Bit>,
    empty_reg: DFF<Bit>,
    overflow_reg: DFF<Bit>,
    overflow_slot_reg: DFF<Bits<SB>>,
    dropped_reg: DFF<Bit>,
    dropped_slot_reg: DFF<Bits<SB>>,
    /// The pushing and the popping slot's stack pointer and first row.
    push_sp: Signal<Local, Bits<PB>>,
    push_base: Signal<Local, Bits<RB>>,
    pop_sp: Signal<Local, Bits<PB>>,
    pop_base: Signal<Local, Bits<RB>>,
    /// The push's count in pointer bits, the pointer after it; the pointer and the count in
    /// bank address bits.
    push_n: Signal<Local, Bits<PB>>,
    push_end: Signal<Local, Bits<PB>>,
    push_sp_wide: Signal<Local, Bits<RB>>,
    push_n_wide: Signal<Local, Bits<RB>>,
    pushes: Signal<Local, Bit>,
    push_fits: Signal<Local, Bit>,
    pop_finds: Signal<Local, Bit>,
    /// The index popped (`sp − 1`).
    popped_index: Signal<Local, Bits<PB>>,
    popped_index_wide: Signal<Local, Bits<RB>>,
    /// Per bank: how far above the pointer the push's index in this bank is, that index, and
    /// which entry of the push (`j`) goes there.
    offset: Vec<Signal<Local, Bits<RB>>>,
    index: Vec<Signal<Local, Bits<RB>>>,
    entry: Vec<Signal<Local, Bits<RB>>>,
}

impl<const S: usize, const SB: usize, const PB: usize, const RB: usize, const W: usize>
    BankedStacks<S, SB, PB, RB, W>
{
    /// Stacks of `depth` entries over `banks` banks (the node width: 2, 4 or 8).
    pub fn new(banks: usize, depth: usize) -> Self {
        assert!(
            banks.is_power_of_two() && (2..=8).contains(&banks),
            "{banks} banks: a banked stack has 2, 4 or 8"
        );
        assert!(S <= 1 << SB, "{S} slots need more than {SB} bits");
        assert!(
            depth > 0 && depth + banks - 1 < 1 << PB && PB >= 4,
            "depth {depth} with pushes of {} needs more than {PB} bits",
            banks - 1
        );
        let rows = depth.div_ceil(banks);
        assert!(
            S * rows <= 1 << RB && RB >= PB,
            "{S}×{rows} rows (and pointers of {PB} bits) need more than {RB} bits"
        );
        let c = |x: usize| Constant::new((x as u64).into());
        let r = |x: usize| Constant::new((x as u64).into());
        Self {
            clock: Default::default(),
            push_count: Default::default(),
            push_slot: Default::default(),
            push_data: crate::defaults(banks - 1),
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
            sp: crate::defaults(S),
            base: (0..S)
                .map(|s| Constant::new(((s * rows) as u64).into()))
                .collect(),
            slot_id: (0..S).map(|s| Constant::new((s as u64).into())).collect(),
            depth: c(depth),
            banks: crate::defaults(banks),
            bank_id: (0..banks).map(r).collect(),
            bank_mask: r(banks - 1),
            bank_shift: r(banks.ilog2() as usize),
            position: (1..banks - 1).map(r).collect(),
            pop_bank: Default::default(),
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
            push_n: Default::default(),
            push_end: Default::default(),
            push_sp_wide: Default::default(),
            push_n_wide: Default::default(),
            pushes: Default::default(),
            push_fits: Default::default(),
            pop_finds: Default::default(),
            popped_index: Default::default(),
            popped_index_wide: Default::default(),
            offset: crate::defaults(banks),
            index: crate::defaults(banks),
            entry: crate::defaults(banks),
        }
    }
}

impl<const S: usize, const SB: usize, const PB: usize, const RB: usize, const W: usize> Logic
    for BankedStacks<S, SB, PB, RB, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, pop_bank, overflow_reg, overflow_slot_reg);
        clock!(
            self,
            clock,
            popped_reg,
            empty_reg,
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
        self.push_n.next = bit_cast::<PB, 4>(self.push_count.val());
        self.push_end.next = self.push_sp.val() + self.push_n.val();
        self.pushes.next = self.push_count.val().any();
        self.push_fits.next = self.push_end.val() <= self.depth.val();
        self.pop_finds.next = self.pop_sp.val().any();
        self.popped_index.next = self.pop_sp.val() - 1;
        self.push_sp_wide.next = bit_cast::<RB, PB>(self.push_sp.val());
        self.push_n_wide.next = bit_cast::<RB, PB>(self.push_n.val());
        self.popped_index_wide.next = bit_cast::<RB, PB>(self.popped_index.val());
        // Push: bank b takes index sp + ((b − sp) mod K) if it is below sp + count: the entry
        // j = count − 1 − offset (the last of the push lands at sp, the first on top).
        for b in 0..self.banks.len() {
            self.banks[b].read_clock.next = self.clock.val();
            self.banks[b].write_clock.next = self.clock.val();
            self.offset[b].next =
                (self.bank_id[b].val() - self.push_sp_wide.val()) & self.bank_mask.val();
            self.index[b].next = self.push_sp_wide.val() + self.offset[b].val();
            self.entry[b].next = self.push_n_wide.val() - 1 - self.offset[b].val();
            self.banks[b].write_enable.next = self.pushes.val()
                & self.push_fits.val()
                & (self.offset[b].val() < self.push_n_wide.val());
            self.banks[b].write_address.next =
                self.push_base.val() + (self.index[b].val() >> self.bank_shift.val());
            self.banks[b].write_data.next = self.push_data[0].val();
            for j in 1..self.push_data.len() {
                if self.entry[b].val() == self.position[j - 1].val() {
                    self.banks[b].write_data.next = self.push_data[j].val();
                }
            }
            // Pop: every bank reads the popped index's row; its bank answers next cycle.
            self.banks[b].read_address.next =
                self.pop_base.val() + (self.popped_index_wide.val() >> self.bank_shift.val());
        }
        self.pop_bank.d.next = self.popped_index_wide.val() & self.bank_mask.val();
        self.pop_data.next = self.banks[0].read_data.val();
        for b in 1..self.banks.len() {
            if self.pop_bank.q.val() == self.bank_id[b].val() {
                self.pop_data.next = self.banks[b].read_data.val();
            }
        }
        for i in 0..S {
            if self.pushes.val()
                & self.push_fits.val()
                & (self.push_slot.val() == self.slot_id[i].val())
            {
                self.sp[i].d.next = self.push_end.val();
            }
            if self.pop.val()
                & self.pop_finds.val()
                & (self.pop_slot.val() == self.slot_id[i].val())
            {
                self.sp[i].d.next = self.popped_index.val();
            }
            if self.clear.val() & (self.clear_slot.val() == self.slot_id[i].val()) {
                self.sp[i].d.next = 0.into();
            }
        }
        self.popped_reg.d.next = self.pop.val() & self.pop_finds.val();
        self.empty_reg.d.next = self.pop.val() & !self.pop_finds.val();
        self.popped.next = self.popped_reg.q.val();
        self.empty.next = self.empty_reg.q.val();
        if self.pushes.val() & !self.push_fits.val() & !self.overflow_reg.q.val() {
            self.overflow_reg.d.next = true;
            self.overflow_slot_reg.d.next = self.push_slot.val();
        }
        self.dropped_reg.d.next = self.pushes.val() & !self.push_fits.val();
        self.dropped_slot_reg.d.next = self.push_slot.val();
        self.dropped.next = self.dropped_reg.q.val();
        self.dropped_slot.next = self.dropped_slot_reg.q.val();
        self.overflow.next = self.overflow_reg.q.val();
        self.overflow_slot.next = self.overflow_slot_reg.q.val();
    }
}
