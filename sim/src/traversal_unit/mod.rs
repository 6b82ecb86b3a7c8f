//! The traversal unit (`hdl::traversal::unit`, docs/traversal-unit.md) driven cycle by
//! cycle: a scene image loaded through the scene stream, rays streamed in, answers collected
//! by ray id, the counters and the overflow bit read.
//!
//! [`UnitDriver`] speaks the port contract through [`UnitPorts`], so the same driver runs
//! the Verilated unit and, in its own tests, a unit that misbehaves on purpose. Every ray
//! must be answered exactly once; a watchdog turns a unit that stops making progress into
//! an error describing its state instead of a hang.

mod engine;
mod verilated;

pub use engine::{UnitEngine, UnitSimStats};
pub use verilated::{unit_model, UnitModel, VerilatedUnit};

use std::collections::HashMap;

use hdl::traversal::scene_memory_driver::{
    check_before_load_in, status_result_in, LoadStatus, MemoryConfig, NodeLayout, SceneMemoryError,
};
use hw_model::traversal::packet::{hit_from_words, HIT_WORDS, RAY_WORDS};
use hw_model::traversal::scene_image::SceneImageError;
use hw_model::traversal::{TraversalError, UnitCounters, UnitRay};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sw_renderer::hit::Hit;

use crate::SimError;

/// The unit's inputs the driver sets (each at most 32 bits; the ray stream's `tdata` is
/// [`UnitPorts::ray_data`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
    ResetN,
    SceneStart,
    SceneTdata,
    SceneTvalid,
    SceneTlast,
    RayTvalid,
    HitTready,
}

/// The unit's outputs the driver reads (each at most 32 bits; the hit stream's `tdata` is
/// [`UnitPorts::hit_data`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Out {
    SceneTready,
    SceneLoaded,
    SceneError,
    SceneErrorCode,
    SceneErrorWord,
    SceneErrorValue,
    RayTready,
    HitTvalid,
    Idle,
    Overflow,
    OverflowRay,
    CountRays,
    CountNodeVisits,
    CountBoxTests,
    CountMtTests,
    CountBusyCycles,
}

/// The unit's Verilog top (every format and memory size has the same ports).
type UnitTop = hdl::traversal::unit_top::fp32::Unit4x5;

/// rust-hdl's flattened name of the unit top's port `bundle.signal` (`scene$tdata`) or
/// `signal` (`reset_n`), from the top's own fields (`hdl::traversal::ports`): the compiler
/// checks that the top has each port the harness names.
macro_rules! port {
    ($signal:ident) => {{
        const _: fn(&UnitTop) = |unit| {
            let _ = &unit.$signal;
        };
        stringify!($signal)
    }};
    ($bundle:ident . $signal:ident) => {{
        const _: fn(&UnitTop) = |unit| {
            let _ = &unit.$bundle.$signal;
        };
        concat!(stringify!($bundle), "$", stringify!($signal))
    }};
}

/// The ports the driver sets, in [`In`] order.
pub const IN_NAMES: [(In, &str); 7] = [
    (In::ResetN, port!(reset_n)),
    (In::SceneStart, port!(control.scene_start)),
    (In::SceneTdata, port!(scene.tdata)),
    (In::SceneTvalid, port!(scene.tvalid)),
    (In::SceneTlast, port!(scene.tlast)),
    (In::RayTvalid, port!(ray.tvalid)),
    (In::HitTready, port!(hit.tready)),
];

