//! A leaf port, one per Möller-Trumbore lane: one triangle a cycle of the leaf of the slot
//! its scheduler grants, issued to the lane, and the lane's answers folded into the slot's
//! nearest hit.
//!
//! The grant reads the triangle from the lane's copy of the triangles and the slot's lane
//! words and pad from this port's slot RAMs; the cycle after, the triangle is tested (the
//! query packed in the lane's operand order) or skipped (an excluded triangle, and a
//! non-shadow-caster for an any-hit ray: no test). What the answer needs travels beside
//! the lane. The answer is judged against the slot's nearest hit ([`HitUpdate`]; the
//! nearest hit is read a cycle ahead from a slot RAM, a write in that cycle forwarded) and
//! reported as a [`LeafStep`]; after a leaf's last triangle a closest-hit ray whose hit got
//! nearer has its far end recomputed from `next_up(t)` ([`FarEnd`]) before it pops, an
//! any-hit ray with a hit is done. The judgement and `next_up` end in the comparison's
//! registers (as many as an fp32 `lt` has at the depth) before the far end's multiplier: the
//! two together were the unit's longest path (yosys: 24 levels, a 28-bit carry into a DSP48E1
//! without an input register).
//!
//! The port keeps its lane's copies of the slot words it reads (every copy written at
//! entry) and of the nearest hit (only this lane writes it, so each RAM has one writer):
//! one read at the answers, one at the hit output's grant (`out_slot`, `out_best`).
//!
//! rust-hdl cannot derive widths: `SB` slot bits, `TB` triangle address bits, `LF` a link's
//! first.

use hw_model::traversal::packet::ray_word;
use rust_hdl::prelude::*;

use super::far_end::FarEnd;
use super::hit_update::HitUpdate;
use super::scene_memory::{INDEX_BITS, VERTEX_BITS};
use super::slot_ports::{
    Entered, LeafGrant, LeafStep, NearestHit, SetUp, LANE_WORDS_BITS, LEAF_WORDS_BITS,
};
use crate::formats::fp32;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::mt::{LanePort, T_MIN_WORD};
use crate::top::stream::QUERY_BITS;

// The kernel spells bit offsets as numbers (hdl_gen leaks a named const into the Verilog):
// the query's vertices at word 6 and t_min at word 15 (`mt::query_words`), a slot's lane
// words as the ray packet's (t_max at 192, t_min at 224), the excluded triangle after them.
const _: () = assert!(
    32 * T_MIN_WORD == 480
        && 32 * 6 + VERTEX_BITS == 480
        && QUERY_BITS == 512
        && ray_word::T_MAX == 6
        && ray_word::T_MIN == 7
        && LANE_WORDS_BITS == 256
);

