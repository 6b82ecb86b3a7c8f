//! The traversal unit's AXI4-Lite register map (`traversal::unit_axil`): control, status,
//! scene size and the counters. The rays, the answers and the scene image travel on the
//! unit's AXI4-Stream ports; this map starts a scene load and reads how it went.
//!
//! The counters are the unit's 32-bit wrapping counters, read live: software takes
//! differences of two readings (as `sim::traversal_unit` does). A set read while `IDLE` is
//! consistent, as nothing counts in an idle unit (busy cycles count only with a ray in it),
//! so no snapshot register is needed. RESET clears them.

use super::{field, word, Access, Field, Register, RegisterMap};
use crate::traversal::scene_memory::ERROR_CODE_BITS;

/// Control: LOAD_START, RESET (pulses).
pub const CONTROL: usize = 0x00;
/// Status: IDLE, SCENE_LOADED, SCENE_ERROR, OVERFLOW, RESETTING, ERROR_CODE.
pub const STATUS: usize = 0x04;
/// Identification: [`UNIT_ID`] in bits 31:16, version major 15:8, minor 7:0.
pub const ID: usize = 0x08;
/// The lane's configuration, packed by `regmap::ConfigWord::pack` (as the accelerator's).
pub const CONFIG: usize = 0x0C;
/// The unit's sizes, packed by [`MemoryWord::pack`].
pub const MEMORY: usize = 0x10;
/// Words the scene stream delivered since the last LOAD_START.
pub const SCENE_WORDS: usize = 0x14;
/// The first load error's word index and value.
pub const SCENE_ERROR_WORD: usize = 0x18;
pub const SCENE_ERROR_VALUE: usize = 0x1C;
/// The first ray whose stack overflowed.
pub const OVERFLOW_RAY: usize = 0x20;
pub const RAYS: usize = 0x24;
pub const NODE_VISITS: usize = 0x28;
pub const BOX_TESTS: usize = 0x2C;
pub const MT_TESTS: usize = 0x30;
pub const BUSY_CYCLES: usize = 0x34;

/// The counters in port order (`count_rays`, `count_node_visits`, `count_box_tests`,
/// `count_mt_tests`, `count_busy_cycles`).
pub const COUNTERS: [usize; 5] = [RAYS, NODE_VISITS, BOX_TESTS, MT_TESTS, BUSY_CYCLES];

/// Bits of [`CONTROL`].
pub const LOAD_START: u32 = 1 << 0;
pub const RESET: u32 = 1 << 1;
/// Bits of [`STATUS`].
pub const IDLE: u32 = 1 << 0;
pub const SCENE_LOADED: u32 = 1 << 1;
pub const SCENE_ERROR: u32 = 1 << 2;
pub const OVERFLOW: u32 = 1 << 3;
pub const RESETTING: u32 = 1 << 4;
/// The load error's code (`scene_memory::LoadError`, 0: none) at bits 8 and up.
pub const ERROR_CODE_LSB: u32 = 8;

/// Cycles a RESET holds the unit in reset: longer than any step in flight (a lane plus the
/// far end), which finishes into its slot (docs/traversal-unit.md "Ports").
pub const RESET_CYCLES: u32 = 255;

/// "RU" (ray unit) in the upper half of the id register.
pub const UNIT_ID: u16 = 0x5255;
pub const VERSION: (u8, u8) = (1, 0);
pub const ID_VALUE: u32 = super::id_word(UNIT_ID, VERSION);

/// Contents of the [`MEMORY`] register: the unit's sizes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryWord {
    /// Address bits of the node and the triangle memory (capacity 2^bits records).
    pub node_bits: u8,
    pub triangle_bits: u8,
    /// Entries of a ray's stack, and ray slots.
    pub stack_depth: u8,
    pub slots: u8,
}

impl MemoryWord {
    pub fn pack(self) -> u32 {
        u32::from_le_bytes([
            self.node_bits,
            self.triangle_bits,
            self.stack_depth,
            self.slots,
        ])
    }

    pub fn unpack(word: u32) -> Self {
        let [node_bits, triangle_bits, stack_depth, slots] = word.to_le_bytes();
        Self {
            node_bits,
            triangle_bits,
            stack_depth,
            slots,
        }
    }
}

