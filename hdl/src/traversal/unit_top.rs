//! The traversal unit's top in every format: the core (`unit::TraversalCore`, format-free)
//! beside the format's Möller-Trumbore lane, with the core's ports (docs/traversal-unit.md).
//! The lane stays outside the core so that the large core is compiled once per scene memory
//! size, and only this small wiring once per format.

use super::unit::UnitConfig;

/// Defines `UnitTop` over the lane type `$lane` (the accelerator's `LaneSlot` of a format:
/// the MT lane behind a packed query port) and its latency `$latency(depth)`, its aliases per
/// scene memory size and `verilog`.
macro_rules! unit_top {
    ($lane:ty, $latency:path) => {
        use hw_model::Advance;
        use rust_hdl::prelude::*;
        use $crate::traversal::leaf_advance::{around_lane_latency, AroundLane};
        use $crate::traversal::scene_memory::{triangle_record_bits, ERROR_CODE_BITS};
        use $crate::traversal::unit::{TraversalCore, HIT_BITS, RAY_BITS};

        #[derive(LogicBlock)]
        pub struct UnitTop<
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
            core: TraversalCore<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>,
            lanes: Vec<$lane>,
            /// With `--advance leaf-box`, one per lane between the core and the lane (else
            /// none: the Verilog of `none` has no trace of the advance).
            around: Vec<AroundLane>,
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
            > UnitTop<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>
        {
            /// Operators with `depth` pipeline registers each, stacks of `stack_depth`, `lanes`
            /// MT lanes starting a leaf's queries where `advance` says (`None` or `LeafBox`,
            /// `UnitConfig::check`).
            pub fn new(depth: usize, stack_depth: usize, lanes: usize, advance: Advance) -> Self {
                let lane_latency = $latency(depth);
                let (around, around_latency) = match advance {
                    Advance::LeafBox => (lanes, around_lane_latency(depth)),
                    Advance::None | Advance::TriangleBox => (0, 0),
                };
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
                    core: TraversalCore::new(
                        depth,
                        stack_depth,
                        lanes,
                        lane_latency + around_latency,
                        around > 0,
                    ),
                    lanes: (0..lanes).map(|_| <$lane>::new(depth)).collect(),
                    around: (0..around)
                        .map(|_| AroundLane::new(depth, lane_latency))
                        .collect(),
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
            > Logic for UnitTop<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>
        {
            #[hdl_gen]
            fn update(&mut self) {
                self.core.clock.next = self.clock.val();
                self.core.reset_n.next = self.reset_n.val();
                self.core.scene_start.next = self.scene_start.val();
                self.core.scene_tdata.next = self.scene_tdata.val();
                self.core.scene_tvalid.next = self.scene_tvalid.val();
                self.core.scene_tlast.next = self.scene_tlast.val();
                self.scene_tready.next = self.core.scene_tready.val();
                self.scene_loaded.next = self.core.scene_loaded.val();
                self.scene_error.next = self.core.scene_error.val();
                self.scene_error_code.next = self.core.scene_error_code.val();
                self.scene_error_word.next = self.core.scene_error_word.val();
                self.scene_error_value.next = self.core.scene_error_value.val();
                self.core.ray_tdata.next = self.ray_tdata.val();
                self.core.ray_tvalid.next = self.ray_tvalid.val();
                self.ray_tready.next = self.core.ray_tready.val();
                self.hit_tdata.next = self.core.hit_tdata.val();
                self.hit_tvalid.next = self.core.hit_tvalid.val();
                self.core.hit_tready.next = self.hit_tready.val();
                self.idle.next = self.core.idle.val();
                self.overflow.next = self.core.overflow.val();
                self.overflow_ray.next = self.core.overflow_ray.val();
                self.count_rays.next = self.core.count_rays.val();
                self.count_node_visits.next = self.core.count_node_visits.val();
                self.count_box_tests.next = self.core.count_box_tests.val();
                self.count_mt_tests.next = self.core.count_mt_tests.val();
                self.count_busy_cycles.next = self.core.count_busy_cycles.val();
                for l in 0..self.lanes.len() {
                    self.lanes[l].clock.next = self.clock.val();
                    self.lanes[l].valid_in.next = self.core.lane_valid[l].val();
                    self.lanes[l].query.next = self.core.lane_query[l].val();
                    self.core.lane_hit[l].next = self.lanes[l].hit.val();
                    self.core.lane_t[l].next = self.lanes[l].t.val();
                    self.core.lane_u[l].next = self.lanes[l].u.val();
                    self.core.lane_v[l].next = self.lanes[l].v.val();
                }
                // The leaf advance, when built, between the core and each lane.
                for l in 0..self.around.len() {
                    self.around[l].clock.next = self.clock.val();
                    self.around[l].valid_in.next = self.core.lane_valid[l].val();
                    self.around[l].query_in.next = self.core.lane_query[l].val();
                    self.around[l].entry.next = self.core.lane_entry[l].val();
                    self.lanes[l].valid_in.next = self.around[l].lane_valid.val();
                    self.lanes[l].query.next = self.around[l].lane_query.val();
                    self.around[l].lane_hit.next = self.lanes[l].hit.val();
                    self.around[l].lane_t.next = self.lanes[l].t.val();
                    self.around[l].lane_u.next = self.lanes[l].u.val();
                    self.around[l].lane_v.next = self.lanes[l].v.val();
                    self.core.lane_hit[l].next = self.around[l].hit.val();
                    self.core.lane_t[l].next = self.around[l].t.val();
                    self.core.lane_u[l].next = self.around[l].u.val();
                    self.core.lane_v[l].next = self.around[l].v.val();
                }
            }
        }

        /// The unit at each scene memory size of `unit::TraversalCore4x5` and its siblings.
        pub type Unit4x5 = UnitTop<4, 5, 5, 6, 406, { triangle_record_bits() }, 32, 5, 6, 10, 43>;
        pub type Unit9x10 =
            UnitTop<9, 10, 10, 11, 426, { triangle_record_bits() }, 32, 5, 6, 10, 53>;
        pub type Unit11x12 =
            UnitTop<11, 12, 12, 13, 434, { triangle_record_bits() }, 32, 5, 6, 10, 57>;
        pub type Unit12x13 =
            UnitTop<12, 13, 13, 14, 438, { triangle_record_bits() }, 32, 5, 6, 10, 59>;

        /// The unit's Verilog with a scene memory of `(node bits, triangle bits)`, one of
        /// the aliases' (checked by `UnitConfig::check`).
        pub fn verilog(
            depth: usize,
            stack_depth: usize,
            lanes: usize,
            memory: (usize, usize),
            advance: Advance,
        ) -> String {
            fn generate<U: Block>(unit: U) -> String {
                let mut unit = Box::new(unit);
                unit.connect_all();
                generate_verilog(unit.as_ref())
            }
            match memory {
                (4, 5) => generate(Unit4x5::new(depth, stack_depth, lanes, advance)),
                (9, 10) => generate(Unit9x10::new(depth, stack_depth, lanes, advance)),
                (11, 12) => generate(Unit11x12::new(depth, stack_depth, lanes, advance)),
                _ => generate(Unit12x13::new(depth, stack_depth, lanes, advance)),
            }
        }
    };
}

/// `per_format!` over the `hw_model::hw_formats!` list: a module `name` with the unit over
/// `formats::name::MtLane` for every format, and [`verilog`] dispatching on it.
macro_rules! per_format {
    ($($name:ident: $kind:ident($($arg:tt),*), $description:literal;)*) => {
        $(
            pub mod $name {
                unit_top!(
                    $crate::top::accelerator::$name::LaneSlot,
                    $crate::top::accelerator::$name::Accelerator::latency
                );
            }
        )*

        /// Verilog generators of the units, in catalogue order.
        static UNITS: &[fn(usize, usize, usize, (usize, usize), hw_model::Advance) -> String] =
            &[$($name::verilog),*];
    };
}

hw_model::hw_formats!(per_format);

/// The Verilog of a checked configuration (`unit::unit_verilog` checks and calls this).
pub(super) fn verilog(config: &UnitConfig) -> String {
    let memory = (config.memory.node_bits, config.memory.triangle_bits);
    UNITS[usize::from(config.format.code())](
        config.depth,
        config.stack_depth,
        config.lanes,
        memory,
        config.advance,
    )
}
