//! The generated C header and driver: every register appears with its offset, the C
//! compiles, and the driver, run against a fake register file, touches the right offsets.
use std::path::Path;
use std::process::Command;

use hdl::cgen::{
    c_driver, c_header, unit_c_driver, unit_c_header, DRIVER_HEADER_FILE, DRIVER_SOURCE_FILE,
    HEADER_FILE, UNIT_DRIVER_HEADER_FILE, UNIT_DRIVER_SOURCE_FILE, UNIT_HEADER_FILE,
};
use hdl::regmap::{self, unit, RegisterMap};

/// Stand-in for the Xilinx BSP's xil_io.h (same types and signatures).
const XIL_IO_STUB: &str = r#"
#ifndef XIL_IO_H
#define XIL_IO_H
#include <stdint.h>
typedef uint32_t u32;
typedef uintptr_t UINTPTR;
u32 Xil_In32(UINTPTR Addr);
void Xil_Out32(UINTPTR Addr, u32 Value);
#endif
"#;

/// A fake device: a register array behind Xil_In32/Xil_Out32. Writing ap_start "computes"
/// the result (hit = 1, t = orig_x + dir_x, u = v0_x, v = v2_z) and sets ap_done; reading the
/// control register clears ap_done, as the hardware does.
const FAKE_DEVICE: &str = r#"
#include <stdio.h>
#include <string.h>
#include "xrtfpga.h"
#define BASE 0x43c00000u
static u32 regs[32];
static int reads_of_ctrl;
static float f(u32 b) { float x; memcpy(&x, &b, 4); return x; }
static u32 b(float x) { u32 r; memcpy(&r, &x, 4); return r; }
u32 Xil_In32(UINTPTR a) {
    u32 off = (u32)(a - BASE);
    u32 v = regs[off / 4];
    if (off == XRTFPGA_CONTROL_ADDR_AP_CTRL) {
        reads_of_ctrl++;
        regs[0] &= ~XRTFPGA_CONTROL_AP_CTRL_AP_DONE_MASK;
    }
    return v;
}
void Xil_Out32(UINTPTR a, u32 v) {
    u32 off = (u32)(a - BASE);
    if (off == XRTFPGA_CONTROL_ADDR_AP_CTRL && (v & XRTFPGA_CONTROL_AP_CTRL_AP_START_MASK)) {
        regs[XRTFPGA_CONTROL_ADDR_RESULT_DATA / 4] = 1;
        regs[XRTFPGA_CONTROL_ADDR_T_DATA / 4] = b(f(regs[XRTFPGA_CONTROL_ADDR_ORIG_X_DATA / 4]) + f(regs[XRTFPGA_CONTROL_ADDR_DIR_X_DATA / 4]));
        regs[XRTFPGA_CONTROL_ADDR_U_DATA / 4] = regs[XRTFPGA_CONTROL_ADDR_V0_X_DATA / 4];
        regs[XRTFPGA_CONTROL_ADDR_V_DATA / 4] = regs[XRTFPGA_CONTROL_ADDR_V2_Z_DATA / 4];
        regs[0] |= XRTFPGA_CONTROL_AP_CTRL_AP_DONE_MASK;
        return;
    }
    regs[off / 4] = v;
}
int main(void) {
    XRtfpga dev;
    XRtfpga_Ray ray = {{1.0f, 2.0f, 3.0f}, {0.5f, 0.25f, -1.0f}, 0.125f};
    XRtfpga_Triangle tri = {{7.0f, 8.0f, 9.0f}, {10.0f, 11.0f, 12.0f}, {13.0f, 14.0f, 15.0f}};
    XRtfpga_Result res;
    regs[XRTFPGA_CONTROL_ADDR_ID_DATA / 4] = XRTFPGA_CONTROL_ID_VALUE;
    regs[XRTFPGA_CONTROL_ADDR_CONFIG_DATA / 4] = 0x00040307u;
    XRtfpga_Initialize(&dev, BASE);
    if (XRtfpga_Intersect(&dev, &ray, &tri, &res, 10) != 0) return 10;
    printf("%u %g %g %g %u %u %u %u\n", res.Hit, res.T, res.U, res.V,
           XRtfpga_ReadId(&dev), XRTFPGA_CONTROL_CONFIG_FORMAT(XRtfpga_ReadConfig(&dev)),
           XRTFPGA_CONTROL_CONFIG_DEPTH(XRtfpga_ReadConfig(&dev)),
           XRTFPGA_CONTROL_CONFIG_LANES(XRtfpga_ReadConfig(&dev)));
    for (int i = 0; i < XRTFPGA_CONTROL_OPERAND_COUNT; i++) printf("%g ", f(regs[4 + i]));
    printf("\n");
    static const char *const Names[] = XRTFPGA_CONTROL_FORMAT_NAMES;
    unsigned code = XRTFPGA_CONTROL_CONFIG_FORMAT(XRtfpga_ReadConfig(&dev));
    if (sizeof Names / sizeof Names[0] != XRTFPGA_CONTROL_FORMAT_COUNT) return 11;
    printf("%s %d %d\n", Names[code], XRTFPGA_CONTROL_FORMAT_FP32, XRTFPGA_CONTROL_FORMAT_FP16);
    return 0;
}
"#;

