//! C header and bare-metal driver generated from the register map ([`crate::regmap`]).
//!
//! The names follow what Vitis HLS emits for an `s_axi_control` slave
//! (`XRTFPGA_CONTROL_ADDR_AP_CTRL`, `..._ADDR_ORIG_X_DATA`, `..._BITS_ORIG_X_DATA`), so a
//! thesis-style bare-metal program ports over; the driver talks to the device only through
//! `Xil_In32`/`Xil_Out32` of the Xilinx standalone BSP (`xil_io.h`).
use std::fmt::Write;

use hw_model::HwFormat;

use crate::regmap::{self, unit, Access, Register, RegisterMap};

/// File names of the generated sources (the driver includes the header by these names).
pub const HEADER_FILE: &str = "xrtfpga_hw.h";
pub const DRIVER_HEADER_FILE: &str = "xrtfpga.h";
pub const DRIVER_SOURCE_FILE: &str = "xrtfpga.c";
/// The traversal unit's (`regmap::unit`).
pub const UNIT_HEADER_FILE: &str = "xrtfpga_unit_hw.h";
pub const UNIT_DRIVER_HEADER_FILE: &str = "xrtfpga_unit.h";
pub const UNIT_DRIVER_SOURCE_FILE: &str = "xrtfpga_unit.c";

/// Registers that carry a value (operands, results, id, config, counters) get Vitis'
/// `_DATA` suffix; the block-control registers keep their bare name.
fn addr_macro(map: &RegisterMap, r: &Register) -> String {
    let prefix = map.c_prefix;
    if map.control.contains(&r.offset) {
        format!("{prefix}_ADDR_{}", r.name)
    } else {
        format!("{prefix}_ADDR_{}_DATA", r.name)
    }
}

fn access_text(a: Access) -> &'static str {
    match a {
        Access::Rw => "Read/Write",
        Access::Ro => "Read",
        Access::Cor => "Read/COR",
        Access::W1t => "Read/TOW",
        Access::Pulse => "Write 1/Pulse",
    }
}

/// `#define NAME value` in the header's column layout.
fn define(s: &mut String, name: &str, value: impl std::fmt::Display) {
    writeln!(s, "#define {name:<40} {value}").unwrap();
}

/// A register-map header: addresses, widths, bit masks, `constants` (name after the
/// prefix, value), the id and the CONFIG word's decoding, the format codes, then `tail`.
fn map_header(map: &RegisterMap, file: &str, constants: &[(&str, String)], tail: &str) -> String {
    let p = map.c_prefix;
    let mut s = String::new();
    let guard = file.to_ascii_uppercase().replace('.', "_");
    writeln!(s, "// Generated from {} — do not edit.", map.source).unwrap();
    writeln!(
        s,
        "// AXI4-Lite register map of the {} (s_axi_control).",
        map.title
    )
    .unwrap();
    for r in map.registers {
        writeln!(
            s,
            "// 0x{:02x} : {} — {} ({})",
            r.offset,
            r.name,
            r.description,
            access_text(r.access)
        )
        .unwrap();
        for f in r.fields {
            let bits = if f.width == 1 {
                format!("bit {}", f.lsb)
            } else {
                format!("bits {}:{}", f.lsb + f.width - 1, f.lsb)
            };
            writeln!(
                s,
                "//        {bits} - {} ({}): {}",
                f.name,
                access_text(f.access),
                f.description
            )
            .unwrap();
        }
    }
    writeln!(
        s,
        "// Unmapped offsets and writes to read-only registers answer SLVERR."
    )
    .unwrap();
    writeln!(s, "\n#ifndef {guard}\n#define {guard}\n").unwrap();
    for r in map.registers {
        define(&mut s, &addr_macro(map, r), format!("0x{:02x}", r.offset));
        if !map.control.contains(&r.offset) {
            define(&mut s, &format!("{p}_BITS_{}_DATA", r.name), r.width);
        }
    }
    writeln!(s).unwrap();
    for r in map.registers {
        for f in r.fields {
            define(
                &mut s,
                &format!("{p}_{}_{}_MASK", r.name, f.name),
                format!("0x{:08x}u", f.mask()),
            );
        }
    }
    writeln!(s).unwrap();
    for (name, value) in constants {
        define(&mut s, &format!("{p}_{name}"), value);
    }
    define(
        &mut s,
        &format!("{p}_ID_VALUE"),
        format!("0x{:08x}u", map.id_value),
    );
    writeln!(s, "#define {p}_CONFIG_FORMAT(w) ((unsigned)(w) & 0xffu)").unwrap();
    writeln!(
        s,
        "#define {p}_CONFIG_DEPTH(w)  (((unsigned)(w) >> 8) & 0xffu)"
    )
    .unwrap();
    writeln!(
        s,
        "#define {p}_CONFIG_LANES(w)  (((unsigned)(w) >> 16) & 0xffu)"
    )
    .unwrap();
    format_codes(&mut s, p);
    s.push_str(tail);
    writeln!(s, "\n#endif // {guard}").unwrap();
    s
}

