// Generated from hdl/src/regmap/unit.rs — do not edit.
// AXI4-Lite register map of the traversal unit (s_axi_control).
// 0x00 : CONTROL — unit control (Write 1/Pulse)
//        bit 0 - LOAD_START (Write 1/Pulse): write 1 to begin a scene load (then stream the image); only while idle
//        bit 1 - RESET (Write 1/Pulse): write 1 to reset the unit for RESET_CYCLES cycles: slots emptied, counters and overflow cleared
// 0x04 : STATUS — unit status (Read)
//        bit 0 - IDLE (Read): no ray in the unit
//        bit 1 - SCENE_LOADED (Read): the last scene load succeeded
//        bit 2 - SCENE_ERROR (Read): the last scene load failed (ERROR_CODE, SCENE_ERROR_WORD, SCENE_ERROR_VALUE)
//        bit 3 - OVERFLOW (Read): sticky: a ray's stack overflowed (OVERFLOW_RAY); cleared by RESET
//        bit 4 - RESETTING (Read): a RESET is in progress
//        bits 11:8 - ERROR_CODE (Read): the load error's code (docs/scene-image.md), 0: none
// 0x08 : ID — identification: 0x5255 in 31:16, version major 15:8, minor 7:0 (Read)
// 0x0c : CONFIG — lane configuration: format code 7:0, pipeline depth 15:8, lanes 23:16 (Read)
// 0x10 : MEMORY — sizes: node address bits 7:0, triangle address bits 15:8, stack depth 23:16, slots 31:24 (Read)
// 0x14 : SCENE_WORDS — scene image words taken since the last LOAD_START (Read)
// 0x18 : SCENE_ERROR_WORD — index of the image word the load refused (Read)
// 0x1c : SCENE_ERROR_VALUE — the refused word's value (Read)
// 0x20 : OVERFLOW_RAY — id of the first ray whose stack overflowed (Read)
// 0x24 : RAYS — rays taken (wrapping) (Read)
// 0x28 : NODE_VISITS — nodes visited, inner nodes and leaves (wrapping) (Read)
// 0x2c : BOX_TESTS — box tests: both children of a node, or the root's box (wrapping) (Read)
// 0x30 : MT_TESTS — Moller-Trumbore tests (wrapping) (Read)
// 0x34 : BUSY_CYCLES — cycles with a ray in the unit (wrapping) (Read)
// Unmapped offsets and writes to read-only registers answer SLVERR.

#ifndef XRTFPGA_UNIT_HW_H
#define XRTFPGA_UNIT_HW_H

#define XRTFPGA_UNIT_CONTROL_ADDR_CONTROL        0x00
#define XRTFPGA_UNIT_CONTROL_ADDR_STATUS         0x04
#define XRTFPGA_UNIT_CONTROL_ADDR_ID_DATA        0x08
#define XRTFPGA_UNIT_CONTROL_BITS_ID_DATA        32
#define XRTFPGA_UNIT_CONTROL_ADDR_CONFIG_DATA    0x0c
#define XRTFPGA_UNIT_CONTROL_BITS_CONFIG_DATA    24
#define XRTFPGA_UNIT_CONTROL_ADDR_MEMORY_DATA    0x10
#define XRTFPGA_UNIT_CONTROL_BITS_MEMORY_DATA    32
#define XRTFPGA_UNIT_CONTROL_ADDR_SCENE_WORDS_DATA 0x14
#define XRTFPGA_UNIT_CONTROL_BITS_SCENE_WORDS_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_WORD_DATA 0x18
#define XRTFPGA_UNIT_CONTROL_BITS_SCENE_ERROR_WORD_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_VALUE_DATA 0x1c
#define XRTFPGA_UNIT_CONTROL_BITS_SCENE_ERROR_VALUE_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_OVERFLOW_RAY_DATA 0x20
#define XRTFPGA_UNIT_CONTROL_BITS_OVERFLOW_RAY_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_RAYS_DATA      0x24
#define XRTFPGA_UNIT_CONTROL_BITS_RAYS_DATA      32
#define XRTFPGA_UNIT_CONTROL_ADDR_NODE_VISITS_DATA 0x28
#define XRTFPGA_UNIT_CONTROL_BITS_NODE_VISITS_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_BOX_TESTS_DATA 0x2c
#define XRTFPGA_UNIT_CONTROL_BITS_BOX_TESTS_DATA 32
#define XRTFPGA_UNIT_CONTROL_ADDR_MT_TESTS_DATA  0x30
#define XRTFPGA_UNIT_CONTROL_BITS_MT_TESTS_DATA  32
#define XRTFPGA_UNIT_CONTROL_ADDR_BUSY_CYCLES_DATA 0x34
#define XRTFPGA_UNIT_CONTROL_BITS_BUSY_CYCLES_DATA 32