fn write_sources(dir: &Path) {
    let (h, c) = c_driver();
    std::fs::write(dir.join("xil_io.h"), XIL_IO_STUB).unwrap();
    std::fs::write(dir.join(HEADER_FILE), c_header()).unwrap();
    std::fs::write(dir.join(DRIVER_HEADER_FILE), h).unwrap();
    std::fs::write(dir.join(DRIVER_SOURCE_FILE), c).unwrap();
}

fn gcc(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::new("gcc")
        .current_dir(dir)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-I."])
        .args(args)
        .output()
        .expect("gcc is installed")
}

/// Every register of `map` has its address macro (bare for the control registers, `_DATA`
/// for the others) with its offset, and every field its mask.
fn every_register_appears_in(map: &RegisterMap, header: &str) {
    let p = map.c_prefix;
    for r in map.registers {
        let names = if map.control.contains(&r.offset) {
            [format!("{p}_ADDR_{}", r.name)]
        } else {
            [format!("{p}_ADDR_{}_DATA", r.name)]
        };
        let tokens = header
            .lines()
            .map(|l| l.split_whitespace().collect::<Vec<_>>())
            .find(|t| t.len() == 3 && t[0] == "#define" && names.iter().any(|n| n == t[1]))
            .unwrap_or_else(|| panic!("no address macro for {}", r.name));
        let value = tokens[2];
        assert_eq!(value, format!("0x{:02x}", r.offset), "{}", r.name);
        for f in r.fields {
            let name = format!("{p}_{}_{}_MASK", r.name, f.name);
            let mask = header.lines().find(|l| l.contains(&name)).unwrap();
            assert!(mask.ends_with(&format!("0x{:08x}u", f.mask())), "{mask}");
        }
    }
    let id = format!("{p}_ID_VALUE");
    let id = header.lines().find(|l| l.contains(&id)).unwrap();
    assert!(id.ends_with(&format!("0x{:08x}u", map.id_value)), "{id}");
}

#[test]
fn every_register_appears_with_its_offset() {
    let header = c_header();
    every_register_appears_in(&regmap::MAP, &header);
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_AP_CTRL"));
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_V2_Z_DATA"));
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_T_MIN_DATA"));
}

#[test]
fn every_unit_register_appears_with_its_offset() {
    let header = unit_c_header();
    every_register_appears_in(&unit::MAP, &header);
    assert!(header.contains("#define XRTFPGA_UNIT_CONTROL_ADDR_STATUS "));
    assert!(header.contains("#define XRTFPGA_UNIT_CONTROL_ADDR_BUSY_CYCLES_DATA"));
    assert!(header.contains("bits 11:8 - ERROR_CODE"));
}

