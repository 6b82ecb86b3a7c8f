// Generated from hdl/src/regmap/unit.rs — do not edit.
#include "xrtfpga_unit.h"

static u32 ReadReg(const XRtfpga_unit *InstancePtr, u32 Offset)
{
    return Xil_In32(InstancePtr->BaseAddress + Offset);
}

static void WriteReg(const XRtfpga_unit *InstancePtr, u32 Offset, u32 Value)
{
    Xil_Out32(InstancePtr->BaseAddress + Offset, Value);
}

void XRtfpga_unit_Initialize(XRtfpga_unit *InstancePtr, UINTPTR BaseAddress)
{
    InstancePtr->BaseAddress = BaseAddress;
}

u32 XRtfpga_unit_ReadId(XRtfpga_unit *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_ID_DATA);
}

u32 XRtfpga_unit_ReadConfig(XRtfpga_unit *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_CONFIG_DATA);
}

u32 XRtfpga_unit_ReadMemory(XRtfpga_unit *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_MEMORY_DATA);
}

u32 XRtfpga_unit_ReadStatus(XRtfpga_unit *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_STATUS);
}

u32 XRtfpga_unit_IsIdle(XRtfpga_unit *InstancePtr)
{
    return (XRtfpga_unit_ReadStatus(InstancePtr) & XRTFPGA_UNIT_CONTROL_STATUS_IDLE_MASK) != 0;
}

void XRtfpga_unit_StartSceneLoad(XRtfpga_unit *InstancePtr)
{
    WriteReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_CONTROL, XRTFPGA_UNIT_CONTROL_CONTROL_LOAD_START_MASK);
}

int XRtfpga_unit_SceneStatus(XRtfpga_unit *InstancePtr, XRtfpga_unit_SceneError *Error)
{
    u32 Status = XRtfpga_unit_ReadStatus(InstancePtr);
    if (Status & XRTFPGA_UNIT_CONTROL_STATUS_SCENE_LOADED_MASK) {
        return 1;
    }
    if (Status & XRTFPGA_UNIT_CONTROL_STATUS_SCENE_ERROR_MASK) {
        Error->Code = (Status & XRTFPGA_UNIT_CONTROL_STATUS_ERROR_CODE_MASK) >> XRTFPGA_UNIT_CONTROL_STATUS_ERROR_CODE_SHIFT;
        Error->Word = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_WORD_DATA);
        Error->Value = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_SCENE_ERROR_VALUE_DATA);
        return 0;
    }
    return -1;
}

u32 XRtfpga_unit_ReadSceneWords(XRtfpga_unit *InstancePtr)
{
    return ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_SCENE_WORDS_DATA);
}

u32 XRtfpga_unit_Overflowed(XRtfpga_unit *InstancePtr, u32 *RayId)
{
    if ((XRtfpga_unit_ReadStatus(InstancePtr) & XRTFPGA_UNIT_CONTROL_STATUS_OVERFLOW_MASK) == 0) {
        return 0;
    }
    *RayId = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_OVERFLOW_RAY_DATA);
    return 1;
}

int XRtfpga_unit_Reset(XRtfpga_unit *InstancePtr, u32 MaxPolls)
{
    WriteReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_CONTROL, XRTFPGA_UNIT_CONTROL_CONTROL_RESET_MASK);
    for (u32 Poll = 0; Poll < MaxPolls; Poll++) {
        if ((XRtfpga_unit_ReadStatus(InstancePtr) & XRTFPGA_UNIT_CONTROL_STATUS_RESETTING_MASK) == 0) {
            return 0;
        }
    }
    return -1;
}

void XRtfpga_unit_ReadCounters(XRtfpga_unit *InstancePtr, XRtfpga_unit_Counters *Counters)
{
    Counters->Rays = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_RAYS_DATA);
    Counters->NodeVisits = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_NODE_VISITS_DATA);
    Counters->BoxTests = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_BOX_TESTS_DATA);
    Counters->MtTests = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_MT_TESTS_DATA);
    Counters->BusyCycles = ReadReg(InstancePtr, XRTFPGA_UNIT_CONTROL_ADDR_BUSY_CYCLES_DATA);
}

void XRtfpga_unit_CountersSince(const XRtfpga_unit_Counters *Before,
                                const XRtfpga_unit_Counters *After,
                                XRtfpga_unit_Counters *Diff)
{
    Diff->Rays = After->Rays - Before->Rays;
    Diff->NodeVisits = After->NodeVisits - Before->NodeVisits;
    Diff->BoxTests = After->BoxTests - Before->BoxTests;
    Diff->MtTests = After->MtTests - Before->MtTests;
    Diff->BusyCycles = After->BusyCycles - Before->BusyCycles;
}
