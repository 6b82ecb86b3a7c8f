//! The traversal unit's core: the scene in block RAM, rays in, answers out — the blocks of
//! this module wired around the ports of 1 to [`MAX_LANES`] Möller-Trumbore lanes, which
//! `unit_top` puts beside it in the configured format. The whole unit is bit for bit
//! `hw_model::traversal::TraversalModel` (answers and counters). Ports and packets:
//! docs/traversal-unit.md.
//!
//! ```text
//!  ray stream ─► RayEntry (ray setup) ──► Entered, SetUp: into every block keeping slot words
//!                        │
//!                     SlotState: state, schedulers, next-state logic
//!   grants │ ▲ steps
//!          ▼ │
//!   BoxPort    node read + box test    ─► LinkStep, Push ─► StackPort
//!   StackPort  SlotStacks: pop, beyond t_hi? ─► LinkStep (overflow report)
//!   LeafPort l triangle read, lane l, hit update, far end ─► LeafStep    (one per lane)
//!   HitOutput  id + nearest hit ─► one register ─► hit stream
//!   Counters
//! ```
//!
//! [`SlotState`] holds the 32 ray slots' state and grants them to the ports; each port is a
//! block behind a grant in and a step out ([`super::slot_ports`]). The unit's external
//! bundles are [`super::ports`]'.

use rust_hdl::prelude::*;

use super::box_port::BoxPort;
use super::config::MAX_LANES;
use super::counters::Counters;
use super::hit_output::HitOutput;
use super::leaf_port::LeafPort;
use super::ports::{ControlPort, CounterPort, HitStream, RayStream, SceneStream};
use super::ray_entry::RayEntry;
use super::scene_memory::SceneMemory;
use super::slot_ports::{
    BoxGrantSource, EnteredSource, LeafGrantSource, LeafStep, LinkStep, OutGrantSource,
    PopGrantSource, Push, SetUpSource,
};
use super::slots::SlotState;
use super::stack_port::StackPort;
use crate::defaults;
use crate::macros::clock;
use crate::mt::LanePort;

