//! The AXI4-Lite register maps — the one source of truth.
//!
//! The accelerator's map is this module: the offset constants are what the HDL decoder
//! (`axil::slave`) and the simulation bus drivers use; [`REGISTERS`] is the table the C
//! header/driver generator (`cgen`) and the documentation are produced from. The layout
//! follows Vitis HLS' `s_axi_control` slave (`ap_ctrl_hs` block protocol) so the thesis'
//! bare-metal driver style works unchanged. The traversal unit's map is [`unit`], in the same
//! machinery ([`Register`], [`Field`], [`RegisterMap`]).

pub mod unit;

/// Width of the byte address on the AXI4-Lite bus (0x00–0x7F, like a Vitis slave of this size).
pub const ADDR_BITS: usize = 7;
/// Number of addressable 32-bit words (`1 << (ADDR_BITS - 2)`).
pub const WORDS: usize = 1 << (ADDR_BITS - 2);

/// Control: ap_start, ap_done, ap_idle, ap_ready, auto_restart.
pub const CONTROL: usize = 0x00;
/// Global interrupt enable (bit 0).
pub const GIE: usize = 0x04;
/// IP interrupt enable: bit 0 done, bit 1 ready.
pub const IER: usize = 0x08;
/// IP interrupt status: bit 0 done, bit 1 ready; writing 1 toggles a bit.
pub const ISR: usize = 0x0C;
pub const ORIG_X: usize = 0x10;
pub const ORIG_Y: usize = 0x14;
pub const ORIG_Z: usize = 0x18;
pub const DIR_X: usize = 0x1C;
pub const DIR_Y: usize = 0x20;
pub const DIR_Z: usize = 0x24;
pub const V0_X: usize = 0x28;
pub const V0_Y: usize = 0x2C;
pub const V0_Z: usize = 0x30;
pub const V1_X: usize = 0x34;
pub const V1_Y: usize = 0x38;
pub const V1_Z: usize = 0x3C;
pub const V2_X: usize = 0x40;
pub const V2_Y: usize = 0x44;
pub const V2_Z: usize = 0x48;
/// The query's lower bound: a hit needs t > T_MIN (fp32 bits; reset 0, the reference's t > 0).
pub const T_MIN: usize = 0x4C;
/// Result flags: bit 0 hit.
pub const RESULT: usize = 0x50;
pub const T: usize = 0x54;
pub const U: usize = 0x58;
pub const V: usize = 0x5C;
/// Identification: [`ACCEL_ID`] in bits 31:16, version major 15:8, minor 7:0.
pub const ID: usize = 0x60;
/// Configuration of the attached core, packed by [`ConfigWord::pack`].
pub const CONFIG: usize = 0x64;

/// The 16 operands in port order: origin xyz, direction xyz, v0 xyz, v1 xyz, v2 xyz, t_min
/// (`hdl::mt::query_words`, the stream slot's words 0–15).
pub const OPERANDS: [usize; 16] = [
    ORIG_X, ORIG_Y, ORIG_Z, DIR_X, DIR_Y, DIR_Z, V0_X, V0_Y, V0_Z, V1_X, V1_Y, V1_Z, V2_X, V2_Y,
    V2_Z, T_MIN,
];
pub const OPERAND_COUNT: usize = OPERANDS.len();

/// Bits of [`CONTROL`].
pub const AP_START: u32 = 1 << 0;
pub const AP_DONE: u32 = 1 << 1;
pub const AP_IDLE: u32 = 1 << 2;
pub const AP_READY: u32 = 1 << 3;
pub const AUTO_RESTART: u32 = 1 << 7;
/// Bits of [`IER`] and [`ISR`].
pub const INT_DONE: u32 = 1 << 0;
pub const INT_READY: u32 = 1 << 1;
/// Bit of [`GIE`].
pub const GIE_ENABLE: u32 = 1 << 0;
/// Bit of [`RESULT`].
pub const RESULT_HIT: u32 = 1 << 0;

/// AXI response codes.
pub const RESP_OKAY: u32 = 0b00;
pub const RESP_SLVERR: u32 = 0b10;

/// "RF" (ray/FPGA) in the upper half of the id register.
pub const ACCEL_ID: u16 = 0x5246;
/// Version of this register map (1.1: T_MIN at 0x4C; a 1.0 driver that never writes it
/// gets 1.0's t > 0).
pub const VERSION: (u8, u8) = (1, 1);
/// The value the id register reads.
pub const ID_VALUE: u32 = id_word(ACCEL_ID, VERSION);

