// Generated from hdl/src/regmap.rs — do not edit.
// Bare-metal driver of the ray/triangle accelerator (register mode).
#ifndef XRTFPGA_H
#define XRTFPGA_H

#include "xil_io.h"
#include "xrtfpga_hw.h"

typedef struct {
    UINTPTR BaseAddress;
} XRtfpga;

typedef struct {
    float Orig[3];
    float Dir[3];
    /* A hit needs t > TMin (0: every hit in front of the origin). */
    float TMin;
} XRtfpga_Ray;

typedef struct {
    float V0[3];
    float V1[3];
    float V2[3];
} XRtfpga_Triangle;

typedef struct {
    u32 Hit;
    float T;
    float U;
    float V;
} XRtfpga_Result;

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
/* Mask: XRTFPGA_CONTROL_IER_DONE_MASK | XRTFPGA_CONTROL_IER_READY_MASK */
void XRtfpga_InterruptEnable(XRtfpga *InstancePtr, u32 Mask);
void XRtfpga_InterruptDisable(XRtfpga *InstancePtr, u32 Mask);
/* Clears the given pending bits (the status register toggles on a written 1). */
void XRtfpga_InterruptClear(XRtfpga *InstancePtr, u32 Mask);
u32 XRtfpga_InterruptGetStatus(XRtfpga *InstancePtr);

#endif // XRTFPGA_H
