//! The traversal unit's core: the scene in block RAM, rays in, answers out — the blocks of
//! this module assembled around the ports of 1 to [`MAX_LANES`] Möller-Trumbore lanes, which
//! `unit_top` puts beside it in the configured format. The whole unit is bit for bit
//! `hw_model::traversal::TraversalModel` (answers and counters). Ports and packets:
//! docs/traversal-unit.md.
//!
//! `S` ray slots hold the rays in flight. A slot is in one of five states, kept as one bit
//! vector each (a slot's bit set in at most one; none set while it waits for an answer):
//! `busy` (holds a ray), `want_box`, `want_leaf`, `want_pop`, `want_out`. Four round-robin
//! arbiters ([`RoundRobin`]) grant one slot each cycle to each shared resource:
//!
//! - the **box port**: the slot's node is read (or the root's box for a new ray), then the box
//!   test of both children; its answer picks the next link (both entered: the farther is
//!   pushed on the slot's stack with its entry distance, the nearer taken), or a pop;
//! - the **leaf ports**, one per lane over that lane's slots (slot s: lane s mod lanes, the
//!   schedule model's partition): one triangle of the slot's leaf a cycle is read from the
//!   lane's copy of the triangles and issued to the lane (an excluded triangle, and a
//!   non-shadow-caster for an any-hit ray, is skipped: no test); the slot waits after its
//!   last triangle;
//! - the **stack port**: a pop, whose entry is skipped if it was entered beyond the slot's far
//!   end `t_hi` (then it pops again), or ends the walk when the stack is empty;
//! - the **hit output**: the slot's answer leaves, and the slot is free.
//!
//! A lane's answers fold into the slot's nearest hit in issue order (`HitUpdate`, one per
//! lane); after a leaf a closest-hit ray whose hit got nearer has its far end recomputed from
//! `next_up(t)` (`FarEnd`, one per lane) before it pops, an any-hit ray with a hit is done.
//! Every write-back targets a slot in a distinct state, and the lanes' write-backs target
//! slots of distinct lanes, so writers never collide.
//!
//! A slot's wide words that have one writer live in synchronous slot RAMs (LUTRAM, 32 deep),
//! read at a port's grant so that the word arrives the cycle after, as a register would
//! bring it: the box-test words (written by the ray setup, read at the box grant), the lane
//! words and excluded triangle (written at entry, read at the leaf grant), the pad (written
//! by the setup, read at the leaf grant and carried beside the lane), the nearest hit (read
//! one cycle before each lane answer, the previous cycle's write forwarded) and, for the hit
//! output and the overflow report, copies of the nearest hit and of the ray id. The RAMs a
//! leaf port reads or a lane writes have one copy per lane (lane l writes only its nearest-hit
//! copy, so each RAM keeps one writer). Words with several writers in one cycle (the far end
//! `t_hi`, the current link) stay flip-flops.

