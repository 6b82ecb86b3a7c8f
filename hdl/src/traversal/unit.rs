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

/// The struct literal of a core (the binary or the wide one) for `lanes` lanes whose answers
/// come `lane_latency` cycles after their queries (with `entries`, each beside its leaf's
/// entry), operators of `depth` registers: the shared blocks, then the core's own (`own`:
/// its scene memory, ports and counters).
macro_rules! core_new {
    ($lanes:expr, $lane_latency:expr, $entries:expr, $depth:expr, { $($own:tt)* }) => {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            scene: Default::default(),
            ray: Default::default(),
            hit: Default::default(),
            control: Default::default(),
            counters: Default::default(),
            lane: defaults($lanes),
            lane_entry: defaults(if $entries { $lanes } else { 0 }),
            entry: RayEntry::new($depth),
            slots: SlotState::new($lanes, $entries),
            leaf: (0..$lanes)
                .map(|_| LeafPort::new($depth, $lane_latency))
                .collect(),
            hits: HitOutput::new($lanes),
            $($own)*
        }
    };
}
pub(crate) use core_new;

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
        core_new!(lanes, lane_latency, entries, depth, {
            memory: SceneMemory::new(lanes),
            box_port: BoxPort::new(depth),
            stack_port: StackPort::new(stack_depth),
            counting: Counters::new(lanes),
        })
    }
}

