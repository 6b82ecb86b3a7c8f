//! The traversal core walking wide nodes (`--nodes bvh2-q8 | bvh4-q8 | bvh8-q8`): the binary
//! core's blocks ([`super::unit`]: ray entry, slots, leaf ports, hit output, counters) around
//! the wide scene memory, the wide box port and the wide stack port. Bit for bit
//! `hw_model::traversal::TraversalModel` walking a `UnitImage::Wide` (answers and counters).
//!
//! ```text
//!  ray stream ─► RayEntry ─► WideSetUp (pad_t) ──► SetUp: slots, box port, leaf ports
//!   BoxPort    node read + WideBoxStage ─► LinkStep; push of up to K − 1 ─► StackPort
//!   StackPort  BankedStacks: pop, t_hi < t0? ─► LinkStep, entry word ─► BoxPort
//!   LeafPort l, HitOutput, Counters: as the binary core's
//! ```
//!
//! A new ray's walk starts at the root node (node 0) entered at 0, unbounded: its first box
//! test is the root node's, counted as a node visit at its grant.

use rust_hdl::prelude::*;

use super::config::MAX_LANES;
use super::counters::Counters;
use super::hit_output::HitOutput;
use super::leaf_port::LeafPort;
use super::ports::{ControlPort, CounterPort, HitStream, RayStream, SceneStream};
use super::ray_entry::RayEntry;
use super::scene_records::WIDE_COUNT_BITS;
use super::slot_ports::{
    BoxGrantSource, EnteredSource, LeafGrantSource, LeafStep, LinkStep, OutGrantSource,
    PopGrantSource, SetUpSource,
};
use super::slots::SlotState;
use super::unit::{core_logic, core_new};
use super::wide_box_port::WideBoxPort;
use super::wide_scene_memory::WideSceneMemory;
use super::wide_set_up::WideSetUp;
use super::wide_stack_port::WideStackPort;
use crate::defaults;
use crate::macros::clock;
use crate::mt::LanePort;

/// The wide core. Const parameters (computed by [`wide_unit_sized!`]): the wide scene
/// memory's `NB, TB, LF, LK, HB, LB, NW, TW` (see [`WideSceneMemory`]); `S` slots of `SB`
/// bits; the banked stacks' pointer bits `PB` and bank address bits `RB`; a stack entry of
/// `W` bits (`wide_box_port::wide_stack_entry_bits`).
#[derive(LogicBlock)]
pub struct WideTraversalCore<
    const NB: usize,
    const TB: usize,
    const LF: usize,
    const LK: usize,
    const HB: usize,
    const LB: usize,
    const NW: usize,
    const TW: usize,
    const S: usize,
    const SB: usize,
    const PB: usize,
    const RB: usize,
    const W: usize,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active low: empties the slots, clears the overflow bit and the counters.
    pub reset_n: Signal<In, Bit>,
    pub scene: SceneStream,
    pub ray: RayStream,
    pub hit: HitStream,
    pub control: ControlPort,
    pub counters: CounterPort,
    /// The Möller-Trumbore lanes, outside the core (as the binary core's).
    pub lane: Vec<LanePort>,
    /// With the leaf advance (else none): the entry t0 of the query's leaf.
    pub lane_entry: Vec<Signal<Out, Bits<32>>>,
    memory: WideSceneMemory<NB, TB, LF, LK, HB, LB, NW, TW>,
    entry: RayEntry<SB>,
    wide_set_up: WideSetUp<SB>,
    slots: SlotState<S, SB, LF, WIDE_COUNT_BITS>,
    box_port: WideBoxPort<S, SB, NB, LF, LK, W>,
    stack_port: WideStackPort<S, SB, PB, RB, W, LF>,
    leaf: Vec<LeafPort<SB, TB, LF>>,
    hits: HitOutput<SB>,
    counting: Counters,
}

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LK: usize,
        const HB: usize,
        const LB: usize,
        const NW: usize,
        const TW: usize,
        const S: usize,
        const SB: usize,
        const PB: usize,
        const RB: usize,
        const W: usize,
    > WideTraversalCore<NB, TB, LF, LK, HB, LB, NW, TW, S, SB, PB, RB, W>
{
    /// A core for nodes of `width` children; the rest as `unit::TraversalCore::new`'s.
    pub fn new(
        width: usize,
        depth: usize,
        stack_depth: usize,
        lanes: usize,
        lane_latency: usize,
        entries: bool,
    ) -> Self {
        assert!(
            (1..=MAX_LANES).contains(&lanes),
            "{lanes} lanes: 1 to {MAX_LANES}"
        );
        core_new!(lanes, lane_latency, entries, depth, {
            memory: WideSceneMemory::new(width, lanes),
            wide_set_up: WideSetUp::new(depth),
            box_port: WideBoxPort::new(width, depth),
            stack_port: WideStackPort::new(width, stack_depth),
            counting: Counters::wide(lanes),
        })
    }
}