#define XRTFPGA_UNIT_CONTROL_CONTROL_LOAD_START_MASK 0x00000001u
#define XRTFPGA_UNIT_CONTROL_CONTROL_RESET_MASK  0x00000002u
#define XRTFPGA_UNIT_CONTROL_STATUS_IDLE_MASK    0x00000001u
#define XRTFPGA_UNIT_CONTROL_STATUS_SCENE_LOADED_MASK 0x00000002u
#define XRTFPGA_UNIT_CONTROL_STATUS_SCENE_ERROR_MASK 0x00000004u
#define XRTFPGA_UNIT_CONTROL_STATUS_OVERFLOW_MASK 0x00000008u
#define XRTFPGA_UNIT_CONTROL_STATUS_RESETTING_MASK 0x00000010u
#define XRTFPGA_UNIT_CONTROL_STATUS_ERROR_CODE_MASK 0x00000f00u

#define XRTFPGA_UNIT_CONTROL_COUNTER_COUNT       5
#define XRTFPGA_UNIT_CONTROL_RESET_CYCLES        255
#define XRTFPGA_UNIT_CONTROL_STATUS_ERROR_CODE_SHIFT 8
#define XRTFPGA_UNIT_CONTROL_ID_VALUE            0x52550100u
#define XRTFPGA_UNIT_CONTROL_CONFIG_FORMAT(w) ((unsigned)(w) & 0xffu)
#define XRTFPGA_UNIT_CONTROL_CONFIG_DEPTH(w)  (((unsigned)(w) >> 8) & 0xffu)
#define XRTFPGA_UNIT_CONTROL_CONFIG_LANES(w)  (((unsigned)(w) >> 16) & 0xffu)

// Format codes of XRTFPGA_UNIT_CONTROL_CONFIG_FORMAT (the format catalogue, `rtfpga formats`).
#define XRTFPGA_UNIT_CONTROL_FORMAT_FP32         0
#define XRTFPGA_UNIT_CONTROL_FORMAT_FP24         1
#define XRTFPGA_UNIT_CONTROL_FORMAT_BF16         2
#define XRTFPGA_UNIT_CONTROL_FORMAT_FP16         3
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX16_10      4
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX16_10_RND_SAT 5
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX16_13      6
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX16_13_RND_SAT 7
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX21_12      8
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX21_12_RND_SAT 9
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX25_10      10
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX25_10_RND_SAT 11
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX32_16      12
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX32_16_RND_SAT 13
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX32_20      14
#define XRTFPGA_UNIT_CONTROL_FORMAT_FX32_20_RND_SAT 15
#define XRTFPGA_UNIT_CONTROL_FORMAT_E5M14        16
#define XRTFPGA_UNIT_CONTROL_FORMAT_COUNT        17
// Names by code: static const char *const Names[] = XRTFPGA_UNIT_CONTROL_FORMAT_NAMES;
#define XRTFPGA_UNIT_CONTROL_FORMAT_NAMES { "fp32", "fp24", "bf16", "fp16", "fx16_10", "fx16_10_rnd_sat", "fx16_13", "fx16_13_rnd_sat", "fx21_12", "fx21_12_rnd_sat", "fx25_10", "fx25_10_rnd_sat", "fx32_16", "fx32_16_rnd_sat", "fx32_20", "fx32_20_rnd_sat", "e5m14" }

// The MEMORY word's fields.
#define XRTFPGA_UNIT_CONTROL_MEMORY_NODE_BITS(w) (((unsigned)(w) >> 0) & 0xffu)
#define XRTFPGA_UNIT_CONTROL_MEMORY_TRIANGLE_BITS(w) (((unsigned)(w) >> 8) & 0xffu)
#define XRTFPGA_UNIT_CONTROL_MEMORY_STACK_DEPTH(w) (((unsigned)(w) >> 16) & 0xffu)
#define XRTFPGA_UNIT_CONTROL_MEMORY_SLOTS(w) (((unsigned)(w) >> 24) & 0xffu)

#endif // XRTFPGA_UNIT_HW_H
