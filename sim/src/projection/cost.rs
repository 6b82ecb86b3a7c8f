//! The cost terms of a frame on the ZedBoard and how a design adds them up.
//!
//! Times are seconds, frequencies MHz, per-event costs nanoseconds. The equations are
//! derived in `docs/projection.md`; the constants of [`Board`] come from the calibration.

use super::workload::{Traversal, UnitWork, Workload};
use super::ProjectionError;

/// Clock of the ZedBoard's Cortex-A9 cores.
pub const ARM_MHZ: f64 = 667.0;

/// The thesis' bare-metal driver, per ray-triangle test on one accelerator: 15 operand
/// writes (origin, direction, v0, v1, v2) and the ap_start write…
pub const SETUP_ACCESSES: f64 = 16.0;
/// …then polls of the control register until ap_done, then reads of hit, t, u, v.
pub const RESULT_READS: f64 = 4.0;

/// Bytes one query takes on the stream: origin, direction, v0, v1, v2 as fp32.
pub const QUERY_BYTES: f64 = 60.0;
/// Bytes one answer takes: hit, t, u, v as 32-bit words.
pub const RESULT_BYTES: f64 = 16.0;
/// Bytes an HP port moves per fabric cycle (64-bit data bus).
pub const HP_PORT_BYTES_PER_CYCLE: f64 = 8.0;
/// Bytes of one ray on the traversal unit's input stream, and of one answer on its output.
pub const RAY_BYTES: f64 = 4.0 * hw_model::traversal::RAY_WORDS as f64;
pub const HIT_BYTES: f64 = 4.0 * hw_model::traversal::HIT_WORDS as f64;
/// AXI-Lite accesses to start one batch on an AXI DMA (MM2S and S2MM: address, length,
/// control each) and to see it finish (one status read each).
pub const DMA_ACCESSES_PER_BATCH: f64 = 8.0;
/// A chunk load uses one channel (MM2S) of such a batch.
pub const DMA_ACCESSES_PER_LOAD: f64 = DMA_ACCESSES_PER_BATCH / 2.0;

/// The board's fitted constants.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Board {
    /// ARM time per ray for everything but the ray-triangle tests (ray generation, shading,
    /// recursion, writing the pixel).
    pub arm_ray_ns: f64,
    /// ARM time of one software Möller-Trumbore test, triangle loop included.
    pub arm_test_ns: f64,
    /// Part of one AXI4-Lite register access on GP0 that does not scale with f_PL: the ARM's
    /// driver code and the PS side of the interconnect.
    pub access_fixed_ns: f64,
    /// Fabric cycles of one register access (PL interconnect and the slave's handshakes).
    pub access_pl_cycles: f64,
}

/// ARM time of one two-child box test of a software BVH walk, in MT tests: an assumption,
/// not fitted (the thesis had no BVH). The box test is 12 subtractions, 12 multiplications
/// and about 14 compares and selects with their branches, the Möller-Trumbore test 27
/// multiplications, 23 additions and a division: the same order of VFP work, so one each.
pub const ARM_BOX_TESTS_PER_MT_TEST: f64 = 1.0;

impl Board {
    /// One AXI4-Lite register access with the fabric at `fpl_mhz`.
    pub fn access_ns(&self, fpl_mhz: f64) -> f64 {
        self.access_fixed_ns + self.access_pl_cycles * 1e3 / fpl_mhz
    }

    /// ARM time of everything but the tests.
    pub fn arm_rays_s(&self, w: &Workload) -> f64 {
        w.rays() as f64 * self.arm_ray_ns * 1e-9
    }

    /// The software renderer alone on the ARM, testing as `traversal` finds candidates (for
    /// the BVH the ARM's traversal itself is not counted: see docs/projection.md).
    pub fn arm_only_s(&self, w: &Workload, traversal: Traversal) -> f64 {
        self.arm_rays_s(w) + w.tests(traversal) as f64 * self.arm_test_ns * 1e-9
    }

    /// The project's renderer on the ARM with its BVH walk counted: the MT tests of the BVH
    /// render plus the traversal unit's box tests (the same walk), each box test costing
    /// [`ARM_BOX_TESTS_PER_MT_TEST`] MT tests. `None` without the unit's measurement.
    pub fn arm_bvh_walk_s(&self, w: &Workload) -> Option<f64> {
        let unit = w.unit.as_ref()?;
        Some(
            self.arm_only_s(w, Traversal::Bvh)
                + unit.box_tests as f64 * ARM_BOX_TESTS_PER_MT_TEST * self.arm_test_ns * 1e-9,
        )
    }
}