#[test]
fn generated_c_compiles() {
    let dir = tempfile::tempdir().unwrap();
    write_sources(dir.path());
    let out = gcc(
        dir.path(),
        &[
            "-fsyntax-only",
            HEADER_FILE,
            DRIVER_HEADER_FILE,
            DRIVER_SOURCE_FILE,
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn driver_writes_and_reads_the_mapped_offsets() {
    let dir = tempfile::tempdir().unwrap();
    write_sources(dir.path());
    std::fs::write(dir.path().join("main.c"), FAKE_DEVICE).unwrap();
    let out = gcc(
        dir.path(),
        &["-O1", "-o", "fake", "main.c", DRIVER_SOURCE_FILE],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = Command::new(dir.path().join("fake")).output().unwrap();
    assert!(
        run.status.success(),
        "driver returned {:?}",
        run.status.code()
    );
    let text = String::from_utf8(run.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("1 1.5 7 15 {} 7 3 4", regmap::ID_VALUE)
    );
    assert_eq!(
        lines.next().unwrap().trim(),
        "1 2 3 0.5 0.25 -1 7 8 9 10 11 12 13 14 15 0.125"
    );
    // The header's code -> name table is the catalogue's.
    let fp16 = hw_model::HwFormat::named("fp16");
    assert_eq!(
        lines.next().unwrap(),
        format!(
            "{} {} {}",
            hw_model::catalogue()[7].name,
            hw_model::HwFormat::FP32.code(),
            fp16.code()
        )
    );
}

fn write_unit_sources(dir: &Path) {
    let (h, c) = unit_c_driver();
    std::fs::write(dir.join("xil_io.h"), XIL_IO_STUB).unwrap();
    std::fs::write(dir.join(UNIT_HEADER_FILE), unit_c_header()).unwrap();
    std::fs::write(dir.join(UNIT_DRIVER_HEADER_FILE), h).unwrap();
    std::fs::write(dir.join(UNIT_DRIVER_SOURCE_FILE), c).unwrap();
}

/// A fake unit: a register array behind Xil_In32/Xil_Out32. LOAD_START counts the starts;
/// RESET sets RESETTING for two status reads and then clears the counters; the counters
/// are seeded with values that wrap.
const FAKE_UNIT: &str = r#"
#include <stdio.h>
#include "xrtfpga_unit.h"
#define BASE 0x43c10000u
static u32 regs[32];
static int starts, reset_reads;
u32 Xil_In32(UINTPTR a) {
    u32 off = (u32)(a - BASE);
    if (off == XRTFPGA_UNIT_CONTROL_ADDR_STATUS && reset_reads > 0 && --reset_reads == 0) {
        regs[off / 4] &= ~XRTFPGA_UNIT_CONTROL_STATUS_RESETTING_MASK;
        for (int i = 0; i < XRTFPGA_UNIT_CONTROL_COUNTER_COUNT; i++)
            regs[XRTFPGA_UNIT_CONTROL_ADDR_RAYS_DATA / 4 + i] = 0;
    }
    return regs[off / 4];
}
void Xil_Out32(UINTPTR a, u32 v) {
    u32 off = (u32)(a - BASE);
    if (off != XRTFPGA_UNIT_CONTROL_ADDR_CONTROL) { regs[off / 4] = 0xdead; return; }
    if (v & XRTFPGA_UNIT_CONTROL_CONTROL_LOAD_START_MASK) starts++;
    if (v & XRTFPGA_UNIT_CONTROL_CONTROL_RESET_MASK) {
        regs[XRTFPGA_UNIT_CONTROL_ADDR_STATUS / 4] |= XRTFPGA_UNIT_CONTROL_STATUS_RESETTING_MASK;
        reset_reads = 2;
    }
}
int main(void) {
    XRtfpga_unit dev;
    XRtfpga_unit_SceneError err = {0, 0, 0};
    XRtfpga_unit_Counters before, after, diff;
    u32 ray = 0;
    XRtfpga_unit_Initialize(&dev, BASE);
    regs[XRTFPGA_UNIT_CONTROL_ADDR_ID_DATA / 4] = XRTFPGA_UNIT_CONTROL_ID_VALUE;
    regs[XRTFPGA_UNIT_CONTROL_ADDR_MEMORY_DATA / 4] = 0x20200d0cu;
    regs[XRTFPGA_UNIT_CONTROL_ADDR_STATUS / 4] = XRTFPGA_UNIT_CONTROL_STATUS_IDLE_MASK;
    if (XRtfpga_unit_SceneStatus(&dev, &err) != -1) return 10;
    XRtfpga_unit_StartSceneLoad(&dev);
    regs[XRTFPGA_UNIT_CONTROL_ADDR_STATUS / 4] |= XRTFPGA_UNIT_CONTROL_STATUS_SCENE_ERROR_MASK
        | (7u << XRTFPGA_UNIT_CONTROL_STATUS_ERROR_CODE_SHIFT);
    regs[XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_WORD_DATA / 4] = 1234;
    regs[XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_VALUE_DATA / 4] = 0xabcdu;
    if (XRtfpga_unit_SceneStatus(&dev, &err) != 0) return 11;
    for (int i = 0; i < XRTFPGA_UNIT_CONTROL_COUNTER_COUNT; i++)
        regs[XRTFPGA_UNIT_CONTROL_ADDR_RAYS_DATA / 4 + i] = 0xfffffff0u + (u32)i;
    XRtfpga_unit_ReadCounters(&dev, &before);
    for (int i = 0; i < XRTFPGA_UNIT_CONTROL_COUNTER_COUNT; i++)
        regs[XRTFPGA_UNIT_CONTROL_ADDR_RAYS_DATA / 4 + i] = 10u * (u32)i;
    XRtfpga_unit_ReadCounters(&dev, &after);
    XRtfpga_unit_CountersSince(&before, &after, &diff);
    regs[XRTFPGA_UNIT_CONTROL_ADDR_STATUS / 4] |= XRTFPGA_UNIT_CONTROL_STATUS_OVERFLOW_MASK;
    regs[XRTFPGA_UNIT_CONTROL_ADDR_OVERFLOW_RAY_DATA / 4] = 77;
    if (!XRtfpga_unit_Overflowed(&dev, &ray)) return 12;
    if (XRtfpga_unit_Reset(&dev, 5) != 0) return 13;
    XRtfpga_unit_ReadCounters(&dev, &after);
    printf("%u %u %u %u %u %u\n", XRtfpga_unit_ReadId(&dev), starts, err.Code, err.Word, err.Value, ray);
    printf("%u %u %u %u %u\n", diff.Rays, diff.NodeVisits, diff.BoxTests, diff.MtTests, diff.BusyCycles);
    printf("%u %u %u %u %u\n", after.Rays, after.BusyCycles,
           XRTFPGA_UNIT_CONTROL_MEMORY_NODE_BITS(XRtfpga_unit_ReadMemory(&dev)),
           XRTFPGA_UNIT_CONTROL_MEMORY_TRIANGLE_BITS(XRtfpga_unit_ReadMemory(&dev)),
           XRTFPGA_UNIT_CONTROL_MEMORY_SLOTS(XRtfpga_unit_ReadMemory(&dev)));
    return 0;
}
"#;

#[test]
fn unit_driver_compiles_and_reads_the_mapped_offsets() {
    let dir = tempfile::tempdir().unwrap();
    write_unit_sources(dir.path());
    std::fs::write(dir.path().join("main.c"), FAKE_UNIT).unwrap();
    let out = gcc(
        dir.path(),
        &["-O1", "-o", "fake", "main.c", UNIT_DRIVER_SOURCE_FILE],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = Command::new(dir.path().join("fake")).output().unwrap();
    assert!(
        run.status.success(),
        "driver returned {:?}",
        run.status.code()
    );
    let text = String::from_utf8(run.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        [
            format!("{} 1 7 1234 43981 77", unit::ID_VALUE).as_str(),
            // 0 - 0xfffffff0, 10 - 0xfffffff1, …: the counters wrapped.
            "16 25 34 43 52",
            "0 0 12 13 32",
        ]
    );
}

/// docs/traversal-unit.md "Control registers" has one row per register of the unit's map,
/// in order, with its offset and name.
#[test]
fn the_units_register_table_in_the_docs_is_the_map() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/traversal-unit.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let section = doc
        .split("## Control registers")
        .nth(1)
        .expect("a Control registers section");
    let rows: Vec<(String, String)> = section
        .lines()
        .take_while(|l| !l.starts_with("## "))
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let offset = cells.get(1)?.strip_prefix("0x")?;
            Some((
                offset.to_ascii_lowercase(),
                cells[2].trim_matches('`').to_string(),
            ))
        })
        .collect();
    let want: Vec<(String, String)> = unit::REGISTERS
        .iter()
        .map(|r| (format!("{:02x}", r.offset), r.name.to_string()))
        .collect();
    assert_eq!(rows, want, "{path}");
}