/// The core. Const parameters (rust-hdl cannot derive widths; [`unit_sized!`] computes them
/// from a scene memory size): the scene memory's `NB, TB, LF, LC, NW, TW` (see
/// [`SceneMemory`]); `S` slots addressed by `SB` bits; the stacks' pointer bits `PB` and RAM
/// address bits `AB`; a stack entry of `W` = LF + LC + 32 bits (a link and its entry
/// distance).
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
    /// Synchronous, active low: empties the slots, clears the overflow bit and the counters.
    pub reset_n: Signal<In, Bit>,
    pub scene: SceneStream,
    pub ray: RayStream,
    pub hit: HitStream,
    pub control: ControlPort,
    pub counters: CounterPort,
    /// The Möller-Trumbore lanes, outside the core so that one core serves every format
    /// (`unit_top`): per lane a query a cycle out, its answer `lane_latency` cycles later.
    pub lane: Vec<LanePort>,
    /// With the leaf advance (else no lanes): the entry distance of the query's leaf,
    /// beside the query (`unit_top` puts `leaf_advance::AroundLane` between core and lane).
    pub lane_entry: Vec<Signal<Out, Bits<32>>>,
    memory: SceneMemory<NB, TB, LF, LC, NW, TW>,
    entry: RayEntry<SB>,
    slots: SlotState<S, SB, LF, LC>,
    box_port: BoxPort<SB, NB, LF, LC, W>,
    stack_port: StackPort<S, SB, PB, AB, W, LF, LC>,
    leaf: Vec<LeafPort<SB, TB, LF>>,
    hits: HitOutput<SB>,
    counting: Counters,
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
        assert!(
            (1..=MAX_LANES).contains(&lanes),
            "{lanes} lanes: 1 to {MAX_LANES}"
        );
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            scene: Default::default(),
            ray: Default::default(),
            hit: Default::default(),
            control: Default::default(),
            counters: Default::default(),
            lane: defaults(lanes),
            lane_entry: defaults(if entries { lanes } else { 0 }),
            memory: SceneMemory::new(lanes),
            entry: RayEntry::new(depth),
            slots: SlotState::new(lanes, entries),
            box_port: BoxPort::new(depth),
            stack_port: StackPort::new(stack_depth),
            leaf: (0..lanes)
                .map(|_| LeafPort::new(depth, lane_latency))
                .collect(),
            hits: HitOutput::new(lanes),
            counting: Counters::new(lanes),
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
        clock!(self, clock, memory, entry, slots, box_port, stack_port, hits, counting);
        self.entry.reset_n.next = self.reset_n.val();
        self.slots.reset_n.next = self.reset_n.val();
        self.stack_port.reset_n.next = self.reset_n.val();
        self.hits.reset_n.next = self.reset_n.val();
        self.counting.reset_n.next = self.reset_n.val();

        // ---- The scene stream into the scene memory, and the load's status.
        self.memory.start_load.next = self.control.scene_start.val();
        self.memory.s_tdata.next = self.scene.tdata.val();
        self.memory.s_tvalid.next = self.scene.tvalid.val();
        self.memory.s_tlast.next = self.scene.tlast.val();
        self.scene.tready.next = self.memory.s_tready.val();
        self.control.scene_loaded.next = self.memory.loaded.val();
        self.control.scene_error.next = self.memory.error.val();
        self.control.scene_error_code.next = self.memory.error_code.val();
        self.control.scene_error_word.next = self.memory.error_word.val();
        self.control.scene_error_value.next = self.memory.error_value.val();

        // ---- Rays in, to the slots and to every block that keeps a slot word.
        RayStream::link(&mut self.ray, &mut self.entry.ray);
        self.entry.loaded.next = self.memory.loaded.val();
        self.entry.free.next = self.slots.free.val();
        self.entry.slot.next = self.slots.enter_slot.val();
        self.slots.has_triangles.next = self.memory.triangles.val().any();
        EnteredSource::<SB>::join(&mut self.entry.entered, &mut self.slots.entered);
        EnteredSource::<SB>::join(&mut self.entry.entered, &mut self.stack_port.entered);
        EnteredSource::<SB>::join(&mut self.entry.entered, &mut self.hits.entered);
        SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.slots.set_up);
        SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.box_port.set_up);

        // ---- The box port: the node read, its steps and pushes.
        BoxGrantSource::<SB, LF>::join(&mut self.slots.box_grant, &mut self.box_port.grant);
        self.memory.node_address.next = self.box_port.node_address.val();
        for j in 0..6 {
            self.box_port.min[j].next = self.memory.min[j].val();
            self.box_port.max[j].next = self.memory.max[j].val();
        }
        for c in 0..2 {
            self.box_port.child_first[c].next = self.memory.child_first[c].val();
            self.box_port.child_count[c].next = self.memory.child_count[c].val();
        }
        for k in 0..3 {
            self.box_port.root_min[k].next = self.memory.root_min[k].val();
            self.box_port.root_max[k].next = self.memory.root_max[k].val();
        }
        self.box_port.root_first.next = self.memory.root_first.val();
        self.box_port.root_count.next = self.memory.root_count.val();
        LinkStep::<SB, LF, LC>::join(&mut self.box_port.step, &mut self.slots.box_step);
        Push::<SB, W>::join(&mut self.box_port.push, &mut self.stack_port.push);

        // ---- The stack port.
        PopGrantSource::<SB>::join(&mut self.slots.pop_grant, &mut self.stack_port.grant);
        LinkStep::<SB, LF, LC>::join(&mut self.stack_port.step, &mut self.slots.pop_step);

        // ---- The leaf ports, one per lane, each with its lane's triangle read.
        for l in 0..self.leaf.len() {
            clock!(self, clock, leaf[l]);
            EnteredSource::<SB>::join(&mut self.entry.entered, &mut self.leaf[l].entered);
            SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.leaf[l].set_up);
            LeafGrantSource::<SB, LF>::join(&mut self.slots.leaf_grant[l], &mut self.leaf[l].grant);
            LeafStep::<SB>::join(&mut self.leaf[l].step, &mut self.slots.leaf_step[l]);
            self.memory.triangle_address[l].next = self.leaf[l].triangle_address.val();
            self.leaf[l].vertices.next = self.memory.vertices[l].val();
            self.leaf[l].global_index.next = self.memory.global_index[l].val();
            self.leaf[l].casts_shadow.next = self.memory.casts_shadow[l].val();
            LanePort::link(&mut self.lane[l], &mut self.leaf[l].lane);
            self.leaf[l].out_slot.next = self.slots.out_grant.slot.val();
            self.hits.lane_best[l].next = self.leaf[l].out_best.val();
            // (A linked bundle is read on the core's side: the port's own name is the link's.)
            self.counting.mt_test[l].next = self.lane[l].valid.val();
        }
        for l in 0..self.lane_entry.len() {
            self.lane_entry[l].next = self.slots.lane_entry[l].val();
        }

        // ---- The hit output.
        OutGrantSource::<SB>::join(&mut self.slots.out_grant, &mut self.hits.grant);
        HitStream::link(&mut self.hit, &mut self.hits.hit);

        // ---- Status and counters.
        self.control.idle.next = !self.slots.occupied.val() & !self.hits.pending.val();
        self.control.overflow.next = self.stack_port.overflow.val();
        self.control.overflow_ray.next = self.stack_port.overflow_ray.val();
        self.counting.ray.next = self.entry.entered.valid.val();
        self.counting.box_test.next = self.slots.box_grant.valid.val();
        self.counting.box_visit.next =
            self.box_port.step.valid.val() & self.box_port.step.enter.val();
        self.counting.pop_visit.next =
            self.stack_port.step.valid.val() & self.stack_port.step.enter.val();
        self.counting.busy.next = self.slots.occupied.val();
        CounterPort::link(&mut self.counters, &mut self.counting.port);
    }
}

