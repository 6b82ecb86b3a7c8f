// Generated from hdl/src/regmap.rs — do not edit.
#include <string.h>
#include "xrtfpga.h"

static const u32 RayOffsets[6] = {
    XRTFPGA_CONTROL_ADDR_ORIG_X_DATA,
    XRTFPGA_CONTROL_ADDR_ORIG_Y_DATA,
    XRTFPGA_CONTROL_ADDR_ORIG_Z_DATA,
    XRTFPGA_CONTROL_ADDR_DIR_X_DATA,
    XRTFPGA_CONTROL_ADDR_DIR_Y_DATA,
    XRTFPGA_CONTROL_ADDR_DIR_Z_DATA
};

static const u32 TriangleOffsets[9] = {
    XRTFPGA_CONTROL_ADDR_V0_X_DATA,
    XRTFPGA_CONTROL_ADDR_V0_Y_DATA,
    XRTFPGA_CONTROL_ADDR_V0_Z_DATA,
    XRTFPGA_CONTROL_ADDR_V1_X_DATA,
    XRTFPGA_CONTROL_ADDR_V1_Y_DATA,
    XRTFPGA_CONTROL_ADDR_V1_Z_DATA,
    XRTFPGA_CONTROL_ADDR_V2_X_DATA,
    XRTFPGA_CONTROL_ADDR_V2_Y_DATA,
    XRTFPGA_CONTROL_ADDR_V2_Z_DATA
};

static u32 FloatBits(float F)
{
    u32 Bits;
    memcpy(&Bits, &F, sizeof Bits);
    return Bits;
}

static float BitsFloat(u32 Bits)
{
    float F;
    memcpy(&F, &Bits, sizeof F);
    return F;
}

static u32 ReadReg(const XRtfpga *InstancePtr, u32 Offset)
{
    return Xil_In32(InstancePtr->BaseAddress + Offset);
}

static void WriteReg(const XRtfpga *InstancePtr, u32 Offset, u32 Value)
{
    Xil_Out32(InstancePtr->BaseAddress + Offset, Value);
}

void XRtfpga_Initialize(XRtfpga *InstancePtr, UINTPTR BaseAddress)
{
    InstancePtr->BaseAddress = BaseAddress;
}

void XRtfpga_WriteRay(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray)
{
    for (int i = 0; i < 3; i++) {
        WriteReg(InstancePtr, RayOffsets[i], FloatBits(Ray->Orig[i]));
        WriteReg(InstancePtr, RayOffsets[3 + i], FloatBits(Ray->Dir[i]));
    }
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_T_MIN_DATA, FloatBits(Ray->TMin));
}

void XRtfpga_WriteTriangle(XRtfpga *InstancePtr, const XRtfpga_Triangle *Tri)
{
    for (int i = 0; i < 3; i++) {
        WriteReg(InstancePtr, TriangleOffsets[i], FloatBits(Tri->V0[i]));
        WriteReg(InstancePtr, TriangleOffsets[3 + i], FloatBits(Tri->V1[i]));
        WriteReg(InstancePtr, TriangleOffsets[6 + i], FloatBits(Tri->V2[i]));
    }
}

void XRtfpga_Start(XRtfpga *InstancePtr)
{
    u32 Ctrl = ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL) & XRTFPGA_CONTROL_AP_CTRL_AUTO_RESTART_MASK;
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL, Ctrl | XRTFPGA_CONTROL_AP_CTRL_AP_START_MASK);
}

u32 XRtfpga_IsDone(XRtfpga *InstancePtr)
{
    return (ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL) & XRTFPGA_CONTROL_AP_CTRL_AP_DONE_MASK) != 0;
}

u32 XRtfpga_IsIdle(XRtfpga *InstancePtr)
{
    return (ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL) & XRTFPGA_CONTROL_AP_CTRL_AP_IDLE_MASK) != 0;
}

void XRtfpga_EnableAutoRestart(XRtfpga *InstancePtr)
{
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL, XRTFPGA_CONTROL_AP_CTRL_AUTO_RESTART_MASK);
}

void XRtfpga_DisableAutoRestart(XRtfpga *InstancePtr)
{
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_AP_CTRL, 0);
}

void XRtfpga_ReadResult(XRtfpga *InstancePtr, XRtfpga_Result *Result)
{
    Result->Hit = (ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_RESULT_DATA) & XRTFPGA_CONTROL_RESULT_HIT_MASK) != 0;
    Result->T = BitsFloat(ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_T_DATA));
    Result->U = BitsFloat(ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_U_DATA));
    Result->V = BitsFloat(ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_V_DATA));
}

u32 XRtfpga_ReadId(XRtfpga *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_ID_DATA);
}

u32 XRtfpga_ReadConfig(XRtfpga *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_CONFIG_DATA);
}

int XRtfpga_Intersect(XRtfpga *InstancePtr, const XRtfpga_Ray *Ray,
                      const XRtfpga_Triangle *Tri, XRtfpga_Result *Result, u32 MaxPolls)
{
    XRtfpga_WriteRay(InstancePtr, Ray);
    XRtfpga_WriteTriangle(InstancePtr, Tri);
    XRtfpga_Start(InstancePtr);
    for (u32 Poll = 0; Poll < MaxPolls; Poll++) {
        if (XRtfpga_IsDone(InstancePtr)) {
            XRtfpga_ReadResult(InstancePtr, Result);
            return 0;
        }
    }
    return -1;
}

void XRtfpga_InterruptGlobalEnable(XRtfpga *InstancePtr)
{
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_GIE, XRTFPGA_CONTROL_GIE_ENABLE_MASK);
}

void XRtfpga_InterruptGlobalDisable(XRtfpga *InstancePtr)
{
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_GIE, 0);
}

void XRtfpga_InterruptEnable(XRtfpga *InstancePtr, u32 Mask)
{
    u32 Enabled = ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_IER);
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_IER, Enabled | Mask);
}

void XRtfpga_InterruptDisable(XRtfpga *InstancePtr, u32 Mask)
{
    u32 Enabled = ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_IER);
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_IER, Enabled & ~Mask);
}

void XRtfpga_InterruptClear(XRtfpga *InstancePtr, u32 Mask)
{
    /* Toggle only the bits that are set, so a clear never raises a bit. */
    u32 Pending = ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_ISR);
    WriteReg(InstancePtr, XRTFPGA_CONTROL_ADDR_ISR, Pending & Mask);
}

u32 XRtfpga_InterruptGetStatus(XRtfpga *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_CONTROL_ADDR_ISR);
}
