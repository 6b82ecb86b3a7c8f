// Generated from hdl/src/regmap.rs — do not edit.
// AXI4-Lite register map of the ray/triangle accelerator (s_axi_control).
// 0x00 : AP_CTRL — block-level control (ap_ctrl_hs) (Read/Write)
//        bit 0 - AP_START (Read/Write): write 1 to start; cleared when the core is ready unless auto_restart
//        bit 1 - AP_DONE (Read/COR): the core finished; cleared by reading this register
//        bit 2 - AP_IDLE (Read): the core is not processing
//        bit 3 - AP_READY (Read/COR): the core took the operands; cleared by reading this register
//        bit 7 - AUTO_RESTART (Read/Write): restart automatically after each completion
// 0x04 : GIE — global interrupt enable (Read/Write)
//        bit 0 - ENABLE (Read/Write): enable the interrupt output
// 0x08 : IER — IP interrupt enable (Read/Write)
//        bit 0 - DONE (Read/Write): interrupt on ap_done
//        bit 1 - READY (Read/Write): interrupt on ap_ready
// 0x0c : ISR — IP interrupt status (set on an enabled event, write 1 to toggle) (Read/TOW)
//        bit 0 - DONE (Read/TOW): ap_done happened
//        bit 1 - READY (Read/TOW): ap_ready happened
// 0x10 : ORIG_X — ray origin x (fp32 bits) (Read/Write)
// 0x14 : ORIG_Y — ray origin y (fp32 bits) (Read/Write)
// 0x18 : ORIG_Z — ray origin z (fp32 bits) (Read/Write)
// 0x1c : DIR_X — ray direction x (fp32 bits) (Read/Write)
// 0x20 : DIR_Y — ray direction y (fp32 bits) (Read/Write)
// 0x24 : DIR_Z — ray direction z (fp32 bits) (Read/Write)
// 0x28 : V0_X — triangle vertex 0 x (fp32 bits) (Read/Write)
// 0x2c : V0_Y — triangle vertex 0 y (fp32 bits) (Read/Write)
// 0x30 : V0_Z — triangle vertex 0 z (fp32 bits) (Read/Write)
// 0x34 : V1_X — triangle vertex 1 x (fp32 bits) (Read/Write)
// 0x38 : V1_Y — triangle vertex 1 y (fp32 bits) (Read/Write)
// 0x3c : V1_Z — triangle vertex 1 z (fp32 bits) (Read/Write)
// 0x40 : V2_X — triangle vertex 2 x (fp32 bits) (Read/Write)
// 0x44 : V2_Y — triangle vertex 2 y (fp32 bits) (Read/Write)
// 0x48 : V2_Z — triangle vertex 2 z (fp32 bits) (Read/Write)
// 0x4c : T_MIN — lower bound: a hit needs t > t_min (fp32 bits, compared in the core's format) (Read/Write)
// 0x50 : RESULT — result flags of the last completed test (Read)
//        bit 0 - HIT (Read): the ray hits the triangle
// 0x54 : T — distance along the ray (fp32 bits) (Read)
// 0x58 : U — barycentric u (fp32 bits) (Read)
// 0x5c : V — barycentric v (fp32 bits) (Read)
// 0x60 : ID — identification: 0x5246 in 31:16, version major 15:8, minor 7:0 (Read)
// 0x64 : CONFIG — core configuration: format code 7:0, pipeline depth 15:8, lanes 23:16 (Read)
// Unmapped offsets and writes to read-only registers answer SLVERR.

#ifndef XRTFPGA_HW_H
#define XRTFPGA_HW_H

#define XRTFPGA_CONTROL_ADDR_AP_CTRL             0x00
#define XRTFPGA_CONTROL_ADDR_GIE                 0x04
#define XRTFPGA_CONTROL_ADDR_IER                 0x08
#define XRTFPGA_CONTROL_ADDR_ISR                 0x0c
#define XRTFPGA_CONTROL_ADDR_ORIG_X_DATA         0x10
#define XRTFPGA_CONTROL_BITS_ORIG_X_DATA         32
#define XRTFPGA_CONTROL_ADDR_ORIG_Y_DATA         0x14
#define XRTFPGA_CONTROL_BITS_ORIG_Y_DATA         32
#define XRTFPGA_CONTROL_ADDR_ORIG_Z_DATA         0x18
#define XRTFPGA_CONTROL_BITS_ORIG_Z_DATA         32
#define XRTFPGA_CONTROL_ADDR_DIR_X_DATA          0x1c
#define XRTFPGA_CONTROL_BITS_DIR_X_DATA          32
#define XRTFPGA_CONTROL_ADDR_DIR_Y_DATA          0x20
#define XRTFPGA_CONTROL_BITS_DIR_Y_DATA          32
#define XRTFPGA_CONTROL_ADDR_DIR_Z_DATA          0x24
#define XRTFPGA_CONTROL_BITS_DIR_Z_DATA          32
#define XRTFPGA_CONTROL_ADDR_V0_X_DATA           0x28
#define XRTFPGA_CONTROL_BITS_V0_X_DATA           32
#define XRTFPGA_CONTROL_ADDR_V0_Y_DATA           0x2c
#define XRTFPGA_CONTROL_BITS_V0_Y_DATA           32
#define XRTFPGA_CONTROL_ADDR_V0_Z_DATA           0x30
#define XRTFPGA_CONTROL_BITS_V0_Z_DATA           32
#define XRTFPGA_CONTROL_ADDR_V1_X_DATA           0x34
#define XRTFPGA_CONTROL_BITS_V1_X_DATA           32
#define XRTFPGA_CONTROL_ADDR_V1_Y_DATA           0x38
#define XRTFPGA_CONTROL_BITS_V1_Y_DATA           32
#define XRTFPGA_CONTROL_ADDR_V1_Z_DATA           0x3c
#define XRTFPGA_CONTROL_BITS_V1_Z_DATA           32
#define XRTFPGA_CONTROL_ADDR_V2_X_DATA           0x40
#define XRTFPGA_CONTROL_BITS_V2_X_DATA           32
#define XRTFPGA_CONTROL_ADDR_V2_Y_DATA           0x44
#define XRTFPGA_CONTROL_BITS_V2_Y_DATA           32
#define XRTFPGA_CONTROL_ADDR_V2_Z_DATA           0x48
#define XRTFPGA_CONTROL_BITS_V2_Z_DATA           32
#define XRTFPGA_CONTROL_ADDR_T_MIN_DATA          0x4c
#define XRTFPGA_CONTROL_BITS_T_MIN_DATA          32
#define XRTFPGA_CONTROL_ADDR_RESULT_DATA         0x50
#define XRTFPGA_CONTROL_BITS_RESULT_DATA         1
#define XRTFPGA_CONTROL_ADDR_T_DATA              0x54
#define XRTFPGA_CONTROL_BITS_T_DATA              32
#define XRTFPGA_CONTROL_ADDR_U_DATA              0x58
#define XRTFPGA_CONTROL_BITS_U_DATA              32
#define XRTFPGA_CONTROL_ADDR_V_DATA              0x5c
#define XRTFPGA_CONTROL_BITS_V_DATA              32
#define XRTFPGA_CONTROL_ADDR_ID_DATA             0x60
#define XRTFPGA_CONTROL_BITS_ID_DATA             32
#define XRTFPGA_CONTROL_ADDR_CONFIG_DATA         0x64
#define XRTFPGA_CONTROL_BITS_CONFIG_DATA         24