/// The accelerator's register-map header ([`HEADER_FILE`]).
pub fn c_header() -> String {
    map_header(
        &regmap::MAP,
        HEADER_FILE,
        &[("OPERAND_COUNT", regmap::OPERAND_COUNT.to_string())],
        "",
    )
}

/// The traversal unit's register-map header ([`UNIT_HEADER_FILE`]): also the MEMORY
/// word's decoding and the error code's position.
pub fn unit_c_header() -> String {
    let p = unit::MAP.c_prefix;
    let memory = ["NODE_BITS", "TRIANGLE_BITS", "STACK_DEPTH", "SLOTS"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            format!(
                "#define {p}_MEMORY_{name}(w) (((unsigned)(w) >> {}) & 0xffu)\n",
                8 * k
            )
        })
        .collect::<String>();
    map_header(
        &unit::MAP,
        UNIT_HEADER_FILE,
        &[
            ("COUNTER_COUNT", unit::COUNTERS.len().to_string()),
            ("RESET_CYCLES", unit::RESET_CYCLES.to_string()),
            ("STATUS_ERROR_CODE_SHIFT", unit::ERROR_CODE_LSB.to_string()),
        ],
        &format!("\n// The MEMORY word's fields.\n{memory}"),
    )
}

/// The CONFIG register's format codes: a macro a format and the code → name table.
fn format_codes(s: &mut String, p: &str) {
    writeln!(
        s,
        "\n// Format codes of {p}_CONFIG_FORMAT (the format catalogue, `rtfpga formats`)."
    )
    .unwrap();
    for f in HwFormat::all() {
        let name = format!("{p}_FORMAT_{}", f.name().to_ascii_uppercase());
        define(s, &name, f.code());
    }
    define(s, &format!("{p}_FORMAT_COUNT"), HwFormat::all().len());
    let names: Vec<String> = HwFormat::all().map(|f| format!("\"{f}\"")).collect();
    writeln!(
        s,
        "// Names by code: static const char *const Names[] = {p}_FORMAT_NAMES;"
    )
    .unwrap();
    writeln!(s, "#define {p}_FORMAT_NAMES {{ {} }}", names.join(", ")).unwrap();
}

/// The address macros of `offsets`, one a line (a C initialiser list).
fn offset_list(map: &RegisterMap, offsets: &[usize]) -> String {
    offsets
        .iter()
        .map(|&o| addr_macro(map, map.register(o)))
        .collect::<Vec<_>>()
        .join(",\n    ")
}

fn data_macro(map: &RegisterMap, offset: usize) -> String {
    addr_macro(map, map.register(offset))
}

/// The driver's access functions (`ReadReg`, `WriteReg` through the BSP) of `instance`.
fn register_access(instance: &str) -> String {
    format!(
        r#"static u32 ReadReg(const {instance} *InstancePtr, u32 Offset)
{{
    return Xil_In32(InstancePtr->BaseAddress + Offset);
}}

static void WriteReg(const {instance} *InstancePtr, u32 Offset, u32 Value)
{{
    Xil_Out32(InstancePtr->BaseAddress + Offset, Value);
}}
"#
    )
}

