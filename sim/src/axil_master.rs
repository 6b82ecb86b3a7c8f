//! An AXI4-Lite master driving `s_axi_control` channel by channel, and the thesis' bare-metal
//! sequence for one test on it: write the operands (the thesis' 15 and, since register map
//! 1.1, T_MIN: one write more per test), write ap_start, wait for completion (poll ap_done,
//! or the `interrupt` line with GIE/IER set), read hit, t, u, v.
//!
//! Transactions are blocking, like `Xil_Out32`/`Xil_In32` on the Zynq: one outstanding at a
//! time; `bready`/`rready` are high from the start. Addresses come from `hdl::regmap`.

use crate::accel_model::{Accel, In, Out};
use crate::cosim_error::CosimError;
use hdl::mt::query_words;
use hdl::regmap;
use hw_model::{MtQuery, MtResult};

/// Cycles a single transaction or a completion wait may take before it counts as a hang.
const BUDGET: u64 = 1 << 16;

/// How software learns that a test has completed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Completion {
    /// Read the control register until ap_done is set (the thesis' driver).
    Poll,
    /// Wait for the `interrupt` output (GIE and IER.done set once), then acknowledge the ISR.
    Interrupt,
}

/// Bus work so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BusStats {
    pub writes: u64,
    pub reads: u64,
    /// Cycles spent in transactions and completion waits.
    pub cycles: u64,
    /// Tests run with [`AxiLiteMaster::test`].
    pub tests: u64,
}

impl BusStats {
    pub fn transactions(&self) -> u64 {
        self.writes + self.reads
    }
}

impl std::ops::AddAssign for BusStats {
    fn add_assign(&mut self, o: Self) {
        self.writes += o.writes;
        self.reads += o.reads;
        self.cycles += o.cycles;
        self.tests += o.tests;
    }
}

/// The master; counts what it does in [`BusStats`].
#[derive(Debug)]
pub struct AxiLiteMaster {
    pub completion: Completion,
    pub stats: BusStats,
    interrupts_enabled: bool,
}

fn protocol(accel: &Accel, message: String) -> CosimError {
    CosimError::Protocol {
        bus: "AXI4-Lite",
        cycle: accel.cycles(),
        message,
    }
}

impl AxiLiteMaster {
    pub fn new(completion: Completion) -> Self {
        AxiLiteMaster {
            completion,
            stats: BusStats::default(),
            interrupts_enabled: false,
        }
    }

    /// Runs cycles until `done` says so (checked after each cycle), within [`BUDGET`].
    fn until(
        &mut self,
        accel: &mut Accel,
        what: impl Fn() -> String,
        mut done: impl FnMut(&mut Accel) -> bool,
    ) -> Result<(), CosimError> {
        for _ in 0..BUDGET {
            accel.cycle()?;
            self.stats.cycles += 1;
            if done(accel) {
                return Ok(());
            }
        }
        Err(CosimError::Timeout {
            what: what(),
            cycles: BUDGET,
        })
    }

    /// One write; returns the response code (`regmap::RESP_*`).
    pub fn write_resp(
        &mut self,
        accel: &mut Accel,
        addr: usize,
        data: u32,
    ) -> Result<u32, CosimError> {
        accel.set(In::AwAddr, addr as u32);
        accel.set(In::WData, data);
        accel.set(In::WStrb, 0xF);
        accel.set(In::AwValid, 1);
        accel.set(In::WValid, 1);
        accel.set(In::BReady, 1);
        let mut resp = 0;
        self.until(
            accel,
            || format!("AXI4-Lite write of {data:#x} to {addr:#04x}"),
            |a| {
                // A channel whose handshake happened at this edge drops its valid.
                if a.get(Out::AwReady) == 1 {
                    a.set(In::AwValid, 0);
                }
                if a.get(Out::WReady) == 1 {
                    a.set(In::WValid, 0);
                }
                if a.get(Out::BValid) == 1 {
                    resp = a.get(Out::BResp);
                    return true;
                }
                false
            },
        )?;
        accel.set(In::AwValid, 0);
        accel.set(In::WValid, 0);
        accel.set(In::BReady, 0);
        self.stats.writes += 1;
        Ok(resp)
    }

    /// One read; returns (data, response code).
    pub fn read_resp(&mut self, accel: &mut Accel, addr: usize) -> Result<(u32, u32), CosimError> {
        accel.set(In::ArAddr, addr as u32);
        accel.set(In::ArValid, 1);
        accel.set(In::RReady, 1);
        let mut answer = (0, 0);
        self.until(
            accel,
            || format!("AXI4-Lite read of {addr:#04x}"),
            |a| {
                if a.get(Out::ArReady) == 1 {
                    a.set(In::ArValid, 0);
                }
                if a.get(Out::RValid) == 1 {
                    answer = (a.get(Out::RData), a.get(Out::RResp));
                    return true;
                }
                false
            },
        )?;
        accel.set(In::ArValid, 0);
        accel.set(In::RReady, 0);
        self.stats.reads += 1;
        Ok(answer)
    }

    /// A write that must be answered OKAY.
    pub fn write(&mut self, accel: &mut Accel, addr: usize, data: u32) -> Result<(), CosimError> {
        match self.write_resp(accel, addr, data)? {
            regmap::RESP_OKAY => Ok(()),
            resp => Err(protocol(
                accel,
                format!("write to {addr:#04x} answered bresp {resp:#b}"),
            )),
        }
    }

    /// A read that must be answered OKAY.
    pub fn read(&mut self, accel: &mut Accel, addr: usize) -> Result<u32, CosimError> {
        match self.read_resp(accel, addr)? {
            (data, regmap::RESP_OKAY) => Ok(data),
            (_, resp) => Err(protocol(
                accel,
                format!("read of {addr:#04x} answered rresp {resp:#b}"),
            )),
        }
    }

    /// One Möller-Trumbore test in register mode (on lane 0).
    pub fn test(&mut self, accel: &mut Accel, q: &MtQuery) -> Result<MtResult, CosimError> {
        if self.completion == Completion::Interrupt && !self.interrupts_enabled {
            self.write(accel, regmap::GIE, regmap::GIE_ENABLE)?;
            self.write(accel, regmap::IER, regmap::INT_DONE)?;
            self.interrupts_enabled = true;
        }
        for (addr, word) in regmap::OPERANDS.iter().zip(query_words(q)) {
            self.write(accel, *addr, word)?;
        }
        self.write(accel, regmap::CONTROL, regmap::AP_START)?;
        match self.completion {
            Completion::Poll => {
                let start = accel.cycles();
                while self.read(accel, regmap::CONTROL)? & regmap::AP_DONE == 0 {
                    if accel.cycles() - start > BUDGET {
                        return Err(CosimError::Timeout {
                            what: "polling ap_done".into(),
                            cycles: BUDGET,
                        });
                    }
                }
            }
            Completion::Interrupt => {
                self.until(
                    accel,
                    || "waiting for the interrupt line".into(),
                    |a| a.get(Out::Interrupt) == 1,
                )?;
                // Writing 1 toggles the ISR's done bit back to 0, which drops the line.
                self.write(accel, regmap::ISR, regmap::INT_DONE)?;
            }
        }
        let hit = self.read(accel, regmap::RESULT)? & regmap::RESULT_HIT != 0;
        let t = f32::from_bits(self.read(accel, regmap::T)?);
        let u = f32::from_bits(self.read(accel, regmap::U)?);
        let v = f32::from_bits(self.read(accel, regmap::V)?);
        self.stats.tests += 1;
        Ok(MtResult { hit, t, u, v })
    }
}
