//! The box port for wide nodes: one node test a cycle for the slot the box scheduler grants,
//! in [`WideBoxStage`]. The grant reads the slot's node from the scene memory (a new ray's
//! first test: the root, node 0), the slot's ray words (its origin, kept at its entry; its
//! inv_dir and pad_t, from [`super::wide_set_up::WideSetUp`]) and the slot's entry word: where
//! the walk entered the node (t0 and width exponent; the root: 0, unbounded). The cycle after,
//! the stage's test starts; its answer is a [`LinkStep`] and a push: no child entered → a pop;
//! else the nearest becomes the slot's link and entry word, and the others are pushed onto
//! the slot's stack farthest first in the same cycle (`push_data[0]`, popped first, is the
//! second nearest: [`super::banked_stack::BankedStacks`]).
//!
//! The entry word is written by this port's answers and by the stack port's (a popped entry
//! entered), possibly in one cycle for two slots: two RAMs, one per writer, and a bit per slot
//! saying which holds the slot's word (a live value table).
//!
//! rust-hdl cannot derive widths: `S` slots of `SB` bits, `NB` node address bits, `LF` a
//! link's first, `LK` a link (first and its 4-bit count), `W` = [`ENTRY_BITS`] + LK a stack
//! entry (the entry word in bits 0–41, the link above).

use hw_model::traversal::wide::box_test::WIDTH_UNBOUNDED;
use rust_hdl::prelude::*;

use super::scene_records::WIDE_COUNT_BITS;
use super::slot_ports::{BoxGrant, Entered, LinkStep, SetUp, BOX_WORDS_BITS};
use super::wide::{Code, Count, WideBoxStage, WidthExp};
use super::wide_set_up::WIDE_RAY_BITS;
use crate::macros::{clock, dff_setup};

/// A slot's entry word: t0 (fp32) in bits 0–31, the width exponent in bits 32–41.
pub const ENTRY_BITS: usize = 32 + WidthExp::BITS;

/// `W` of a stack entry of links of `link_bits`: the entry word and the link above it.
pub const fn wide_stack_entry_bits(link_bits: usize) -> usize {
    ENTRY_BITS + link_bits
}

#[derive(LogicBlock)]
pub struct WideBoxPort<
    const S: usize,
    const SB: usize,
    const NB: usize,
    const LF: usize,
    const LK: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    pub grant: BoxGrant<SB, LF>,
    /// A new ray: its origin is kept.
    pub entered: Entered<SB>,
    /// The wide setup's answer: the slot's inv_dir and pad_t.
    pub set_up: SetUp<SB>,
    /// The stack port's pop that entered its entry: the slot's entry word.
    pub popped: Signal<In, Bit>,
    pub popped_slot: Signal<In, Bits<SB>>,
    pub popped_entry: Signal<In, Bits<ENTRY_BITS>>,
    /// The node read: the address at the grant, the node's fields the cycle after.
    pub node_address: Signal<Out, Bits<NB>>,
    pub origin: [Signal<In, Bits<32>>; 3],
    pub exp: [Signal<In, Bits<8>>; 3],
    pub children: Signal<In, Count>,
    pub lo: Vec<Signal<In, Code>>,
    pub hi: Vec<Signal<In, Code>>,
    pub link: Vec<Signal<In, Bits<LK>>>,
    pub step: LinkStep<SB, LF, WIDE_COUNT_BITS>,
    /// The nearest child's width exponent, beside `step.entry` (its t0).
    pub step_width: Signal<Out, WidthExp>,
    /// The push: `push_count` entries (0: none) of `push_slot`, `push_data[j]` popped j-th.
    pub push_count: Signal<Out, Count>,
    pub push_slot: Signal<Out, Bits<SB>>,
    pub push_data: Vec<Signal<Out, Bits<W>>>,
    origins: RAM<Bits<96>, SB>,
    rays: RAM<Bits<WIDE_RAY_BITS>, SB>,
    /// The entry words as this port's answers and the stack port's wrote them, and per slot
    /// whether the stack port's is the live one.
    box_entries: RAM<Bits<ENTRY_BITS>, SB>,
    pop_entries: RAM<Bits<ENTRY_BITS>, SB>,
    from_pop: DFF<Bits<S>>,
    /// The granted slot's state, registered beside the reads.
    valid: DFF<Bit>,
    slot: DFF<Bits<SB>>,
    root: DFF<Bit>,
    t_hi: DFF<Bits<32>>,
    live_pop: DFF<Bit>,
    stage: WideBoxStage<LK>,
    one: Constant<Bits<S>>,
    root_node: Constant<Bits<NB>>,
    unbounded: Constant<WidthExp>,
    at_link: Constant<Bits<8>>,
    at_count: Constant<Bits<8>>,
    /// The entry word the test reads; the answer entered a child.
    entry_read: Signal<Local, Bits<ENTRY_BITS>>,
    takes: Signal<Local, Bit>,
    /// A pushed child's words, one after the other.
    pushed_t0: Signal<Local, Bits<32>>,
    pushed_width: Signal<Local, WidthExp>,
    pushed_link: Signal<Local, Bits<LK>>,
    /// `from_pop` shifted to the granted slot's bit.
    granted_from_pop: Signal<Local, Bits<S>>,
    box_done: Signal<Local, Bits<S>>,
    pop_done: Signal<Local, Bits<S>>,
}

