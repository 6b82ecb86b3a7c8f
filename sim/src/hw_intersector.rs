//! The Verilated accelerator as the renderer's [`Intersector`]: batches go through the stream
//! front end (every lane busy) or, one test at a time, through the AXI4-Lite registers.
//!
//! Each calling thread takes a simulated instance from a pool (creating one when none is
//! free), so rayon workers simulate in parallel. A simulation error is the batch's error: the
//! render stops with it (an instance that failed is dropped, not reused).

use crate::accel_model::{top_model, Accel, TopModel, VcdWindow};
use crate::axil_master::{AxiLiteMaster, Completion};
use crate::cosim_error::CosimError;
use crate::sim_clock::{core_seconds, SimClock};
use crate::stream_driver::stream_batch;
use hdl::top::TopConfig;
use hw_model::{MtQuery, MtResult};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use sw_renderer::intersect::Intersector;
use sw_renderer::rays::EngineError;

/// How queries reach the hardware.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// AXI4-Stream batches, one query per lane per cycle.
    Stream,
    /// The thesis' register sequence per query over AXI4-Lite (lane 0), finishing each test by
    /// polling ap_done or by waiting for the interrupt.
    Register(Completion),
}

impl std::fmt::Display for Mode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Mode::Stream => "stream",
            Mode::Register(Completion::Poll) => "register",
            Mode::Register(Completion::Interrupt) => "register-irq",
        })
    }
}

/// Counters over everything the intersector simulated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HwStats {
    /// Ray-triangle tests.
    pub tests: u64,
    /// Clock cycles simulated for them (summed over instances).
    pub cycles: u64,
    /// Lane-cycles that issued a query (= tests).
    pub busy_lane_cycles: u64,
    /// Lanes × cycles.
    pub lane_cycles: u64,
    /// AXI4-Lite transactions (register mode) or stream beats in (stream mode).
    pub transactions: u64,
    /// Wall time spent inside the simulator, summed over threads.
    pub sim_time: Duration,
    /// CPU time the simulating threads ran for it (zero where the OS does not say): unlike
    /// the wall time, it does not grow when other processes share the cores.
    pub sim_cpu_time: Duration,
    /// Simulated instances (threads that used the hardware).
    pub instances: usize,
}

impl HwStats {
    /// Busy lane-cycles / lane-cycles.
    pub fn lane_utilisation(&self) -> f64 {
        self.busy_lane_cycles as f64 / self.lane_cycles.max(1) as f64
    }

    /// Seconds one core spent simulating: the CPU time, or the wall time where it is unknown.
    pub fn core_seconds(&self) -> f64 {
        core_seconds(self.sim_time, self.sim_cpu_time)
    }

    /// Simulated clock cycles per second of one core.
    pub fn cycles_per_sec(&self) -> f64 {
        self.cycles as f64 / self.core_seconds()
    }

    /// Tests per second of one core.
    pub fn tests_per_sec(&self) -> f64 {
        self.tests as f64 / self.core_seconds()
    }

    pub fn cycles_per_test(&self) -> f64 {
        self.cycles as f64 / self.tests.max(1) as f64
    }
}

/// How the register-mode bus master of an instance finishes a test.
fn completion(mode: Mode) -> Completion {
    match mode {
        Mode::Register(c) => c,
        // Stream instances never use their bus master.
        Mode::Stream => Completion::Poll,
    }
}

struct Shared {
    pool: Vec<(Accel, AxiLiteMaster)>,
    stats: HwStats,
}

pub struct HwIntersector {
    top: Arc<TopModel>,
    mode: Mode,
    shared: Mutex<Shared>,
}

impl HwIntersector {
    /// Builds (or reuses) the model of `config`.
    pub fn new(config: &TopConfig, mode: Mode) -> Result<Self, CosimError> {
        Self::build(config, mode, None)
    }

    /// Like [`HwIntersector::new`], with a trace-enabled model whose first instance writes
    /// the cycles of `window` to a VCD file.
    pub fn with_vcd(config: &TopConfig, mode: Mode, window: VcdWindow) -> Result<Self, CosimError> {
        Self::build(config, mode, Some(window))
    }

    fn build(config: &TopConfig, mode: Mode, vcd: Option<VcdWindow>) -> Result<Self, CosimError> {
        let top = top_model(config, vcd.is_some())?;
        // Create one instance now, so a broken model fails here rather than mid-render.
        let mut first = Accel::new(&top)?;
        if let Some(w) = vcd {
            first.record_vcd(w)?;
        }
        let shared = Shared {
            pool: vec![(first, AxiLiteMaster::new(completion(mode)))],
            stats: HwStats {
                instances: 1,
                ..HwStats::default()
            },
        };
        Ok(HwIntersector {
            top,
            mode,
            shared: Mutex::new(shared),
        })
    }

    pub fn config(&self) -> &TopConfig {
        &self.top.config
    }

    pub fn model(&self) -> &TopModel {
        &self.top
    }

    pub fn mode(&self) -> Mode {
        self.mode
    }

    pub fn stats(&self) -> HwStats {
        self.lock().stats
    }

    /// Closes every open VCD file (instances close theirs when dropped, too).
    pub fn close_vcd(&self) {
        for (accel, _) in &mut self.lock().pool {
            accel.close_vcd();
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Shared> {
        self.shared
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Runs one batch on an instance taken from the pool.
    fn simulate(&self, queries: &[MtQuery], results: &mut [MtResult]) -> Result<(), CosimError> {
        let taken = self.lock().pool.pop();
        let (mut accel, mut bus) = match taken {
            Some(instance) => instance,
            None => {
                let accel = Accel::new(&self.top)?;
                self.lock().stats.instances += 1;
                (accel, AxiLiteMaster::new(completion(self.mode)))
            }
        };
        let clock = SimClock::start();
        let cycles_before = accel.cycles();
        // (tests, transactions) of this batch.
        let outcome = match self.mode {
            Mode::Stream => {
                stream_batch(&mut accel, queries, results, &mut || true).map(|s| s.beats)
            }
            Mode::Register(_) => {
                let before = bus.stats.transactions();
                let mut run = || -> Result<(), CosimError> {
                    for (q, r) in queries.iter().zip(results.iter_mut()) {
                        *r = bus.test(&mut accel, q)?;
                    }
                    Ok(())
                };
                run().map(|()| bus.stats.transactions() - before)
            }
        };
        let (elapsed, cpu) = clock.elapsed();
        let mut shared = self.lock();
        shared.stats.sim_time += elapsed;
        shared.stats.sim_cpu_time += cpu;
        let transactions = outcome?;
        let cycles = accel.cycles() - cycles_before;
        let s = &mut shared.stats;
        s.tests += queries.len() as u64;
        s.cycles += cycles;
        s.busy_lane_cycles += queries.len() as u64;
        s.lane_cycles += cycles * self.top.config.lanes as u64;
        s.transactions += transactions;
        shared.pool.push((accel, bus));
        Ok(())
    }
}

impl Intersector for HwIntersector {
    fn name(&self) -> String {
        let c = &self.top.config;
        format!("hw {} d{} l{} {}", c.format, c.depth, c.lanes, self.mode)
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        Ok(self.simulate(queries, results)?)
    }
}