/// An id register: the block's id in bits 31:16, version major 15:8, minor 7:0.
pub const fn id_word(id: u16, version: (u8, u8)) -> u32 {
    (id as u32) << 16 | (version.0 as u32) << 8 | version.1 as u32
}

/// How software may access a register (or a bit of one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// Read/write.
    Rw,
    /// Read-only; a write to a wholly read-only register answers SLVERR and changes nothing.
    Ro,
    /// Read-only, cleared by a read of the register.
    Cor,
    /// Readable; writing 1 to a bit toggles it.
    W1t,
    /// Writing 1 triggers an action; reads 0.
    Pulse,
}

/// One named bit (or bit group) of a register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: &'static str,
    pub lsb: u32,
    pub width: u32,
    pub access: Access,
    pub description: &'static str,
}

impl Field {
    pub fn mask(&self) -> u32 {
        (((1u64 << self.width) - 1) << self.lsb) as u32
    }
}

/// One 32-bit register of the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Register {
    pub name: &'static str,
    pub offset: usize,
    /// Access of the register as a whole (its fields may refine it).
    pub access: Access,
    /// Number of meaningful bits (from bit 0); the others read 0.
    pub width: u32,
    pub reset: u32,
    pub description: &'static str,
    pub fields: &'static [Field],
}

/// A one-bit field.
pub const fn field(
    name: &'static str,
    lsb: u32,
    access: Access,
    description: &'static str,
) -> Field {
    Field {
        name,
        lsb,
        width: 1,
        access,
        description,
    }
}

/// A 32-bit register without fields, reset 0 (an fp32 operand, a counter, a status word).
const fn word(
    name: &'static str,
    offset: usize,
    access: Access,
    description: &'static str,
) -> Register {
    Register {
        name,
        offset,
        access,
        width: 32,
        reset: 0,
        description,
        fields: &[],
    }
}

/// The register map, in offset order.
pub const REGISTERS: &[Register] = &[
    Register {
        name: "AP_CTRL",
        offset: CONTROL,
        access: Access::Rw,
        width: 8,
        reset: AP_IDLE,
        description: "block-level control (ap_ctrl_hs)",
        fields: &[
            field(
                "AP_START",
                0,
                Access::Rw,
                "write 1 to start; cleared when the core is ready unless auto_restart",
            ),
            field(
                "AP_DONE",
                1,
                Access::Cor,
                "the core finished; cleared by reading this register",
            ),
            field("AP_IDLE", 2, Access::Ro, "the core is not processing"),
            field(
                "AP_READY",
                3,
                Access::Cor,
                "the core took the operands; cleared by reading this register",
            ),
            field(
                "AUTO_RESTART",
                7,
                Access::Rw,
                "restart automatically after each completion",
            ),
        ],
    },
    Register {
        name: "GIE",
        offset: GIE,
        access: Access::Rw,
        width: 1,
        reset: 0,
        description: "global interrupt enable",
        fields: &[field(
            "ENABLE",
            0,
            Access::Rw,
            "enable the interrupt output",
        )],
    },
    Register {
        name: "IER",
        offset: IER,
        access: Access::Rw,
        width: 2,
        reset: 0,
        description: "IP interrupt enable",
        fields: &[
            field("DONE", 0, Access::Rw, "interrupt on ap_done"),
            field("READY", 1, Access::Rw, "interrupt on ap_ready"),
        ],
    },
    Register {
        name: "ISR",
        offset: ISR,
        access: Access::W1t,
        width: 2,
        reset: 0,
        description: "IP interrupt status (set on an enabled event, write 1 to toggle)",
        fields: &[
            field("DONE", 0, Access::W1t, "ap_done happened"),
            field("READY", 1, Access::W1t, "ap_ready happened"),
        ],
    },
    word("ORIG_X", ORIG_X, Access::Rw, "ray origin x (fp32 bits)"),
    word("ORIG_Y", ORIG_Y, Access::Rw, "ray origin y (fp32 bits)"),
    word("ORIG_Z", ORIG_Z, Access::Rw, "ray origin z (fp32 bits)"),
    word("DIR_X", DIR_X, Access::Rw, "ray direction x (fp32 bits)"),
    word("DIR_Y", DIR_Y, Access::Rw, "ray direction y (fp32 bits)"),
    word("DIR_Z", DIR_Z, Access::Rw, "ray direction z (fp32 bits)"),
    word("V0_X", V0_X, Access::Rw, "triangle vertex 0 x (fp32 bits)"),
    word("V0_Y", V0_Y, Access::Rw, "triangle vertex 0 y (fp32 bits)"),
    word("V0_Z", V0_Z, Access::Rw, "triangle vertex 0 z (fp32 bits)"),
    word("V1_X", V1_X, Access::Rw, "triangle vertex 1 x (fp32 bits)"),
    word("V1_Y", V1_Y, Access::Rw, "triangle vertex 1 y (fp32 bits)"),
    word("V1_Z", V1_Z, Access::Rw, "triangle vertex 1 z (fp32 bits)"),
    word("V2_X", V2_X, Access::Rw, "triangle vertex 2 x (fp32 bits)"),
    word("V2_Y", V2_Y, Access::Rw, "triangle vertex 2 y (fp32 bits)"),
    word("V2_Z", V2_Z, Access::Rw, "triangle vertex 2 z (fp32 bits)"),
    word(
        "T_MIN",
        T_MIN,
        Access::Rw,
        "lower bound: a hit needs t > t_min (fp32 bits, compared in the core's format)",
    ),
    Register {
        name: "RESULT",
        offset: RESULT,
        access: Access::Ro,
        width: 1,
        reset: 0,
        description: "result flags of the last completed test",
        fields: &[field("HIT", 0, Access::Ro, "the ray hits the triangle")],
    },
    word("T", T, Access::Ro, "distance along the ray (fp32 bits)"),
    word("U", U, Access::Ro, "barycentric u (fp32 bits)"),
    word("V", V, Access::Ro, "barycentric v (fp32 bits)"),
    Register {
        name: "ID",
        offset: ID,
        access: Access::Ro,
        width: 32,
        reset: ID_VALUE,
        description: "identification: 0x5246 in 31:16, version major 15:8, minor 7:0",
        fields: &[],
    },
    Register {
        name: "CONFIG",
        offset: CONFIG,
        access: Access::Ro,
        width: 24,
        reset: 0,
        description: "core configuration: format code 7:0, pipeline depth 15:8, lanes 23:16",
        fields: &[],
    },
];