use hw_model::traversal::packet::{hit_word, ray_word, ANY_HIT, HAS_EXCLUDE, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::schedule::UnitTiming;
use hw_model::{Advance, HwFormat};
use rust_hdl::prelude::*;
use thiserror::Error;

use super::arbiter::RoundRobin;
use super::box_test::BoxTest;
use super::far_end::FarEnd;
use super::hit_update::{F32Order, HitUpdate};
use super::ray_setup::RaySetupUnit;
use super::scene_memory::{
    triangle_record_bits, zynq_address_bits, SceneMemory, ERROR_CODE_BITS, INDEX_BITS,
};
use super::scene_memory_driver::MemoryConfig;
use super::stack::SlotStacks;
use super::timing::unit_timing;
use crate::defaults;
use crate::mt::delay::Delay;
use crate::top::stream::QUERY_BITS;
use crate::top::with_build_stack;

/// Bits of a ray packet and of an answer packet.
pub const RAY_BITS: usize = 32 * RAY_WORDS;
pub const HIT_BITS: usize = 32 * HIT_WORDS;
/// A slot's box-test words: orig_lo x y z, orig_hi x y z, inv_dir x y z.
const BOX_WORDS_BITS: usize = 9 * 32;
/// A slot's lane words: orig x y z, dir x y z, t_min, t_max.
const LANE_WORDS_BITS: usize = 8 * 32;
/// A slot's leaf-port words: the lane words, then the excluded triangle.
const LEAF_WORDS_BITS: usize = LANE_WORDS_BITS + INDEX_BITS;
/// A slot's nearest hit: t, u, v, triangle (zero-extended).
const BEST_BITS: usize = 4 * 32;

/// The unit. Const parameters (rust-hdl cannot derive widths): the scene memory's
/// `NB, TB, LF, LC, NW, TW` (see [`SceneMemory`]); `S` slots addressed by `SB` bits; the
/// stacks' pointer bits `PB` and RAM address bits `AB`; a stack entry of `W` = LF + LC + 32
/// bits (a link and its entry distance).
#[derive(LogicBlock)]
pub struct TraversalCore<
    const NB: usize,
    const TB: usize,
    const LF: usize,
    const LC: usize,
    const NW: usize,
    const TW: usize,
    const S: usize,
    const SB: usize,
    const PB: usize,
    const AB: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub scene_start: Signal<In, Bit>,
    pub scene_tdata: Signal<In, Bits<32>>,
    pub scene_tvalid: Signal<In, Bit>,
    pub scene_tlast: Signal<In, Bit>,
    pub scene_tready: Signal<Out, Bit>,
    pub scene_loaded: Signal<Out, Bit>,
    pub scene_error: Signal<Out, Bit>,
    pub scene_error_code: Signal<Out, Bits<ERROR_CODE_BITS>>,
    pub scene_error_word: Signal<Out, Bits<32>>,
    pub scene_error_value: Signal<Out, Bits<32>>,
    pub ray_tdata: Signal<In, Bits<RAY_BITS>>,
    pub ray_tvalid: Signal<In, Bit>,
    pub ray_tready: Signal<Out, Bit>,
    pub hit_tdata: Signal<Out, Bits<HIT_BITS>>,
    pub hit_tvalid: Signal<Out, Bit>,
    pub hit_tready: Signal<In, Bit>,
    pub idle: Signal<Out, Bit>,
    pub overflow: Signal<Out, Bit>,
    pub overflow_ray: Signal<Out, Bits<32>>,
    pub count_rays: Signal<Out, Bits<32>>,
    pub count_node_visits: Signal<Out, Bits<32>>,
    pub count_box_tests: Signal<Out, Bits<32>>,
    pub count_mt_tests: Signal<Out, Bits<32>>,
    pub count_busy_cycles: Signal<Out, Bits<32>>,
    /// The Möller-Trumbore lanes, outside the core so that one core serves every format
    /// (`unit_top`): per lane a query a cycle out (the operands packed as the accelerator's
    /// stream packs them), its answer `lane_latency` cycles later in.
    pub lane_valid: Vec<Signal<Out, Bit>>,
    pub lane_query: Vec<Signal<Out, Bits<QUERY_BITS>>>,
    pub lane_hit: Vec<Signal<In, Bit>>,
    pub lane_t: Vec<Signal<In, Bits<32>>>,
    pub lane_u: Vec<Signal<In, Bits<32>>>,
    pub lane_v: Vec<Signal<In, Bits<32>>>,
    /// With the leaf advance (else no lanes): the entry distance of the query's leaf,
    /// beside `lane_query` (`unit_top` puts `leaf_advance::AroundLane` between core and lane).
    pub lane_entry: Vec<Signal<Out, Bits<32>>>,

    memory: SceneMemory<NB, TB, LF, LC, NW, TW>,
    setup: RaySetupUnit,
    boxes: BoxTest,
    stacks: SlotStacks<S, SB, PB, AB, W>,
    // Per lane (index l; slot s belongs to lane s mod lanes): the far end, the hit update,
    // the leaf port's arbiter.
    far: Vec<FarEnd>,
    update: Vec<HitUpdate>,
    /// lt(t_hi, entry distance) of a popped entry: entered beyond the far end.
    beyond: F32Order,
    box_arb: RoundRobin<S>,
    leaf_arb: Vec<RoundRobin<S>>,
    /// The slots of each lane.
    lane_slots: Vec<Constant<Bits<S>>>,
    pop_arb: RoundRobin<S>,
    out_arb: RoundRobin<S>,

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
    // The slots' words: one-writer words in slot RAMs (address: the slot) …
    box_ram: RAM<Bits<BOX_WORDS_BITS>, SB>,
    /// Per lane: its leaf port's copy of the lane words and the pad (every copy written at
    /// entry, each read by its own port).
    leaf_ram: Vec<RAM<Bits<LEAF_WORDS_BITS>, SB>>,
    pad_ram: Vec<RAM<Bits<32>, SB>>,
    /// Per lane, the nearest hit of its slots, read for the lane's answers (`best_ram`) and
    /// for the hit output: only lane l writes copy l, so each RAM keeps one writer.
    best_ram: Vec<RAM<Bits<BEST_BITS>, SB>>,
    best_out_ram: Vec<RAM<Bits<BEST_BITS>, SB>>,
    /// The ray id, read for the hit output and for the overflow report.
    id_out_ram: RAM<Bits<32>, SB>,
    id_overflow_ram: RAM<Bits<32>, SB>,
    // … the rest in flip-flops.
    t_hi: Vec<DFF<Bits<32>>>,
    /// The current link: a node, or the leaf's next triangle and how many are left.
    link_first: Vec<DFF<Bits<LF>>>,
    link_count: Vec<DFF<Bits<LC>>>,
    /// With the leaf advance (else no slots): where the box test entered the current link
    /// (the box answer's `near`, a popped entry's distance), the model's `entry`.
    link_entry: Vec<DFF<Bits<32>>>,
    slot_id: Vec<Constant<Bits<SB>>>,
    one: Constant<Bits<S>>,
    one_count: Constant<Bits<LC>>,
    /// A stack entry: the distance in bits 0–31, the count at 32, the first at `at_first`.
    at_first: Constant<Bits<8>>,
    abs_mask: Constant<Bits<32>>,
    /// Where a word enters a packed record: its top word.
    box_top: Constant<Bits<16>>,
    hit_top: Constant<Bits<16>>,
    best_top: Constant<Bits<16>>,
    query_top: Constant<Bits<16>>,
    /// Where the excluded triangle sits in a leaf-port word.
    exclude_at: Constant<Bits<16>>,

    // The box port: the granted slot's state, registered beside the node and word reads.
    box_valid: DFF<Bit>,
    box_slot: DFF<Bits<SB>>,
    box_root: DFF<Bit>,
    box_t_hi: DFF<Bits<32>>,
    /// The node's child links travel beside the box test.
    child_first_at: [Delay<Bits<LF>>; 2],
    child_count_at: [Delay<Bits<LC>>; 2],
    root_at: Delay<Bit>,
    // The leaf ports, per lane: the slot's state, registered beside the triangle and word
    // reads.
    leaf_valid: Vec<DFF<Bit>>,
    leaf_last: Vec<DFF<Bit>>,
    leaf_any_hit: Vec<DFF<Bit>>,
    leaf_has_exclude: Vec<DFF<Bit>>,
    /// With the leaf advance: the granted slot's `link_entry`, beside the query.
    leaf_entry: Vec<DFF<Bits<32>>>,
    /// What travels beside each lane: issued (tested or skipped), tested, last of its leaf,
    /// triangle, the window, the pad.
    issued_at: Vec<Delay<Bit>>,
    tested_at: Vec<Delay<Bit>>,
    last_at: Vec<Delay<Bit>>,
    index_at: Vec<Delay<Bits<INDEX_BITS>>>,
    t_min_at: Vec<Delay<Bits<32>>>,
    t_max_at: Vec<Delay<Bits<32>>>,
    any_hit_at: Vec<Delay<Bit>>,
    pad_at: Vec<Delay<Bits<32>>>,
    /// The answer's slot one cycle early (from the grant, the lane's latency): the address
    /// of the nearest hit's read; then the answer's slot itself.
    slot_at: Vec<Delay<Bits<SB>>>,
    answer_slot: Vec<DFF<Bits<SB>>>,
    /// The nearest hit written in the cycle of the read (the RAM reads the old word).
    best_forward: Vec<DFF<Bit>>,
    best_written: Vec<DFF<Bits<BEST_BITS>>>,
    // The stack port.
    pop_valid: DFF<Bit>,
    pop_slot: DFF<Bits<SB>>,
    pop_t_hi: DFF<Bits<32>>,
    // The hit output: the granted slot's words arrive from the RAMs the cycle after the
    // grant (`out_fresh`), and `out_data` holds them while the output waits.
    out_valid: DFF<Bit>,
    out_fresh: DFF<Bit>,
    out_hit: DFF<Bit>,
    out_data: DFF<Bits<HIT_BITS>>,
    /// The granted slot's lane: which copy of the nearest hit the answer takes.
    out_lane: Vec<DFF<Bit>>,
    overflow_q: DFF<Bit>,
    overflow_ray_q: DFF<Bits<32>>,
    rays: DFF<Bits<32>>,
    node_visits: DFF<Bits<32>>,
    box_tests: DFF<Bits<32>>,
    mt_tests: DFF<Bits<32>>,
    busy_cycles: DFF<Bits<32>>,

    // Combinational helpers.
    ray_words: [Signal<Local, Bits<32>>; RAY_WORDS],
    hit_words: [Signal<Local, Bits<32>>; HIT_WORDS],
    free: Signal<Local, Bits<S>>,
    enter: Signal<Local, Bits<S>>,
    enter_slot: Signal<Local, Bits<SB>>,
    accept: Signal<Local, Bit>,
    box_grant_slot: Signal<Local, Bits<SB>>,
    pop_grant_slot: Signal<Local, Bits<SB>>,
    out_grant_slot: Signal<Local, Bits<SB>>,
    /// Write-backs: one-hot slot masks and what they write.
    setup_done: Signal<Local, Bits<S>>,
    setup_slot: Signal<Local, Bits<SB>>,
    box_done: Signal<Local, Bits<S>>,
    box_done_slot: Signal<Local, Bits<SB>>,
    box_link_first: Signal<Local, Bits<LF>>,
    box_link_count: Signal<Local, Bits<LC>>,
    /// The box answer enters a link (else: pop, or for the root, out).
    box_enters: Signal<Local, Bit>,
    pop_done: Signal<Local, Bits<S>>,
    pop_link_first: Signal<Local, Bits<LF>>,
    pop_link_count: Signal<Local, Bits<LC>>,
    pop_enters: Signal<Local, Bit>,
    pop_again: Signal<Local, Bit>,
    // Per lane, what the slots' state update reads.
    lane_done: Vec<Signal<Local, Bits<S>>>,
    lane_best_valid: Vec<Signal<Local, Bit>>,
    lane_changed: Vec<Signal<Local, Bit>>,
    /// This result becomes the slot's nearest hit (closest-hit), or its answer (any-hit).
    lane_take: Vec<Signal<Local, Bit>>,
    lane_any_hit: Vec<Signal<Local, Bit>>,
    far_done: Vec<Signal<Local, Bits<S>>>,
    leaf_grant: Vec<Signal<Local, Bits<S>>>,
    leaf_grant_last: Vec<Signal<Local, Bit>>,
    /// Every lane's far-end answers.
    far_done_all: Signal<Local, Bits<S>>,
    // One lane's values within its iteration of the kernel's lane loops (a lane's port
    // logic is written once, for lane l).
    leaf_grant_slot: Signal<Local, Bits<SB>>,
    lane_slot: Signal<Local, Bits<SB>>,
    lane_best: Signal<Local, Bits<BEST_BITS>>,
    /// The nearest hit this answer writes.
    lane_written: Signal<Local, Bits<BEST_BITS>>,
    far_slot: Signal<Local, Bits<SB>>,
    far_tag: Signal<Local, Bits<16>>,
    skip: Signal<Local, Bit>,
    next_up: Signal<Local, Bits<32>>,
    new_t: Signal<Local, Bits<32>>,
    leaf_link: Signal<Local, Bits<LF>>,
    leaf_read: Signal<Local, Bits<LEAF_WORDS_BITS>>,
    /// An entering ray's leaf-port words.
    entry_words: Signal<Local, Bits<LEAF_WORDS_BITS>>,
    leaf_words: Signal<Local, Bits<LANE_WORDS_BITS>>,
    leaf_exclude: Signal<Local, Bits<INDEX_BITS>>,
    lane_index: Signal<Local, Bits<INDEX_BITS>>,
    query: Signal<Local, Bits<QUERY_BITS>>,
    out_best: Signal<Local, Bits<BEST_BITS>>,
    mt_count: Signal<Local, Bits<32>>,
    out_grant: Signal<Local, Bits<S>>,
    entering: Signal<Local, Bits<S>>,
    /// A word on its way into a packed record (an indexed word cannot go into `bit_cast`
    /// directly: hdl_gen loses the index).
    packed_word: Signal<Local, Bits<32>>,
    box_link: Signal<Local, Bits<LF>>,
    ray_exclude: Signal<Local, Bits<INDEX_BITS>>,
    setup_words: Signal<Local, Bits<BOX_WORDS_BITS>>,
    out_word: Signal<Local, Bits<HIT_BITS>>,
    box_visit: Signal<Local, Bit>,
    next_busy: Signal<Local, Bits<S>>,
    next_box: Signal<Local, Bits<S>>,
    next_leaf: Signal<Local, Bits<S>>,
    next_pop: Signal<Local, Bits<S>>,
    next_out: Signal<Local, Bits<S>>,
    next_changed: Signal<Local, Bits<S>>,
    next_best_valid: Signal<Local, Bits<S>>,
}

