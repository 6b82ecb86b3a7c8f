//! What a traversal unit is built from ([`UnitConfig`]), what the RTL builds, and the unit's
//! Verilog ([`unit_verilog`]).

use hw_model::traversal::schedule::UnitTiming;
use hw_model::traversal::wide::NodeFormat;
use hw_model::{Advance, HwFormat};
use thiserror::Error;

use super::scene_memory::{link_count_bits, link_first_bits, zynq_address_bits};
use super::scene_memory_driver::MemoryConfig;
use super::timing::{node_timing, unit_timing};
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

/// Slots of the wide unit: 8-wide nodes with 32 slots are latency-bound (the schedule model
/// on the Utah teapot: 6.9 cycles a ray with 32 slots, 4.99 with 64).
pub const WIDE_SLOTS: usize = 64;
pub const WIDE_SLOT_BITS: usize = WIDE_SLOTS.ilog2() as usize;
const _: () = assert!(WIDE_SLOTS.is_power_of_two() && MAX_LANES <= WIDE_SLOTS);

/// The slots of a unit of `nodes`.
pub fn slots_for(nodes: NodeFormat) -> usize {
    match nodes.width() {
        Some(_) => WIDE_SLOTS,
        None => UNIT_SLOTS,
    }
}

/// The wide units the RTL builds, as (node width, node bits, triangle bits): the small test
/// memories and the XC7Z020's 8-wide memory (2,048 nodes, 8,192 triangles).
pub const BUILT_WIDE_MEMORY_BITS: [(usize, usize, usize); 3] = [(4, 4, 5), (8, 4, 5), (8, 11, 13)];
/// The wide memory on the XC7Z020.
pub const ZYNQ_WIDE_MEMORY_BITS: (usize, usize) = (11, 13);

/// The scene memories the RTL builds, as (node, triangle) address bits: a type each
/// (`scene_memory::SceneMemory4x5` …, `unit_top::<format>::Unit4x5` …).
pub const BUILT_MEMORY_BITS: [(usize, usize); 4] = [(4, 5), (9, 10), (11, 12), (12, 13)];

/// A unit the RTL builds: one Rust type per node format and scene memory size
/// (`unit_top::<format>::Unit4x5` … `WideUnit8w11x13`, and `unit_axil`'s AXI4-Lite tops around
/// them). Both dispatch on it, exhaustively, so a configuration builds the same unit with and
/// without its register slave.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BuiltUnit {
    Binary4x5,
    Binary9x10,
    Binary11x12,
    Binary12x13,
    Wide4w4x5,
    Wide8w4x5,
    Wide8w11x13,
}

impl BuiltUnit {
    /// Each unit with its node width (none: binary) and its (node, triangle) address bits:
    /// `BUILT_MEMORY_BITS` and `BUILT_WIDE_MEMORY_BITS` (a test keeps them equal).
    pub const ALL: [(BuiltUnit, Option<usize>, (usize, usize)); 7] = [
        (BuiltUnit::Binary4x5, None, (4, 5)),
        (BuiltUnit::Binary9x10, None, (9, 10)),
        (BuiltUnit::Binary11x12, None, (11, 12)),
        (BuiltUnit::Binary12x13, None, (12, 13)),
        (BuiltUnit::Wide4w4x5, Some(4), (4, 5)),
        (BuiltUnit::Wide8w4x5, Some(8), (4, 5)),
        (BuiltUnit::Wide8w11x13, Some(8), (11, 13)),
    ];
}