/// One slave's register map: what `cgen` generates a C header and driver from.
#[derive(Clone, Copy, Debug)]
pub struct RegisterMap {
    /// What the slave controls (the generated files' first comment).
    pub title: &'static str,
    /// The Rust source of the table (named in the generated files).
    pub source: &'static str,
    /// Prefix of the generated C identifiers, Vitis' `X<IP>_<BUS>`.
    pub c_prefix: &'static str,
    pub registers: &'static [Register],
    /// Offsets of the block-control registers: their C names are bare, Vitis gives every
    /// other register a `_DATA` suffix.
    pub control: &'static [usize],
    /// What the ID register reads.
    pub id_value: u32,
}

impl RegisterMap {
    /// The register at a byte offset, if any (the low two address bits are ignored, as the
    /// bus is word-addressed with byte strobes).
    pub fn register_at(&self, offset: usize) -> Option<&'static Register> {
        self.registers.iter().find(|r| r.offset == offset & !3)
    }

    /// The register at `offset`, which the map's own constants name.
    pub fn register(&self, offset: usize) -> &'static Register {
        self.register_at(offset)
            .unwrap_or_else(|| panic!("{}: no register at 0x{offset:02x}", self.title))
    }
}

/// The accelerator's map.
pub const MAP: RegisterMap = RegisterMap {
    title: "ray/triangle accelerator",
    source: "hdl/src/regmap.rs",
    c_prefix: "XRTFPGA_CONTROL",
    registers: REGISTERS,
    control: &[CONTROL, GIE, IER, ISR],
    id_value: ID_VALUE,
};

/// The accelerator's register at a byte offset, if any ([`RegisterMap::register_at`]).
pub fn register_at(offset: usize) -> Option<&'static Register> {
    MAP.register_at(offset)
}

/// Contents of the [`CONFIG`] register: which core is attached.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConfigWord {
    /// Index of the number format in the format catalogue.
    pub format_code: u8,
    /// Pipeline depth setting of the core.
    pub depth: u8,
    /// Number of parallel datapath lanes.
    pub lanes: u8,
}

impl ConfigWord {
    pub fn pack(self) -> u32 {
        self.format_code as u32 | (self.depth as u32) << 8 | (self.lanes as u32) << 16
    }

    pub fn unpack(word: u32) -> Self {
        Self {
            format_code: word as u8,
            depth: (word >> 8) as u8,
            lanes: (word >> 16) as u8,
        }
    }
}