// hdl_gen cannot index by a named constant, so the kernel spells the packets' word
// indices as numbers; these assertions tie them to `packet`. A slot's lane words are the ray
// packet's first eight words as they come.
const _: () = assert!(
    ray_word::ORIG == 0
        && ray_word::DIR == 3
        && ray_word::T_MAX == 6
        && ray_word::T_MIN == 7
        && ray_word::FLAGS == 8
        && ray_word::EXCLUDE == 9
        && ray_word::ID == 10
        && ANY_HIT == 1 << 0
        && HAS_EXCLUDE == 1 << 1
);
const _: () = assert!(
    hit_word::ID == 0
        && hit_word::FLAGS == 1
        && hit_word::TRIANGLE == 2
        && hit_word::T == 3
        && hit_word::U == 4
        && hit_word::V == 5
);

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LC: usize,
        const NW: usize,
        const TW: usize,
        const S: usize,
        const SB: usize,
        const PB: usize,
        const AB: usize,
        const W: usize,
    > TraversalCore<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>
{
    /// A core whose operators have `depth` pipeline registers each (at most their maximum),
    /// whose slots have stacks of `stack_depth` entries, for `lanes` lanes of `lane_latency`
    /// cycles (query to answer, with whatever `unit_top` puts around the lane). With
    /// `entries`, it keeps each slot's entry distance and gives it beside each query
    /// (`lane_entry`, for the leaf advance); without, it has none of that logic.
    pub fn new(
        depth: usize,
        stack_depth: usize,
        lanes: usize,
        lane_latency: usize,
        entries: bool,
    ) -> Self {
        assert_eq!(W, LF + LC + 32, "a stack entry is a link and a distance");
        assert!(
            S <= 1 << SB && S <= 1 << 16,
            "{S} slots need more than {SB} bits"
        );
        assert!(
            (1..=S).contains(&lanes),
            "{lanes} lanes for {S} slots: 1 to {S}"
        );
        let box_latency = super::box_test::latency(depth);
        fn beside_lane<T: Synth>(lanes: usize, latency: usize) -> Vec<Delay<T>> {
            (0..lanes).map(|_| Delay::new(latency)).collect()
        }
        let lane_mask = |l: usize| (l..S).step_by(lanes).fold(0u64, |m, s| m | 1 << s);
        let (entry_slots, entry_lanes) = if entries { (S, lanes) } else { (0, 0) };
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            scene_start: Default::default(),
            scene_tdata: Default::default(),
            scene_tvalid: Default::default(),
            scene_tlast: Default::default(),
            scene_tready: Default::default(),
            scene_loaded: Default::default(),
            scene_error: Default::default(),
            scene_error_code: Default::default(),
            scene_error_word: Default::default(),
            scene_error_value: Default::default(),
            ray_tdata: Default::default(),
            ray_tvalid: Default::default(),
            ray_tready: Default::default(),
            hit_tdata: Default::default(),
            hit_tvalid: Default::default(),
            hit_tready: Default::default(),
            idle: Default::default(),
            overflow: Default::default(),
            overflow_ray: Default::default(),
            count_rays: Default::default(),
            count_node_visits: Default::default(),
            count_box_tests: Default::default(),
            count_mt_tests: Default::default(),
            count_busy_cycles: Default::default(),
            lane_valid: defaults(lanes),
            lane_query: defaults(lanes),
            lane_hit: defaults(lanes),
            lane_t: defaults(lanes),
            lane_u: defaults(lanes),
            lane_v: defaults(lanes),
            lane_entry: defaults(entry_lanes),
            memory: SceneMemory::new(lanes),
            setup: RaySetupUnit::new(depth),
            boxes: BoxTest::new(depth),
            far: (0..lanes).map(|_| FarEnd::new(depth)).collect(),
            stacks: SlotStacks::new(stack_depth),
            update: defaults(lanes),
            beyond: Default::default(),
            box_arb: Default::default(),
            leaf_arb: defaults(lanes),
            lane_slots: (0..lanes)
                .map(|l| Constant::new(lane_mask(l).into()))
                .collect(),
            pop_arb: Default::default(),
            out_arb: Default::default(),
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
            box_ram: Default::default(),
            leaf_ram: defaults(lanes),
            pad_ram: defaults(lanes),
            best_ram: defaults(lanes),
            best_out_ram: defaults(lanes),
            id_out_ram: Default::default(),
            id_overflow_ram: Default::default(),
            t_hi: defaults(S),
            link_first: defaults(S),
            link_count: defaults(S),
            link_entry: defaults(entry_slots),
            slot_id: (0..S).map(|s| Constant::new((s as u64).into())).collect(),
            one: Constant::new(1.into()),
            one_count: Constant::new(1.into()),
            at_first: Constant::new(((LC + 32) as u64).into()),
            abs_mask: Constant::new(0x7FFF_FFFFu64.into()),
            box_top: Constant::new(((BOX_WORDS_BITS - 32) as u64).into()),
            hit_top: Constant::new(((HIT_BITS - 32) as u64).into()),
            best_top: Constant::new(((BEST_BITS - 32) as u64).into()),
            query_top: Constant::new(((QUERY_BITS - 32) as u64).into()),
            exclude_at: Constant::new((LANE_WORDS_BITS as u64).into()),
            box_valid: Default::default(),
            box_slot: Default::default(),
            box_root: Default::default(),
            box_t_hi: Default::default(),
            child_first_at: Delay::lines(box_latency),
            child_count_at: Delay::lines(box_latency),
            root_at: Delay::new(box_latency),
            leaf_valid: defaults(lanes),
            leaf_last: defaults(lanes),
            leaf_any_hit: defaults(lanes),
            leaf_has_exclude: defaults(lanes),
            leaf_entry: defaults(entry_lanes),
            issued_at: beside_lane(lanes, lane_latency),
            tested_at: beside_lane(lanes, lane_latency),
            last_at: beside_lane(lanes, lane_latency),
            index_at: beside_lane(lanes, lane_latency),
            t_min_at: beside_lane(lanes, lane_latency),
            t_max_at: beside_lane(lanes, lane_latency),
            any_hit_at: beside_lane(lanes, lane_latency),
            pad_at: beside_lane(lanes, lane_latency),
            slot_at: beside_lane(lanes, lane_latency),
            answer_slot: defaults(lanes),
            best_forward: defaults(lanes),
            best_written: defaults(lanes),
            pop_valid: Default::default(),
            pop_slot: Default::default(),
            pop_t_hi: Default::default(),
            out_valid: Default::default(),
            out_fresh: Default::default(),
            out_hit: Default::default(),
            out_data: Default::default(),
            out_lane: defaults(lanes),
            overflow_q: Default::default(),
            overflow_ray_q: Default::default(),
            rays: Default::default(),
            node_visits: Default::default(),
            box_tests: Default::default(),
            mt_tests: Default::default(),
            busy_cycles: Default::default(),
            ray_words: Default::default(),
            hit_words: Default::default(),
            free: Default::default(),
            enter: Default::default(),
            enter_slot: Default::default(),
            accept: Default::default(),
            box_grant_slot: Default::default(),
            pop_grant_slot: Default::default(),
            out_grant_slot: Default::default(),
            setup_done: Default::default(),
            setup_slot: Default::default(),
            box_done: Default::default(),
            box_done_slot: Default::default(),
            box_link_first: Default::default(),
            box_link_count: Default::default(),
            box_enters: Default::default(),
            pop_done: Default::default(),
            pop_link_first: Default::default(),
            pop_link_count: Default::default(),
            pop_enters: Default::default(),
            pop_again: Default::default(),
            lane_done: defaults(lanes),
            lane_best_valid: defaults(lanes),
            lane_changed: defaults(lanes),
            lane_take: defaults(lanes),
            lane_any_hit: defaults(lanes),
            far_done: defaults(lanes),
            leaf_grant: defaults(lanes),
            leaf_grant_last: defaults(lanes),
            far_done_all: Default::default(),
            leaf_grant_slot: Default::default(),
            lane_slot: Default::default(),
            lane_best: Default::default(),
            lane_written: Default::default(),
            far_slot: Default::default(),
            far_tag: Default::default(),
            skip: Default::default(),
            next_up: Default::default(),
            new_t: Default::default(),
            leaf_link: Default::default(),
            leaf_read: Default::default(),
            entry_words: Default::default(),
            leaf_words: Default::default(),
            leaf_exclude: Default::default(),
            lane_index: Default::default(),
            query: Default::default(),
            out_best: Default::default(),
            mt_count: Default::default(),
            out_grant: Default::default(),
            entering: Default::default(),
            packed_word: Default::default(),
            box_link: Default::default(),
            ray_exclude: Default::default(),
            setup_words: Default::default(),
            out_word: Default::default(),
            box_visit: Default::default(),
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

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LC: usize,
        const NW: usize,
        const TW: usize,
        const S: usize,
        const SB: usize,
        const PB: usize,
        const AB: usize,
        const W: usize,
    > Logic for TraversalCore<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.memory.clock.next = self.clock.val();
        self.setup.clock.next = self.clock.val();
        self.boxes.clock.next = self.clock.val();
        self.stacks.clock.next = self.clock.val();
        self.box_arb.clock.next = self.clock.val();
        self.pop_arb.clock.next = self.clock.val();
        self.out_arb.clock.next = self.clock.val();
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
            changed,
            box_valid,
            box_slot,
            box_root,
            box_t_hi,
            pop_valid,
            pop_slot,
            pop_t_hi,
            out_valid,
            out_fresh,
            out_hit,
            out_data,
            overflow_q,
            overflow_ray_q,
            rays,
            node_visits,
            box_tests,
            mt_tests,
            busy_cycles
        );
        self.box_ram.read_clock.next = self.clock.val();
        self.box_ram.write_clock.next = self.clock.val();
        self.id_out_ram.read_clock.next = self.clock.val();
        self.id_out_ram.write_clock.next = self.clock.val();
        self.id_overflow_ram.read_clock.next = self.clock.val();
        self.id_overflow_ram.write_clock.next = self.clock.val();
        for i in 0..S {
            self.t_hi[i].clock.next = self.clock.val();
            self.t_hi[i].d.next = self.t_hi[i].q.val();
            self.link_first[i].clock.next = self.clock.val();
            self.link_first[i].d.next = self.link_first[i].q.val();
            self.link_count[i].clock.next = self.clock.val();
            self.link_count[i].d.next = self.link_count[i].q.val();
        }
        for c in 0..2 {
            self.child_first_at[c].clock.next = self.clock.val();
            self.child_count_at[c].clock.next = self.clock.val();
        }
        self.root_at.clock.next = self.clock.val();
        for l in 0..self.leaf_arb.len() {
            self.far[l].clock.next = self.clock.val();
            self.leaf_arb[l].clock.next = self.clock.val();
            self.leaf_ram[l].read_clock.next = self.clock.val();
            self.leaf_ram[l].write_clock.next = self.clock.val();
            self.pad_ram[l].read_clock.next = self.clock.val();
            self.pad_ram[l].write_clock.next = self.clock.val();
            self.best_ram[l].read_clock.next = self.clock.val();
            self.best_ram[l].write_clock.next = self.clock.val();
            self.best_out_ram[l].read_clock.next = self.clock.val();
            self.best_out_ram[l].write_clock.next = self.clock.val();
            self.issued_at[l].clock.next = self.clock.val();
            self.tested_at[l].clock.next = self.clock.val();
            self.last_at[l].clock.next = self.clock.val();
            self.slot_at[l].clock.next = self.clock.val();
            self.index_at[l].clock.next = self.clock.val();
            self.t_min_at[l].clock.next = self.clock.val();
            self.t_max_at[l].clock.next = self.clock.val();
            self.any_hit_at[l].clock.next = self.clock.val();
            self.pad_at[l].clock.next = self.clock.val();
            self.leaf_valid[l].clock.next = self.clock.val();
            self.leaf_valid[l].d.next = self.leaf_valid[l].q.val();
            self.leaf_last[l].clock.next = self.clock.val();
            self.leaf_last[l].d.next = self.leaf_last[l].q.val();
            self.leaf_any_hit[l].clock.next = self.clock.val();
            self.leaf_any_hit[l].d.next = self.leaf_any_hit[l].q.val();
            self.leaf_has_exclude[l].clock.next = self.clock.val();
            self.leaf_has_exclude[l].d.next = self.leaf_has_exclude[l].q.val();
            self.answer_slot[l].clock.next = self.clock.val();
            self.answer_slot[l].d.next = self.answer_slot[l].q.val();
            self.best_forward[l].clock.next = self.clock.val();
            self.best_forward[l].d.next = self.best_forward[l].q.val();
            self.best_written[l].clock.next = self.clock.val();
            self.best_written[l].d.next = self.best_written[l].q.val();
            self.out_lane[l].clock.next = self.clock.val();
            self.out_lane[l].d.next = self.out_lane[l].q.val();
        }

        // ---- The scene memory and its stream.
        self.memory.start_load.next = self.scene_start.val();
        self.memory.s_tdata.next = self.scene_tdata.val();
        self.memory.s_tvalid.next = self.scene_tvalid.val();
        self.memory.s_tlast.next = self.scene_tlast.val();
        self.scene_tready.next = self.memory.s_tready.val();
        self.scene_loaded.next = self.memory.loaded.val();
        self.scene_error.next = self.memory.error.val();
        self.scene_error_code.next = self.memory.error_code.val();
        self.scene_error_word.next = self.memory.error_word.val();
        self.scene_error_value.next = self.memory.error_value.val();

        // ---- Rays in: the lowest free slot, into the ray setup.
        for k in 0..RAY_WORDS {
            self.ray_words[k].next = self.ray_tdata.val().get_bits::<32>(32 * k);
        }
        self.free.next = !self.busy.q.val();
        self.enter.next = self.free.val() & (!self.free.val() + self.one.val());
        self.enter_slot.next = 0.into();
        for i in 0..S {
            if self.enter.val().get_bit(i) {
                self.enter_slot.next = self.slot_id[i].val();
            }
        }
        self.ray_tready.next =
            self.memory.loaded.val() & self.free.val().any() & self.reset_n.val();
        self.accept.next = self.ray_tready.val() & self.ray_tvalid.val();
        self.entering.next = 0.into();
        if self.accept.val() {
            self.entering.next = self.enter.val();
        }
        self.setup.valid_in.next = self.accept.val();
        self.setup.tag_in.next = bit_cast::<16, SB>(self.enter_slot.val());
        for k in 0..3 {
            self.setup.orig[k].next = self.ray_words[k].val();
            self.setup.dir[k].next = self.ray_words[3 + k].val();
        }
        self.setup.bound.next = self.ray_words[6].val();
        self.stacks.clear.next = self.accept.val();
        self.stacks.clear_slot.next = self.enter_slot.val();
        // The setup's answer: the slot's box words, pad and far end.
        self.setup_slot.next = bit_cast::<SB, 16>(self.setup.tag_out.val());
        self.setup_done.next = 0.into();
        if self.setup.valid_out.val() {
            self.setup_done.next = self.one.val() << self.setup_slot.val();
        }
        // Packed by shifting each word in from the top (word 0 ends lowest).
        self.setup_words.next = 0.into();
        for k in 0..3 {
            self.packed_word.next = self.setup.orig_lo[k].val();
            self.setup_words.next = (self.setup_words.val() >> 32)
                | (bit_cast::<BOX_WORDS_BITS, 32>(self.packed_word.val()) << self.box_top.val());
        }
        for k in 0..3 {
            self.packed_word.next = self.setup.orig_hi[k].val();
            self.setup_words.next = (self.setup_words.val() >> 32)
                | (bit_cast::<BOX_WORDS_BITS, 32>(self.packed_word.val()) << self.box_top.val());
        }
        for k in 0..3 {
            self.packed_word.next = self.setup.inv_dir[k].val();
            self.setup_words.next = (self.setup_words.val() >> 32)
                | (bit_cast::<BOX_WORDS_BITS, 32>(self.packed_word.val()) << self.box_top.val());
        }
        self.box_ram.write_enable.next = self.setup.valid_out.val();
        self.box_ram.write_address.next = self.setup_slot.val();
        self.box_ram.write_data.next = self.setup_words.val();
        for l in 0..self.leaf_arb.len() {
            self.pad_ram[l].write_enable.next = self.setup.valid_out.val();
            self.pad_ram[l].write_address.next = self.setup_slot.val();
            self.pad_ram[l].write_data.next = self.setup.pad.val();
        }
        // The entering ray's words for the leaf port and its id.
        self.packed_word.next = self.ray_words[9].val();
        self.ray_exclude.next = bit_cast::<INDEX_BITS, 32>(self.packed_word.val());
        self.entry_words.next =
            bit_cast::<LEAF_WORDS_BITS, LANE_WORDS_BITS>(bit_cast::<LANE_WORDS_BITS, RAY_BITS>(
                self.ray_tdata.val(),
            )) | (bit_cast::<LEAF_WORDS_BITS, INDEX_BITS>(self.ray_exclude.val())
                << self.exclude_at.val());
        for l in 0..self.leaf_arb.len() {
            self.leaf_ram[l].write_enable.next = self.accept.val();
            self.leaf_ram[l].write_address.next = self.enter_slot.val();
            self.leaf_ram[l].write_data.next = self.entry_words.val();
        }
        self.id_out_ram.write_enable.next = self.accept.val();
        self.id_out_ram.write_address.next = self.enter_slot.val();
        self.id_out_ram.write_data.next = self.ray_words[10].val();
        self.id_overflow_ram.write_enable.next = self.accept.val();
        self.id_overflow_ram.write_address.next = self.enter_slot.val();
        self.id_overflow_ram.write_data.next = self.ray_words[10].val();

        // ---- The box port: the grant reads the slot's words and its node …
        self.box_arb.request.next = self.want_box.q.val();
        self.box_grant_slot.next = 0.into();
        self.box_link.next = 0.into();
        self.box_t_hi.d.next = 0.into();
        for i in 0..S {
            if self.box_arb.grant.val().get_bit(i) {
                self.box_grant_slot.next = self.slot_id[i].val();
                self.box_t_hi.d.next = self.t_hi[i].q.val();
                self.box_link.next = self.link_first[i].q.val();
            }
        }
        self.memory.node_address.next = bit_cast::<NB, LF>(self.box_link.val());
        self.box_ram.read_address.next = self.box_grant_slot.val();
        self.box_valid.d.next = self.box_arb.grant.val().any();
        self.box_slot.d.next = self.box_grant_slot.val();
        self.box_root.d.next = (self.at_root.q.val() & self.box_arb.grant.val()).any();
        // … the next cycle the test starts (a new ray's first test is the root's box) …
        self.boxes.valid_in.next = self.box_valid.q.val();
        self.boxes.tag_in.next = bit_cast::<16, SB>(self.box_slot.q.val());
        for k in 0..3 {
            self.boxes.orig_lo[k].next = self.box_ram.read_data.val().get_bits::<32>(32 * k);
            self.boxes.orig_hi[k].next = self.box_ram.read_data.val().get_bits::<32>(32 * (3 + k));
            self.boxes.inv_dir[k].next = self.box_ram.read_data.val().get_bits::<32>(32 * (6 + k));
        }
        self.boxes.t_hi.next = self.box_t_hi.q.val();
        for j in 0..6 {
            self.boxes.min[j].next = self.memory.min[j].val();
            self.boxes.max[j].next = self.memory.max[j].val();
        }
        if self.box_root.q.val() {
            for j in 0..6 {
                self.boxes.min[j].next = self.memory.root_min[j / 2].val();
                self.boxes.max[j].next = self.memory.root_max[j / 2].val();
            }
        }
        for c in 0..2 {
            self.child_first_at[c].d.next = self.memory.child_first[c].val();
            self.child_count_at[c].d.next = self.memory.child_count[c].val();
        }
        self.root_at.d.next = self.box_root.q.val();
        // … and its answer picks the next link, pushing the farther child when both are
        // entered.
        self.box_done_slot.next = bit_cast::<SB, 16>(self.boxes.tag_out.val());
        self.box_done.next = 0.into();
        if self.boxes.valid_out.val() {
            self.box_done.next = self.one.val() << self.box_done_slot.val();
        }
        self.box_enters.next = false;
        self.box_link_first.next = 0.into();
        self.box_link_count.next = 0.into();
        self.stacks.push.next = false;
        self.stacks.push_slot.next = self.box_done_slot.val();
        self.stacks.push_data.next = 0.into();
        if self.root_at.q.val() {
            self.box_enters.next = self.boxes.enters[0].val();
            self.box_link_first.next = self.memory.root_first.val();
            self.box_link_count.next = self.memory.root_count.val();
        } else if self.boxes.enters[0].val() & self.boxes.enters[1].val() {
            self.box_enters.next = true;
            self.stacks.push.next = self.boxes.valid_out.val();
            if self.boxes.first.val() {
                self.box_link_first.next = self.child_first_at[1].q.val();
                self.box_link_count.next = self.child_count_at[1].q.val();
                self.stacks.push_data.next = (bit_cast::<W, LF>(self.child_first_at[0].q.val())
                    << self.at_first.val())
                    | (bit_cast::<W, LC>(self.child_count_at[0].q.val()) << 32)
                    | bit_cast::<W, 32>(self.boxes.near[0].val());
            } else {
                self.box_link_first.next = self.child_first_at[0].q.val();
                self.box_link_count.next = self.child_count_at[0].q.val();
                self.stacks.push_data.next = (bit_cast::<W, LF>(self.child_first_at[1].q.val())
                    << self.at_first.val())
                    | (bit_cast::<W, LC>(self.child_count_at[1].q.val()) << 32)
                    | bit_cast::<W, 32>(self.boxes.near[1].val());
            }
        } else if self.boxes.enters[0].val() {
            self.box_enters.next = true;
            self.box_link_first.next = self.child_first_at[0].q.val();
            self.box_link_count.next = self.child_count_at[0].q.val();
        } else if self.boxes.enters[1].val() {
            self.box_enters.next = true;
            self.box_link_first.next = self.child_first_at[1].q.val();
            self.box_link_count.next = self.child_count_at[1].q.val();
        }
        self.box_visit.next = self.boxes.valid_out.val() & self.box_enters.val();

        // ---- The stack port: a pop answers the next cycle.
        self.pop_arb.request.next = self.want_pop.q.val();
        self.pop_grant_slot.next = 0.into();
        self.pop_t_hi.d.next = 0.into();
        for i in 0..S {
            if self.pop_arb.grant.val().get_bit(i) {
                self.pop_grant_slot.next = self.slot_id[i].val();
                self.pop_t_hi.d.next = self.t_hi[i].q.val();
            }
        }
        self.stacks.pop.next = self.pop_arb.grant.val().any();
        self.stacks.pop_slot.next = self.pop_grant_slot.val();
        self.pop_valid.d.next = self.pop_arb.grant.val().any();
        self.pop_slot.d.next = self.pop_grant_slot.val();
        self.pop_done.next = 0.into();
        if self.pop_valid.q.val() {
            self.pop_done.next = self.one.val() << self.pop_slot.q.val();
        }
        self.pop_link_first.next =
            bit_cast::<LF, W>(self.stacks.pop_data.val() >> self.at_first.val());
        self.pop_link_count.next = bit_cast::<LC, W>(self.stacks.pop_data.val() >> 32);
        self.beyond.a.next = self.pop_t_hi.q.val();
        self.beyond.b.next = bit_cast::<32, W>(self.stacks.pop_data.val());
        self.pop_again.next = self.stacks.popped.val() & self.beyond.lt.val();
        self.pop_enters.next = self.stacks.popped.val() & !self.beyond.lt.val();

        // ---- The leaf ports, one per lane, each over its own slots (s mod lanes = l): one
        // triangle a cycle; the slot waits after its last.
        self.far_done_all.next = 0.into();
        for l in 0..self.leaf_arb.len() {
            self.leaf_arb[l].request.next = self.want_leaf.q.val() & self.lane_slots[l].val();
            self.leaf_grant[l].next = self.leaf_arb[l].grant.val();
            self.leaf_grant_slot.next = 0.into();
            self.leaf_grant_last[l].next = false;
            self.leaf_link.next = 0.into();
            for i in 0..S {
                if self.leaf_grant[l].val().get_bit(i) {
                    self.leaf_grant_slot.next = self.slot_id[i].val();
                    self.leaf_link.next = self.link_first[i].q.val();
                    self.leaf_grant_last[l].next =
                        self.link_count[i].q.val() == self.one_count.val();
                }
            }
            self.memory.triangle_address[l].next = bit_cast::<TB, LF>(self.leaf_link.val());
            self.leaf_ram[l].read_address.next = self.leaf_grant_slot.val();
            self.pad_ram[l].read_address.next = self.leaf_grant_slot.val();
            self.leaf_valid[l].d.next = self.leaf_grant[l].val().any();
            self.leaf_last[l].d.next = self.leaf_grant_last[l].val();
            self.leaf_any_hit[l].d.next = (self.any_hit.q.val() & self.leaf_grant[l].val()).any();
            self.leaf_has_exclude[l].d.next =
                (self.has_exclude.q.val() & self.leaf_grant[l].val()).any();
            // The cycle after: the triangle and the slot's words are read, the triangle is
            // tested or skipped.
            self.leaf_read.next = self.leaf_ram[l].read_data.val();
            self.leaf_words.next =
                bit_cast::<LANE_WORDS_BITS, LEAF_WORDS_BITS>(self.leaf_read.val());
            self.leaf_exclude.next = bit_cast::<INDEX_BITS, LEAF_WORDS_BITS>(
                self.leaf_read.val() >> self.exclude_at.val(),
            );
            self.skip.next = (self.leaf_any_hit[l].q.val() & !self.memory.casts_shadow[l].val())
                | (self.leaf_has_exclude[l].q.val()
                    & (self.leaf_exclude.val() == self.memory.global_index[l].val()));
            self.lane_valid[l].next = self.leaf_valid[l].q.val() & !self.skip.val();
            // The query in the lane's operand order (docs/stream.md), packed by shifting each
            // word in from the top: orig, dir, v0, v1, v2, t_min.
            self.query.next = 0.into();
            for k in 0..6 {
                self.packed_word.next = self.leaf_words.val().get_bits::<32>(32 * k);
                self.query.next = (self.query.val() >> 32)
                    | (bit_cast::<QUERY_BITS, 32>(self.packed_word.val()) << self.query_top.val());
            }
            for k in 0..9 {
                self.packed_word.next = self.memory.vert[9 * l + k].val();
                self.query.next = (self.query.val() >> 32)
                    | (bit_cast::<QUERY_BITS, 32>(self.packed_word.val()) << self.query_top.val());
            }
            self.packed_word.next = self.leaf_words.val().get_bits::<32>(224);
            self.query.next = (self.query.val() >> 32)
                | (bit_cast::<QUERY_BITS, 32>(self.packed_word.val()) << self.query_top.val());
            self.lane_query[l].next = self.query.val();
            self.t_min_at[l].d.next = self.leaf_words.val().get_bits::<32>(224);
            self.t_max_at[l].d.next = self.leaf_words.val().get_bits::<32>(192);
            self.issued_at[l].d.next = self.leaf_valid[l].q.val();
            self.tested_at[l].d.next = self.leaf_valid[l].q.val() & !self.skip.val();
            self.last_at[l].d.next = self.leaf_last[l].q.val();
            self.index_at[l].d.next = self.memory.global_index[l].val();
            self.any_hit_at[l].d.next = self.leaf_any_hit[l].q.val();
            self.pad_at[l].d.next = self.pad_ram[l].read_data.val();
            // The lane's answer, folded into its slot's nearest hit (closest-hit) or kept as
            // the first counting hit (any-hit). The nearest hit is read a cycle ahead.
            self.slot_at[l].d.next = self.leaf_grant_slot.val();
            self.best_ram[l].read_address.next = self.slot_at[l].q.val();
            self.answer_slot[l].d.next = self.slot_at[l].q.val();
            self.lane_slot.next = self.answer_slot[l].q.val();
            self.lane_done[l].next = 0.into();
            if self.issued_at[l].q.val() {
                self.lane_done[l].next = self.one.val() << self.lane_slot.val();
            }
            self.lane_best.next = self.best_ram[l].read_data.val();
            if self.best_forward[l].q.val() {
                self.lane_best.next = self.best_written[l].q.val();
            }
            self.lane_index.next = self.index_at[l].q.val();
            self.update[l].hit.next = self.lane_hit[l].val() & self.tested_at[l].q.val();
            self.update[l].t.next = self.lane_t[l].val();
            self.update[l].triangle.next = bit_cast::<32, INDEX_BITS>(self.lane_index.val());
            self.update[l].t_min.next = self.t_min_at[l].q.val();
            self.update[l].bound.next = self.t_max_at[l].q.val();
            self.update[l].best_valid.next =
                (self.best_valid.q.val() & self.lane_done[l].val()).any();
            self.update[l].best_t.next = self.lane_best.val().get_bits::<32>(0);
            self.update[l].best_triangle.next = self.lane_best.val().get_bits::<32>(96);
            self.lane_any_hit[l].next = self.any_hit_at[l].q.val();
            self.lane_take[l].next = self.update[l].closer.val();
            if self.lane_any_hit[l].val() {
                self.lane_take[l].next =
                    self.update[l].counts.val() & !self.update[l].best_valid.val();
            }
            self.lane_best_valid[l].next =
                self.update[l].best_valid.val() | self.lane_take[l].val();
            self.lane_changed[l].next =
                (self.changed.q.val() & self.lane_done[l].val()).any() | self.lane_take[l].val();
            // The nearest hit written: t, u, v, triangle (shifted in from the top).
            self.lane_written.next = 0.into();
            self.packed_word.next = self.lane_t[l].val();
            self.lane_written.next = (self.lane_written.val() >> 32)
                | (bit_cast::<BEST_BITS, 32>(self.packed_word.val()) << self.best_top.val());
            self.packed_word.next = self.lane_u[l].val();
            self.lane_written.next = (self.lane_written.val() >> 32)
                | (bit_cast::<BEST_BITS, 32>(self.packed_word.val()) << self.best_top.val());
            self.packed_word.next = self.lane_v[l].val();
            self.lane_written.next = (self.lane_written.val() >> 32)
                | (bit_cast::<BEST_BITS, 32>(self.packed_word.val()) << self.best_top.val());
            self.packed_word.next = bit_cast::<32, INDEX_BITS>(self.lane_index.val());
            self.lane_written.next = (self.lane_written.val() >> 32)
                | (bit_cast::<BEST_BITS, 32>(self.packed_word.val()) << self.best_top.val());
            self.best_ram[l].write_enable.next =
                self.lane_take[l].val() & self.issued_at[l].q.val();
            self.best_ram[l].write_address.next = self.lane_slot.val();
            self.best_ram[l].write_data.next = self.lane_written.val();
            self.best_out_ram[l].write_enable.next =
                self.lane_take[l].val() & self.issued_at[l].q.val();
            self.best_out_ram[l].write_address.next = self.lane_slot.val();
            self.best_out_ram[l].write_data.next = self.lane_written.val();
            self.best_forward[l].d.next = self.lane_take[l].val()
                & self.issued_at[l].q.val()
                & (self.lane_slot.val() == self.slot_at[l].q.val());
            self.best_written[l].d.next = self.lane_written.val();
            // After a leaf with a nearer hit: the far end of next_up(t) (t is a counting
            // hit's, so finite and not NaN).
            self.new_t.next = self.lane_best.val().get_bits::<32>(0);
            if self.lane_take[l].val() {
                self.new_t.next = self.lane_t[l].val();
            }
            if !(self.new_t.val() & self.abs_mask.val()).any() {
                self.next_up.next = 1.into();
            } else if self.new_t.val().get_bit(31) {
                self.next_up.next = self.new_t.val() - 1;
            } else {
                self.next_up.next = self.new_t.val() + 1;
            }
            self.far[l].valid_in.next = self.issued_at[l].q.val()
                & self.last_at[l].q.val()
                & !self.lane_any_hit[l].val()
                & self.lane_changed[l].val();
            self.far[l].tag_in.next = bit_cast::<16, SB>(self.lane_slot.val());
            self.far[l].bound.next = self.next_up.val();
            self.far[l].pad.next = self.pad_at[l].q.val();
            self.far_tag.next = self.far[l].tag_out.val();
            self.far_slot.next = bit_cast::<SB, 16>(self.far_tag.val());
            self.far_done[l].next = 0.into();
            if self.far[l].valid_out.val() {
                self.far_done[l].next = self.one.val() << self.far_slot.val();
            }
            self.far_done_all.next = self.far_done_all.val() | self.far_done[l].val();
        }

        // ---- The hit output: one register, refilled in the cycle it drains.
        self.out_arb.request.next = 0.into();
        if !self.out_valid.q.val() | self.hit_tready.val() {
            self.out_arb.request.next = self.want_out.q.val();
        }
        self.out_grant.next = self.out_arb.grant.val();
        self.out_grant_slot.next = 0.into();
        for i in 0..S {
            if self.out_grant.val().get_bit(i) {
                self.out_grant_slot.next = self.slot_id[i].val();
            }
        }
        self.id_out_ram.read_address.next = self.out_grant_slot.val();
        self.out_best.next = 0.into();
        for l in 0..self.leaf_arb.len() {
            self.best_out_ram[l].read_address.next = self.out_grant_slot.val();
            self.out_lane[l].d.next = (self.out_grant.val() & self.lane_slots[l].val()).any();
            // The cycle after the grant: the granted slot's lane's copy.
            if self.out_lane[l].q.val() {
                self.out_best.next = self.best_out_ram[l].read_data.val();
            }
        }
        self.out_fresh.d.next = self.out_grant.val().any();
        self.out_hit.d.next = (self.best_valid.q.val() & self.out_grant.val()).any();
        // The cycle after the grant: the answer from the RAMs' words.
        for k in 0..HIT_WORDS {
            self.hit_words[k].next = 0.into();
        }
        self.hit_words[0].next = self.id_out_ram.read_data.val();
        if self.out_hit.q.val() {
            self.hit_words[1].next = 1.into();
            self.hit_words[3].next = self.out_best.val().get_bits::<32>(0);
            self.hit_words[4].next = self.out_best.val().get_bits::<32>(32);
            self.hit_words[5].next = self.out_best.val().get_bits::<32>(64);
            self.hit_words[2].next = self.out_best.val().get_bits::<32>(96);
        }
        self.out_word.next = 0.into();
        for k in 0..HIT_WORDS {
            self.packed_word.next = self.hit_words[k].val();
            self.out_word.next = (self.out_word.val() >> 32)
                | (bit_cast::<HIT_BITS, 32>(self.packed_word.val()) << self.hit_top.val());
        }
        if self.hit_tready.val() {
            self.out_valid.d.next = false;
        }
        if self.out_grant.val().any() {
            self.out_valid.d.next = true;
        }
        self.hit_tvalid.next = self.out_valid.q.val();
        self.hit_tdata.next = self.out_data.q.val();
        if self.out_fresh.q.val() {
            self.hit_tdata.next = self.out_word.val();
        }
        self.out_data.d.next = self.hit_tdata.val();

        // ---- The slots' states: each writer targets slots in its own state.
        self.next_busy.next = (self.busy.q.val() & !self.out_grant.val()) | self.entering.val();
        self.next_box.next = self.want_box.q.val() & !self.box_arb.grant.val();
        self.next_leaf.next = self.want_leaf.q.val();
        for l in 0..self.leaf_arb.len() {
            if self.leaf_grant_last[l].val() {
                self.next_leaf.next = self.next_leaf.val() & !self.leaf_grant[l].val();
            }
        }
        self.next_pop.next =
            (self.want_pop.q.val() & !self.pop_arb.grant.val()) | self.far_done_all.val();
        self.next_out.next = self.want_out.q.val() & !self.out_grant.val();
        self.next_changed.next = self.changed.q.val() & !self.entering.val();
        self.next_best_valid.next = self.best_valid.q.val() & !self.entering.val();
        // A set-up ray tests the root's box; an empty scene answers a miss at once.
        if self.memory.triangles.val().any() {
            self.next_box.next = self.next_box.val() | self.setup_done.val();
        } else {
            self.next_out.next = self.next_out.val() | self.setup_done.val();
        }
        // The box answer: a node or a leaf entered, else a pop (for the root: the end).
        if self.box_enters.val() {
            if self.box_link_count.val().any() {
                self.next_leaf.next = self.next_leaf.val() | self.box_done.val();
            } else {
                self.next_box.next = self.next_box.val() | self.box_done.val();
            }
        } else if self.root_at.q.val() {
            self.next_out.next = self.next_out.val() | self.box_done.val();
        } else {
            self.next_pop.next = self.next_pop.val() | self.box_done.val();
        }
        // The pop's answer: an entry entered, one beyond the far end (pop again), the end.
        if self.pop_enters.val() {
            if self.pop_link_count.val().any() {
                self.next_leaf.next = self.next_leaf.val() | self.pop_done.val();
            } else {
                self.next_box.next = self.next_box.val() | self.pop_done.val();
            }
        } else if self.pop_again.val() {
            self.next_pop.next = self.next_pop.val() | self.pop_done.val();
        } else {
            self.next_out.next = self.next_out.val() | self.pop_done.val();
        }
        // The lanes' answers (each for a slot of its own); after a leaf's last: out (an
        // any-hit ray with a hit), the far end (a nearer hit; it then pops), else a pop.
        for l in 0..self.leaf_arb.len() {
            if self.lane_take[l].val() {
                self.next_best_valid.next = self.next_best_valid.val() | self.lane_done[l].val();
                if !self.lane_any_hit[l].val() {
                    self.next_changed.next = self.next_changed.val() | self.lane_done[l].val();
                }
            }
            if self.issued_at[l].q.val() & self.last_at[l].q.val() {
                self.next_changed.next = self.next_changed.val() & !self.lane_done[l].val();
                if self.lane_any_hit[l].val() & self.lane_best_valid[l].val() {
                    self.next_out.next = self.next_out.val() | self.lane_done[l].val();
                } else if self.lane_any_hit[l].val() | !self.lane_changed[l].val() {
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
        // The entering slot takes the ray's flag; the others keep theirs. (Written without
        // reading `.d` back: rust-hdl's simulator returns its previous settled value there.)
        if self.ray_words[8].val().get_bit(0) {
            self.any_hit.d.next = self.any_hit.q.val() | self.entering.val();
        } else {
            self.any_hit.d.next = self.any_hit.q.val() & !self.entering.val();
        }
        if self.ray_words[8].val().get_bit(1) {
            self.has_exclude.d.next = self.has_exclude.q.val() | self.entering.val();
        } else {
            self.has_exclude.d.next = self.has_exclude.q.val() & !self.entering.val();
        }

        // ---- The slots' flip-flop words.
        for i in 0..S {
            if self.setup_done.val().get_bit(i) {
                self.t_hi[i].d.next = self.setup.t_hi.val();
            }
            for l in 0..self.leaf_arb.len() {
                if self.far_done[l].val().get_bit(i) {
                    self.t_hi[i].d.next = self.far[l].t_hi.val();
                }
            }
            if self.box_visit.val() & self.box_done.val().get_bit(i) {
                self.link_first[i].d.next = self.box_link_first.val();
                self.link_count[i].d.next = self.box_link_count.val();
            }
            if self.pop_enters.val() & self.pop_done.val().get_bit(i) {
                self.link_first[i].d.next = self.pop_link_first.val();
                self.link_count[i].d.next = self.pop_link_count.val();
            }
            for l in 0..self.leaf_arb.len() {
                if self.leaf_grant[l].val().get_bit(i) {
                    self.link_first[i].d.next = self.link_first[i].q.val() + 1;
                    self.link_count[i].d.next = self.link_count[i].q.val() - 1;
                }
            }
        }

        // ---- The leaf advance's entry distances (none without it).
        for i in 0..self.link_entry.len() {
            self.link_entry[i].clock.next = self.clock.val();
            self.link_entry[i].d.next = self.link_entry[i].q.val();
            // The entered child's (the root's box is child 0), as `box_link_first` picks it.
            if self.box_visit.val() & self.box_done.val().get_bit(i) {
                if self.root_at.q.val()
                    | (self.boxes.enters[0].val()
                        & !(self.boxes.enters[1].val() & self.boxes.first.val()))
                {
                    self.link_entry[i].d.next = self.boxes.near[0].val();
                } else {
                    self.link_entry[i].d.next = self.boxes.near[1].val();
                }
            }
            if self.pop_enters.val() & self.pop_done.val().get_bit(i) {
                self.link_entry[i].d.next = bit_cast::<32, W>(self.stacks.pop_data.val());
            }
        }
        for l in 0..self.leaf_entry.len() {
            self.leaf_entry[l].clock.next = self.clock.val();
            self.leaf_entry[l].d.next = self.leaf_entry[l].q.val();
            for i in 0..self.link_entry.len() {
                if self.leaf_grant[l].val().get_bit(i) {
                    self.leaf_entry[l].d.next = self.link_entry[i].q.val();
                }
            }
            self.lane_entry[l].next = self.leaf_entry[l].q.val();
        }

        // ---- Status and counters.
        self.overflow_q.d.next = self.overflow_q.q.val();
        self.overflow_ray_q.d.next = self.overflow_ray_q.q.val();
        // The pushing slot's id is read with the push, ready when the stack reports the drop.
        self.id_overflow_ram.read_address.next = self.box_done_slot.val();
        if self.stacks.dropped.val() & !self.overflow_q.q.val() {
            self.overflow_q.d.next = true;
            self.overflow_ray_q.d.next = self.id_overflow_ram.read_data.val();
        }
        if self.accept.val() {
            self.rays.d.next = self.rays.q.val() + 1;
        }
        if self.box_arb.grant.val().any() {
            self.box_tests.d.next = self.box_tests.q.val() + 1;
        }
        self.mt_count.next = self.mt_tests.q.val();
        for l in 0..self.leaf_arb.len() {
            if self.lane_valid[l].val() {
                self.mt_count.next = self.mt_count.val() + 1;
            }
        }
        self.mt_tests.d.next = self.mt_count.val();
        if self.box_visit.val() & self.pop_enters.val() {
            self.node_visits.d.next = self.node_visits.q.val() + 2;
        } else if self.box_visit.val() | self.pop_enters.val() {
            self.node_visits.d.next = self.node_visits.q.val() + 1;
        }
        if self.busy.q.val().any() {
            self.busy_cycles.d.next = self.busy_cycles.q.val() + 1;
        }
        if !self.reset_n.val() {
            self.busy.d.next = 0.into();
            self.want_box.d.next = 0.into();
            self.want_leaf.d.next = 0.into();
            self.want_pop.d.next = 0.into();
            self.want_out.d.next = 0.into();
            self.out_valid.d.next = false;
            self.overflow_q.d.next = false;
            self.rays.d.next = 0.into();
            self.node_visits.d.next = 0.into();
            self.box_tests.d.next = 0.into();
            self.mt_tests.d.next = 0.into();
            self.busy_cycles.d.next = 0.into();
        }
        self.idle.next = !self.busy.q.val().any() & !self.out_valid.q.val();
        self.overflow.next = self.overflow_q.q.val();
        self.overflow_ray.next = self.overflow_ray_q.q.val();
        self.count_rays.next = self.rays.q.val();
        self.count_node_visits.next = self.node_visits.q.val();
        self.count_box_tests.next = self.box_tests.q.val();
        self.count_mt_tests.next = self.mt_tests.q.val();
        self.count_busy_cycles.next = self.busy_cycles.q.val();
    }
}

/// The core at each scene memory size the XC7Z020 takes (`scene_memory`'s aliases), with 32
/// slots (`timing::DEFAULT_SLOTS`) and stack RAMs of 1,024 entries (32 a slot at most);
/// `unit_top` puts a lane beside it.
pub type TraversalCore4x5 =
    TraversalCore<4, 5, 5, 6, 406, { triangle_record_bits() }, 32, 5, 6, 10, 43>;
pub type TraversalCore9x10 =
    TraversalCore<9, 10, 10, 11, 426, { triangle_record_bits() }, 32, 5, 6, 10, 53>;
pub type TraversalCore11x12 =
    TraversalCore<11, 12, 12, 13, 434, { triangle_record_bits() }, 32, 5, 6, 10, 57>;
pub type TraversalCore12x13 =
    TraversalCore<12, 13, 13, 14, 438, { triangle_record_bits() }, 32, 5, 6, 10, 59>;

/// The (node, triangle) address bits of the scene memories built, one per alias above.
pub const BUILT_MEMORY_BITS: [(usize, usize); 4] = [(4, 5), (9, 10), (11, 12), (12, 13)];

/// Slots of every built unit, and the deepest stack its stack RAM holds.
pub const UNIT_SLOTS: usize = super::timing::DEFAULT_SLOTS;
// The aliases (here and in `unit_top`) spell S = 32, SB = 5 as numbers.
const _: () = assert!(UNIT_SLOTS == 32);
pub const MAX_STACK_DEPTH: usize = 32;
/// Lanes a unit is built with at most: the box port is the unit's bottleneck (87–99 % busy
/// with one lane), so more lanes add area and no speed.
pub const MAX_LANES: usize = 3;

/// What a unit is built from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitConfig {
    pub format: HwFormat,
    pub depth: usize,
    pub lanes: usize,
    pub slots: usize,
    pub stack_depth: usize,
    pub memory: MemoryConfig,
    /// Where the lanes start a leaf's queries: `None` or `LeafBox` (`leaf_advance::AroundLane`
    /// around every lane).
    pub advance: Advance,
}

/// A configuration the RTL does not build.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum UnitConfigError {
    #[error("{0} Möller-Trumbore lanes: the traversal unit is built with 1 to {MAX_LANES}")]
    Lanes(usize),
    #[error("depth = {depth}: format {format} has pipeline registers for depth 0 to {max}")]
    Depth {
        format: HwFormat,
        depth: usize,
        max: usize,
    },
    #[error("the traversal unit's RTL has {UNIT_SLOTS} ray slots, not {0}")]
    Slots(usize),
    #[error("a stack of {0} entries: the unit's stacks hold 1 to {MAX_STACK_DEPTH}")]
    StackDepth(usize),
    #[error("the traversal unit's RTL advances to the leaf box (leaf-box) or not at all (none), not {}", .0.name())]
    Advance(Advance),
    #[error("no scene memory of {node_bits} node and {triangle_bits} triangle address bits is built (sizes: {})", built_memory_bits())]
    Memory {
        node_bits: usize,
        triangle_bits: usize,
    },
}