/// The bare-metal driver: (`xrtfpga.h`, `xrtfpga.c`). It needs the BSP's `xil_io.h` and the
/// header from [`c_header`] saved as [`HEADER_FILE`].
pub fn c_driver() -> (String, String) {
    let map = &regmap::MAP;
    let p = map.c_prefix;
    let source = map.source;
    let header = format!(
        r#"// Generated from {source} — do not edit.
// Bare-metal driver of the ray/triangle accelerator (register mode).
#ifndef XRTFPGA_H
#define XRTFPGA_H

#include "xil_io.h"
#include "{HEADER_FILE}"

typedef struct {{
    UINTPTR BaseAddress;
}} XRtfpga;

typedef struct {{
    float Orig[3];
    float Dir[3];
    /* A hit needs t > TMin (0: every hit in front of the origin). */
    float TMin;
}} XRtfpga_Ray;

typedef struct {{
    float V0[3];
    float V1[3];
    float V2[3];
}} XRtfpga_Triangle;

typedef struct {{
    u32 Hit;
    float T;
    float U;
    float V;
}} XRtfpga_Result;

void XRtfpga_Initialize(XRtfpga *InstancePtr, UINTPTR BaseAddress);
void XRtfpga_WriteRay(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray);
void XRtfpga_WriteTriangle(XRtfpga *InstancePtr, const XRtfpga_Triangle *Tri);
void XRtfpga_Start(XRtfpga *InstancePtr);
/* Reading the control register clears ap_done and ap_ready. */
u32 XRtfpga_IsDone(XRtfpga *InstancePtr);
u32 XRtfpga_IsIdle(XRtfpga *InstancePtr);
void XRtfpga_EnableAutoRestart(XRtfpga *InstancePtr);
void XRtfpga_DisableAutoRestart(XRtfpga *InstancePtr);
void XRtfpga_ReadResult(XRtfpga *InstancePtr, XRtfpga_Result *Result);
u32 XRtfpga_ReadId(XRtfpga *InstancePtr);
u32 XRtfpga_ReadConfig(XRtfpga *InstancePtr);
/* Write the ray and the triangle, start, poll ap_done at most MaxPolls times and read the
   result. Returns 0 on success, -1 if the core did not finish in time. */
int XRtfpga_Intersect(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray,
                      const XRtfpga_Triangle *Tri, XRtfpga_Result *Result, u32 MaxPolls);

void XRtfpga_InterruptGlobalEnable(XRtfpga *InstancePtr);
void XRtfpga_InterruptGlobalDisable(XRtfpga *InstancePtr);
/* Mask: {p}_IER_DONE_MASK | {p}_IER_READY_MASK */
void XRtfpga_InterruptEnable(XRtfpga *InstancePtr, u32 Mask);
void XRtfpga_InterruptDisable(XRtfpga *InstancePtr, u32 Mask);
/* Clears the given pending bits (the status register toggles on a written 1). */
void XRtfpga_InterruptClear(XRtfpga *InstancePtr, u32 Mask);
u32 XRtfpga_InterruptGetStatus(XRtfpga *InstancePtr);

#endif // XRTFPGA_H
"#
    );
    let source = format!(
        r#"// Generated from {source} — do not edit.
#include <string.h>
#include "{DRIVER_HEADER_FILE}"

static const u32 RayOffsets[6] = {{
    {ray}
}};

static const u32 TriangleOffsets[9] = {{
    {tri}
}};

static u32 FloatBits(float F)
{{
    u32 Bits;
    memcpy(&Bits, &F, sizeof Bits);
    return Bits;
}}

static float BitsFloat(u32 Bits)
{{
    float F;
    memcpy(&F, &Bits, sizeof F);
    return F;
}}

{access}
void XRtfpga_Initialize(XRtfpga *InstancePtr, UINTPTR BaseAddress)
{{
    InstancePtr->BaseAddress = BaseAddress;
}}

void XRtfpga_WriteRay(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray)
{{
    for (int i = 0; i < 3; i++) {{
        WriteReg(InstancePtr, RayOffsets[i], FloatBits(Ray->Orig[i]));
        WriteReg(InstancePtr, RayOffsets[3 + i], FloatBits(Ray->Dir[i]));
    }}
    WriteReg(InstancePtr, {t_min}, FloatBits(Ray->TMin));
}}

void XRtfpga_WriteTriangle(XRtfpga *InstancePtr, const XRtfpga_Triangle *Tri)
{{
    for (int i = 0; i < 3; i++) {{
        WriteReg(InstancePtr, TriangleOffsets[i], FloatBits(Tri->V0[i]));
        WriteReg(InstancePtr, TriangleOffsets[3 + i], FloatBits(Tri->V1[i]));
        WriteReg(InstancePtr, TriangleOffsets[6 + i], FloatBits(Tri->V2[i]));
    }}
}}

void XRtfpga_Start(XRtfpga *InstancePtr)
{{
    u32 Ctrl = ReadReg(InstancePtr, {p}_ADDR_AP_CTRL) & {p}_AP_CTRL_AUTO_RESTART_MASK;
    WriteReg(InstancePtr, {p}_ADDR_AP_CTRL, Ctrl | {p}_AP_CTRL_AP_START_MASK);
}}

u32 XRtfpga_IsDone(XRtfpga *InstancePtr)
{{
    return (ReadReg(InstancePtr, {p}_ADDR_AP_CTRL) & {p}_AP_CTRL_AP_DONE_MASK) != 0;
}}

u32 XRtfpga_IsIdle(XRtfpga *InstancePtr)
{{
    return (ReadReg(InstancePtr, {p}_ADDR_AP_CTRL) & {p}_AP_CTRL_AP_IDLE_MASK) != 0;
}}

void XRtfpga_EnableAutoRestart(XRtfpga *InstancePtr)
{{
    WriteReg(InstancePtr, {p}_ADDR_AP_CTRL, {p}_AP_CTRL_AUTO_RESTART_MASK);
}}

void XRtfpga_DisableAutoRestart(XRtfpga *InstancePtr)
{{
    WriteReg(InstancePtr, {p}_ADDR_AP_CTRL, 0);
}}

void XRtfpga_ReadResult(XRtfpga *InstancePtr, XRtfpga_Result *Result)
{{
    Result->Hit = (ReadReg(InstancePtr, {result}) & {p}_RESULT_HIT_MASK) != 0;
    Result->T = BitsFloat(ReadReg(InstancePtr, {t}));
    Result->U = BitsFloat(ReadReg(InstancePtr, {u}));
    Result->V = BitsFloat(ReadReg(InstancePtr, {v}));
}}

u32 XRtfpga_ReadId(XRtfpga *InstancePtr)
{{
    return ReadReg(InstancePtr, {id});
}}

u32 XRtfpga_ReadConfig(XRtfpga *InstancePtr)
{{
    return ReadReg(InstancePtr, {config});
}}

int XRtfpga_Intersect(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray,
                      const XRtfpga_Triangle *Tri, XRtfpga_Result *Result, u32 MaxPolls)
{{
    XRtfpga_WriteRay(InstancePtr, Ray);
    XRtfpga_WriteTriangle(InstancePtr, Tri);
    XRtfpga_Start(InstancePtr);
    for (u32 Poll = 0; Poll < MaxPolls; Poll++) {{
        if (XRtfpga_IsDone(InstancePtr)) {{
            XRtfpga_ReadResult(InstancePtr, Result);
            return 0;
        }}
    }}
    return -1;
}}

void XRtfpga_InterruptGlobalEnable(XRtfpga *InstancePtr)
{{
    WriteReg(InstancePtr, {p}_ADDR_GIE, {p}_GIE_ENABLE_MASK);
}}

void XRtfpga_InterruptGlobalDisable(XRtfpga *InstancePtr)
{{
    WriteReg(InstancePtr, {p}_ADDR_GIE, 0);
}}

void XRtfpga_InterruptEnable(XRtfpga *InstancePtr, u32 Mask)
{{
    u32 Enabled = ReadReg(InstancePtr, {p}_ADDR_IER);
    WriteReg(InstancePtr, {p}_ADDR_IER, Enabled | Mask);
}}

void XRtfpga_InterruptDisable(XRtfpga *InstancePtr, u32 Mask)
{{
    u32 Enabled = ReadReg(InstancePtr, {p}_ADDR_IER);
    WriteReg(InstancePtr, {p}_ADDR_IER, Enabled & ~Mask);
}}

void XRtfpga_InterruptClear(XRtfpga *InstancePtr, u32 Mask)
{{
    /* Toggle only the bits that are set, so a clear never raises a bit. */
    u32 Pending = ReadReg(InstancePtr, {p}_ADDR_ISR);
    WriteReg(InstancePtr, {p}_ADDR_ISR, Pending & Mask);
}}

u32 XRtfpga_InterruptGetStatus(XRtfpga *InstancePtr)
{{
    return ReadReg(InstancePtr, {p}_ADDR_ISR);
}}
"#,
        access = register_access("XRtfpga"),
        ray = offset_list(map, &regmap::OPERANDS[..6]),
        tri = offset_list(map, &regmap::OPERANDS[6..crate::mt::T_MIN_WORD]),
        t_min = data_macro(map, regmap::T_MIN),
        result = data_macro(map, regmap::RESULT),
        t = data_macro(map, regmap::T),
        u = data_macro(map, regmap::U),
        v = data_macro(map, regmap::V),
        id = data_macro(map, regmap::ID),
        config = data_macro(map, regmap::CONFIG),
    );
    (header, source)
}