#[derive(LogicBlock)]
pub struct LeafPort<const SB: usize, const TB: usize, const LF: usize> {
    pub clock: Signal<In, Clock>,
    pub grant: LeafGrant<SB, LF>,
    pub step: LeafStep<SB>,
    /// An entering ray's lane words and excluded triangle; a set-up ray's pad.
    pub entered: Entered<SB>,
    pub set_up: SetUp<SB>,
    /// The triangle read (the scene memory's read port of this lane): the address at the
    /// grant, the record the cycle after.
    pub triangle_address: Signal<Out, Bits<TB>>,
    pub vertices: Signal<In, Bits<VERTEX_BITS>>,
    pub global_index: Signal<In, Bits<INDEX_BITS>>,
    pub casts_shadow: Signal<In, Bit>,
    pub lane: LanePort,
    /// The hit output's read of this lane's nearest hits: the granted slot in, its nearest
    /// hit the cycle after.
    pub out_slot: Signal<In, Bits<SB>>,
    pub out_best: Signal<Out, NearestHit>,
    /// The slots' lane words and excluded triangle, and pads.
    words: RAM<Bits<LEAF_WORDS_BITS>, SB>,
    pads: RAM<Bits<32>, SB>,
    /// The slots' nearest hits, read for the answers and for the hit output.
    best: RAM<NearestHit, SB>,
    best_out: RAM<NearestHit, SB>,
    /// The granted slot's state, registered beside the triangle and word reads.
    valid: DFF<Bit>,
    last: DFF<Bit>,
    any_hit: DFF<Bit>,
    has_exclude: DFF<Bit>,
    /// What travels beside the lane: issued (tested or skipped), tested, last of its leaf,
    /// triangle, the window, the flag, the pad.
    issued_at: Delay<Bit>,
    tested_at: Delay<Bit>,
    last_at: Delay<Bit>,
    index_at: Delay<Bits<INDEX_BITS>>,
    t_min_at: Delay<Bits<32>>,
    t_max_at: Delay<Bits<32>>,
    any_hit_at: Delay<Bit>,
    pad_at: Delay<Bits<32>>,
    /// The answer's slot one cycle early (from the grant, the lane's latency): the address
    /// of the nearest hit's read; then the answer's slot itself.
    slot_at: Delay<Bits<SB>>,
    answer_slot: DFF<Bits<SB>>,
    /// The nearest hit written in the cycle of the read (the RAM reads the old word).
    forward: DFF<Bit>,
    written_q: DFF<NearestHit>,
    update: HitUpdate,
    /// The far end's inputs in the comparison's registers.
    far_valid_at: Delay<Bit>,
    far_slot_at: Delay<Bits<SB>>,
    far_bound_at: Delay<Bits<32>>,
    far_pad_at: Delay<Bits<32>>,
    far: FarEnd,
    abs_mask: Constant<Bits<32>>,
    /// The granted slot's lane words and excluded triangle (the cycle after the grant).
    lane_words: Signal<Local, Bits<LANE_WORDS_BITS>>,
    exclude: Signal<Local, Bits<INDEX_BITS>>,
    skip: Signal<Local, Bit>,
    /// The answer's slot's nearest hit, and the one this answer writes.
    kept: Signal<Local, NearestHit>,
    written: Signal<Local, NearestHit>,
    /// The slot has a hit, its hit got nearer during the leaf (with this answer).
    has_hit: Signal<Local, Bit>,
    got_nearer: Signal<Local, Bit>,
    /// The far end's bound: next_up of the nearest hit's t.
    new_t: Signal<Local, Bits<32>>,
    next_up: Signal<Local, Bits<32>>,
}

impl<const SB: usize, const TB: usize, const LF: usize> LeafPort<SB, TB, LF> {
    /// A port whose operators have `depth` pipeline registers each, beside a lane of
    /// `lane_latency` cycles (query to answer, with whatever sits around the lane).
    pub fn new(depth: usize, lane_latency: usize) -> Self {
        let compare = OpLatencies::for_depth(depth, fp32::max_stages).lt;
        Self {
            clock: Default::default(),
            grant: Default::default(),
            step: Default::default(),
            entered: Default::default(),
            set_up: Default::default(),
            triangle_address: Default::default(),
            vertices: Default::default(),
            global_index: Default::default(),
            casts_shadow: Default::default(),
            lane: Default::default(),
            out_slot: Default::default(),
            out_best: Default::default(),
            words: Default::default(),
            pads: Default::default(),
            best: Default::default(),
            best_out: Default::default(),
            valid: Default::default(),
            last: Default::default(),
            any_hit: Default::default(),
            has_exclude: Default::default(),
            issued_at: Delay::new(lane_latency),
            tested_at: Delay::new(lane_latency),
            last_at: Delay::new(lane_latency),
            index_at: Delay::new(lane_latency),
            t_min_at: Delay::new(lane_latency),
            t_max_at: Delay::new(lane_latency),
            any_hit_at: Delay::new(lane_latency),
            pad_at: Delay::new(lane_latency),
            slot_at: Delay::new(lane_latency),
            answer_slot: Default::default(),
            forward: Default::default(),
            written_q: Default::default(),
            update: Default::default(),
            far_valid_at: Delay::new(compare),
            far_slot_at: Delay::new(compare),
            far_bound_at: Delay::new(compare),
            far_pad_at: Delay::new(compare),
            far: FarEnd::new(depth),
            abs_mask: Constant::new(0x7FFF_FFFFu64.into()),
            lane_words: Default::default(),
            exclude: Default::default(),
            skip: Default::default(),
            kept: Default::default(),
            written: Default::default(),
            has_hit: Default::default(),
            got_nearer: Default::default(),
            new_t: Default::default(),
            next_up: Default::default(),
        }
    }
}

