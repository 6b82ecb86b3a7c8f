//! A dual-precision lane pair: `N` filter lanes (bfp, or Plücker: [`SlotFilter`]) share one
//! fp32 Möller-Trumbore lane.
//!
//! Each slot ([`FilterSlot`]) takes one query a cycle. A certain miss is answered at once,
//! [`miss_latency`] after the query, on the slot's `miss_*` port; every other query waits in
//! its slot's forward queue for the fp32 lane, which takes one a cycle from the queues in
//! round-robin order ([`RoundRobin`]) and answers on the `fp_*` port. The answers are the
//! model's `DualIntersector` (pair bfp18/fp32, filter bfp or plucker-signs) bit for bit: a certain miss is
//! `MtResult::default()` (no hit, t = u = v = 0), the rest the fp32 lane's result.
//!
//! Answers leave out of order, each with the `tag` its query came with. The fp32 lane
//! serves a forwarded share f of N query streams, so the pair keeps one query a slot per
//! cycle while N·f < 1 on average; the queues absorb the bursts and `ready` holds the inputs
//! back when they do not suffice: it falls while some slot holds [`QUEUE_DEPTH`] queries.
//!
//! No reset, like the lanes: the slots and the arbiter start from the flip-flops' power-on
//! zeros.

use rust_hdl::prelude::*;

use super::plucker_operands::OPERAND_BITS;
pub use super::slot::{miss_latency, SlotFilter, QUEUE_DEPTH, TAG};
use super::slot::{queued_latency, FilterSlot, ENTRY_BITS};
use crate::formats::fp32;
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::regmap::OPERAND_COUNT;
use crate::top::stream::QUERY_BITS;
use crate::traversal::arbiter::RoundRobin;

// The kernel spells the entry's layout as literals.
const _: () = assert!(QUERY_BITS == 512 && TAG == 24 && OPERAND_COUNT == 16);

/// Clock edges from a forwarded query to its answer when it finds its queue empty and the
/// fp32 lane free (more while the lane serves other slots): to the queue's head, then the
/// fp32 lane at `depth`.
pub fn forward_latency(kind: SlotFilter, depth: usize) -> usize {
    queued_latency(kind) + fp32::MtLane::latency(depth)
}

/// `N` filter slots and one fp32 lane at pipeline depth `depth` (`DualPair::new`).
#[derive(LogicBlock)]
pub struct DualPair<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Per slot: a query (fp32 words, the register map's order: orig, dir, v0, v1, v2,
    /// t_min) and its tag, taken when `valid` and `ready`.
    pub valid: Vec<Signal<In, Bit>>,
    pub query: Vec<Signal<In, Bits<QUERY_BITS>>>,
    pub tag: Vec<Signal<In, Bits<TAG>>>,
    /// Per slot of a Plücker pair (none in a bfp pair): the query's operands
    /// (`plucker_operands`).
    pub operands: Vec<Signal<In, Bits<OPERAND_BITS>>>,
    /// Every slot has room for one more query (the same for all slots).
    pub ready: Signal<Out, Bit>,
    /// Per slot: the filter's certain misses (no hit, t = u = v = 0).
    pub miss_valid: Vec<Signal<Out, Bit>>,
    pub miss_tag: Vec<Signal<Out, Bits<TAG>>>,
    /// The fp32 lane's answers to forwarded queries.
    pub fp_valid: Signal<Out, Bit>,
    pub fp_tag: Signal<Out, Bits<TAG>>,
    pub fp_hit: Signal<Out, Bit>,
    pub fp_t: Signal<Out, Bits<32>>,
    pub fp_u: Signal<Out, Bits<32>>,
    pub fp_v: Signal<Out, Bits<32>>,
    slots: Vec<FilterSlot>,
    arbiter: RoundRobin<N>,
    lane: fp32::MtLane,
    /// The tag waits beside the fp32 lane.
    lane_tag: Delay<Bits<TAG>>,
    /// Slot i's bit in the arbiter's vectors, 1 << i (rust-hdl emits a bit select of a
    /// one-bit vector, which Verilog does not take, so the slots' bits are masks).
    slot_bit: Vec<Constant<Bits<N>>>,
    has_room: Signal<Local, Bit>,
    /// The slots whose queue holds a query (a local: a block's input does not accumulate
    /// in rust-hdl's simulation).
    requests: Signal<Local, Bits<N>>,
    /// The entry the arbiter granted.
    granted: Signal<Local, Bits<ENTRY_BITS>>,
}

