//! The traversal unit's port bundles, each defined once and joined where two blocks meet:
//! the scene stream, the ray and hit streams, the control and status signals, the counters
//! (docs/traversal-unit.md "Ports"). A bundle's mirror (`#[join]`) is the other side's: a
//! register slave holds a [`ControlMaster`] and a [`CounterReader`], and a block that feeds
//! the unit rays or takes its answers (a frame unit's ray generator, its shader) holds an
//! [`AxisOut`] for the rays and an [`AxisIn`] for the answers.
//!
//! The unit's Verilog top has the bundles' signals as ports under rust-hdl's flattened
//! names, `<bundle>$<signal>` (`scene$tdata`, `control$idle`, `counters$rays`): those names
//! are derived from these definitions, by rust-hdl in the Verilog and by
//! `sim::traversal_unit`'s `port!` in the co-simulation harness.

use hw_model::traversal::packet::{HIT_WORDS, RAY_WORDS};
use rust_hdl::prelude::*;

use super::scene_memory::ERROR_CODE_BITS;

/// Bits of a ray packet and of an answer packet (`hw_model::traversal::packet`).
pub const RAY_BITS: usize = 32 * RAY_WORDS;
pub const HIT_BITS: usize = 32 * HIT_WORDS;

/// An AXI4-Stream without `tlast`, seen from its receiver.
#[derive(LogicInterface, Default)]
#[join = "AxisOut"]
pub struct AxisIn<T: Synth> {
    pub tdata: Signal<In, T>,
    pub tvalid: Signal<In, Bit>,
    pub tready: Signal<Out, Bit>,
}

/// An AXI4-Stream without `tlast`, seen from its sender.
#[derive(LogicInterface, Default)]
#[join = "AxisIn"]
pub struct AxisOut<T: Synth> {
    pub tdata: Signal<Out, T>,
    pub tvalid: Signal<Out, Bit>,
    pub tready: Signal<In, Bit>,
}

/// Rays into the unit: one ray packet a beat.
pub type RayStream = AxisIn<Bits<RAY_BITS>>;
/// Answers out of the unit: one answer packet a beat, in any order, tagged with the ray id.
pub type HitStream = AxisOut<Bits<HIT_BITS>>;

/// The scene image's words into the unit (docs/scene-image.md), an AXI4-Stream with
/// `tlast` on the image's last word.
#[derive(LogicInterface, Default)]
#[join = "SceneSource"]
pub struct SceneStream {
    pub tdata: Signal<In, Bits<32>>,
    pub tvalid: Signal<In, Bit>,
    pub tlast: Signal<In, Bit>,
    pub tready: Signal<Out, Bit>,
}

/// What sends a scene image.
#[derive(LogicInterface, Default)]
#[join = "SceneStream"]
pub struct SceneSource {
    pub tdata: Signal<Out, Bits<32>>,
    pub tvalid: Signal<Out, Bit>,
    pub tlast: Signal<Out, Bit>,
    pub tready: Signal<In, Bit>,
}

/// The unit's control and status (its register slave's registers, `regmap::unit`).
#[derive(LogicInterface, Default)]
#[join = "ControlMaster"]
pub struct ControlPort {
    /// A pulse: a new scene load begins; only while `idle`.
    pub scene_start: Signal<In, Bit>,
    /// No ray in the unit.
    pub idle: Signal<Out, Bit>,
    /// The load finished; it failed, with the first failure's code
    /// (`scene_memory::LoadError`), word index and word.
    pub scene_loaded: Signal<Out, Bit>,
    pub scene_error: Signal<Out, Bit>,
    pub scene_error_code: Signal<Out, Bits<ERROR_CODE_BITS>>,
    pub scene_error_word: Signal<Out, Bits<32>>,
    pub scene_error_value: Signal<Out, Bits<32>>,
    /// Sticky: a ray's stack overflowed, and the first such ray's id.
    pub overflow: Signal<Out, Bit>,
    pub overflow_ray: Signal<Out, Bits<32>>,
}

/// What controls the unit and reads its status.
#[derive(LogicInterface, Default)]
#[join = "ControlPort"]
pub struct ControlMaster {
    pub scene_start: Signal<Out, Bit>,
    pub idle: Signal<In, Bit>,
    pub scene_loaded: Signal<In, Bit>,
    pub scene_error: Signal<In, Bit>,
    pub scene_error_code: Signal<In, Bits<ERROR_CODE_BITS>>,
    pub scene_error_word: Signal<In, Bits<32>>,
    pub scene_error_value: Signal<In, Bits<32>>,
    pub overflow: Signal<In, Bit>,
    pub overflow_ray: Signal<In, Bits<32>>,
}

/// The unit's wrapping 32-bit counters, in `regmap::unit::COUNTERS` order: rays taken, nodes
/// visited, box tests, Möller-Trumbore tests, cycles with a ray in the unit.
#[derive(LogicInterface, Default)]
#[join = "CounterReader"]
pub struct CounterPort {
    pub rays: Signal<Out, Bits<32>>,
    pub node_visits: Signal<Out, Bits<32>>,
    pub box_tests: Signal<Out, Bits<32>>,
    pub mt_tests: Signal<Out, Bits<32>>,
    pub busy_cycles: Signal<Out, Bits<32>>,
}

/// What reads the counters.
#[derive(LogicInterface, Default)]
#[join = "CounterPort"]
pub struct CounterReader {
    pub rays: Signal<In, Bits<32>>,
    pub node_visits: Signal<In, Bits<32>>,
    pub box_tests: Signal<In, Bits<32>>,
    pub mt_tests: Signal<In, Bits<32>>,
    pub busy_cycles: Signal<In, Bits<32>>,
}
