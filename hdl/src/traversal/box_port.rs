//! The box port: one box test a cycle for the slot the box scheduler grants. The grant reads
//! the slot's node from the scene memory (a new ray's first test: the root's box) and its
//! box-test words from a slot RAM; the cycle after, the test of both children starts
//! ([`BoxTest`], II = 1), the children's links travelling beside it; its answer is a
//! [`LinkStep`]: the nearer entered child taken, the farther pushed onto the slot's stack
//! with its entry distance ([`Push`]) when both are entered, else a pop (for the root's box:
//! the end of the walk).
//!
//! The seam to the rest of the unit is [`BoxGrant`] in, [`LinkStep`] and [`Push`] out (and
//! the node read): a box port of another tree (more children a beat) answers the same steps.
//!
//! rust-hdl cannot derive widths: `SB` slot bits, `NB` node address bits, `LF`, `LC` link
//! widths, `W` = LF + LC + 32 a stack entry (a link and its entry distance).

use rust_hdl::prelude::*;

use super::box_test::BoxTest;
use super::slot_ports::{BoxGrant, LinkStep, Push, SetUp, BOX_WORDS_BITS};
use crate::macros::clock;
use crate::mt::delay::Delay;

#[derive(LogicBlock)]
pub struct BoxPort<
    const SB: usize,
    const NB: usize,
    const LF: usize,
    const LC: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    pub grant: BoxGrant<SB, LF>,
    /// A set-up ray's box-test words, written into the slot RAM.
    pub set_up: SetUp<SB>,
    /// The node read: the address at the grant, the node's children (boxes and links) and
    /// the root's box and link the cycle after (`scene_memory::SceneMemory`'s read port).
    pub node_address: Signal<Out, Bits<NB>>,
    pub min: [Signal<In, Bits<32>>; 6],
    pub max: [Signal<In, Bits<32>>; 6],
    pub child_first: [Signal<In, Bits<LF>>; 2],
    pub child_count: [Signal<In, Bits<LC>>; 2],
    pub root_min: [Signal<In, Bits<32>>; 3],
    pub root_max: [Signal<In, Bits<32>>; 3],
    pub root_first: Signal<In, Bits<LF>>,
    pub root_count: Signal<In, Bits<LC>>,
    pub step: LinkStep<SB, LF, LC>,
    pub push: Push<SB, W>,
    /// The slots' box-test words, read at the grant.
    words: RAM<Bits<BOX_WORDS_BITS>, SB>,
    /// The granted slot's state, registered beside the node and word reads.
    valid: DFF<Bit>,
    slot: DFF<Bits<SB>>,
    root: DFF<Bit>,
    t_hi: DFF<Bits<32>>,
    boxes: BoxTest,
    /// The node's child links and the root flag travel beside the box test.
    child_first_at: [Delay<Bits<LF>>; 2],
    child_count_at: [Delay<Bits<LC>>; 2],
    root_at: Delay<Bit>,
    /// A stack entry: the distance in bits 0–31, the count at 32, the first at `at_first`.
    at_first: Constant<Bits<8>>,
    /// The child taken: child 1 (else child 0).
    take_second: Signal<Local, Bit>,
}

impl<const SB: usize, const NB: usize, const LF: usize, const LC: usize, const W: usize>
    BoxPort<SB, NB, LF, LC, W>
{
    /// A port whose operators have `depth` pipeline registers each.
    pub fn new(depth: usize) -> Self {
        assert_eq!(W, LF + LC + 32, "a stack entry is a link and a distance");
        let latency = super::box_test::latency(depth);
        Self {
            clock: Default::default(),
            grant: Default::default(),
            set_up: Default::default(),
            node_address: Default::default(),
            min: Default::default(),
            max: Default::default(),
            child_first: Default::default(),
            child_count: Default::default(),
            root_min: Default::default(),
            root_max: Default::default(),
            root_first: Default::default(),
            root_count: Default::default(),
            step: Default::default(),
            push: Default::default(),
            words: Default::default(),
            valid: Default::default(),
            slot: Default::default(),
            root: Default::default(),
            t_hi: Default::default(),
            boxes: BoxTest::new(depth),
            child_first_at: Delay::lines(latency),
            child_count_at: Delay::lines(latency),
            root_at: Delay::new(latency),
            at_first: Constant::new(((LC + 32) as u64).into()),
            take_second: Default::default(),
        }
    }
}

