//! The Verilated traversal unit as the renderer's ray engine.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use hdl::traversal::config::UnitConfig;
use hdl::traversal::scene_memory_driver::NodeLayout;
use hw_model::traversal::capacity::{chunks, run_passes};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::wide::image::WideImage;
use hw_model::traversal::{SceneCapacity, SceneMemory, UnitRay};
use sw_renderer::hit::Hit;
use sw_renderer::rays::{CastStats, EngineError, Ray, RayCaster, RayEngine};
use sw_renderer::trace::PreparedScene;

use crate::sim_clock::{core_seconds, SimClock};

use super::verilated::{unit_model, UnitModel, VerilatedUnit};
use super::{Traffic, UnitDriver, UnitError, UnitRun};

/// What the simulations of an engine did, over every render it prepared.
#[derive(Clone, Copy, Debug, Default)]
pub struct UnitSimStats {
    /// The rays' runs (cycles from the first ray in to the last answer out, per pass).
    pub runs: UnitRun,
    /// Scene loads and their cycles.
    pub loads: u64,
    pub load_cycles: u64,
    /// Every simulated cycle (reset, loads, runs and the waits between).
    pub sim_cycles: u64,
    /// Wall time inside the simulations, summed over the threads that ran them.
    pub sim_time: Duration,
    /// CPU time those threads ran for it (zero where the OS does not say).
    pub sim_cpu_time: Duration,
    /// Simulated units created.
    pub instances: u64,
}

impl UnitSimStats {
    /// Seconds one core spent simulating: the CPU time, or the wall time where it is unknown.
    pub fn core_seconds(&self) -> f64 {
        core_seconds(self.sim_time, self.sim_cpu_time)
    }
}

/// Renders through the Verilated unit of `config`: the scene image written from the
/// renderer's BVH, split for the unit's scene memory (chunked passes as
/// `hw_model::traversal::TraversalEngine` runs them, or an error naming the sizes when
/// `chunked` is off), each wavefront streamed with `traffic`. Each rayon worker takes a
/// simulated unit from a pool; a simulation error is the wavefront's error.
pub struct UnitEngine {
    model: Arc<UnitModel>,
    pub traffic: Traffic,
    pub chunked: bool,
    stats: Mutex<UnitSimStats>,
}

impl UnitEngine {
    /// Builds (or loads) the unit's model.
    pub fn new(config: &UnitConfig, traffic: Traffic, chunked: bool) -> Result<Self, UnitError> {
        Ok(UnitEngine {
            model: unit_model(config)?,
            traffic,
            chunked,
            stats: Mutex::default(),
        })
    }

    pub fn model(&self) -> &UnitModel {
        &self.model
    }

    pub fn config(&self) -> &UnitConfig {
        &self.model.config
    }

    pub fn stats(&self) -> UnitSimStats {
        *self.stats.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The scene memory as `hw_model::traversal::capacity` takes it.
    pub fn memory(&self) -> SceneMemory {
        let (nodes, triangles) = self.config().memory.capacity();
        let capacity = SceneCapacity {
            nodes: nodes as u32,
            triangles: triangles as u32,
        };
        match self.chunked {
            true => SceneMemory::Chunked(capacity),
            false => SceneMemory::Whole(capacity),
        }
    }
}

impl RayEngine for UnitEngine {
    /// "hw traversal fp32 d5 l1": like the accelerator's "hw fp32 d5 l1 stream" (the
    /// bit-accurate model of the unit is "traversal model fp32"); a wide unit's name ends with
    /// its node format ("… bvh8-q8").
    fn name(&self) -> String {
        let c = self.config();
        let name = format!("hw traversal {} d{} l{}", c.format, c.depth, c.lanes);
        match c.nodes.width() {
            Some(_) => format!("{name} {}", c.nodes.name()),
            None => name,
        }
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a PreparedScene,
    ) -> Result<Box<dyn RayCaster + 'a>, EngineError> {
        // The chunks as the unit's nodes hold them: the binary images, or each written wide.
        let nodes = self.config().nodes;
        let parts = chunks(&SceneImage::new(scene), self.memory(), nodes)?;
        let (bytes, chunks) = match nodes.width() {
            None => (parts.iter())
                .map(|c| (c.bytes() as u64, c.to_words()))
                .unzip(),
            Some(width) => {
                let wide: Vec<WideImage> = (parts.iter())
                    .map(|c| WideImage::of(c, width))
                    .collect::<Result<_, _>>()?;
                wide.iter()
                    .map(|w| (w.bytes() as u64, w.to_words()))
                    .unzip()
            }
        };
        Ok(Box::new(Caster {
            engine: self,
            bytes,
            chunks,
            pool: Mutex::default(),
        }))
    }
}

/// A simulated unit and the chunk its memory holds.
struct Instance {
    driver: UnitDriver<VerilatedUnit>,
    loaded: Option<usize>,
}

struct Caster<'a> {
    engine: &'a UnitEngine,
    chunks: Vec<Vec<u32>>,
    bytes: Vec<u64>,
    pool: Mutex<Vec<Instance>>,
}

impl Caster<'_> {
    fn instance(&self) -> Result<Instance, UnitError> {
        if let Some(i) = self.pool.lock().unwrap_or_else(|p| p.into_inner()).pop() {
            return Ok(i);
        }
        let c = &self.engine.model.config;
        let unit = VerilatedUnit::new(&self.engine.model)?;
        self.engine
            .stats
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .instances += 1;
        Ok(Instance {
            driver: UnitDriver::new(unit, c.memory, NodeLayout::of(c.nodes), c.stack_depth)?,
            loaded: None,
        })
    }
}

impl RayCaster for Caster<'_> {
    /// One pass per chunk with the rays that still need it; a unit keeps the chunk it last
    /// loaded (a resident scene is loaded once per unit).
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError> {
        let clock = SimClock::start();
        let mut unit = self.instance()?;
        let first_cycle = unit.driver.cycles();
        let unit_rays: Vec<UnitRay> = (rays.iter().enumerate())
            .map(|(id, ray)| UnitRay::of(ray, id as u32))
            .collect();
        let mut sim = UnitSimStats::default();
        let mut stats = run_passes(&self.bytes, &unit_rays, hits, |k, rays, answers| {
            if unit.loaded != Some(k) {
                let before = unit.driver.cycles();
                unit.loaded = None;
                unit.driver.load(&self.chunks[k])?;
                unit.loaded = Some(k);
                sim.loads += 1;
                sim.load_cycles += unit.driver.cycles() - before;
            }
            sim.runs += unit.driver.run(rays, answers, self.engine.traffic)?;
            Ok::<_, UnitError>(())
        })?;
        sim.sim_cycles = unit.driver.cycles() - first_cycle;
        (sim.sim_time, sim.sim_cpu_time) = clock.elapsed();
        // Only a unit that finished cleanly goes back: after an error its state is unknown.
        self.pool
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .push(unit);
        let c = sim.runs.counters;
        stats.batches = 1;
        stats.cycles = sim.runs.cycles;
        stats.mt_tests = c.mt_tests;
        stats.box_tests = c.box_tests;
        stats.node_visits = c.node_visits;
        stats.ray_passes = c.rays;
        let mut total = self.engine.stats.lock().unwrap_or_else(|p| p.into_inner());
        total.runs += sim.runs;
        total.loads += sim.loads;
        total.load_cycles += sim.load_cycles;
        total.sim_cycles += sim.sim_cycles;
        total.sim_time += sim.sim_time;
        total.sim_cpu_time += sim.sim_cpu_time;
        Ok(stats)
    }
}