#define XRTFPGA_CONTROL_AP_CTRL_AP_START_MASK    0x00000001u
#define XRTFPGA_CONTROL_AP_CTRL_AP_DONE_MASK     0x00000002u
#define XRTFPGA_CONTROL_AP_CTRL_AP_IDLE_MASK     0x00000004u
#define XRTFPGA_CONTROL_AP_CTRL_AP_READY_MASK    0x00000008u
#define XRTFPGA_CONTROL_AP_CTRL_AUTO_RESTART_MASK 0x00000080u
#define XRTFPGA_CONTROL_GIE_ENABLE_MASK          0x00000001u
#define XRTFPGA_CONTROL_IER_DONE_MASK            0x00000001u
#define XRTFPGA_CONTROL_IER_READY_MASK           0x00000002u
#define XRTFPGA_CONTROL_ISR_DONE_MASK            0x00000001u
#define XRTFPGA_CONTROL_ISR_READY_MASK           0x00000002u
#define XRTFPGA_CONTROL_RESULT_HIT_MASK          0x00000001u

#define XRTFPGA_CONTROL_OPERAND_COUNT            16
#define XRTFPGA_CONTROL_ID_VALUE                 0x52460101u
#define XRTFPGA_CONTROL_CONFIG_FORMAT(w) ((unsigned)(w) & 0xffu)
#define XRTFPGA_CONTROL_CONFIG_DEPTH(w)  (((unsigned)(w) >> 8) & 0xffu)
#define XRTFPGA_CONTROL_CONFIG_LANES(w)  (((unsigned)(w) >> 16) & 0xffu)

// Format codes of XRTFPGA_CONTROL_CONFIG_FORMAT (the format catalogue, `rtfpga formats`).
#define XRTFPGA_CONTROL_FORMAT_FP32              0
#define XRTFPGA_CONTROL_FORMAT_FP24              1
#define XRTFPGA_CONTROL_FORMAT_BF16              2
#define XRTFPGA_CONTROL_FORMAT_FP16              3
#define XRTFPGA_CONTROL_FORMAT_FX16_10           4
#define XRTFPGA_CONTROL_FORMAT_FX16_10_RND_SAT   5
#define XRTFPGA_CONTROL_FORMAT_FX16_13           6
#define XRTFPGA_CONTROL_FORMAT_FX16_13_RND_SAT   7
#define XRTFPGA_CONTROL_FORMAT_FX21_12           8
#define XRTFPGA_CONTROL_FORMAT_FX21_12_RND_SAT   9
#define XRTFPGA_CONTROL_FORMAT_FX25_10           10
#define XRTFPGA_CONTROL_FORMAT_FX25_10_RND_SAT   11
#define XRTFPGA_CONTROL_FORMAT_FX32_16           12
#define XRTFPGA_CONTROL_FORMAT_FX32_16_RND_SAT   13
#define XRTFPGA_CONTROL_FORMAT_FX32_20           14
#define XRTFPGA_CONTROL_FORMAT_FX32_20_RND_SAT   15
#define XRTFPGA_CONTROL_FORMAT_E5M14             16
#define XRTFPGA_CONTROL_FORMAT_COUNT             17
// Names by code: static const char *const Names[] = XRTFPGA_CONTROL_FORMAT_NAMES;
#define XRTFPGA_CONTROL_FORMAT_NAMES { "fp32", "fp24", "bf16", "fp16", "fx16_10", "fx16_10_rnd_sat", "fx16_13", "fx16_13_rnd_sat", "fx21_12", "fx21_12_rnd_sat", "fx25_10", "fx25_10_rnd_sat", "fx32_16", "fx32_16_rnd_sat", "fx32_20", "fx32_20_rnd_sat", "e5m14" }

#endif // XRTFPGA_HW_H