/// The scene memories the RTL builds for `nodes`, as "4/5, 9/10, …".
fn built_memory_bits(nodes: NodeFormat) -> String {
    let sizes: Vec<String> = match nodes.width() {
        None => BUILT_MEMORY_BITS
            .iter()
            .map(|(n, t)| format!("{n}/{t}"))
            .collect(),
        Some(width) => BUILT_WIDE_MEMORY_BITS
            .iter()
            .filter(|(k, _, _)| *k == width)
            .map(|(_, n, t)| format!("{n}/{t}"))
            .collect(),
    };
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
    #[error("the traversal unit's RTL walks bvh2-fp32, bvh4-q8 and bvh8-q8 nodes, not {}", .0.name())]
    Nodes(NodeFormat),
    #[error("the traversal unit's RTL for {} nodes has {} ray slots, not {slots}", .nodes.name(), slots_for(*.nodes))]
    Slots { nodes: NodeFormat, slots: usize },
    #[error("a stack of {0} entries: the unit's stacks hold 1 to {MAX_STACK_DEPTH}")]
    StackDepth(usize),
    #[error("the traversal unit's RTL advances to the leaf box (leaf-box) or not at all (none), not {}", .0.name())]
    Advance(Advance),
    #[error("no scene memory of {node_bits} node and {triangle_bits} triangle address bits is built for {} nodes (sizes: {})", .nodes.name(), built_memory_bits(*.nodes))]
    Memory {
        nodes: NodeFormat,
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

    /// The unit walking `nodes` (its slots and, for wide nodes, the XC7Z020's wide memory).
    pub fn with_nodes(self, nodes: NodeFormat) -> UnitConfig {
        let memory = match nodes.width() {
            Some(_) => MemoryConfig {
                node_bits: ZYNQ_WIDE_MEMORY_BITS.0,
                triangle_bits: ZYNQ_WIDE_MEMORY_BITS.1,
            },
            None => {
                let (node_bits, triangle_bits) = zynq_address_bits(self.lanes);
                MemoryConfig {
                    node_bits,
                    triangle_bits,
                }
            }
        };
        UnitConfig {
            nodes,
            slots: slots_for(nodes),
            memory,
            ..self
        }
    }

    /// The unit's timing, as the schedule model takes it.
    pub fn timing(&self) -> UnitTiming {
        let binary = unit_timing(
            self.format,
            self.depth,
            self.lanes,
            self.slots,
            self.advance,
        );
        node_timing(binary, self.nodes, self.depth, 1)
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
        if self.nodes == NodeFormat::Bvh2Q8 {
            return Err(UnitConfigError::Nodes(self.nodes));
        }
        if self.slots != slots_for(self.nodes) {
            return Err(UnitConfigError::Slots {
                nodes: self.nodes,
                slots: self.slots,
            });
        }
        if !(1..=MAX_STACK_DEPTH).contains(&self.stack_depth) {
            return Err(UnitConfigError::StackDepth(self.stack_depth));
        }
        if self.advance == Advance::TriangleBox {
            return Err(UnitConfigError::Advance(self.advance));
        }
        self.built().map(|_| ())
    }

    /// The unit type the RTL builds for this configuration's node format and memory, or the
    /// error naming the sizes it builds.
    pub fn built(&self) -> Result<BuiltUnit, UnitConfigError> {
        let bits = (self.memory.node_bits, self.memory.triangle_bits);
        BuiltUnit::ALL
            .iter()
            .find(|(_, width, b)| *width == self.nodes.width() && *b == bits)
            .map(|(unit, _, _)| *unit)
            .ok_or(UnitConfigError::Memory {
                nodes: self.nodes,
                node_bits: bits.0,
                triangle_bits: bits.1,
            })
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
/// bits (a pointer up to the depth plus a push of K − 1) and bank address bits (slots ×
/// ⌈depth / K⌉ rows a bank).
pub const fn wide_stack_pointer_bits(k: usize) -> usize {
    (MAX_STACK_DEPTH + k - 1).ilog2() as usize + 1
}
pub const fn wide_stack_row_bits(k: usize) -> usize {
    let rows = (WIDE_SLOTS * MAX_STACK_DEPTH.div_ceil(k)).ilog2() as usize;
    let pointer = wide_stack_pointer_bits(k);
    if rows > pointer {
        rows
    } else {
        pointer
    }
}
