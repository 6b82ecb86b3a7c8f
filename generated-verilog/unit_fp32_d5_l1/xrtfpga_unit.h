// Generated from hdl/src/regmap/unit.rs — do not edit.
// Bare-metal driver of the traversal unit's control registers.
#ifndef XRTFPGA_UNIT_H
#define XRTFPGA_UNIT_H

#include "xil_io.h"
#include "xrtfpga_unit_hw.h"

typedef struct {
    UINTPTR BaseAddress;
} XRtfpga_unit;

/* The unit's wrapping 32-bit counters. */
typedef struct {
    u32 Rays;
    u32 NodeVisits;
    u32 BoxTests;
    u32 MtTests;
    u32 BusyCycles;
} XRtfpga_unit_Counters;

/* The first refusal of a scene load: its code (0: none, docs/scene-image.md), the image
   word's index and value. */
typedef struct {
    u32 Code;
    u32 Word;
    u32 Value;
} XRtfpga_unit_SceneError;

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
