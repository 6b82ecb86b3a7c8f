//! The generated C header and driver: every register appears with its offset, the C
//! compiles, and the driver, run against a fake register file, touches the right offsets.
use std::path::Path;
use std::process::Command;

use hdl::cgen::{c_driver, c_header, DRIVER_HEADER_FILE, DRIVER_SOURCE_FILE, HEADER_FILE};
use hdl::regmap::{self, REGISTERS};

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

#[test]
fn every_register_appears_with_its_offset() {
    let header = c_header();
    for r in REGISTERS {
        let names = [
            format!("XRTFPGA_CONTROL_ADDR_{}", r.name),
            format!("XRTFPGA_CONTROL_ADDR_{}_DATA", r.name),
        ];
        let tokens = header
            .lines()
            .map(|l| l.split_whitespace().collect::<Vec<_>>())
            .find(|t| t.len() == 3 && t[0] == "#define" && names.iter().any(|n| n == t[1]))
            .unwrap_or_else(|| panic!("no address macro for {}", r.name));
        let value = tokens[2];
        assert_eq!(value, format!("0x{:02x}", r.offset), "{}", r.name);
        for f in r.fields {
            let name = format!("XRTFPGA_CONTROL_{}_{}_MASK", r.name, f.name);
            let mask = header.lines().find(|l| l.contains(&name)).unwrap();
            assert!(mask.ends_with(&format!("0x{:08x}u", f.mask())), "{mask}");
        }
    }
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_AP_CTRL"));
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_V2_Z_DATA"));
    assert!(header.contains("#define XRTFPGA_CONTROL_ADDR_T_MIN_DATA"));
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