/// The unit's register map, in offset order.
pub const REGISTERS: &[Register] = &[
    Register {
        name: "CONTROL",
        offset: CONTROL,
        access: Access::Pulse,
        width: 2,
        reset: 0,
        description: "unit control",
        fields: &[
            field(
                "LOAD_START",
                0,
                Access::Pulse,
                "write 1 to begin a scene load (then stream the image); only while idle",
            ),
            field(
                "RESET",
                1,
                Access::Pulse,
                "write 1 to reset the unit for RESET_CYCLES cycles: slots emptied, counters and overflow cleared",
            ),
        ],
    },
    Register {
        name: "STATUS",
        offset: STATUS,
        access: Access::Ro,
        width: ERROR_CODE_LSB + ERROR_CODE_BITS as u32,
        reset: IDLE,
        description: "unit status",
        fields: &[
            field("IDLE", 0, Access::Ro, "no ray in the unit"),
            field("SCENE_LOADED", 1, Access::Ro, "the last scene load succeeded"),
            field(
                "SCENE_ERROR",
                2,
                Access::Ro,
                "the last scene load failed (ERROR_CODE, SCENE_ERROR_WORD, SCENE_ERROR_VALUE)",
            ),
            field(
                "OVERFLOW",
                3,
                Access::Ro,
                "sticky: a ray's stack overflowed (OVERFLOW_RAY); cleared by RESET",
            ),
            field("RESETTING", 4, Access::Ro, "a RESET is in progress"),
            Field {
                name: "ERROR_CODE",
                lsb: ERROR_CODE_LSB,
                width: ERROR_CODE_BITS as u32,
                access: Access::Ro,
                description: "the load error's code (docs/scene-image.md), 0: none",
            },
        ],
    },
    Register {
        name: "ID",
        offset: ID,
        access: Access::Ro,
        width: 32,
        reset: ID_VALUE,
        description: "identification: 0x5255 in 31:16, version major 15:8, minor 7:0",
        fields: &[],
    },
    Register {
        name: "CONFIG",
        offset: CONFIG,
        access: Access::Ro,
        width: 24,
        reset: 0,
        description: "lane configuration: format code 7:0, pipeline depth 15:8, lanes 23:16",
        fields: &[],
    },
    word(
        "MEMORY",
        MEMORY,
        Access::Ro,
        "sizes: node address bits 7:0, triangle address bits 15:8, stack depth 23:16, slots 31:24",
    ),
    word(
        "SCENE_WORDS",
        SCENE_WORDS,
        Access::Ro,
        "scene image words taken since the last LOAD_START",
    ),
    word(
        "SCENE_ERROR_WORD",
        SCENE_ERROR_WORD,
        Access::Ro,
        "index of the image word the load refused",
    ),
    word(
        "SCENE_ERROR_VALUE",
        SCENE_ERROR_VALUE,
        Access::Ro,
        "the refused word's value",
    ),
    word(
        "OVERFLOW_RAY",
        OVERFLOW_RAY,
        Access::Ro,
        "id of the first ray whose stack overflowed",
    ),
    word("RAYS", RAYS, Access::Ro, "rays taken (wrapping)"),
    word(
        "NODE_VISITS",
        NODE_VISITS,
        Access::Ro,
        "nodes visited, inner nodes and leaves (wrapping)",
    ),
    word(
        "BOX_TESTS",
        BOX_TESTS,
        Access::Ro,
        "box tests: both children of a node, or the root's box (wrapping)",
    ),
    word(
        "MT_TESTS",
        MT_TESTS,
        Access::Ro,
        "Moller-Trumbore tests (wrapping)",
    ),
    word(
        "BUSY_CYCLES",
        BUSY_CYCLES,
        Access::Ro,
        "cycles with a ray in the unit (wrapping)",
    ),
];

/// The unit's map.
pub const MAP: RegisterMap = RegisterMap {
    title: "traversal unit",
    source: "hdl/src/regmap/unit.rs",
    c_prefix: "XRTFPGA_UNIT_CONTROL",
    registers: REGISTERS,
    control: &[CONTROL, STATUS],
    id_value: ID_VALUE,
};