impl<
        const S: usize,
        const SB: usize,
        const NB: usize,
        const LF: usize,
        const LK: usize,
        const W: usize,
    > WideBoxPort<S, SB, NB, LF, LK, W>
{
    /// A port for nodes of `width` children whose stage has `depth` pipeline registers a
    /// block.
    pub fn new(width: usize, depth: usize) -> Self {
        assert_eq!(
            LK,
            LF + WIDE_COUNT_BITS,
            "a wide link is a first and a count"
        );
        assert_eq!(
            W,
            wide_stack_entry_bits(LK),
            "a stack entry is an entry word and a link"
        );
        assert!(S <= 1 << SB, "{S} slots need more than {SB} bits");
        Self {
            clock: Default::default(),
            grant: Default::default(),
            entered: Default::default(),
            set_up: Default::default(),
            popped: Default::default(),
            popped_slot: Default::default(),
            popped_entry: Default::default(),
            node_address: Default::default(),
            origin: Default::default(),
            exp: Default::default(),
            children: Default::default(),
            lo: crate::defaults(3 * width),
            hi: crate::defaults(3 * width),
            link: crate::defaults(width),
            step: Default::default(),
            step_width: Default::default(),
            push_count: Default::default(),
            push_slot: Default::default(),
            push_data: crate::defaults(width - 1),
            origins: Default::default(),
            rays: Default::default(),
            box_entries: Default::default(),
            pop_entries: Default::default(),
            from_pop: Default::default(),
            valid: Default::default(),
            slot: Default::default(),
            root: Default::default(),
            t_hi: Default::default(),
            live_pop: Default::default(),
            stage: WideBoxStage::new(width, depth),
            one: Constant::new(1.into()),
            root_node: Constant::new(0.into()),
            unbounded: Constant::new((WIDTH_UNBOUNDED as u64 & 0x3FF).into()),
            at_link: Constant::new((ENTRY_BITS as u64).into()),
            at_count: Constant::new((LF as u64).into()),
            entry_read: Default::default(),
            takes: Default::default(),
            pushed_t0: Default::default(),
            pushed_width: Default::default(),
            pushed_link: Default::default(),
            granted_from_pop: Default::default(),
            box_done: Default::default(),
            pop_done: Default::default(),
        }
    }

    /// Cycles from a grant to its step: the reads, then the stage.
    pub fn latency(depth: usize) -> usize {
        1 + super::wide::latency(depth)
    }
}