impl<const SB: usize, const TB: usize, const LF: usize> Logic for LeafPort<SB, TB, LF> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            issued_at,
            tested_at,
            last_at,
            index_at,
            t_min_at,
            t_max_at,
            any_hit_at,
            pad_at,
            slot_at,
            far_valid_at,
            far_slot_at,
            far_bound_at,
            far_pad_at,
            far
        );
        dff_setup!(
            self,
            clock,
            valid,
            last,
            any_hit,
            has_exclude,
            answer_slot,
            forward,
            written_q
        );
        self.words.read_clock.next = self.clock.val();
        self.words.write_clock.next = self.clock.val();
        self.pads.read_clock.next = self.clock.val();
        self.pads.write_clock.next = self.clock.val();
        self.best.read_clock.next = self.clock.val();
        self.best.write_clock.next = self.clock.val();
        self.best_out.read_clock.next = self.clock.val();
        self.best_out.write_clock.next = self.clock.val();
        self.words.write_enable.next = self.entered.valid.val();
        self.words.write_address.next = self.entered.slot.val();
        self.words.write_data.next = self.entered.leaf_words.val();
        self.pads.write_enable.next = self.set_up.valid.val();
        self.pads.write_address.next = self.set_up.slot.val();
        self.pads.write_data.next = self.set_up.pad.val();

        // The grant reads the triangle and the slot's words …
        self.triangle_address.next = bit_cast::<TB, LF>(self.grant.triangle.val());
        self.words.read_address.next = self.grant.slot.val();
        self.pads.read_address.next = self.grant.slot.val();
        self.valid.d.next = self.grant.valid.val();
        self.last.d.next = self.grant.last.val();
        self.any_hit.d.next = self.grant.any_hit.val();
        self.has_exclude.d.next = self.grant.has_exclude.val();
        // … the cycle after, the triangle is tested or skipped.
        self.lane_words.next =
            bit_cast::<LANE_WORDS_BITS, LEAF_WORDS_BITS>(self.words.read_data.val());
        self.exclude.next =
            bit_cast::<INDEX_BITS, LEAF_WORDS_BITS>(self.words.read_data.val() >> 256);
        self.skip.next = (self.any_hit.q.val() & !self.casts_shadow.val())
            | (self.has_exclude.q.val() & (self.exclude.val() == self.global_index.val()));
        self.lane.valid.next = self.valid.q.val() & !self.skip.val();
        // The query in the lane's operand order (docs/stream.md): orig, dir (the lane words'
        // first six), v0, v1, v2, t_min.
        self.lane.query.next =
            bit_cast::<QUERY_BITS, 192>(bit_cast::<192, LANE_WORDS_BITS>(self.lane_words.val()))
                | (bit_cast::<QUERY_BITS, VERTEX_BITS>(self.vertices.val()) << 192)
                | (bit_cast::<QUERY_BITS, 32>(self.lane_words.val().get_bits::<32>(224)) << 480);
        self.t_min_at.d.next = self.lane_words.val().get_bits::<32>(224);
        self.t_max_at.d.next = self.lane_words.val().get_bits::<32>(192);
        self.issued_at.d.next = self.valid.q.val();
        self.tested_at.d.next = self.valid.q.val() & !self.skip.val();
        self.last_at.d.next = self.last.q.val();
        self.index_at.d.next = self.global_index.val();
        self.any_hit_at.d.next = self.any_hit.q.val();
        self.pad_at.d.next = self.pads.read_data.val();

        // The lane's answer, folded into its slot's nearest hit (closest-hit) or kept as
        // the first counting hit (any-hit). The nearest hit is read a cycle ahead.
        self.slot_at.d.next = self.grant.slot.val();
        self.best.read_address.next = self.slot_at.q.val();
        self.answer_slot.d.next = self.slot_at.q.val();
        self.step.valid.next = self.issued_at.q.val();
        self.step.slot.next = self.answer_slot.q.val();
        self.kept.next = self.best.read_data.val();
        if self.forward.q.val() {
            self.kept.next = self.written_q.q.val();
        }
        self.update.hit.next = self.lane.hit.val() & self.tested_at.q.val();
        self.update.t.next = self.lane.t.val();
        self.update.triangle.next = bit_cast::<32, INDEX_BITS>(self.index_at.q.val());
        self.update.t_min.next = self.t_min_at.q.val();
        self.update.bound.next = self.t_max_at.q.val();
        self.update.best_valid.next = self.step.best_valid.val();
        self.update.best_t.next = self.kept.val().t;
        self.update.best_triangle.next = self.kept.val().triangle;
        self.step.take.next = self.update.closer.val();
        if self.any_hit_at.q.val() {
            self.step.take.next = self.update.counts.val() & !self.step.best_valid.val();
        }
        self.has_hit.next = self.step.best_valid.val() | self.step.take.val();
        self.got_nearer.next = self.step.changed.val() | self.step.take.val();
        self.step.nearer.next = self.step.take.val() & !self.any_hit_at.q.val();
        // After a leaf's last answer: out (an any-hit ray with a hit), the far end (a nearer
        // hit; it then pops), else a pop.
        self.step.last.next = self.issued_at.q.val() & self.last_at.q.val();
        self.step.out.next = self.any_hit_at.q.val() & self.has_hit.val();
        self.step.pop.next = self.any_hit_at.q.val() | !self.got_nearer.val();
        self.written.next.t = self.lane.t.val();
        self.written.next.u = self.lane.u.val();
        self.written.next.v = self.lane.v.val();
        self.written.next.triangle = bit_cast::<32, INDEX_BITS>(self.index_at.q.val());
        self.best.write_enable.next = self.step.take.val() & self.issued_at.q.val();
        self.best.write_address.next = self.answer_slot.q.val();
        self.best.write_data.next = self.written.val();
        self.best_out.write_enable.next = self.step.take.val() & self.issued_at.q.val();
        self.best_out.write_address.next = self.answer_slot.q.val();
        self.best_out.write_data.next = self.written.val();
        self.forward.d.next = self.step.take.val()
            & self.issued_at.q.val()
            & (self.answer_slot.q.val() == self.slot_at.q.val());
        self.written_q.d.next = self.written.val();
        // The far end of next_up(t) (t is a counting hit's, so finite and not NaN).
        self.new_t.next = self.kept.val().t;
        if self.step.take.val() {
            self.new_t.next = self.lane.t.val();
        }
        if !(self.new_t.val() & self.abs_mask.val()).any() {
            self.next_up.next = 1.into();
        } else if self.new_t.val().get_bit(31) {
            self.next_up.next = self.new_t.val() - 1;
        } else {
            self.next_up.next = self.new_t.val() + 1;
        }
        self.far_valid_at.d.next = self.issued_at.q.val()
            & self.last_at.q.val()
            & !self.any_hit_at.q.val()
            & self.got_nearer.val();
        self.far_slot_at.d.next = self.answer_slot.q.val();
        self.far_bound_at.d.next = self.next_up.val();
        self.far_pad_at.d.next = self.pad_at.q.val();
        self.far.valid_in.next = self.far_valid_at.q.val();
        self.far.tag_in.next = bit_cast::<16, SB>(self.far_slot_at.q.val());
        self.far.bound.next = self.far_bound_at.q.val();
        self.far.pad.next = self.far_pad_at.q.val();
        self.step.far_valid.next = self.far.valid_out.val();
        self.step.far_slot.next = bit_cast::<SB, 16>(self.far.tag_out.val());
        self.step.t_hi.next = self.far.t_hi.val();

        // The hit output's read.
        self.best_out.read_address.next = self.out_slot.val();
        self.out_best.next = self.best_out.read_data.val();
    }
}
