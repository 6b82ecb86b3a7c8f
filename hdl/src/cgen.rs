//! C header and bare-metal driver generated from the register map ([`crate::regmap`]).
//!
//! The names follow what Vitis HLS emits for an `s_axi_control` slave
//! (`XRTFPGA_CONTROL_ADDR_AP_CTRL`, `..._ADDR_ORIG_X_DATA`, `..._BITS_ORIG_X_DATA`), so a
//! thesis-style bare-metal program ports over; the driver talks to the device only through
//! `Xil_In32`/`Xil_Out32` of the Xilinx standalone BSP (`xil_io.h`).
use std::fmt::Write;

use hw_model::HwFormat;

use crate::regmap::{self, Access, Register, REGISTERS};

/// Prefix of every generated C identifier.
const PREFIX: &str = "XRTFPGA_CONTROL";
/// File names of the generated sources (the driver includes the header by these names).
pub const HEADER_FILE: &str = "xrtfpga_hw.h";
pub const DRIVER_HEADER_FILE: &str = "xrtfpga.h";
pub const DRIVER_SOURCE_FILE: &str = "xrtfpga.c";

/// Registers that carry a value (operands, results, id, config) get Vitis' `_DATA` suffix;
/// the block-control registers keep their bare name.
fn is_data_register(r: &Register) -> bool {
    ![regmap::CONTROL, regmap::GIE, regmap::IER, regmap::ISR].contains(&r.offset)
}

fn addr_macro(r: &Register) -> String {
    if is_data_register(r) {
        format!("{PREFIX}_ADDR_{}_DATA", r.name)
    } else {
        format!("{PREFIX}_ADDR_{}", r.name)
    }
}

fn access_text(a: Access) -> &'static str {
    match a {
        Access::Rw => "Read/Write",
        Access::Ro => "Read",
        Access::Cor => "Read/COR",
        Access::W1t => "Read/TOW",
    }
}

/// The register-map header: addresses, widths, bit masks, id and config decoding.
pub fn c_header() -> String {
    let mut s = String::new();
    let guard = "XRTFPGA_HW_H";
    writeln!(s, "// Generated from hdl/src/regmap.rs — do not edit.").unwrap();
    writeln!(
        s,
        "// AXI4-Lite register map of the ray/triangle accelerator (s_axi_control)."
    )
    .unwrap();
    for r in REGISTERS {
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
            writeln!(
                s,
                "//        bit {} - {} ({}): {}",
                f.lsb,
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
    for r in REGISTERS {
        writeln!(s, "#define {:<40} 0x{:02x}", addr_macro(r), r.offset).unwrap();
        if is_data_register(r) {
            writeln!(
                s,
                "#define {:<40} {}",
                format!("{PREFIX}_BITS_{}_DATA", r.name),
                r.width
            )
            .unwrap();
        }
    }
    writeln!(s).unwrap();
    for r in REGISTERS {
        for f in r.fields {
            writeln!(
                s,
                "#define {:<40} 0x{:08x}u",
                format!("{PREFIX}_{}_{}_MASK", r.name, f.name),
                f.mask()
            )
            .unwrap();
        }
    }
    writeln!(s).unwrap();
    writeln!(
        s,
        "#define {:<40} {}",
        format!("{PREFIX}_OPERAND_COUNT"),
        regmap::OPERAND_COUNT
    )
    .unwrap();
    writeln!(
        s,
        "#define {:<40} 0x{:08x}u",
        format!("{PREFIX}_ID_VALUE"),
        regmap::ID_VALUE
    )
    .unwrap();
    writeln!(
        s,
        "#define {PREFIX}_CONFIG_FORMAT(w) ((unsigned)(w) & 0xffu)"
    )
    .unwrap();
    writeln!(
        s,
        "#define {PREFIX}_CONFIG_DEPTH(w)  (((unsigned)(w) >> 8) & 0xffu)"
    )
    .unwrap();
    writeln!(
        s,
        "#define {PREFIX}_CONFIG_LANES(w)  (((unsigned)(w) >> 16) & 0xffu)"
    )
    .unwrap();
    format_codes(&mut s);
    writeln!(s, "\n#endif // {guard}").unwrap();
    s
}

/// The CONFIG register's format codes: a macro a format and the code → name table.
fn format_codes(s: &mut String) {
    writeln!(
        s,
        "\n// Format codes of {PREFIX}_CONFIG_FORMAT (the format catalogue, `rtfpga formats`)."
    )
    .unwrap();
    for f in HwFormat::all() {
        let name = format!("{PREFIX}_FORMAT_{}", f.name().to_ascii_uppercase());
        writeln!(s, "#define {name:<40} {}", f.code()).unwrap();
    }
    writeln!(
        s,
        "#define {:<40} {}",
        format!("{PREFIX}_FORMAT_COUNT"),
        HwFormat::all().len()
    )
    .unwrap();
    let names: Vec<String> = HwFormat::all().map(|f| format!("\"{f}\"")).collect();
    writeln!(
        s,
        "// Names by code: static const char *const Names[] = {PREFIX}_FORMAT_NAMES;"
    )
    .unwrap();
    writeln!(
        s,
        "#define {PREFIX}_FORMAT_NAMES {{ {} }}",
        names.join(", ")
    )
    .unwrap();
}

fn offset_list(offsets: &[usize]) -> String {
    offsets
        .iter()
        .map(|&o| addr_macro(regmap::register_at(o).expect("operand offsets are in the table")))
        .collect::<Vec<_>>()
        .join(",\n    ")
}

fn data_macro(offset: usize) -> String {
    addr_macro(regmap::register_at(offset).expect("register offsets are in the table"))
}

/// The bare-metal driver: (`xrtfpga.h`, `xrtfpga.c`). It needs the BSP's `xil_io.h` and the
/// header from [`c_header`] saved as [`HEADER_FILE`].
pub fn c_driver() -> (String, String) {
    let p = PREFIX;
    let header = format!(
        r#"// Generated from hdl/src/regmap.rs — do not edit.
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
        r#"// Generated from hdl/src/regmap.rs — do not edit.
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

static u32 ReadReg(const XRtfpga *InstancePtr, u32 Offset)
{{
    return Xil_In32(InstancePtr->BaseAddress + Offset);
}}

static void WriteReg(const XRtfpga *InstancePtr, u32 Offset, u32 Value)
{{
    Xil_Out32(InstancePtr->BaseAddress + Offset, Value);
}}

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
        ray = offset_list(&regmap::OPERANDS[..6]),
        tri = offset_list(&regmap::OPERANDS[6..crate::mt::T_MIN_WORD]),
        t_min = data_macro(regmap::T_MIN),
        result = data_macro(regmap::RESULT),
        t = data_macro(regmap::T),
        u = data_macro(regmap::U),
        v = data_macro(regmap::V),
        id = data_macro(regmap::ID),
        config = data_macro(regmap::CONFIG),
    );
    (header, source)
}
