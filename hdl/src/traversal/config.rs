//! What a traversal unit is built from ([`UnitConfig`]), what the RTL builds, and the unit's
//! Verilog ([`unit_verilog`]).

use hw_model::traversal::schedule::UnitTiming;
use hw_model::traversal::wide::NodeFormat;
use hw_model::{Advance, HwFormat};
use thiserror::Error;

use super::scene_memory::{link_count_bits, link_first_bits, zynq_address_bits};
use super::scene_memory_driver::MemoryConfig;
use super::timing::unit_timing;
use crate::top::with_build_stack;

/// Slots of every built unit, and the deepest stack its stack RAM holds.
pub const UNIT_SLOTS: usize = super::timing::DEFAULT_SLOTS;
pub const MAX_STACK_DEPTH: usize = 32;
/// The widths they give the core's parameters (`unit::unit_sized!`): a slot's index, a
/// stack pointer (0 to the depth), a stack RAM address (every slot's whole stack).
pub const SLOT_BITS: usize = UNIT_SLOTS.ilog2() as usize;
pub const STACK_POINTER_BITS: usize = MAX_STACK_DEPTH.ilog2() as usize + 1;
pub const STACK_ADDRESS_BITS: usize = (UNIT_SLOTS * MAX_STACK_DEPTH).ilog2() as usize;
const _: () = assert!(
    UNIT_SLOTS.is_power_of_two()
        && MAX_STACK_DEPTH.is_power_of_two()
        && UNIT_SLOTS <= 1 << 16
        && MAX_LANES <= UNIT_SLOTS
);

/// The scene memories the RTL builds, as (node, triangle) address bits: a type each
/// (`scene_memory::SceneMemory4x5` …, `unit_top::<format>::Unit4x5` …).
pub const BUILT_MEMORY_BITS: [(usize, usize); 4] = [(4, 5), (9, 10), (11, 12), (12, 13)];

/// [`BUILT_MEMORY_BITS`] as "4/5, 9/10, …".
fn built_memory_bits() -> String {
    let sizes: Vec<String> = BUILT_MEMORY_BITS
        .iter()
        .map(|(n, t)| format!("{n}/{t}"))
        .collect();
    sizes.join(", ")
}

/// A stack entry's bits with a scene memory of these address bits: a link (first, count)
/// and its entry distance.
pub const fn stack_entry_bits(node_bits: usize, triangle_bits: usize) -> usize {
    link_first_bits(node_bits, triangle_bits) + link_count_bits(triangle_bits) + 32
}
/// Lanes a unit is built with at most: the box port is the unit's bottleneck (87–99 % busy
/// with one lane), so more lanes add area and no speed.
pub const MAX_LANES: usize = 3;

/// What a unit is built from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitConfig {
    pub format: HwFormat,
    /// How the scene memory holds the inner nodes (`--nodes`).
    pub nodes: NodeFormat,
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
    #[error("the traversal unit's RTL walks bvh2-fp32 nodes, not {}: the wide unit is not built yet", .0.name())]
    Nodes(NodeFormat),
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
    /// Binary fp32 nodes, `slots` and `stack_depth` at their defaults, the scene memory that
    /// fits the XC7Z020 beside `lanes` lanes.
    pub fn new(format: HwFormat, depth: usize, lanes: usize) -> UnitConfig {
        let (node_bits, triangle_bits) = zynq_address_bits(lanes);
        UnitConfig {
            format,
            nodes: NodeFormat::Bvh2Fp32,
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
        if self.nodes != NodeFormat::Bvh2Fp32 {
            return Err(UnitConfigError::Nodes(self.nodes));
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
        let (node_bits, triangle_bits) = (self.memory.node_bits, self.memory.triangle_bits);
        if BUILT_MEMORY_BITS.contains(&(node_bits, triangle_bits)) {
            Ok(())
        } else {
            Err(UnitConfigError::Memory {
                node_bits,
                triangle_bits,
            })
        }
    }
}

/// The unit's Verilog (rust-hdl's, top module `top`): the core and the lane of the
/// configuration's format (`unit_top`).
pub fn unit_verilog(config: &UnitConfig) -> Result<String, UnitConfigError> {
    config.check()?;
    let config = *config;
    Ok(with_build_stack(move || super::unit_top::verilog(&config)))
}

/// The wide unit's banked stacks (`wide_unit::wide_unit_sized!`) for `k`-wide nodes: pointer
/// bits (a pointer up to the depth plus a push of K − 1) and bank address bits (`slots` ×
/// ⌈depth / K⌉ rows a bank).
pub const fn wide_stack_pointer_bits(k: usize) -> usize {
    (MAX_STACK_DEPTH + k - 1).ilog2() as usize + 1
}
pub const fn wide_stack_row_bits(k: usize, slots: usize) -> usize {
    let rows = (slots * MAX_STACK_DEPTH.div_ceil(k)).ilog2() as usize;
    let pointer = wide_stack_pointer_bits(k);
    if rows > pointer {
        rows
    } else {
        pointer
    }
}