/// `$block` (the core, or the unit top over it) with a scene memory of `$nb` node and `$tb`
/// triangle address bits, every width parameter computed: the memory's
/// ([`super::scene_memory::memory_sized!`]'s), [`UNIT_SLOTS`](super::config::UNIT_SLOTS)
/// slots and their index bits, the stacks' pointer and address bits, a stack entry.
macro_rules! unit_sized {
    ($block:ident, $nb:literal, $tb:literal) => {
        $block<
            $nb,
            $tb,
            { $crate::traversal::scene_memory::link_first_bits($nb, $tb) },
            { $crate::traversal::scene_memory::link_count_bits($tb) },
            { $crate::traversal::scene_memory::node_record_bits($nb, $tb) },
            { $crate::traversal::scene_memory::triangle_record_bits() },
            { $crate::traversal::config::UNIT_SLOTS },
            { $crate::traversal::config::SLOT_BITS },
            { $crate::traversal::config::STACK_POINTER_BITS },
            { $crate::traversal::config::STACK_ADDRESS_BITS },
            { $crate::traversal::config::stack_entry_bits($nb, $tb) },
        >
    };
}
pub(crate) use unit_sized;

/// The core at each scene memory size the XC7Z020 takes (`scene_memory`'s aliases);
/// `unit_top` puts a lane beside it.
pub type TraversalCore4x5 = unit_sized!(TraversalCore, 4, 5);
pub type TraversalCore9x10 = unit_sized!(TraversalCore, 9, 10);
pub type TraversalCore11x12 = unit_sized!(TraversalCore, 11, 12);
pub type TraversalCore12x13 = unit_sized!(TraversalCore, 12, 13);