/// The traversal unit's bare-metal driver (`xrtfpga_unit.h`, `xrtfpga_unit.c`): id and
/// configuration, scene load start and status, reset, the counters. The scene image, the
/// rays and the answers travel on the unit's AXI4-Stream ports (a DMA's job). It needs the
/// BSP's `xil_io.h` and the header from [`unit_c_header`] saved as [`UNIT_HEADER_FILE`].
pub fn unit_c_driver() -> (String, String) {
    let map = &unit::MAP;
    let (p, source) = (map.c_prefix, map.source);
    let header = format!(
        r#"// Generated from {source} — do not edit.
// Bare-metal driver of the traversal unit's control registers.
#ifndef XRTFPGA_UNIT_H
#define XRTFPGA_UNIT_H

#include "xil_io.h"
#include "{UNIT_HEADER_FILE}"

typedef struct {{
    UINTPTR BaseAddress;
}} XRtfpga_unit;

/* The unit's wrapping 32-bit counters. */
typedef struct {{
    u32 Rays;
    u32 NodeVisits;
    u32 BoxTests;
    u32 MtTests;
    u32 BusyCycles;
}} XRtfpga_unit_Counters;

/* The first refusal of a scene load: its code (0: none, docs/scene-image.md), the image
   word's index and value. */
typedef struct {{
    u32 Code;
    u32 Word;
    u32 Value;
}} XRtfpga_unit_SceneError;

void XRtfpga_unit_Initialize(XRtfpga_unit *InstancePtr, UINTPTR BaseAddress);
u32 XRtfpga_unit_ReadId(XRtfpga_unit *InstancePtr);
u32 XRtfpga_unit_ReadConfig(XRtfpga_unit *InstancePtr);
u32 XRtfpga_unit_ReadMemory(XRtfpga_unit *InstancePtr);
u32 XRtfpga_unit_ReadStatus(XRtfpga_unit *InstancePtr);
u32 XRtfpga_unit_IsIdle(XRtfpga_unit *InstancePtr);
/* Begin a scene load (only while idle); then stream the image on the scene port. */
void XRtfpga_unit_StartSceneLoad(XRtfpga_unit *InstancePtr);
/* After the image: 1 loaded, 0 refused (Error filled in), -1 neither yet (still loading). */
int XRtfpga_unit_SceneStatus(XRtfpga_unit *InstancePtr, XRtfpga_unit_SceneError *Error);
u32 XRtfpga_unit_ReadSceneWords(XRtfpga_unit *InstancePtr);
/* 1 if a ray's stack overflowed (sticky until a reset; RayId: the first such ray). */
u32 XRtfpga_unit_Overflowed(XRtfpga_unit *InstancePtr, u32 *RayId);
/* Reset the unit (slots emptied, counters and overflow cleared) and wait at most MaxPolls
   status reads for the reset to end. Returns 0, or -1 if it did not end in time. */
int XRtfpga_unit_Reset(XRtfpga_unit *InstancePtr, u32 MaxPolls);
void XRtfpga_unit_ReadCounters(XRtfpga_unit *InstancePtr, XRtfpga_unit_Counters *Counters);
/* Diff = After - Before, counter by counter, modulo 2^32 (the counters wrap). */
void XRtfpga_unit_CountersSince(const XRtfpga_unit_Counters *Before,
                                const XRtfpga_unit_Counters *After,
                                XRtfpga_unit_Counters *Diff);

#endif // XRTFPGA_UNIT_H
"#
    );
    let driver = format!(
        r#"// Generated from {source} — do not edit.
#include "{UNIT_DRIVER_HEADER_FILE}"

{access}
void XRtfpga_unit_Initialize(XRtfpga_unit *InstancePtr, UINTPTR BaseAddress)
{{
    InstancePtr->BaseAddress = BaseAddress;
}}

u32 XRtfpga_unit_ReadId(XRtfpga_unit *InstancePtr)
{{
    return ReadReg(InstancePtr, {id});
}}

u32 XRtfpga_unit_ReadConfig(XRtfpga_unit *InstancePtr)
{{
    return ReadReg(InstancePtr, {config});
}}

u32 XRtfpga_unit_ReadMemory(XRtfpga_unit *InstancePtr)
{{
    return ReadReg(InstancePtr, {memory});
}}

u32 XRtfpga_unit_ReadStatus(XRtfpga_unit *InstancePtr)
{{
    return ReadReg(InstancePtr, {p}_ADDR_STATUS);
}}

u32 XRtfpga_unit_IsIdle(XRtfpga_unit *InstancePtr)
{{
    return (XRtfpga_unit_ReadStatus(InstancePtr) & {p}_STATUS_IDLE_MASK) != 0;
}}

void XRtfpga_unit_StartSceneLoad(XRtfpga_unit *InstancePtr)
{{
    WriteReg(InstancePtr, {p}_ADDR_CONTROL, {p}_CONTROL_LOAD_START_MASK);
}}

int XRtfpga_unit_SceneStatus(XRtfpga_unit *InstancePtr, XRtfpga_unit_SceneError *Error)
{{
    u32 Status = XRtfpga_unit_ReadStatus(InstancePtr);
    if (Status & {p}_STATUS_SCENE_LOADED_MASK) {{
        return 1;
    }}
    if (Status & {p}_STATUS_SCENE_ERROR_MASK) {{
        Error->Code = (Status & {p}_STATUS_ERROR_CODE_MASK) >> {p}_STATUS_ERROR_CODE_SHIFT;
        Error->Word = ReadReg(InstancePtr, {error_word});
        Error->Value = ReadReg(InstancePtr, {error_value});
        return 0;
    }}
    return -1;
}}

u32 XRtfpga_unit_ReadSceneWords(XRtfpga_unit *InstancePtr)
{{
    return ReadReg(InstancePtr, {scene_words});
}}

u32 XRtfpga_unit_Overflowed(XRtfpga_unit *InstancePtr, u32 *RayId)
{{
    if ((XRtfpga_unit_ReadStatus(InstancePtr) & {p}_STATUS_OVERFLOW_MASK) == 0) {{
        return 0;
    }}
    *RayId = ReadReg(InstancePtr, {overflow_ray});
    return 1;
}}

int XRtfpga_unit_Reset(XRtfpga_unit *InstancePtr, u32 MaxPolls)
{{
    WriteReg(InstancePtr, {p}_ADDR_CONTROL, {p}_CONTROL_RESET_MASK);
    for (u32 Poll = 0; Poll < MaxPolls; Poll++) {{
        if ((XRtfpga_unit_ReadStatus(InstancePtr) & {p}_STATUS_RESETTING_MASK) == 0) {{
            return 0;
        }}
    }}
    return -1;
}}

void XRtfpga_unit_ReadCounters(XRtfpga_unit *InstancePtr, XRtfpga_unit_Counters *Counters)
{{
    Counters->Rays = ReadReg(InstancePtr, {rays});
    Counters->NodeVisits = ReadReg(InstancePtr, {node_visits});
    Counters->BoxTests = ReadReg(InstancePtr, {box_tests});
    Counters->MtTests = ReadReg(InstancePtr, {mt_tests});
    Counters->BusyCycles = ReadReg(InstancePtr, {busy_cycles});
}}

void XRtfpga_unit_CountersSince(const XRtfpga_unit_Counters *Before,
                                const XRtfpga_unit_Counters *After,
                                XRtfpga_unit_Counters *Diff)
{{
    Diff->Rays = After->Rays - Before->Rays;
    Diff->NodeVisits = After->NodeVisits - Before->NodeVisits;
    Diff->BoxTests = After->BoxTests - Before->BoxTests;
    Diff->MtTests = After->MtTests - Before->MtTests;
    Diff->BusyCycles = After->BusyCycles - Before->BusyCycles;
}}
"#,
        access = register_access("XRtfpga_unit"),
        id = data_macro(map, unit::ID),
        config = data_macro(map, unit::CONFIG),
        memory = data_macro(map, unit::MEMORY),
        error_word = data_macro(map, unit::SCENE_ERROR_WORD),
        error_value = data_macro(map, unit::SCENE_ERROR_VALUE),
        scene_words = data_macro(map, unit::SCENE_WORDS),
        overflow_ray = data_macro(map, unit::OVERFLOW_RAY),
        rays = data_macro(map, unit::RAYS),
        node_visits = data_macro(map, unit::NODE_VISITS),
        box_tests = data_macro(map, unit::BOX_TESTS),
        mt_tests = data_macro(map, unit::MT_TESTS),
        busy_cycles = data_macro(map, unit::BUSY_CYCLES),
    );
    (header, driver)
}