/// The ports the driver reads, in [`Out`] order.
pub const OUT_NAMES: [(Out, &str); 16] = [
    (Out::SceneTready, port!(scene.tready)),
    (Out::SceneLoaded, port!(control.scene_loaded)),
    (Out::SceneError, port!(control.scene_error)),
    (Out::SceneErrorCode, port!(control.scene_error_code)),
    (Out::SceneErrorWord, port!(control.scene_error_word)),
    (Out::SceneErrorValue, port!(control.scene_error_value)),
    (Out::RayTready, port!(ray.tready)),
    (Out::HitTvalid, port!(hit.tvalid)),
    (Out::Idle, port!(control.idle)),
    (Out::Overflow, port!(control.overflow)),
    (Out::OverflowRay, port!(control.overflow_ray)),
    (Out::CountRays, port!(counters.rays)),
    (Out::CountNodeVisits, port!(counters.node_visits)),
    (Out::CountBoxTests, port!(counters.box_tests)),
    (Out::CountMtTests, port!(counters.mt_tests)),
    (Out::CountBusyCycles, port!(counters.busy_cycles)),
];

/// The ray and answer streams' data ports.
pub const RAY_TDATA: &str = port!(ray.tdata);
pub const HIT_TDATA: &str = port!(hit.tdata);

/// A unit's ports, one clock cycle at a time: inputs are held until changed, outputs are
/// sampled before the cycle's rising edge (a handshake seen in them happens at that edge).
pub trait UnitPorts {
    fn set(&mut self, port: In, value: u32);
    /// The ray stream's `tdata` for the following cycles.
    fn ray_data(&mut self) -> &mut [u32; RAY_WORDS];
    fn get(&self, port: Out) -> u32;
    /// The hit stream's `tdata` as sampled in the last cycle.
    fn hit_data(&self) -> [u32; HIT_WORDS];
    fn cycle(&mut self) -> Result<(), SimError>;
    /// Cycles run so far.
    fn cycles(&self) -> u64;
}

/// Cycles `reset_n` is held low (the reset is synchronous).
const RESET_CYCLES: usize = 2;

/// Cycles without any progress (a stream handshake, a counter moving, a load finishing)
/// after which the unit is declared hung. A busy unit counts a box or Möller-Trumbore test
/// every few cycles; the longest quiet stretch is a step's latency plus a chain of skipped
/// pops, well under this.
pub const WATCHDOG_CYCLES: u64 = 20_000;

