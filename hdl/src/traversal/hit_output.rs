//! The hit output: one answer register on the hit stream, refilled in the cycle it drains.
//! Its scheduler grants a slot only while the register can take an answer ([`OutGrant`]'s
//! `ready`); the granted slot's ray id (a slot RAM here) and nearest hit (its lane's copy,
//! read by the lane's leaf port) arrive the cycle after the grant and are packed into an
//! answer packet (`hw_model::traversal::packet::hit_word`), which the register holds while
//! `tready` is low.

use hw_model::traversal::packet::{hit_word, HIT_WORDS};
use rust_hdl::prelude::*;

use super::config::MAX_LANES;
use super::ports::{HitStream, HIT_BITS};
use super::slot_ports::{Entered, NearestHit, OutGrant};

// The kernel spells the answer's word offsets as numbers (hdl_gen leaks a named const into
// the Verilog).
const _: () = assert!(
    HIT_WORDS == 6
        && hit_word::ID == 0
        && hit_word::FLAGS == 1
        && hit_word::TRIANGLE == 2
        && hit_word::T == 3
        && hit_word::U == 4
        && hit_word::V == 5
);

/// `SB` slot bits.
#[derive(LogicBlock)]
pub struct HitOutput<const SB: usize> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub grant: OutGrant<SB>,
    /// An entering ray's id, kept for its answer.
    pub entered: Entered<SB>,
    /// Per lane, its copy of the granted slot's nearest hit (the cycle after the grant).
    pub lane_best: Vec<Signal<In, NearestHit>>,
    pub hit: HitStream,
    /// The register holds an answer.
    pub pending: Signal<Out, Bit>,
    ids: RAM<Bits<32>, SB>,
    valid: DFF<Bit>,
    /// The register takes the RAMs' words this cycle (a grant the cycle before).
    fresh: DFF<Bit>,
    /// The granted slot has a hit, and its lane (one-hot).
    has_hit: DFF<Bit>,
    lane: DFF<Bits<MAX_LANES>>,
    data: DFF<Bits<HIT_BITS>>,
    /// The hit bit (bit 0 of the answer's flags word), in place.
    hit_flag: Constant<Bits<HIT_BITS>>,
    no_hit: Constant<NearestHit>,
    best: Signal<Local, NearestHit>,
    answer: Signal<Local, Bits<HIT_BITS>>,
}

impl<const SB: usize> HitOutput<SB> {
    /// The output of a unit with `lanes` lanes.
    pub fn new(lanes: usize) -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            grant: Default::default(),
            entered: Default::default(),
            lane_best: crate::defaults(lanes),
            hit: Default::default(),
            pending: Default::default(),
            ids: Default::default(),
            valid: Default::default(),
            fresh: Default::default(),
            has_hit: Default::default(),
            lane: Default::default(),
            data: Default::default(),
            hit_flag: Constant::new((1u64 << (32 * hit_word::FLAGS)).into()),
            no_hit: Constant::new(NearestHit::default()),
            best: Default::default(),
            answer: Default::default(),
        }
    }
}

impl<const SB: usize> Logic for HitOutput<SB> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, valid, fresh, has_hit, lane, data);
        self.ids.read_clock.next = self.clock.val();
        self.ids.write_clock.next = self.clock.val();
        self.ids.write_enable.next = self.entered.valid.val();
        self.ids.write_address.next = self.entered.slot.val();
        self.ids.write_data.next = self.entered.id.val();

        // The grant reads the slot's id and nearest hit.
        self.grant.ready.next = !self.valid.q.val() | self.hit.tready.val();
        self.ids.read_address.next = self.grant.slot.val();
        self.fresh.d.next = self.grant.valid.val();
        self.has_hit.d.next = self.grant.hit.val();
        self.lane.d.next = self.grant.lane.val();
        // The cycle after: the answer from the RAMs' words.
        self.best.next = self.no_hit.val();
        for l in 0..self.lane_best.len() {
            if self.lane.q.val().get_bit(l) {
                self.best.next = self.lane_best[l].val();
            }
        }
        self.answer.next = bit_cast::<HIT_BITS, 32>(self.ids.read_data.val());
        if self.has_hit.q.val() {
            self.answer.next = self.answer.val()
                | self.hit_flag.val()
                | (bit_cast::<HIT_BITS, 32>(self.best.val().triangle) << 64)
                | (bit_cast::<HIT_BITS, 32>(self.best.val().t) << 96)
                | (bit_cast::<HIT_BITS, 32>(self.best.val().u) << 128)
                | (bit_cast::<HIT_BITS, 32>(self.best.val().v) << 160);
        }
        if self.hit.tready.val() {
            self.valid.d.next = false;
        }
        if self.grant.valid.val() {
            self.valid.d.next = true;
        }
        self.hit.tvalid.next = self.valid.q.val();
        self.hit.tdata.next = self.data.q.val();
        if self.fresh.q.val() {
            self.hit.tdata.next = self.answer.val();
        }
        self.data.d.next = self.hit.tdata.val();
        if !self.reset_n.val() {
            self.valid.d.next = false;
        }
        self.pending.next = self.valid.q.val();
    }
}
