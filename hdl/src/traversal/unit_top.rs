//! The traversal unit's top in every format: the core (`unit::TraversalCore`, format-free)
//! beside the format's Möller-Trumbore lane, with the core's ports (docs/traversal-unit.md).
//! The lane stays outside the core so that the large core is compiled once per scene memory
//! size, and only this small wiring once per format.

use super::config::{BuiltUnit, UnitConfig};

/// The unit top's wiring, the same for the binary and the wide core: `$top`'s `Logic` over
/// its const parameters `$g`.
macro_rules! top_logic {
    ($top:ident<$($g:ident),*>) => {
        impl<$(const $g: usize),*> Logic for $top<$($g),*> {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, core);
                self.core.reset_n.next = self.reset_n.val();
                SceneStream::link(&mut self.scene, &mut self.core.scene);
                RayStream::link(&mut self.ray, &mut self.core.ray);
                HitStream::link(&mut self.hit, &mut self.core.hit);
                ControlPort::link(&mut self.control, &mut self.core.control);
                CounterPort::link(&mut self.counters, &mut self.core.counters);
                for l in 0..self.lanes.len() {
                    clock!(self, clock, lanes[l]);
                }
                // The leaf advance, when built, between the core and each lane.
                for l in 0..self.around.len() {
                    clock!(self, clock, around[l]);
                    LanePort::join(&mut self.core.lane[l], &mut self.around[l].core);
                    self.around[l].entry.next = self.core.lane_entry[l].val();
                    LanePort::join(&mut self.around[l].lane, &mut self.lanes[l].port);
                }
                for l in self.around.len()..self.lanes.len() {
                    LanePort::join(&mut self.core.lane[l], &mut self.lanes[l].port);
                }
            }
        }
    };
}

/// A unit's Verilog (top module `top`).
fn generate<U: rust_hdl::prelude::Block>(unit: U) -> String {
    let mut unit = Box::new(unit);
    unit.connect_all();
    rust_hdl::prelude::generate_verilog(unit.as_ref())
}

/// Defines `UnitTop` over the lane type `$lane` (the accelerator's `LaneSlot` of a format:
/// the MT lane behind a packed query port) and its latency `$latency(depth)`, its aliases per
/// scene memory size and `verilog`.
macro_rules! unit_top {
    ($lane:ty, $latency:path) => {
        use hw_model::Advance;
        use $crate::traversal::config::BuiltUnit;
        use $crate::macros::prelude::*;
        use $crate::mt::LanePort;
        use $crate::traversal::leaf_advance::{around_lane_latency, AroundLane};
        use $crate::traversal::ports::{
            ControlPort, CounterPort, HitStream, RayStream, SceneStream,
        };
        use $crate::traversal::unit::{unit_sized, TraversalCore};
        use $crate::traversal::unit_top::generate;
        use $crate::traversal::wide_unit::{wide_unit_sized, WideTraversalCore};

        /// The unit: the core's ports (docs/traversal-unit.md "Ports"), its lanes beside it.
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
            pub scene: SceneStream,
            pub ray: RayStream,
            pub hit: HitStream,
            pub control: ControlPort,
            pub counters: CounterPort,
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
                    scene: Default::default(),
                    ray: Default::default(),
                    hit: Default::default(),
                    control: Default::default(),
                    counters: Default::default(),
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

        top_logic!(UnitTop<NB, TB, LF, LC, NW, TW, S, SB, PB, AB, W>);
        top_logic!(WideUnitTop<NB, TB, LF, LK, HB, LB, NW, TW, S, SB, PB, RB, W>);

        /// The wide unit (`--nodes bvh2-q8 | bvh4-q8 | bvh8-q8`): the wide core's ports, as
        /// the binary unit's, its lanes beside it.
        #[derive(LogicBlock)]
        pub struct WideUnitTop<
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
            pub reset_n: Signal<In, Bit>,
            pub scene: SceneStream,
            pub ray: RayStream,
            pub hit: HitStream,
            pub control: ControlPort,
            pub counters: CounterPort,
            core: WideTraversalCore<NB, TB, LF, LK, HB, LB, NW, TW, S, SB, PB, RB, W>,
            lanes: Vec<$lane>,
            around: Vec<AroundLane>,
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
            > WideUnitTop<NB, TB, LF, LK, HB, LB, NW, TW, S, SB, PB, RB, W>
        {
            /// The unit for nodes of `width` children; the rest as [`UnitTop::new`]'s.
            pub fn new(
                width: usize,
                depth: usize,
                stack_depth: usize,
                lanes: usize,
                advance: Advance,
            ) -> Self {
                let lane_latency = $latency(depth);
                let (around, around_latency) = match advance {
                    Advance::LeafBox => (lanes, around_lane_latency(depth)),
                    Advance::None | Advance::TriangleBox => (0, 0),
                };
                Self {
                    clock: Default::default(),
                    reset_n: Default::default(),
                    scene: Default::default(),
                    ray: Default::default(),
                    hit: Default::default(),
                    control: Default::default(),
                    counters: Default::default(),
                    core: WideTraversalCore::new(
                        width,
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

        /// The wide units (`config::BUILT_WIDE_MEMORY_BITS`): the small test memories (16
        /// nodes, 32 triangles) and the XC7Z020's 8-wide memory.
        pub type WideUnit4w4x5 = wide_unit_sized!(WideUnitTop, 4, 4, 5);
        pub type WideUnit8w4x5 = wide_unit_sized!(WideUnitTop, 8, 4, 5);
        pub type WideUnit8w11x13 = wide_unit_sized!(WideUnitTop, 8, 11, 13);

        /// The unit at each scene memory size of `unit::TraversalCore4x5` and its siblings.
        pub type Unit4x5 = unit_sized!(UnitTop, 4, 5);
        pub type Unit9x10 = unit_sized!(UnitTop, 9, 10);
        pub type Unit11x12 = unit_sized!(UnitTop, 11, 12);
        pub type Unit12x13 = unit_sized!(UnitTop, 12, 13);

        /// The Verilog of the unit `unit` (`UnitConfig::built`).
        pub fn verilog(
            unit: BuiltUnit,
            depth: usize,
            stack_depth: usize,
            lanes: usize,
            advance: Advance,
        ) -> String {
            let (s, l, a) = (stack_depth, lanes, advance);
            match unit {
                BuiltUnit::Binary4x5 => generate(Unit4x5::new(depth, s, l, a)),
                BuiltUnit::Binary9x10 => generate(Unit9x10::new(depth, s, l, a)),
                BuiltUnit::Binary11x12 => generate(Unit11x12::new(depth, s, l, a)),
                BuiltUnit::Binary12x13 => generate(Unit12x13::new(depth, s, l, a)),
                BuiltUnit::Wide4w4x5 => generate(WideUnit4w4x5::new(4, depth, s, l, a)),
                BuiltUnit::Wide8w4x5 => generate(WideUnit8w4x5::new(8, depth, s, l, a)),
                BuiltUnit::Wide8w11x13 => generate(WideUnit8w11x13::new(8, depth, s, l, a)),
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
        static UNITS: &[fn(BuiltUnit, usize, usize, usize, hw_model::Advance) -> String] =
            &[$($name::verilog),*];
    };
}

hw_model::hw_formats!(per_format);

/// The Verilog of a checked configuration (`unit::unit_verilog` checks and calls this).
pub(super) fn verilog(config: &UnitConfig) -> String {
    let unit = config.built().expect("a checked configuration");
    UNITS[usize::from(config.format.code())](
        unit,
        config.depth,
        config.stack_depth,
        config.lanes,
        config.advance,
    )
}