impl<const SB: usize, const NB: usize, const LF: usize, const LC: usize, const W: usize> Logic
    for BoxPort<SB, NB, LF, LC, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, boxes, root_at);
        for c in 0..2 {
            clock!(self, clock, child_first_at[c], child_count_at[c]);
        }
        dff_setup!(self, clock, valid, slot, root, t_hi);
        self.words.read_clock.next = self.clock.val();
        self.words.write_clock.next = self.clock.val();
        self.words.write_enable.next = self.set_up.valid.val();
        self.words.write_address.next = self.set_up.slot.val();
        self.words.write_data.next = self.set_up.box_words.val();

        // The grant reads the slot's words and its node …
        self.node_address.next = bit_cast::<NB, LF>(self.grant.node.val());
        self.words.read_address.next = self.grant.slot.val();
        self.valid.d.next = self.grant.valid.val();
        self.slot.d.next = self.grant.slot.val();
        self.root.d.next = self.grant.root.val();
        self.t_hi.d.next = self.grant.t_hi.val();
        // … the next cycle the test starts (a new ray's first test is the root's box) …
        self.boxes.valid_in.next = self.valid.q.val();
        self.boxes.tag_in.next = bit_cast::<16, SB>(self.slot.q.val());
        for k in 0..3 {
            self.boxes.orig_lo[k].next = self.words.read_data.val().get_bits::<32>(32 * k);
            self.boxes.orig_hi[k].next = self.words.read_data.val().get_bits::<32>(32 * (3 + k));
            self.boxes.inv_dir[k].next = self.words.read_data.val().get_bits::<32>(32 * (6 + k));
        }
        self.boxes.t_hi.next = self.t_hi.q.val();
        for j in 0..6 {
            self.boxes.min[j].next = self.min[j].val();
            self.boxes.max[j].next = self.max[j].val();
        }
        if self.root.q.val() {
            for j in 0..6 {
                self.boxes.min[j].next = self.root_min[j / 2].val();
                self.boxes.max[j].next = self.root_max[j / 2].val();
            }
        }
        for c in 0..2 {
            self.child_first_at[c].d.next = self.child_first[c].val();
            self.child_count_at[c].d.next = self.child_count[c].val();
        }
        self.root_at.d.next = self.root.q.val();

        // … and its answer picks the next link: the nearer entered child, the farther
        // pushed when both are entered (`first`: child 1 is nearer).
        self.step.valid.next = self.boxes.valid_out.val();
        self.step.slot.next = bit_cast::<SB, 16>(self.boxes.tag_out.val());
        self.take_second.next =
            !self.boxes.enters[0].val() | (self.boxes.enters[1].val() & self.boxes.first.val());
        self.step.enter.next = self.boxes.enters[0].val() | self.boxes.enters[1].val();
        self.step.first.next = self.child_first_at[0].q.val();
        self.step.count.next = self.child_count_at[0].q.val();
        self.step.entry.next = self.boxes.near[0].val();
        self.push.data.next = (bit_cast::<W, LF>(self.child_first_at[1].q.val())
            << self.at_first.val())
            | (bit_cast::<W, LC>(self.child_count_at[1].q.val()) << 32)
            | bit_cast::<W, 32>(self.boxes.near[1].val());
        if self.take_second.val() {
            self.step.first.next = self.child_first_at[1].q.val();
            self.step.count.next = self.child_count_at[1].q.val();
            self.step.entry.next = self.boxes.near[1].val();
            self.push.data.next = (bit_cast::<W, LF>(self.child_first_at[0].q.val())
                << self.at_first.val())
                | (bit_cast::<W, LC>(self.child_count_at[0].q.val()) << 32)
                | bit_cast::<W, 32>(self.boxes.near[0].val());
        }
        // The root's box: its one link, entered or the end of the walk.
        if self.root_at.q.val() {
            self.step.enter.next = self.boxes.enters[0].val();
            self.step.first.next = self.root_first.val();
            self.step.count.next = self.root_count.val();
            self.step.entry.next = self.boxes.near[0].val();
        }
        self.step.pop.next = !self.step.enter.val() & !self.root_at.q.val();
        self.push.valid.next = self.boxes.valid_out.val()
            & !self.root_at.q.val()
            & self.boxes.enters[0].val()
            & self.boxes.enters[1].val();
        self.push.slot.next = self.step.slot.val();
    }
}