impl<
        const S: usize,
        const SB: usize,
        const NB: usize,
        const LF: usize,
        const LK: usize,
        const W: usize,
    > Logic for WideBoxPort<S, SB, NB, LF, LK, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, stage);
        dff_setup!(self, clock, from_pop, valid, slot, root, t_hi, live_pop);
        self.origins.read_clock.next = self.clock.val();
        self.origins.write_clock.next = self.clock.val();
        self.rays.read_clock.next = self.clock.val();
        self.rays.write_clock.next = self.clock.val();
        self.box_entries.read_clock.next = self.clock.val();
        self.box_entries.write_clock.next = self.clock.val();
        self.pop_entries.read_clock.next = self.clock.val();
        self.pop_entries.write_clock.next = self.clock.val();
        // A slot's ray words: its origin at its entry, inv_dir and pad_t at its setup.
        self.origins.write_enable.next = self.entered.valid.val();
        self.origins.write_address.next = self.entered.slot.val();
        self.origins.write_data.next = self.entered.leaf_words.val().get_bits::<96>(0);
        self.rays.write_enable.next = self.set_up.valid.val();
        self.rays.write_address.next = self.set_up.slot.val();
        self.rays.write_data.next =
            bit_cast::<WIDE_RAY_BITS, BOX_WORDS_BITS>(self.set_up.box_words.val());

        // The grant reads the slot's words, its entry word and its node (the root: node 0) …
        self.node_address.next = bit_cast::<NB, LF>(self.grant.node.val());
        if self.grant.root.val() {
            self.node_address.next = self.root_node.val();
        }
        self.origins.read_address.next = self.grant.slot.val();
        self.rays.read_address.next = self.grant.slot.val();
        self.box_entries.read_address.next = self.grant.slot.val();
        self.pop_entries.read_address.next = self.grant.slot.val();
        self.valid.d.next = self.grant.valid.val();
        self.slot.d.next = self.grant.slot.val();
        self.root.d.next = self.grant.root.val();
        self.t_hi.d.next = self.grant.t_hi.val();
        self.granted_from_pop.next = self.from_pop.q.val() >> self.grant.slot.val();
        self.live_pop.d.next = self.granted_from_pop.val().get_bit(0);
        // … the next cycle the stage's test starts.
        self.entry_read.next = self.box_entries.read_data.val();
        if self.live_pop.q.val() {
            self.entry_read.next = self.pop_entries.read_data.val();
        }
        self.stage.valid_in.next = self.valid.q.val();
        self.stage.tag_in.next = bit_cast::<16, SB>(self.slot.q.val());
        for a in 0..3 {
            self.stage.orig[a].next = self.origins.read_data.val().get_bits::<32>(32 * a);
            self.stage.inv_dir[a].next = self.rays.read_data.val().get_bits::<32>(32 * a);
            self.stage.pad_t[a].next = self.rays.read_data.val().get_bits::<32>(96 + 32 * a);
            self.stage.origin[a].next = self.origin[a].val();
            self.stage.exp[a].next = self.exp[a].val();
        }
        self.stage.t_hi.next = self.t_hi.q.val();
        self.stage.t0.next = self.entry_read.val().get_bits::<32>(0);
        self.stage.width_exp.next = self.entry_read.val().get_bits::<10>(32);
        if self.root.q.val() {
            self.stage.t0.next = 0.into();
            self.stage.width_exp.next = self.unbounded.val();
        }
        self.stage.children.next = self.children.val();
        for i in 0..self.lo.len() {
            self.stage.lo[i].next = self.lo[i].val();
            self.stage.hi[i].next = self.hi[i].val();
        }
        for c in 0..self.link.len() {
            self.stage.link[c].next = self.link[c].val();
        }

        // The answer: the nearest entered child taken, the others pushed; none: a pop.
        self.takes.next = self.stage.entered.val().any();
        self.step.valid.next = self.stage.valid_out.val();
        self.step.slot.next = bit_cast::<SB, 16>(self.stage.tag_out.val());
        self.step.enter.next = self.takes.val();
        self.step.pop.next = !self.takes.val();
        self.step.first.next = bit_cast::<LF, LK>(self.stage.entry_link[0].val());
        self.step.count.next =
            bit_cast::<4, LK>(self.stage.entry_link[0].val() >> self.at_count.val());
        self.step.entry.next = self.stage.entry_t0[0].val();
        self.step_width.next = self.stage.entry_width[0].val();
        self.push_slot.next = self.step.slot.val();
        self.push_count.next = 0.into();
        if self.stage.valid_out.val() & self.takes.val() {
            self.push_count.next = self.stage.entered.val() - 1;
        }
        for j in 0..self.push_data.len() {
            self.pushed_t0.next = self.stage.entry_t0[j + 1].val();
            self.pushed_width.next = self.stage.entry_width[j + 1].val();
            self.pushed_link.next = self.stage.entry_link[j + 1].val();
            self.push_data[j].next = bit_cast::<W, 32>(self.pushed_t0.val())
                | (bit_cast::<W, 10>(self.pushed_width.val()) << 32)
                | (bit_cast::<W, LK>(self.pushed_link.val()) << self.at_link.val());
        }

        // The entry words: this port's answer and a pop's, each into its RAM.
        self.box_entries.write_enable.next = self.stage.valid_out.val() & self.takes.val();
        self.box_entries.write_address.next = self.step.slot.val();
        self.box_entries.write_data.next = bit_cast::<ENTRY_BITS, 32>(self.step.entry.val())
            | (bit_cast::<ENTRY_BITS, 10>(self.step_width.val()) << 32);
        self.pop_entries.write_enable.next = self.popped.val();
        self.pop_entries.write_address.next = self.popped_slot.val();
        self.pop_entries.write_data.next = self.popped_entry.val();
        self.box_done.next = 0.into();
        if self.box_entries.write_enable.val() {
            self.box_done.next = self.one.val() << self.step.slot.val();
        }
        self.pop_done.next = 0.into();
        if self.popped.val() {
            self.pop_done.next = self.one.val() << self.popped_slot.val();
        }
        self.from_pop.d.next = (self.from_pop.q.val() & !self.box_done.val()) | self.pop_done.val();
    }
}
