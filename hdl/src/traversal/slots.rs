//! The ray slots: their state, the schedulers that grant them to the unit's ports, and the
//! next-state logic that applies the ports' answers.
//!
//! A slot is in one of five states, kept as one bit vector each (a slot's bit set in at most
//! one; none set while it waits for an answer): `busy` (holds a ray), `want_box`,
//! `want_leaf`, `want_pop`, `want_out`. Round-robin schedulers ([`RoundRobin`], a block of
//! its own each) grant one slot a cycle to the box port, to each lane's leaf port (over that
//! lane's slots: slot s belongs to lane s mod lanes), to the stack port and to the hit
//! output; each grant goes out with the slot's words its port reads ([`super::slot_ports`]).
//! The ports answer with steps, each for a slot in a state of its own, so writers never
//! collide; with several lanes the leaf ports' steps are for slots of different lanes.
//!
//! The words a slot's ports write while others read them stay here, in LUT RAM
//! ([`super::slot_banks`]: a bank per writer and reader, and a live-value table in flip-flops
//! saying which writer wrote a slot last): the far end `t_hi` (written by the setup and by
//! each lane's far end, possibly in one cycle; read at the box and pop grants), the current
//! link (written by the box step, the pop step and each lane's leaf grant, which advances it;
//! read at the box and leaf grants) and, with the leaf advance, the link's entry distance
//! (written by the box and pop steps, read at the leaf grants). They are read asynchronously
//! at the grant's slot and written at the edge, as flip-flops would be.

use rust_hdl::prelude::*;

use super::arbiter::RoundRobin;
use super::config::MAX_LANES;
use super::live_table::LiveTable;
use super::slot_banks::SlotBanks;
use super::slot_ports::{
    BoxGrantSource, Entered, LeafGrantSource, LeafStepSink, LinkStepSink, OutGrantSource,
    PopGrantSource, SetUp,
};
use crate::defaults;
use crate::macros::{clock, dff_setup};