/// What goes wrong driving the unit.
#[derive(Debug, thiserror::Error)]
pub enum UnitError {
    /// The RTL does not build this configuration.
    #[error("traversal unit configuration: {0}")]
    Config(#[from] hdl::traversal::config::UnitConfigError),
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The image was refused, by the driver's checks or the unit's loader.
    #[error(transparent)]
    Memory(#[from] SceneMemoryError),
    #[error(transparent)]
    Image(#[from] SceneImageError),
    /// The unit set its overflow bit.
    #[error(transparent)]
    Traversal(#[from] TraversalError),
    /// The unit answered what the driver cannot match (a duplicate, an unknown id).
    #[error("traversal unit, cycle {cycle}: {message}")]
    Protocol { cycle: u64, message: String },
    /// No progress for [`WATCHDOG_CYCLES`].
    #[error("traversal unit hangs: no progress for {cycles} cycles while {state}")]
    Timeout { cycles: u64, state: String },
    /// What the caller asked for cannot be run.
    #[error("traversal unit: {0}")]
    Usage(String),
}

/// Stream traffic: random `tvalid` gaps before each ray and random `tready` back-pressure on
/// the answers, reproducible from the seed. [`Traffic::FULL_SPEED`] has neither.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traffic {
    /// Probability that a cycle in which a ray could be presented is left empty.
    pub ray_gap: f64,
    /// Probability that the hit stream's `tready` is low in a cycle.
    pub hit_stall: f64,
    pub seed: u64,
}

impl Traffic {
    pub const FULL_SPEED: Traffic = Traffic {
        ray_gap: 0.0,
        hit_stall: 0.0,
        seed: 0,
    };

    fn check(&self) -> Result<(), UnitError> {
        for (name, p) in [("ray_gap", self.ray_gap), ("hit_stall", self.hit_stall)] {
            if !(0.0..1.0).contains(&p) {
                return Err(UnitError::Usage(format!(
                    "traffic {name} = {p}: a probability in [0, 1) is needed (1 would never let a beat through)"
                )));
            }
        }
        Ok(())
    }
}

/// What a run of rays cost, from the unit's counters and the simulation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UnitRun {
    /// The unit's counters over the run (wrapping 32-bit differences).
    pub counters: UnitCounters,
    /// Cycles with a ray in the unit (its counter).
    pub busy_cycles: u64,
    /// Cycles from the first ray presented to the last answer taken.
    pub cycles: u64,
    /// Cycles a presented ray waited for `ray_tready`.
    pub ray_stalls: u64,
}

impl std::ops::AddAssign for UnitRun {
    fn add_assign(&mut self, o: UnitRun) {
        self.counters += o.counters;
        self.busy_cycles += o.busy_cycles;
        self.cycles += o.cycles;
        self.ray_stalls += o.ray_stalls;
    }
}

/// The counters' values as sampled now.
#[derive(Clone, Copy)]
struct Counts([u32; 5]);

const COUNTERS: [Out; 5] = [
    Out::CountRays,
    Out::CountNodeVisits,
    Out::CountBoxTests,
    Out::CountMtTests,
    Out::CountBusyCycles,
];

impl Counts {
    fn of(ports: &impl UnitPorts) -> Counts {
        Counts(COUNTERS.map(|c| ports.get(c)))
    }

    /// `self - before`, each counter wrapping at 32 bits.
    fn since(self, before: Counts) -> (UnitCounters, u64) {
        let d: Vec<u64> = (self.0.iter().zip(before.0))
            .map(|(now, then)| u64::from(now.wrapping_sub(then)))
            .collect();
        let counters = UnitCounters {
            rays: d[0],
            node_visits: d[1],
            box_tests: d[2],
            mt_tests: d[3],
        };
        (counters, d[4])
    }
}

/// Drives one unit whose scene memory is `memory` holding `layout`'s nodes and whose rays
/// have `stack_depth` stack entries.
pub struct UnitDriver<P: UnitPorts> {
    ports: P,
    memory: MemoryConfig,
    layout: NodeLayout,
    stack_depth: usize,
    /// The tree depth of the loaded scene; `None` until a checked load succeeds.
    loaded_depth: Option<usize>,
}

impl<P: UnitPorts> UnitDriver<P> {
    /// Takes the unit's ports and resets it.
    pub fn new(
        ports: P,
        memory: MemoryConfig,
        layout: NodeLayout,
        stack_depth: usize,
    ) -> Result<UnitDriver<P>, UnitError> {
        let mut d = UnitDriver {
            ports,
            memory,
            layout,
            stack_depth,
            loaded_depth: None,
        };
        d.reset()?;
        Ok(d)
    }

    pub fn cycles(&self) -> u64 {
        self.ports.cycles()
    }

    /// Holds `reset_n` low with every valid low, then releases it: the slots empty, the
    /// overflow bit and the counters clear; a scene must be loaded again.
    pub fn reset(&mut self) -> Result<(), UnitError> {
        for port in [
            In::ResetN,
            In::SceneStart,
            In::SceneTvalid,
            In::SceneTlast,
            In::RayTvalid,
            In::HitTready,
        ] {
            self.ports.set(port, 0);
        }
        for _ in 0..RESET_CYCLES {
            self.ports.cycle()?;
        }
        self.ports.set(In::ResetN, 1);
        self.ports.cycle()?;
        self.loaded_depth = None;
        Ok(())
    }

    /// Loads a scene image: the driver's checks of the whole image and its size
    /// ([`check_before_load_in`]: version 2 or 3 as the memory holds), then the words
    /// streamed; the memory's status is judged by [`status_result_in`].
    pub fn load(&mut self, words: &[u32]) -> Result<(), UnitError> {
        let depth = check_before_load_in(words, self.memory, self.layout)?;
        self.loaded_depth = None;
        let status = self.stream_image(words)?;
        status_result_in(&status, words, self.memory, self.layout)?;
        self.loaded_depth = Some(depth);
        Ok(())
    }

    /// Streams `words` as they are (no checks: what tests of the unit's own loader use) and
    /// returns the memory's status once the load ended. The driver refuses rays until a
    /// [`UnitDriver::load`] succeeds.
    pub fn stream_image(&mut self, words: &[u32]) -> Result<LoadStatus, UnitError> {
        self.loaded_depth = None;
        let p = &mut self.ports;
        p.set(In::SceneStart, 1);
        p.cycle()?;
        p.set(In::SceneStart, 0);
        let mut quiet = 0;
        let mut sent = 0;
        while sent < words.len() {
            p.set(In::SceneTdata, words[sent]);
            p.set(In::SceneTvalid, 1);
            p.set(In::SceneTlast, u32::from(sent + 1 == words.len()));
            p.cycle()?;
            if p.get(Out::SceneTready) == 1 {
                sent += 1;
                quiet = 0;
            } else if p.get(Out::SceneError) == 1 {
                break;
            } else {
                quiet += 1;
                if quiet > WATCHDOG_CYCLES {
                    return Err(UnitError::Timeout {
                        cycles: WATCHDOG_CYCLES,
                        state: format!(
                            "loading a scene image: word {sent} of {} not taken (the scene stream's tready low, no error)",
                            words.len()
                        ),
                    });
                }
            }
        }
        p.set(In::SceneTvalid, 0);
        p.set(In::SceneTlast, 0);
        // The status follows the last word within a few cycles.
        let mut waited = 0;
        loop {
            p.cycle()?;
            let (loaded, error) = (p.get(Out::SceneLoaded) == 1, p.get(Out::SceneError) == 1);
            if loaded || error {
                return Ok(LoadStatus {
                    loading: false,
                    loaded,
                    error_code: u64::from(p.get(Out::SceneErrorCode)),
                    error_word: p.get(Out::SceneErrorWord),
                    error_value: p.get(Out::SceneErrorValue),
                    // The header's N and T as streamed (the memory's own copy is not a port).
                    nodes: words.get(2).copied().unwrap_or_default(),
                    triangles: words.get(3).copied().unwrap_or_default(),
                });
            }
            waited += 1;
            if waited > WATCHDOG_CYCLES {
                return Err(UnitError::Timeout {
                    cycles: WATCHDOG_CYCLES,
                    state: format!(
                        "waiting for the status of a load of {} words (neither scene_loaded nor scene_error)",
                        words.len()
                    ),
                });
            }
        }
    }

    /// Runs `rays` through the loaded scene with `traffic` on the streams and writes each
    /// ray's answer into `answers` (matched by ray id, which must be unique). An overflow of
    /// a ray's stack is an error naming the ray, after the unit is reset.
    pub fn run(
        &mut self,
        rays: &[UnitRay],
        answers: &mut [Option<Hit>],
        traffic: Traffic,
    ) -> Result<UnitRun, UnitError> {
        assert_eq!(rays.len(), answers.len(), "one answer per ray");
        traffic.check()?;
        let Some(tree_depth) = self.loaded_depth else {
            return Err(UnitError::Usage(
                "no scene is loaded: load one before sending rays".into(),
            ));
        };
        let mut index = HashMap::with_capacity(rays.len());
        for (k, r) in rays.iter().enumerate() {
            if let Some(first) = index.insert(r.id, k) {
                return Err(UnitError::Usage(format!(
                    "rays {first} and {k} share the id {}: answers are matched by id",
                    r.id
                )));
            }
        }
        let mut rng = StdRng::seed_from_u64(traffic.seed);
        let mut answered = vec![false; rays.len()];
        let before = Counts::of(&self.ports);
        let start = self.ports.cycles();
        let (mut sent, mut received, mut stalls) = (0usize, 0usize, 0u64);
        let mut presenting = false;
        let (mut last_progress, mut last_counts) = (start, before);
        let p = &mut self.ports;
        while received < rays.len() {
            if !presenting
                && sent < rays.len()
                && !(traffic.ray_gap > 0.0 && rng.gen_bool(traffic.ray_gap))
            {
                *p.ray_data() = rays[sent].to_words();
                presenting = true;
            }
            let ready = !(traffic.hit_stall > 0.0 && rng.gen_bool(traffic.hit_stall));
            p.set(In::RayTvalid, u32::from(presenting));
            p.set(In::HitTready, u32::from(ready));
            p.cycle()?;
            let mut progress = false;
            if presenting {
                if p.get(Out::RayTready) == 1 {
                    sent += 1;
                    presenting = false;
                    progress = true;
                } else {
                    stalls += 1;
                }
            }
            if ready && p.get(Out::HitTvalid) == 1 {
                let (id, hit) = hit_from_words(&p.hit_data());
                let cycle = p.cycles();
                let protocol = |message| UnitError::Protocol { cycle, message };
                let Some(&k) = index.get(&id) else {
                    return Err(protocol(format!(
                        "an answer for ray id {id}, which is not among the {} rays sent",
                        rays.len()
                    )));
                };
                if k >= sent {
                    return Err(protocol(format!(
                        "an answer for ray id {id} (ray {k}) before the unit took that ray ({sent} taken)"
                    )));
                }
                if std::mem::replace(&mut answered[k], true) {
                    return Err(protocol(format!("ray id {id} (ray {k}) answered twice")));
                }
                answers[k] = hit;
                received += 1;
                progress = true;
            }
            let counts = Counts::of(p);
            if counts.0 != last_counts.0 {
                last_counts = counts;
                progress = true;
            }
            if progress {
                last_progress = p.cycles();
            } else if p.cycles() - last_progress > WATCHDOG_CYCLES {
                let missing: Vec<String> = (0..sent)
                    .filter(|&k| !answered[k])
                    .take(8)
                    .map(|k| rays[k].id.to_string())
                    .collect();
                return Err(UnitError::Timeout {
                    cycles: WATCHDOG_CYCLES,
                    state: format!(
                        "running {} rays: {sent} taken, {received} answered, unanswered ids [{}{}]; ray tvalid {} tready {}, hit tvalid {} tready {}, idle {}, overflow {}",
                        rays.len(),
                        missing.join(", "),
                        if sent - received > missing.len() { ", …" } else { "" },
                        u32::from(presenting),
                        p.get(Out::RayTready),
                        p.get(Out::HitTvalid),
                        u32::from(ready),
                        p.get(Out::Idle),
                        p.get(Out::Overflow),
                    ),
                });
            }
        }
        let cycles = p.cycles() - start;
        p.set(In::RayTvalid, 0);
        // Every ray is answered; the counters are final once the unit says it is idle.
        let mut waited = 0;
        while p.get(Out::Idle) != 1 {
            p.cycle()?;
            waited += 1;
            if waited > WATCHDOG_CYCLES {
                return Err(UnitError::Timeout {
                    cycles: WATCHDOG_CYCLES,
                    state: format!(
                        "every one of {} rays is answered, but the unit is not idle",
                        rays.len()
                    ),
                });
            }
        }
        p.set(In::HitTready, 0);
        if p.get(Out::Overflow) == 1 {
            let id = p.get(Out::OverflowRay);
            self.reset()?;
            return Err(TraversalError::StackOverflow {
                id,
                capacity: self.stack_depth,
                depth: tree_depth,
            }
            .into());
        }
        let (counters, busy_cycles) = Counts::of(&self.ports).since(before);
        Ok(UnitRun {
            counters,
            busy_cycles,
            cycles,
            ray_stalls: stalls,
        })
    }
}

#[cfg(test)]
mod tests;