impl UnitConfig {
    /// `slots` and `stack_depth` at their defaults, the scene memory that fits the XC7Z020
    /// beside `lanes` lanes.
    pub fn new(format: HwFormat, depth: usize, lanes: usize) -> UnitConfig {
        let (node_bits, triangle_bits) = zynq_address_bits(lanes);
        UnitConfig {
            format,
            depth,
            lanes,
            slots: UNIT_SLOTS,
            stack_depth: hw_model::traversal::DEFAULT_STACK_DEPTH,
            memory: MemoryConfig {
                node_bits,
                triangle_bits,
            },
            advance: Advance::None,
        }
    }

    /// The unit's timing, as the schedule model takes it.
    pub fn timing(&self) -> UnitTiming {
        unit_timing(
            self.format,
            self.depth,
            self.lanes,
            self.slots,
            self.advance,
        )
    }

    /// Whether the RTL builds this configuration.
    pub fn check(&self) -> Result<(), UnitConfigError> {
        if !(1..=MAX_LANES).contains(&self.lanes) {
            return Err(UnitConfigError::Lanes(self.lanes));
        }
        let max = crate::mt::max_depth(self.format);
        if self.depth > max {
            return Err(UnitConfigError::Depth {
                format: self.format,
                depth: self.depth,
                max,
            });
        }
        if self.slots != UNIT_SLOTS {
            return Err(UnitConfigError::Slots(self.slots));
        }
        if !(1..=MAX_STACK_DEPTH).contains(&self.stack_depth) {
            return Err(UnitConfigError::StackDepth(self.stack_depth));
        }
        if self.advance == Advance::TriangleBox {
            return Err(UnitConfigError::Advance(self.advance));
        }
        match (self.memory.node_bits, self.memory.triangle_bits) {
            bits if BUILT_MEMORY_BITS.contains(&bits) => Ok(()),
            (node_bits, triangle_bits) => Err(UnitConfigError::Memory {
                node_bits,
                triangle_bits,
            }),
        }
    }
}

/// [`BUILT_MEMORY_BITS`] as "4/5, 9/10, …".
fn built_memory_bits() -> String {
    let sizes: Vec<String> = BUILT_MEMORY_BITS
        .iter()
        .map(|(n, t)| format!("{n}/{t}"))
        .collect();
    sizes.join(", ")
}

/// The unit's Verilog (rust-hdl's, top module `top`): the core and the lane of the
/// configuration's format (`unit_top`).
pub fn unit_verilog(config: &UnitConfig) -> Result<String, UnitConfigError> {
    config.check()?;
    let config = *config;
    Ok(with_build_stack(move || super::unit_top::verilog(&config)))
}