/// The core's wiring, the same for the binary core and the wide one
/// (`wide_unit::WideTraversalCore`): `$core`'s `Logic` over its const parameters, with what differs
/// said by each — the blocks it clocks, the blocks beside the slots that take a new ray (`entered`)
/// and the ray setup's answer (`set_up`, `leaf_set_up` its source), the box port's node fields, its
/// push, the stack port's further wiring, the counters of its own; `count` the width of a link's
/// count. A macro rather than a generic block: the binary core's Verilog stays its own. `self` and
/// `#[hdl_gen]` come from the caller (macro hygiene: the attribute's `connect` takes the caller's
/// `self`), as do the statements that use `self`.
macro_rules! core_logic {
    (
        $pound:tt $hdl_gen:tt
        $this:ident,
        $core:ident<$($g:ident),*>,
        count: $lc:tt,
        clocked: { $($clocked:tt)* },
        entered: { $($entered:tt)* },
        set_up: { $($set_up:tt)* },
        leaf_set_up: { $($leaf_set_up:tt)* },
        box_port: { $($box_port:tt)* },
        push: { $($push:tt)* },
        stack_port: { $($stack_port:tt)* },
        counters: { $($counters:tt)* },
    ) => {
        impl<$(const $g: usize),*> Logic for $core<$($g),*> {
            $pound $hdl_gen
            fn update(&mut $this) {
                clock!($this, clock, $($clocked)*);
                $this.entry.reset_n.next = $this.reset_n.val();
                $this.slots.reset_n.next = $this.reset_n.val();
                $this.stack_port.reset_n.next = $this.reset_n.val();
                $this.hits.reset_n.next = $this.reset_n.val();
                $this.counting.reset_n.next = $this.reset_n.val();

                // ---- The scene stream into the scene memory, and the load's status.
                $this.memory.start_load.next = $this.control.scene_start.val();
                $this.memory.s_tdata.next = $this.scene.tdata.val();
                $this.memory.s_tvalid.next = $this.scene.tvalid.val();
                $this.memory.s_tlast.next = $this.scene.tlast.val();
                $this.scene.tready.next = $this.memory.s_tready.val();
                $this.control.scene_loaded.next = $this.memory.loaded.val();
                $this.control.scene_error.next = $this.memory.error.val();
                $this.control.scene_error_code.next = $this.memory.error_code.val();
                $this.control.scene_error_word.next = $this.memory.error_word.val();
                $this.control.scene_error_value.next = $this.memory.error_value.val();

                // ---- Rays in, to the slots and to every block that keeps a slot word.
                RayStream::link(&mut $this.ray, &mut $this.entry.ray);
                $this.entry.loaded.next = $this.memory.loaded.val();
                $this.entry.free.next = $this.slots.free.val();
                $this.entry.slot.next = $this.slots.enter_slot.val();
                $this.slots.has_triangles.next = $this.memory.triangles.val().any();
                EnteredSource::<SB>::join(&mut $this.entry.entered, &mut $this.slots.entered);
                EnteredSource::<SB>::join(&mut $this.entry.entered, &mut $this.stack_port.entered);
                EnteredSource::<SB>::join(&mut $this.entry.entered, &mut $this.hits.entered);
                $($entered)*
                $($set_up)*

                // ---- The box port: the node read, its steps and pushes.
                BoxGrantSource::<SB, LF>::join(&mut $this.slots.box_grant, &mut $this.box_port.grant);
                $this.memory.node_address.next = $this.box_port.node_address.val();
                $($box_port)*
                LinkStep::<SB, LF, $lc>::join(&mut $this.box_port.step, &mut $this.slots.box_step);
                $($push)*

                // ---- The stack port.
                PopGrantSource::<SB>::join(&mut $this.slots.pop_grant, &mut $this.stack_port.grant);
                LinkStep::<SB, LF, $lc>::join(&mut $this.stack_port.step, &mut $this.slots.pop_step);
                $($stack_port)*

                // ---- The leaf ports, one per lane, each with its lane's triangle read.
                for l in 0..$this.leaf.len() {
                    clock!($this, clock, leaf[l]);
                    EnteredSource::<SB>::join(&mut $this.entry.entered, &mut $this.leaf[l].entered);
                    SetUpSource::<SB>::join(&mut $($leaf_set_up)*, &mut $this.leaf[l].set_up);
                    LeafGrantSource::<SB, LF>::join(&mut $this.slots.leaf_grant[l], &mut $this.leaf[l].grant);
                    LeafStep::<SB>::join(&mut $this.leaf[l].step, &mut $this.slots.leaf_step[l]);
                    $this.memory.triangle_address[l].next = $this.leaf[l].triangle_address.val();
                    $this.leaf[l].vertices.next = $this.memory.vertices[l].val();
                    $this.leaf[l].global_index.next = $this.memory.global_index[l].val();
                    $this.leaf[l].casts_shadow.next = $this.memory.casts_shadow[l].val();
                    LanePort::link(&mut $this.lane[l], &mut $this.leaf[l].lane);
                    $this.leaf[l].out_slot.next = $this.slots.out_grant.slot.val();
                    $this.hits.lane_best[l].next = $this.leaf[l].out_best.val();
                    // (A linked bundle is read on the core's side: the port's own name is the
                    // link's.)
                    $this.counting.mt_test[l].next = $this.lane[l].valid.val();
                }
                for l in 0..$this.lane_entry.len() {
                    $this.lane_entry[l].next = $this.slots.lane_entry[l].val();
                }

                // ---- The hit output.
                OutGrantSource::<SB>::join(&mut $this.slots.out_grant, &mut $this.hits.grant);
                HitStream::link(&mut $this.hit, &mut $this.hits.hit);

                // ---- Status and counters.
                $this.control.idle.next = !$this.slots.occupied.val() & !$this.hits.pending.val();
                $this.control.overflow.next = $this.stack_port.overflow.val();
                $this.control.overflow_ray.next = $this.stack_port.overflow_ray.val();
                $this.counting.ray.next = $this.entry.entered.valid.val();
                $this.counting.box_test.next = $this.slots.box_grant.valid.val();
                $this.counting.box_visit.next =
                    $this.box_port.step.valid.val() & $this.box_port.step.enter.val();
                $this.counting.pop_visit.next =
                    $this.stack_port.step.valid.val() & $this.stack_port.step.enter.val();
                $($counters)*
                $this.counting.busy.next = $this.slots.occupied.val();
                CounterPort::link(&mut $this.counters, &mut $this.counting.port);
            }
        }
    };
}
pub(crate) use core_logic;

core_logic! {
    #[hdl_gen]
    self,
    TraversalCore<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>,
    count: LC,
    clocked: { memory, entry, slots, box_port, stack_port, hits, counting },
    entered: {},
    set_up: {
        SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.slots.set_up);
        SetUpSource::<SB>::join(&mut self.entry.set_up, &mut self.box_port.set_up);
    },
    leaf_set_up: { self.entry.set_up },
    box_port: {
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
    },
    push: { Push::<SB, W>::join(&mut self.box_port.push, &mut self.stack_port.push); },
    stack_port: {},
    counters: {},
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