/// How queries reach the hardware.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Frontend {
    /// The thesis: one AXI4-Lite call per test on each of `units` non-pipelined accelerators,
    /// used round robin, each busy `cycles_per_test` fabric cycles per call (its mean latency).
    Thesis { units: u32, cycles_per_test: f64 },
    /// The project's: queries packed by the ARM into DDR, streamed by an AXI DMA through
    /// `hp_ports` 64-bit HP ports (at `dma_efficiency` of their peak) into `lanes` pipelined
    /// lanes that take a query every `cycles_per_test` cycles (1 = II 1) and answer
    /// `pipeline_latency` cycles later.
    Stream {
        lanes: u32,
        cycles_per_test: f64,
        pipeline_latency: u32,
        hp_ports: u32,
        dma_efficiency: f64,
        /// ARM cycles to pack one query into the DMA buffer (stores, cache clean).
        pack_arm_cycles: f64,
    },
    /// The traversal unit: the scene image loaded once per frame, then per wavefront the
    /// ARM's rays streamed by DMA through `hp_ports` HP ports into the unit and its answers
    /// back; the unit's cycles are the workload's (its schedule model, or a co-simulation).
    Traversal {
        hp_ports: u32,
        dma_efficiency: f64,
        /// ARM cycles to write one ray record and read its answer.
        pack_arm_cycles: f64,
    },
}

/// One accelerator design on the board.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Design {
    pub frontend: Frontend,
    pub traversal: Traversal,
    pub fpl_mhz: f64,
}

impl Design {
    pub fn validate(&self) -> Result<(), ProjectionError> {
        if !(self.fpl_mhz.is_finite() && self.fpl_mhz > 0.0) {
            return Err(ProjectionError::Invalid(format!(
                "fabric clock {} MHz: expected a positive frequency",
                self.fpl_mhz
            )));
        }
        let positive = |what: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(ProjectionError::Invalid(format!(
                    "{what} {x}: expected a positive number"
                )))
            }
        };
        match self.frontend {
            Frontend::Thesis {
                units,
                cycles_per_test,
            } => {
                if units == 0 {
                    return Err(ProjectionError::Invalid(
                        "0 accelerators: expected at least 1".into(),
                    ));
                }
                positive("cycles per test", cycles_per_test)
            }
            Frontend::Traversal {
                hp_ports,
                dma_efficiency,
                pack_arm_cycles,
            } => dma(hp_ports, dma_efficiency, pack_arm_cycles),
            Frontend::Stream {
                lanes,
                cycles_per_test,
                hp_ports,
                dma_efficiency,
                pack_arm_cycles,
                ..
            } => {
                if lanes == 0 {
                    return Err(ProjectionError::Invalid(
                        "0 lanes: expected at least 1".into(),
                    ));
                }
                dma(hp_ports, dma_efficiency, pack_arm_cycles)?;
                positive("cycles per test", cycles_per_test)
            }
        }
    }
}

/// The DMA parameters of a streaming design.
fn dma(hp_ports: u32, dma_efficiency: f64, pack_arm_cycles: f64) -> Result<(), ProjectionError> {
    if !(1..=4).contains(&hp_ports) {
        return Err(ProjectionError::Invalid(format!(
            "{hp_ports} HP ports: the Zynq-7020 has 1 to 4"
        )));
    }
    if !(dma_efficiency > 0.0 && dma_efficiency <= 1.0) {
        return Err(ProjectionError::Invalid(format!(
            "DMA efficiency {dma_efficiency}: expected a fraction in (0, 1]"
        )));
    }
    if !(pack_arm_cycles.is_finite() && pack_arm_cycles >= 0.0) {
        return Err(ProjectionError::Invalid(format!(
            "packing cost {pack_arm_cycles} ARM cycles: expected a number ≥ 0"
        )));
    }
    Ok(())
}

/// Where a frame's time goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Breakdown {
    /// Ray-triangle tests the hardware answers.
    pub tests: u64,
    /// ARM computing: rays, shading, packing queries.
    pub arm_s: f64,
    /// AXI4-Lite traffic on GP0.
    pub bus_s: f64,
    /// Waiting for the accelerator (its exposed latency, or the DMA/lane streaming time).
    pub accel_s: f64,
}

impl Breakdown {
    pub fn total_s(&self) -> f64 {
        self.arm_s + self.bus_s + self.accel_s
    }
}

