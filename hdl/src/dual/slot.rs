//! One slot of a dual-precision pair ([`super::pair`]): a filter lane ([`SlotFilter`]: the
//! bfp filter, or the Plücker filter fed the query's stored vectors;
//! [`super::slot_filter`]) and the queue of the queries it forwards.
//!
//! A query (fp32 words, the register map's order: orig, dir, v0, v1, v2, t_min), its tag
//! and, for a Plücker slot, its operands ([`super::plucker_operands`]) are taken when
//! `valid`. A certain miss comes out on `miss_valid`/`miss_tag` the filter's latency
//! ([`miss_latency`]) after it; every other query joins the queue, whose head shows on `head` while
//! `has_query`, and leaves it on `read`. `full` says the slot holds [`QUEUE_DEPTH`] queries
//! (in its filter and its queue together: a credit count), so a caller that takes no query
//! while it is set never overflows the queue.
//!
//! No reset: the count and the queue start from the flip-flops' power-on zeros.

use rust_hdl::prelude::*;

use super::plucker_operands::OPERAND_BITS;
pub use super::slot_filter::SlotFilter;
use super::slot_filter::{BfpWords, PluckerWords};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::regmap::OPERAND_COUNT;
use crate::top::stream::{QUERY_BITS, TAG_BITS};

/// Bits of a query's tag (the stream front end's).
pub const TAG: usize = TAG_BITS as usize;
/// A queued query: its operands (the register map's order) and its tag above them.
pub const ENTRY_BITS: usize = QUERY_BITS + TAG;
/// Address bits of the forward queue.
pub const QUEUE_ADDR_BITS: usize = 5;
/// Queries a slot may hold in its filter and its queue together.
pub const QUEUE_DEPTH: usize = 1 << QUEUE_ADDR_BITS;
/// Width of the credit count (0 to `QUEUE_DEPTH`).
const PENDING_BITS: usize = QUEUE_ADDR_BITS + 1;
// The kernel spells the operands' and the tag's places as literals.
const _: () = assert!(QUERY_BITS == 512 && TAG == 24 && OPERAND_COUNT == 16);

/// The forward queue (rust-hdl's FIFO: `data_out` shows the head while not `empty`).
type ForwardQueue = SynchronousFIFO<Bits<ENTRY_BITS>, QUEUE_ADDR_BITS, PENDING_BITS, 1>;

/// Clock edges from a query to its `miss_valid`: the filter's latency.
pub const fn miss_latency(kind: SlotFilter) -> usize {
    kind.latency()
}

/// Clock edges from a forwarded query to its `has_query` when the queue was empty: the
/// filter's, then the queue's write and the read of its memory.
pub const fn queued_latency(kind: SlotFilter) -> usize {
    miss_latency(kind) + 2
}

#[derive(LogicBlock)]
pub struct FilterSlot {
    pub clock: Signal<In, Clock>,
    pub valid: Signal<In, Bit>,
    pub query: Signal<In, Bits<QUERY_BITS>>,
    pub tag: Signal<In, Bits<TAG>>,
    /// The query's Plücker operands (read by a Plücker slot only).
    pub operands: Signal<In, Bits<OPERAND_BITS>>,
    /// A certain miss (no hit, t = u = v = 0) and its tag.
    pub miss_valid: Signal<Out, Bit>,
    pub miss_tag: Signal<Out, Bits<TAG>>,
    /// The queue's head (query and tag) while `has_query`; `read` takes it.
    pub has_query: Signal<Out, Bit>,
    pub head: Signal<Out, Bits<ENTRY_BITS>>,
    pub read: Signal<In, Bit>,
    /// The slot holds `QUEUE_DEPTH` queries: take none.
    pub full: Signal<Out, Bit>,
    /// The slot's one filter: a bfp filter or a Plücker filter (the other list is empty).
    bfp: Vec<BfpWords>,
    plucker: Vec<PluckerWords>,
    /// The query and tag wait beside the filter for its decision.
    held: Delay<Bits<ENTRY_BITS>>,
    queue: ForwardQueue,
    pending: DFF<Bits<PENDING_BITS>>,
    queue_depth: Constant<Bits<PENDING_BITS>>,
    /// The credit count while it is updated.
    count: Signal<Local, Bits<PENDING_BITS>>,
    /// The filter's decision: out (`valid_out`), a certain miss, forwarded.
    decided: Signal<Local, Bit>,
    certain: Signal<Local, Bit>,
    uncertain: Signal<Local, Bit>,
}

impl FilterSlot {
    pub fn new(kind: SlotFilter) -> Self {
        let one_if = |on: bool| usize::from(on);
        Self {
            clock: Default::default(),
            valid: Default::default(),
            query: Default::default(),
            tag: Default::default(),
            operands: Default::default(),
            miss_valid: Default::default(),
            miss_tag: Default::default(),
            has_query: Default::default(),
            head: Default::default(),
            read: Default::default(),
            full: Default::default(),
            bfp: crate::defaults(one_if(kind == SlotFilter::Bfp)),
            plucker: crate::defaults(one_if(kind == SlotFilter::Plucker)),
            held: Delay::new(miss_latency(kind)),
            queue: Default::default(),
            pending: Default::default(),
            queue_depth: Constant::new((QUEUE_DEPTH as u64).to_bits()),
            count: Default::default(),
            decided: Default::default(),
            certain: Default::default(),
            uncertain: Default::default(),
        }
    }
}

impl Logic for FilterSlot {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, held, queue, pending);
        self.decided.next = false;
        self.certain.next = false;
        self.uncertain.next = false;
        for i in 0..self.bfp.len() {
            clock!(self, clock, bfp[i]);
            self.bfp[i].valid.next = self.valid.val();
            self.bfp[i].query.next = self.query.val();
            self.decided.next = self.bfp[i].valid_out.val();
            self.certain.next = self.bfp[i].miss.val();
            self.uncertain.next = self.bfp[i].forward.val();
        }
        for i in 0..self.plucker.len() {
            clock!(self, clock, plucker[i]);
            self.plucker[i].valid.next = self.valid.val();
            self.plucker[i].query.next = self.query.val();
            self.plucker[i].operands.next = self.operands.val();
            self.decided.next = self.plucker[i].valid_out.val();
            self.certain.next = self.plucker[i].miss.val();
            self.uncertain.next = self.plucker[i].forward.val();
        }
        self.held.d.next = bit_cast::<ENTRY_BITS, QUERY_BITS>(self.query.val())
            | (bit_cast::<ENTRY_BITS, TAG>(self.tag.val()) << 512);
        // Out of the filter: a certain miss is answered, the rest queued.
        self.miss_valid.next = self.decided.val() & self.certain.val();
        self.miss_tag.next = self.held.q.val().get_bits::<TAG>(512);
        self.queue.write.next = self.decided.val() & self.uncertain.val();
        self.queue.data_in.next = self.held.q.val();
        self.has_query.next = !self.queue.empty.val();
        self.head.next = self.queue.data_out.val();
        self.queue.read.next = self.read.val();
        // Credits: one per query taken, back when it is answered or leaves the queue.
        self.count.next = self.pending.q.val();
        if self.valid.val() {
            self.count.next = self.count.val() + 1;
        }
        if self.miss_valid.val() {
            self.count.next = self.count.val() - 1;
        }
        if self.read.val() & !self.queue.empty.val() {
            self.count.next = self.count.val() - 1;
        }
        self.pending.d.next = self.count.val();
        self.full.next = self.pending.q.val() >= self.queue_depth.val();
    }
}