core_logic! {
    #[hdl_gen]
    self,
    WideTraversalCore<NB, TB, LF, LK, HB, LB, NW, TW, S, SB, PB, RB, W>,
    count: WIDE_COUNT_BITS,
    clocked: { memory, entry, wide_set_up, slots, box_port, stack_port, hits, counting },
    entered: {
        EnteredSource::<SB>::join(&mut self.entry.entered, &mut self.box_port.entered);
    },
    set_up: {
        SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.wide_set_up.fp32);
        SetUpSource::<SB>::join(&mut self.wide_set_up.set_up, &mut self.slots.set_up);
        SetUpSource::<SB>::join(&mut self.wide_set_up.set_up, &mut self.box_port.set_up);
    },
    leaf_set_up: { self.wide_set_up.set_up },
    box_port: {
        for a in 0..3 {
            self.box_port.origin[a].next = self.memory.origin[a].val();
            self.box_port.exp[a].next = self.memory.exp[a].val();
        }
        self.box_port.children.next = self.memory.children.val();
        for i in 0..self.box_port.lo.len() {
            self.box_port.lo[i].next = self.memory.lo[i].val();
            self.box_port.hi[i].next = self.memory.hi[i].val();
        }
        for c in 0..self.box_port.link.len() {
            self.box_port.link[c].next = self.memory.link[c].val();
        }
    },
    push: {
        self.stack_port.push_count.next = self.box_port.push_count.val();
        self.stack_port.push_slot.next = self.box_port.push_slot.val();
        for j in 0..self.box_port.push_data.len() {
            self.stack_port.push_data[j].next = self.box_port.push_data[j].val();
        }
    },
    // An entered pop's entry word goes to the box port.
    stack_port: {
        self.box_port.popped.next =
            self.stack_port.step.valid.val() & self.stack_port.step.enter.val();
        self.box_port.popped_slot.next = self.stack_port.step.slot.val();
        self.box_port.popped_entry.next = self.stack_port.step_entry.val();
    },
    // The root node's visit at its grant.
    counters: {
        for r in 0..self.counting.root_visit.len() {
            self.counting.root_visit[r].next =
                self.slots.box_grant.valid.val() & self.slots.box_grant.root.val();
        }
    },
}

/// `$block` (the wide core, or the unit top over it) for `$k`-wide nodes with a scene memory
/// of `$nb` node and `$tb` triangle address bits, every width parameter computed: the
/// memory's, [`WIDE_SLOTS`](super::config::WIDE_SLOTS) slots and their index bits, the banked
/// stacks' pointer and bank address bits, a stack entry.
macro_rules! wide_unit_sized {
    ($block:ident, $k:literal, $nb:literal, $tb:literal) => {
        $block<
            $nb,
            $tb,
            { $crate::traversal::scene_records::link_first_bits($nb, $tb) },
            { $crate::traversal::scene_records::wide_link_bits($nb, $tb) },
            { $crate::traversal::scene_records::wide_head_bits($k) },
            { $k * $crate::traversal::scene_records::wide_link_bits($nb, $tb) },
            { $crate::traversal::scene_records::wide_node_record_bits($k, $nb, $tb) },
            { $crate::traversal::scene_records::triangle_record_bits() },
            { $crate::traversal::config::WIDE_SLOTS },
            { $crate::traversal::config::WIDE_SLOT_BITS },
            { $crate::traversal::config::wide_stack_pointer_bits($k) },
            { $crate::traversal::config::wide_stack_row_bits($k) },
            {
                $crate::traversal::wide_box_port::wide_stack_entry_bits(
                    $crate::traversal::scene_records::wide_link_bits($nb, $tb),
                )
            },
        >
    };
}
pub(crate) use wide_unit_sized;