/// The frame time of workload `w` on design `d`.
pub fn project(w: &Workload, d: &Design, b: &Board) -> Result<Breakdown, ProjectionError> {
    d.validate()?;
    let tests = match d.frontend {
        Frontend::Traversal { .. } => w.unit.as_ref().map_or(0, |u| u.mt_tests),
        _ => w.tests(d.traversal),
    };
    let n = tests as f64;
    let cycle_s = 1e-6 / d.fpl_mhz;
    let access_s = b.access_ns(d.fpl_mhz) * 1e-9;
    Ok(match d.frontend {
        Frontend::Thesis {
            units,
            cycles_per_test,
        } => {
            // While one unit computes, the driver sets up the other units' calls.
            let hidden = f64::from(units - 1) * SETUP_ACCESSES * access_s;
            let wait = (cycles_per_test * cycle_s - hidden).max(0.0);
            // Polling ends on average half a poll after the unit is done; at least one poll.
            let polling = access_s.max(wait + access_s / 2.0);
            Breakdown {
                tests,
                arm_s: b.arm_rays_s(w),
                bus_s: n * ((SETUP_ACCESSES + RESULT_READS) * access_s + polling - wait),
                accel_s: n * wait,
            }
        }
        Frontend::Stream {
            lanes,
            cycles_per_test,
            pipeline_latency,
            hp_ports,
            dma_efficiency,
            pack_arm_cycles,
        } => {
            let bytes_per_s = dma_bytes_per_cycle(hp_ports, dma_efficiency) / cycle_s;
            // Read and write channels run in parallel; the slower of them and the lanes sets the pace.
            let streaming = (n * QUERY_BYTES / bytes_per_s)
                .max(n * RESULT_BYTES / bytes_per_s)
                .max(n * cycles_per_test * cycle_s / f64::from(lanes));
            let batches = w.batches as f64;
            Breakdown {
                tests,
                arm_s: b.arm_rays_s(w) + n * pack_arm_cycles / (ARM_MHZ * 1e6),
                bus_s: batches * DMA_ACCESSES_PER_BATCH * access_s,
                accel_s: streaming + batches * f64::from(pipeline_latency) * cycle_s,
            }
        }
        Frontend::Traversal {
            hp_ports,
            dma_efficiency,
            pack_arm_cycles,
        } => {
            let unit = w.unit.as_ref().ok_or_else(|| {
                ProjectionError::Invalid(
                    "the traversal design needs the unit's work on the frame (Workload::with_unit)"
                        .into(),
                )
            })?;
            let bytes_per_s = dma_bytes_per_cycle(hp_ports, dma_efficiency) / cycle_s;
            // Every pass streams the rays that take part in it (closest-hit rays carry their
            // nearest hit as t_max); the ARM writes each and folds its answer.
            let rays = unit.ray_passes as f64;
            // Rays in and answers out stream in parallel with the unit's work; the slowest
            // of the three sets the pace (the cycles already hold each pass' drain).
            let streaming = (rays * RAY_BYTES / bytes_per_s)
                .max(rays * HIT_BYTES / bytes_per_s)
                .max(unit.cycles as f64 * cycle_s);
            Breakdown {
                tests,
                arm_s: b.arm_rays_s(w) + rays * pack_arm_cycles / (ARM_MHZ * 1e6),
                bus_s: (unit.passes as f64 * DMA_ACCESSES_PER_BATCH
                    + unit.chunk_loads as f64 * DMA_ACCESSES_PER_LOAD)
                    * access_s,
                // The scene memory is one buffer: a load waits for the pass before it.
                accel_s: streaming + unit_loads(unit, hp_ports, dma_efficiency) * cycle_s,
            }
        }
    })
}

/// Bytes a DMA moves per fabric cycle through `hp_ports` HP ports at `efficiency`.
fn dma_bytes_per_cycle(hp_ports: u32, efficiency: f64) -> f64 {
    f64::from(hp_ports) * HP_PORT_BYTES_PER_CYCLE * efficiency
}

/// Fabric cycles of a frame's scene-memory loads (the whole image, or every chunk load).
fn unit_loads(unit: &UnitWork, hp_ports: u32, efficiency: f64) -> f64 {
    unit.loaded_bytes as f64 / dma_bytes_per_cycle(hp_ports, efficiency)
}

/// Fabric cycles the traversal design spends loading its scene memory for the frame
/// (`None` for the other designs).
pub fn load_cycles(unit: &UnitWork, d: &Design) -> Option<f64> {
    match d.frontend {
        Frontend::Traversal {
            hp_ports,
            dma_efficiency,
            ..
        } => Some(unit_loads(unit, hp_ports, dma_efficiency)),
        _ => None,
    }
}