/// `S` slots addressed by `SB` bits; links of `LF`, `LC` bits (first, count).
#[derive(LogicBlock)]
pub struct SlotState<const S: usize, const SB: usize, const LF: usize, const LC: usize> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    /// The loaded scene has triangles (else a set-up ray is answered a miss at once).
    pub has_triangles: Signal<In, Bit>,
    /// A slot is free, and the lowest free one: where the next ray enters.
    pub free: Signal<Out, Bit>,
    pub enter_slot: Signal<Out, Bits<SB>>,
    /// A slot holds a ray.
    pub occupied: Signal<Out, Bit>,
    pub entered: Entered<SB>,
    pub set_up: SetUp<SB>,
    pub box_grant: BoxGrantSource<SB, LF>,
    pub box_step: LinkStepSink<SB, LF, LC>,
    pub pop_grant: PopGrantSource<SB>,
    pub pop_step: LinkStepSink<SB, LF, LC>,
    /// Per lane: its leaf port's grants and steps.
    pub leaf_grant: Vec<LeafGrantSource<SB, LF>>,
    pub leaf_step: Vec<LeafStepSink<SB>>,
    pub out_grant: OutGrantSource<SB>,
    /// With the leaf advance (else none): per lane, the entry distance of the granted
    /// slot's link, the cycle after the grant (beside the lane's query).
    pub lane_entry: Vec<Signal<Out, Bits<32>>>,
    box_arb: RoundRobin<S>,
    pop_arb: RoundRobin<S>,
    out_arb: RoundRobin<S>,
    leaf_arb: Vec<RoundRobin<S>>,
    /// The slots of each lane.
    lane_slots: Vec<Constant<Bits<S>>>,
    /// Each lane's bit in `out_grant.lane`.
    lane_bit: Vec<Constant<Bits<MAX_LANES>>>,
    // The slots' states (bit i: slot i).
    busy: DFF<Bits<S>>,
    want_box: DFF<Bits<S>>,
    want_leaf: DFF<Bits<S>>,
    want_pop: DFF<Bits<S>>,
    want_out: DFF<Bits<S>>,
    /// The next box test is the root's box.
    at_root: DFF<Bits<S>>,
    any_hit: DFF<Bits<S>>,
    has_exclude: DFF<Bits<S>>,
    best_valid: DFF<Bits<S>>,
    /// The nearest hit changed during the current leaf.
    changed: DFF<Bits<S>>,
    // The slots' words in LUT RAM, each with the table of its writers (`…_live`).
    /// The far end: written by the setup (writer 0) and each lane's far end (1 + lane); read
    /// by the box (reader 0) and pop (1) grants.
    t_hi_live: LiveTable<S>,
    t_hi: SlotBanks<SB, 32>,
    /// The current link, a node or the leaf's next triangle and how many are left: written by
    /// the box step (writer 0), the pop step (1) and each lane's leaf grant (2 + lane); its
    /// first read by the box grant (reader 0) and each lane's (1 + lane), its count by each
    /// lane's (lane).
    link_live: LiveTable<S>,
    link_first: SlotBanks<SB, LF>,
    link_count: SlotBanks<SB, LC>,
    /// With the leaf advance (else no readers, so nothing is built): where the box test
    /// entered the current link (the box answer's `near`, a popped entry's distance), the
    /// model's `entry`, written by the box (writer 0) and pop (1) steps and read by each
    /// lane's grant; and per lane the granted slot's, registered at the grant.
    entry_live: LiveTable<S>,
    link_entry: SlotBanks<SB, 32>,
    leaf_entry: Vec<DFF<Bits<32>>>,
    slot_id: Vec<Constant<Bits<SB>>>,
    one: Constant<Bits<S>>,
    one_count: Constant<Bits<LC>>,
    free_slots: Signal<Local, Bits<S>>,
    /// The lowest free slot, and the same once a ray is taken into it.
    enter: Signal<Local, Bits<S>>,
    entering: Signal<Local, Bits<S>>,
    /// The answers' slots, one-hot.
    setup_done: Signal<Local, Bits<S>>,
    box_done: Signal<Local, Bits<S>>,
    pop_done: Signal<Local, Bits<S>>,
    /// A box or pop step enters a link (writes the slot's link).
    box_enters: Signal<Local, Bit>,
    pop_enters: Signal<Local, Bit>,
    /// Per lane: its answer's slot and its far end's slot.
    lane_done: Vec<Signal<Local, Bits<S>>>,
    far_done: Vec<Signal<Local, Bits<S>>>,
    /// Every lane's far ends.
    far_done_all: Signal<Local, Bits<S>>,
    next_busy: Signal<Local, Bits<S>>,
    next_box: Signal<Local, Bits<S>>,
    next_leaf: Signal<Local, Bits<S>>,
    next_pop: Signal<Local, Bits<S>>,
    next_out: Signal<Local, Bits<S>>,
    next_changed: Signal<Local, Bits<S>>,
    next_best_valid: Signal<Local, Bits<S>>,
}

impl<const S: usize, const SB: usize, const LF: usize, const LC: usize> SlotState<S, SB, LF, LC> {
    /// The slots of `lanes` lanes; with `entries`, each keeps its link's entry distance for
    /// the leaf advance (`lane_entry`), else none of that logic is built.
    pub fn new(lanes: usize, entries: bool) -> Self {
        assert!(
            S <= 1 << SB && S <= 1 << 16,
            "{S} slots need more than {SB} bits"
        );
        assert!(
            (1..=S.min(MAX_LANES)).contains(&lanes),
            "{lanes} lanes for {S} slots: 1 to {}",
            S.min(MAX_LANES)
        );
        let lane_mask = |l: usize| (l..S).step_by(lanes).fold(0u64, |m, s| m | 1 << s);
        let entry_lanes = if entries { lanes } else { 0 };
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            has_triangles: Default::default(),
            free: Default::default(),
            enter_slot: Default::default(),
            occupied: Default::default(),
            entered: Default::default(),
            set_up: Default::default(),
            box_grant: Default::default(),
            box_step: Default::default(),
            pop_grant: Default::default(),
            pop_step: Default::default(),
            leaf_grant: defaults(lanes),
            leaf_step: defaults(lanes),
            out_grant: Default::default(),
            lane_entry: defaults(entry_lanes),
            box_arb: Default::default(),
            pop_arb: Default::default(),
            out_arb: Default::default(),
            leaf_arb: defaults(lanes),
            lane_slots: (0..lanes)
                .map(|l| Constant::new(lane_mask(l).into()))
                .collect(),
            lane_bit: (0..lanes)
                .map(|l| Constant::new((1u64 << l).into()))
                .collect(),
            busy: Default::default(),
            want_box: Default::default(),
            want_leaf: Default::default(),
            want_pop: Default::default(),
            want_out: Default::default(),
            at_root: Default::default(),
            any_hit: Default::default(),
            has_exclude: Default::default(),
            best_valid: Default::default(),
            changed: Default::default(),
            t_hi_live: LiveTable::new(1 + lanes, 2),
            t_hi: SlotBanks::new(1 + lanes, 2),
            link_live: LiveTable::new(2 + lanes, 1 + lanes),
            link_first: SlotBanks::new(2 + lanes, 1 + lanes),
            link_count: SlotBanks::new(2 + lanes, lanes),
            entry_live: LiveTable::new(2, entry_lanes),
            link_entry: SlotBanks::new(2, entry_lanes),
            leaf_entry: defaults(entry_lanes),
            slot_id: (0..S).map(|s| Constant::new((s as u64).into())).collect(),
            one: Constant::new(1.into()),
            one_count: Constant::new(1.into()),
            free_slots: Default::default(),
            enter: Default::default(),
            entering: Default::default(),
            setup_done: Default::default(),
            box_done: Default::default(),
            pop_done: Default::default(),
            box_enters: Default::default(),
            pop_enters: Default::default(),
            lane_done: defaults(lanes),
            far_done: defaults(lanes),
            far_done_all: Default::default(),
            next_busy: Default::default(),
            next_box: Default::default(),
            next_leaf: Default::default(),
            next_pop: Default::default(),
            next_out: Default::default(),
            next_changed: Default::default(),
            next_best_valid: Default::default(),
        }
    }
}