impl<const N: usize> DualPair<N> {
    pub fn new(depth: usize, kind: SlotFilter) -> Self {
        assert!(
            (1..=64).contains(&N),
            "a dual pair has 1 to 64 filter slots"
        );
        Self {
            clock: Default::default(),
            valid: crate::defaults(N),
            query: crate::defaults(N),
            tag: crate::defaults(N),
            operands: crate::defaults(if kind == SlotFilter::Plucker { N } else { 0 }),
            ready: Default::default(),
            miss_valid: crate::defaults(N),
            miss_tag: crate::defaults(N),
            fp_valid: Default::default(),
            fp_tag: Default::default(),
            fp_hit: Default::default(),
            fp_t: Default::default(),
            fp_u: Default::default(),
            fp_v: Default::default(),
            slots: (0..N).map(|_| FilterSlot::new(kind)).collect(),
            arbiter: Default::default(),
            lane: fp32::MtLane::new(depth),
            lane_tag: Delay::new(fp32::MtLane::latency(depth)),
            slot_bit: (0..N)
                .map(|i| Constant::new((1u64 << i).to_bits()))
                .collect(),
            has_room: Default::default(),
            requests: Default::default(),
            granted: Default::default(),
        }
    }
}

impl<const N: usize> Logic for DualPair<N> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, arbiter, lane, lane_tag);
        // Room in every slot: the inputs are taken in this cycle if valid.
        self.has_room.next = true;
        for i in 0..N {
            if self.slots[i].full.val() {
                self.has_room.next = false;
            }
        }
        self.ready.next = self.has_room.val();
        self.requests.next = 0.into();
        for i in 0..N {
            clock!(self, clock, slots[i]);
            self.slots[i].valid.next = self.valid[i].val() & self.has_room.val();
            self.slots[i].query.next = self.query[i].val();
            self.slots[i].tag.next = self.tag[i].val();
            self.slots[i].operands.next = 0.into();
            self.miss_valid[i].next = self.slots[i].miss_valid.val();
            self.miss_tag[i].next = self.slots[i].miss_tag.val();
            if self.slots[i].has_query.val() {
                self.requests.next = self.requests.val() | self.slot_bit[i].val();
            }
        }
        for i in 0..self.operands.len() {
            self.slots[i].operands.next = self.operands[i].val();
        }
        // The fp32 lane takes the granted slot's head.
        self.arbiter.request.next = self.requests.val();
        self.granted.next = 0.into();
        for i in 0..N {
            self.slots[i].read.next = (self.arbiter.grant.val() & self.slot_bit[i].val()).any();
            if (self.arbiter.grant.val() & self.slot_bit[i].val()).any() {
                self.granted.next = self.slots[i].head.val();
            }
        }
        self.lane.valid_in.next = self.arbiter.grant.val().any();
        for k in 0..OPERAND_COUNT {
            self.lane.query[k].next = self.granted.val().get_bits::<32>(k * 32);
        }
        self.lane_tag.d.next = self.granted.val().get_bits::<TAG>(512);
        self.fp_valid.next = self.lane.valid_out.val();
        self.fp_tag.next = self.lane_tag.q.val();
        self.fp_hit.next = self.lane.hit.val();
        self.fp_t.next = self.lane.t.val();
        self.fp_u.next = self.lane.u.val();
        self.fp_v.next = self.lane.v.val();
    }
}

/// Verilog of a pair of `N` filter lanes of `kind` and an fp32 lane at `depth`, top module
/// `top`.
pub fn dual_pair_verilog<const N: usize>(depth: usize, kind: SlotFilter) -> String {
    crate::top::with_build_stack(move || {
        let mut pair = DualPair::<N>::new(depth, kind);
        pair.connect_all();
        generate_verilog(&pair)
    })
}