impl<const S: usize, const SB: usize, const LF: usize, const LC: usize> Logic
    for SlotState<S, SB, LF, LC>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, box_arb, pop_arb, out_arb);
        dff_setup!(
            self,
            clock,
            busy,
            want_box,
            want_leaf,
            want_pop,
            want_out,
            at_root,
            any_hit,
            has_exclude,
            best_valid,
            changed
        );
        clock!(
            self, clock, t_hi_live, t_hi, link_live, link_first, link_count, entry_live, link_entry
        );
        for l in 0..self.leaf_arb.len() {
            clock!(self, clock, leaf_arb[l]);
        }
        for l in 0..self.leaf_entry.len() {
            dff_setup!(self, clock, leaf_entry[l]);
        }

        // ---- Where a ray enters: the lowest free slot (x & −x).
        self.free_slots.next = !self.busy.q.val();
        self.enter.next = self.free_slots.val() & (!self.free_slots.val() + self.one.val());
        self.free.next = self.free_slots.val().any();
        self.occupied.next = self.busy.q.val().any();
        self.entering.next = 0.into();
        if self.entered.valid.val() {
            self.entering.next = self.enter.val();
        }

        // ---- The schedulers, and what each port reads of its granted slot.
        self.box_arb.request.next = self.want_box.q.val();
        self.pop_arb.request.next = self.want_pop.q.val();
        self.out_arb.request.next = 0.into();
        if self.out_grant.ready.val() {
            self.out_arb.request.next = self.want_out.q.val();
        }
        self.box_grant.valid.next = self.box_arb.grant.val().any();
        self.box_grant.root.next = (self.at_root.q.val() & self.box_arb.grant.val()).any();
        self.pop_grant.valid.next = self.pop_arb.grant.val().any();
        self.out_grant.valid.next = self.out_arb.grant.val().any();
        self.out_grant.hit.next = (self.best_valid.q.val() & self.out_arb.grant.val()).any();
        self.out_grant.lane.next = 0.into();
        for l in 0..self.leaf_arb.len() {
            self.leaf_arb[l].request.next = self.want_leaf.q.val() & self.lane_slots[l].val();
            self.leaf_grant[l].valid.next = self.leaf_arb[l].grant.val().any();
            self.leaf_grant[l].any_hit.next =
                (self.any_hit.q.val() & self.leaf_arb[l].grant.val()).any();
            self.leaf_grant[l].has_exclude.next =
                (self.has_exclude.q.val() & self.leaf_arb[l].grant.val()).any();
            if (self.out_arb.grant.val() & self.lane_slots[l].val()).any() {
                self.out_grant.lane.next = self.lane_bit[l].val();
            }
            self.leaf_grant[l].slot.next = 0.into();
            self.leaf_grant[l].triangle.next = 0.into();
            self.leaf_grant[l].last.next = false;
        }
        self.enter_slot.next = 0.into();
        self.box_grant.slot.next = 0.into();
        self.pop_grant.slot.next = 0.into();
        self.out_grant.slot.next = 0.into();
        // The grants' slot indices (one-hot to binary).
        for i in 0..S {
            if self.enter.val().get_bit(i) {
                self.enter_slot.next = self.slot_id[i].val();
            }
            if self.box_arb.grant.val().get_bit(i) {
                self.box_grant.slot.next = self.slot_id[i].val();
            }
            if self.pop_arb.grant.val().get_bit(i) {
                self.pop_grant.slot.next = self.slot_id[i].val();
            }
            if self.out_arb.grant.val().get_bit(i) {
                self.out_grant.slot.next = self.slot_id[i].val();
            }
            for l in 0..self.leaf_arb.len() {
                if self.leaf_arb[l].grant.val().get_bit(i) {
                    self.leaf_grant[l].slot.next = self.slot_id[i].val();
                }
            }
        }
        // Each port's grant reads its slot's words: the banks at the index, their table at
        // the one-hot grant.
        self.t_hi_live.read_select[0].next = self.box_arb.grant.val();
        self.t_hi.read_slot[0].next = self.box_grant.slot.val();
        self.t_hi.live[0].next = self.t_hi_live.live[0].val();
        self.t_hi_live.read_select[1].next = self.pop_arb.grant.val();
        self.t_hi.read_slot[1].next = self.pop_grant.slot.val();
        self.t_hi.live[1].next = self.t_hi_live.live[1].val();
        self.link_live.read_select[0].next = self.box_arb.grant.val();
        self.link_first.read_slot[0].next = self.box_grant.slot.val();
        self.link_first.live[0].next = self.link_live.live[0].val();
        self.box_grant.t_hi.next = 0.into();
        self.box_grant.node.next = 0.into();
        if self.box_grant.valid.val() {
            self.box_grant.t_hi.next = self.t_hi.read_data[0].val();
            self.box_grant.node.next = self.link_first.read_data[0].val();
        }
        self.pop_grant.t_hi.next = 0.into();
        if self.pop_grant.valid.val() {
            self.pop_grant.t_hi.next = self.t_hi.read_data[1].val();
        }
        for l in 0..self.leaf_arb.len() {
            self.link_live.read_select[l + 1].next = self.leaf_arb[l].grant.val();
            self.link_first.read_slot[l + 1].next = self.leaf_grant[l].slot.val();
            self.link_first.live[l + 1].next = self.link_live.live[l + 1].val();
            self.link_count.read_slot[l].next = self.leaf_grant[l].slot.val();
            self.link_count.live[l].next = self.link_live.live[l + 1].val();
            if self.leaf_grant[l].valid.val() {
                self.leaf_grant[l].triangle.next = self.link_first.read_data[l + 1].val();
                self.leaf_grant[l].last.next =
                    self.link_count.read_data[l].val() == self.one_count.val();
            }
        }
        for l in 0..self.leaf_entry.len() {
            self.entry_live.read_select[l].next = self.leaf_arb[l].grant.val();
            self.link_entry.read_slot[l].next = self.leaf_grant[l].slot.val();
            self.link_entry.live[l].next = self.entry_live.live[l].val();
        }

        // ---- The answers' slots, and the flags a lane's answer is judged by.
        self.setup_done.next = 0.into();
        if self.set_up.valid.val() {
            self.setup_done.next = self.one.val() << self.set_up.slot.val();
        }
        self.box_done.next = 0.into();
        if self.box_step.valid.val() {
            self.box_done.next = self.one.val() << self.box_step.slot.val();
        }
        self.pop_done.next = 0.into();
        if self.pop_step.valid.val() {
            self.pop_done.next = self.one.val() << self.pop_step.slot.val();
        }
        self.far_done_all.next = 0.into();
        for l in 0..self.leaf_step.len() {
            self.lane_done[l].next = 0.into();
            if self.leaf_step[l].valid.val() {
                self.lane_done[l].next = self.one.val() << self.leaf_step[l].slot.val();
            }
            self.far_done[l].next = 0.into();
            if self.leaf_step[l].far_valid.val() {
                self.far_done[l].next = self.one.val() << self.leaf_step[l].far_slot.val();
            }
            self.far_done_all.next = self.far_done_all.val() | self.far_done[l].val();
            self.leaf_step[l].best_valid.next =
                (self.best_valid.q.val() & self.lane_done[l].val()).any();
            self.leaf_step[l].changed.next = (self.changed.q.val() & self.lane_done[l].val()).any();
        }

        // ---- The slots' states: each writer targets slots in its own state.
        self.next_busy.next = (self.busy.q.val() & !self.out_arb.grant.val()) | self.entering.val();
        self.next_box.next = self.want_box.q.val() & !self.box_arb.grant.val();
        self.next_leaf.next = self.want_leaf.q.val();
        for l in 0..self.leaf_arb.len() {
            if self.leaf_grant[l].last.val() {
                self.next_leaf.next = self.next_leaf.val() & !self.leaf_arb[l].grant.val();
            }
        }
        self.next_pop.next =
            (self.want_pop.q.val() & !self.pop_arb.grant.val()) | self.far_done_all.val();
        self.next_out.next = self.want_out.q.val() & !self.out_arb.grant.val();
        self.next_changed.next = self.changed.q.val() & !self.entering.val();
        self.next_best_valid.next = self.best_valid.q.val() & !self.entering.val();
        // A set-up ray tests the root's box; an empty scene answers a miss at once.
        if self.has_triangles.val() {
            self.next_box.next = self.next_box.val() | self.setup_done.val();
        } else {
            self.next_out.next = self.next_out.val() | self.setup_done.val();
        }
        // A link step: a node or a leaf entered, else a pop or the end.
        if self.box_step.enter.val() {
            if self.box_step.count.val().any() {
                self.next_leaf.next = self.next_leaf.val() | self.box_done.val();
            } else {
                self.next_box.next = self.next_box.val() | self.box_done.val();
            }
        } else if self.box_step.pop.val() {
            self.next_pop.next = self.next_pop.val() | self.box_done.val();
        } else {
            self.next_out.next = self.next_out.val() | self.box_done.val();
        }
        if self.pop_step.enter.val() {
            if self.pop_step.count.val().any() {
                self.next_leaf.next = self.next_leaf.val() | self.pop_done.val();
            } else {
                self.next_box.next = self.next_box.val() | self.pop_done.val();
            }
        } else if self.pop_step.pop.val() {
            self.next_pop.next = self.next_pop.val() | self.pop_done.val();
        } else {
            self.next_out.next = self.next_out.val() | self.pop_done.val();
        }
        // The lanes' answers (each for a slot of its own).
        for l in 0..self.leaf_step.len() {
            if self.leaf_step[l].take.val() {
                self.next_best_valid.next = self.next_best_valid.val() | self.lane_done[l].val();
            }
            if self.leaf_step[l].nearer.val() {
                self.next_changed.next = self.next_changed.val() | self.lane_done[l].val();
            }
            if self.leaf_step[l].last.val() {
                self.next_changed.next = self.next_changed.val() & !self.lane_done[l].val();
                if self.leaf_step[l].out.val() {
                    self.next_out.next = self.next_out.val() | self.lane_done[l].val();
                } else if self.leaf_step[l].pop.val() {
                    self.next_pop.next = self.next_pop.val() | self.lane_done[l].val();
                }
            }
        }
        self.busy.d.next = self.next_busy.val();
        self.want_box.d.next = self.next_box.val();
        self.want_leaf.d.next = self.next_leaf.val();
        self.want_pop.d.next = self.next_pop.val();
        self.want_out.d.next = self.next_out.val();
        self.changed.d.next = self.next_changed.val();
        self.best_valid.d.next = self.next_best_valid.val();
        self.at_root.d.next = (self.at_root.q.val() & !self.box_done.val()) | self.entering.val();
        // The entering slot takes the ray's flags; the others keep theirs. (Written without
        // reading `.d` back: rust-hdl's simulator returns its previous settled value there.)
        if self.entered.any_hit.val() {
            self.any_hit.d.next = self.any_hit.q.val() | self.entering.val();
        } else {
            self.any_hit.d.next = self.any_hit.q.val() & !self.entering.val();
        }
        if self.entered.has_exclude.val() {
            self.has_exclude.d.next = self.has_exclude.q.val() | self.entering.val();
        } else {
            self.has_exclude.d.next = self.has_exclude.q.val() & !self.entering.val();
        }

        // ---- The slots' words, written at the edge (each writer its slot, one-hot too).
        self.t_hi_live.write_enable[0].next = self.set_up.valid.val();
        self.t_hi_live.write_select[0].next = self.setup_done.val();
        self.t_hi.write_enable[0].next = self.set_up.valid.val();
        self.t_hi.write_slot[0].next = self.set_up.slot.val();
        self.t_hi.write_data[0].next = self.set_up.t_hi.val();
        for l in 0..self.leaf_step.len() {
            self.t_hi_live.write_enable[l + 1].next = self.leaf_step[l].far_valid.val();
            self.t_hi_live.write_select[l + 1].next = self.far_done[l].val();
            self.t_hi.write_enable[l + 1].next = self.leaf_step[l].far_valid.val();
            self.t_hi.write_slot[l + 1].next = self.leaf_step[l].far_slot.val();
            self.t_hi.write_data[l + 1].next = self.leaf_step[l].t_hi.val();
        }
        // A link entered by a box or pop step; a leaf grant advances its lane's slot's link.
        self.box_enters.next = self.box_step.valid.val() & self.box_step.enter.val();
        self.link_live.write_enable[0].next = self.box_enters.val();
        self.link_live.write_select[0].next = self.box_done.val();
        self.link_first.write_enable[0].next = self.box_enters.val();
        self.link_first.write_slot[0].next = self.box_step.slot.val();
        self.link_first.write_data[0].next = self.box_step.first.val();
        self.link_count.write_enable[0].next = self.box_enters.val();
        self.link_count.write_slot[0].next = self.box_step.slot.val();
        self.link_count.write_data[0].next = self.box_step.count.val();
        self.pop_enters.next = self.pop_step.valid.val() & self.pop_step.enter.val();
        self.link_live.write_enable[1].next = self.pop_enters.val();
        self.link_live.write_select[1].next = self.pop_done.val();
        self.link_first.write_enable[1].next = self.pop_enters.val();
        self.link_first.write_slot[1].next = self.pop_step.slot.val();
        self.link_first.write_data[1].next = self.pop_step.first.val();
        self.link_count.write_enable[1].next = self.pop_enters.val();
        self.link_count.write_slot[1].next = self.pop_step.slot.val();
        self.link_count.write_data[1].next = self.pop_step.count.val();
        for l in 0..self.leaf_arb.len() {
            self.link_live.write_enable[l + 2].next = self.leaf_grant[l].valid.val();
            self.link_live.write_select[l + 2].next = self.leaf_arb[l].grant.val();
            self.link_first.write_enable[l + 2].next = self.leaf_grant[l].valid.val();
            self.link_first.write_slot[l + 2].next = self.leaf_grant[l].slot.val();
            self.link_first.write_data[l + 2].next = self.link_first.read_data[l + 1].val() + 1;
            self.link_count.write_enable[l + 2].next = self.leaf_grant[l].valid.val();
            self.link_count.write_slot[l + 2].next = self.leaf_grant[l].slot.val();
            self.link_count.write_data[l + 2].next = self.link_count.read_data[l].val() - 1;
        }
        // The leaf advance's entry distances (no readers, so none, without it).
        self.entry_live.write_enable[0].next = self.box_enters.val();
        self.entry_live.write_select[0].next = self.box_done.val();
        self.link_entry.write_enable[0].next = self.box_enters.val();
        self.link_entry.write_slot[0].next = self.box_step.slot.val();
        self.link_entry.write_data[0].next = self.box_step.entry.val();
        self.entry_live.write_enable[1].next = self.pop_enters.val();
        self.entry_live.write_select[1].next = self.pop_done.val();
        self.link_entry.write_enable[1].next = self.pop_enters.val();
        self.link_entry.write_slot[1].next = self.pop_step.slot.val();
        self.link_entry.write_data[1].next = self.pop_step.entry.val();
        for l in 0..self.leaf_entry.len() {
            if self.leaf_grant[l].valid.val() {
                self.leaf_entry[l].d.next = self.link_entry.read_data[l].val();
            }
            self.lane_entry[l].next = self.leaf_entry[l].q.val();
        }

        if !self.reset_n.val() {
            self.busy.d.next = 0.into();
            self.want_box.d.next = 0.into();
            self.want_leaf.d.next = 0.into();
            self.want_pop.d.next = 0.into();
            self.want_out.d.next = 0.into();
        }
    }
}
