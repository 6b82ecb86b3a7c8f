//! The frame schedule model: how many cycles a whole frame takes on the planned frame unit,
//! stage by stage (docs/frame.md "Frame schedule model"). Each ray's walk comes from the
//! traversal unit's bit-accurate model and each thread's instructions and pushes from the
//! shader core's interpreter, so the schedule only adds time; the image is the frame model's.
//!
//! The planned unit, cycle by cycle:
//! - **ray generation**: one primary ray every `raygen_interval` cycles (the hardware's
//!   [`super::raygen::INTERVAL`]: its operators time-shared) in pixel order, when the pixel's
//!   accumulator
//!   slot is free (slot = pixel mod `pixel_slots`: pixel p opens after pixel p − slots has
//!   finished) and the ray store keeps `spawn_reserve` entries free after it; the ray reaches
//!   the traversal unit's input `raygen_latency` cycles later; its *open* record goes to the
//!   accumulator;
//! - **ray store**: `ray_store` entries, a ray's id in the traversal unit being its entry; a
//!   ray holds its entry from generation (or its push) until it is shaded: a shadow ray's is
//!   freed with its answer, a cast ray's when its thread starts (the thread has read it);
//! - **traversal unit**: [`Unit`] of the schedule model, fed from its input queue (spawned
//!   rays before primary ones, so that pixels finish), one ray in a cycle when a slot is
//!   free, one answer out a cycle;
//! - **shading**: a shadow ray's answer settles beside the cores (a record to the
//!   accumulator); a cast ray's answer waits for a thread, the oldest pixel's first and a
//!   pixel's deepest first. The first waiting ray starts a thread (at most one a cycle) on
//!   the core with the fewest threads, if one has a free context, reserving the ray-store
//!   entries every push of its program may need ([`Program::pushes_from`]; its own entry,
//!   read now, counting), and only if the store keeps the escape's reserve free after it,
//!   unless its program pushes shadow rays only or it is the *escape* (below). A core is a
//!   barrel of `threads` contexts issuing one instruction a cycle round robin among its
//!   ready threads; a thread is ready again `threads` cycles after an issue (the pipeline's
//!   latency), so a thread of n instructions takes about n·`threads` cycles and a core with
//!   fewer threads ready leaves issue slots idle. In the cycle after its last instruction
//!   (`End`) issued, the thread's pushes join the traversal unit's input, its unused
//!   reservations are freed, its settle record goes to the accumulator and its context is
//!   free;
//! - **accumulator**: one record a cycle in arrival order; a pixel whose last ray settles is
//!   finished `accumulate_latency` cycles later, and its slot free.
//!
//! The frame's cycles run from the first pixel to the last finished pixel.
//!
//! **No deadlock, no dropped ray.** A thread starts only with every entry its pushes may
//! need, so no ray is dropped; but rays waiting for a thread hold their entries, and ray
//! trees grow. The threads that push reflection or refraction rays leave the *escape's
//! reserve* of C·D + M entries free (D the scene's max depth, C and M the most reflection
//! and refraction rays and the most rays a thread pushes), ray generation `spawn_reserve` ≥
//! that; threads that push shadow rays only may use the reserve (their rays come back and
//! free their entries without needing more); so may the *escape*: the deepest cast ray in
//! flight of the oldest unfinished pixel, when it is waiting. The escape walks that pixel's
//! tree depth first, so below the reserve it holds at most its path's waiting siblings and
//! one thread's pushes, C·D + M entries. When every ray in flight is waiting, the oldest
//! pixel's deepest is the escape, and the store still has the entries it needs. So
//! `spawn_reserve` must be at least C·D + M and the store one more
//! ([`ScheduleError::SpawnReserve`], [`ScheduleError::RayStore`]); a stall would be a bug of
//! this model, reported as [`ScheduleError::Stalled`], never a hang.

use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap, VecDeque};

use sw_renderer::hit::Hit;
use thiserror::Error;

use super::accumulate::{Accumulator, Settle};
use super::constants::FrameConstants;
use super::engine::{unit_ray, ShaderLoad};
use super::shade::{FrameRay, Load, RayKind, Shaded};
use super::shader::{thread, Program, ProgramKind, Pushes, RunError};
use crate::traversal::schedule::{Schedule, TimingError, Unit, UnitTiming};
use crate::traversal::{Step, TraversalError, TraversalModel, UnitCounters, UnitRay};

/// Ray-store entries unless configured otherwise: 512 rays of about 430 bits (docs/frame.md
/// "No recursion stack") fill 6 of the XC7Z020's 140 RAMB36.
pub const DEFAULT_RAY_STORE: usize = 512;
/// Shader-core threads unless configured otherwise: the core's pipeline latency, between the
/// fp32 multiplier's and the square root's.
pub const DEFAULT_SHADER_THREADS: usize = 16;

/// The planned frame unit's sizes and latencies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameUnit {
    pub traversal: UnitTiming,
    /// Rays in flight at most (the payload RAM's entries).
    pub ray_store: usize,
    /// Entries ray generation leaves free for spawned rays (a quarter of the store unless
    /// configured otherwise).
    pub spawn_reserve: usize,
    pub shader_cores: usize,
    /// Thread contexts of a core, and the cycles from a thread's issue to its next.
    pub threads: usize,
    /// The accumulator's pixel slots (a tile).
    pub pixel_slots: usize,
    /// Pixel accepted → its ray at the traversal unit's input.
    pub raygen_latency: u64,
    /// Cycles from one pixel accepted to the next (the hardware's `raygen::INTERVAL`).
    pub raygen_interval: u64,
    /// Record → finished pixel.
    pub accumulate_latency: u64,
}

/// What a frame took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameSchedule {
    pub unit: FrameUnit,
    /// First pixel to the last finished pixel.
    pub cycles: u64,
    pub pixels: u64,
    /// Traced rays by kind (`RayKind::ALL`'s order).
    pub rays: [u64; RayKind::ALL.len()],
    /// Threads and their instructions by program kind (`ProgramKind::ALL`'s order); the
    /// instructions are the cores' busy issue slots.
    pub threads: [ShaderLoad; ProgramKind::ALL.len()],
    /// The traversal unit's busy box port and lanes; `cycles`: the cycle after its last answer.
    pub traversal: Schedule,
    /// Records the accumulator took (opens and settles).
    pub records: u64,
    /// The most rays held in the ray store at once.
    pub peak_in_flight: usize,
}

/// A frame stage whose busy share [`FrameSchedule::utilisation`] reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    RayGen,
    BoxPort,
    Lanes,
    ShaderIssue,
    Accumulator,
}

impl Stage {
    pub const ALL: [Stage; 5] = [
        Stage::RayGen,
        Stage::BoxPort,
        Stage::Lanes,
        Stage::ShaderIssue,
        Stage::Accumulator,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Stage::RayGen => "raygen",
            Stage::BoxPort => "box_port",
            Stage::Lanes => "lanes",
            Stage::ShaderIssue => "shader_issue",
            Stage::Accumulator => "accumulator",
        }
    }
}

impl FrameSchedule {
    /// The share of the frame's cycles `stage` was busy (of all its ports, lanes or cores).
    pub fn utilisation(&self, stage: Stage) -> f64 {
        let t = &self.unit.traversal;
        let (busy, width) = match stage {
            Stage::RayGen => (self.pixels * self.unit.raygen_interval, 1),
            Stage::BoxPort => (self.traversal.box_busy, t.box_ports),
            Stage::Lanes => (self.traversal.mt_busy, t.lanes),
            Stage::ShaderIssue => (self.instructions(), self.unit.shader_cores),
            Stage::Accumulator => (self.records, 1),
        };
        busy as f64 / (self.cycles.max(1) as f64 * width as f64)
    }

    /// The busiest stage: the one that bounds the frame if any does.
    pub fn busiest(&self) -> Stage {
        Stage::ALL
            .into_iter()
            .max_by(|a, b| self.utilisation(*a).total_cmp(&self.utilisation(*b)))
            .expect("stages")
    }

    pub fn instructions(&self) -> u64 {
        self.threads.iter().map(|l| l.instructions).sum()
    }

    /// Frames a second at `mhz`.
    pub fn fps(&self, mhz: f64) -> f64 {
        mhz * 1e6 / self.cycles.max(1) as f64
    }
}

/// A frame the schedule model cannot time.
#[derive(Debug, Error)]
pub enum ScheduleError {
    #[error("the traversal unit: {0}")]
    Timing(#[from] TimingError),
    #[error("{0} shader cores: the frame unit needs at least one")]
    ShaderCores(usize),
    #[error("shader cores of {0} threads: a core needs at least one")]
    Threads(usize),
    #[error("{0} pixel slots: the accumulator needs at least one")]
    PixelSlots(usize),
    #[error("ray generation every {0} cycles: it needs at least one")]
    RaygenInterval(u64),
    #[error("a spawn reserve of {reserve} entries: this scene's threads push up to {pushes} rays, {cast} of them reflection or refraction rays, {depth} deep, so it needs at least {needed} ({cast}·{depth} + {pushes})")]
    SpawnReserve {
        reserve: usize,
        pushes: usize,
        cast: usize,
        depth: u32,
        needed: usize,
    },
    #[error("a ray store of {entries} entries with a spawn reserve of {reserve}: it needs at least {needed}")]
    RayStore {
        entries: usize,
        reserve: usize,
        needed: usize,
    },
    #[error("the frame stalled at cycle {cycle} with {pixels_left} pixels unfinished: {waiting} shaded rays wait for a thread, the next needing {needed} ray-store entries, and {free} of {entries} are free (a bug of the schedule model)")]
    Stalled {
        cycle: u64,
        pixels_left: u64,
        waiting: usize,
        needed: usize,
        free: usize,
        entries: usize,
    },
    #[error("the traversal unit's model: {0}")]
    Traversal(#[from] TraversalError),
    #[error("a shader core thread: {0}")]
    Thread(#[from] RunError),
}

/// A ray in the store: the frame model's ray and, once traced, its answer.
struct Stored {
    ray: FrameRay,
    hit: Option<Hit>,
}

struct Thread {
    left: u32,
    ready_at: u64,
    pixel: u32,
    settle: Settle,
    spawned: Vec<FrameRay>,
    reserved: usize,
}

struct Core {
    threads: Vec<Thread>,
    /// The context after which round robin looks first.
    last: usize,
}

enum Record {
    Open(usize),
    /// A ray of the pixel shaded.
    Settle(u32, Settle),
}

/// A waiting cast ray's place: its pixel, its depth (deepest first), its order of answer, its
/// id.
type Waiting = (u32, Reverse<u32>, u64, usize);

/// The frame unit's state while a frame runs.
struct Run<'a> {
    c: &'a FrameConstants,
    program: &'a Program,
    model: &'a TraversalModel,
    u: FrameUnit,
    traversal: Unit<Vec<Step>>,
    store: Vec<Option<Stored>>,
    free: Vec<usize>,
    /// Of `free`, the entries running threads reserved.
    reserved: usize,
    primaries: VecDeque<(u64, usize)>,
    spawned: VecDeque<usize>,
    /// Cast rays answered, waiting for a thread: by pixel, deepest first, then in order.
    answers: BinaryHeap<Reverse<Waiting>>,
    answered: u64,
    /// Cast rays in flight by pixel slot and depth.
    cast_depths: Vec<Vec<u32>>,
    /// Pixels generated and not finished.
    unfinished: BTreeSet<u32>,
    /// Entries threads pushing cast rays leave free: the escape's (C·D + M).
    escape_reserve: usize,
    cores: Vec<Core>,
    records: VecDeque<Record>,
    acc: Accumulator,
    /// When each pixel slot is free again (`None`: its pixel is in flight).
    slot_free_at: Vec<Option<u64>>,
    next_pixel: u64,
    /// The first cycle ray generation can take the next pixel.
    raygen_free_at: u64,
    finished: u64,
    shaded: Shaded,
    counters: UnitCounters,
    out: FrameSchedule,
}

/// The cycles of a frame of `c` (its programs `program`, its rays answered by `model`) on
/// `unit`; `progress` is told the pixels finished so far as they finish.
pub fn schedule_frame(
    c: &FrameConstants,
    program: &Program,
    model: &TraversalModel,
    unit: &FrameUnit,
    progress: &dyn Fn(u64),
) -> Result<FrameSchedule, ScheduleError> {
    unit.traversal.check()?;
    if unit.shader_cores == 0 {
        return Err(ScheduleError::ShaderCores(unit.shader_cores));
    }
    if unit.threads == 0 {
        return Err(ScheduleError::Threads(unit.threads));
    }
    if unit.pixel_slots == 0 {
        return Err(ScheduleError::PixelSlots(unit.pixel_slots));
    }
    if unit.raygen_interval == 0 {
        return Err(ScheduleError::RaygenInterval(unit.raygen_interval));
    }
    let entries = std::iter::once(program.miss_entry).chain(program.material_entry.iter().copied());
    let pushes: Vec<Pushes> = entries.map(|e| program.pushes_from(e)).collect();
    let most = pushes.iter().map(|p| p.total()).max().unwrap_or(0);
    let cast = pushes.iter().map(|p| p.cast).max().unwrap_or(0);
    let needed = cast * c.max_depth as usize + most;
    if unit.spawn_reserve < needed {
        return Err(ScheduleError::SpawnReserve {
            reserve: unit.spawn_reserve,
            pushes: most,
            cast,
            depth: c.max_depth,
            needed,
        });
    }
    if unit.ray_store <= unit.spawn_reserve {
        return Err(ScheduleError::RayStore {
            entries: unit.ray_store,
            reserve: unit.spawn_reserve,
            needed: unit.spawn_reserve + 1,
        });
    }
    let mut run = Run {
        c,
        program,
        model,
        u: *unit,
        traversal: Unit::new(unit.traversal),
        store: (0..unit.ray_store).map(|_| None).collect(),
        free: (0..unit.ray_store).rev().collect(),
        reserved: 0,
        primaries: VecDeque::new(),
        spawned: VecDeque::new(),
        answers: BinaryHeap::new(),
        answered: 0,
        cast_depths: vec![vec![0; c.max_depth as usize + 1]; unit.pixel_slots],
        unfinished: BTreeSet::new(),
        escape_reserve: needed,
        cores: (0..unit.shader_cores)
            .map(|_| Core {
                threads: Vec::new(),
                last: usize::MAX,
            })
            .collect(),
        records: VecDeque::new(),
        acc: Accumulator::new(unit.pixel_slots),
        slot_free_at: vec![Some(0); unit.pixel_slots],
        next_pixel: 0,
        raygen_free_at: 0,
        finished: 0,
        shaded: Shaded::default(),
        counters: UnitCounters::default(),
        out: FrameSchedule {
            unit: *unit,
            cycles: 0,
            pixels: u64::from(c.width) * u64::from(c.height),
            rays: [0; RayKind::ALL.len()],
            threads: [ShaderLoad::default(); ProgramKind::ALL.len()],
            traversal: Schedule::default(),
            records: 0,
            peak_in_flight: 0,
        },
    };
    let mut shown = 0;
    loop {
        run.cycle()?;
        if run.finished != shown {
            shown = run.finished;
            progress(shown);
        }
        if run.finished == run.out.pixels {
            break;
        }
        let Some(next) = run.next_event() else {
            return Err(run.stalled());
        };
        run.traversal.skip_to(next);
    }
    run.out.traversal = Schedule {
        cycles: run.out.traversal.cycles,
        ..run.traversal.schedule()
    };
    Ok(run.out)
}

impl Run<'_> {
    fn available(&self) -> usize {
        self.free.len() - self.reserved
    }

    /// One cycle of every stage, then the clock moves on by one.
    fn cycle(&mut self) -> Result<(), ScheduleError> {
        let now = self.traversal.now();
        self.generate(now);
        if let Some(record) = self.records.pop_front() {
            self.accumulate(now, record);
        }
        if self.traversal.has_free_slot() {
            if let Some(id) = self.next_input(now) {
                let walk = self.trace(id)?;
                self.traversal.enter(id, walk);
            }
        }
        if let Some(id) = self.traversal.cycle() {
            self.out.traversal.cycles = now + 1;
            self.answer(id)?;
        }
        self.shade(now)?;
        Ok(())
    }

    /// The ray the traversal unit takes next: a spawned one, else a primary one arrived.
    fn next_input(&mut self, now: u64) -> Option<usize> {
        if let Some(id) = self.spawned.pop_front() {
            return Some(id);
        }
        match self.primaries.front() {
            Some(&(ready, id)) if ready <= now => {
                self.primaries.pop_front();
                Some(id)
            }
            _ => None,
        }
    }

    /// Ray generation: the next pixel's primary ray, if its slot and the store allow.
    fn generate(&mut self, now: u64) {
        if self.next_pixel == self.out.pixels
            || now < self.raygen_free_at
            || self.available() < self.u.spawn_reserve + 1
        {
            return;
        }
        let slot = (self.next_pixel % self.u.pixel_slots as u64) as usize;
        if self.slot_free_at[slot].is_none_or(|t| t > now) {
            return;
        }
        let (i, j) = (
            (self.next_pixel % u64::from(self.c.width)) as u32,
            (self.next_pixel / u64::from(self.c.width)) as u32,
        );
        let id = self.take(FrameRay::primary(self.c, i, j));
        self.unfinished.insert(self.next_pixel as u32);
        self.slot_free_at[slot] = None;
        self.records.push_back(Record::Open(slot));
        self.primaries.push_back((now + self.u.raygen_latency, id));
        self.next_pixel += 1;
        self.raygen_free_at = now + self.u.raygen_interval;
    }

    /// A free entry holding `ray` (its id).
    fn take(&mut self, ray: FrameRay) -> usize {
        let id = self.free.pop().expect("an entry was checked or reserved");
        if let Load::Cast { depth, .. } = ray.load {
            let slot = self.slot(&ray);
            self.cast_depths[slot][depth as usize] += 1;
        }
        self.store[id] = Some(Stored { ray, hit: None });
        self.out.rays[ray.kind() as usize] += 1;
        let in_flight = self.store.len() - self.free.len();
        self.out.peak_in_flight = self.out.peak_in_flight.max(in_flight);
        id
    }

    fn release(&mut self, id: usize) -> Stored {
        self.free.push(id);
        let stored = self.store[id].take().expect("a ray in flight is stored");
        if let Load::Cast { depth, .. } = stored.ray.load {
            let slot = self.slot(&stored.ray);
            self.cast_depths[slot][depth as usize] -= 1;
        }
        stored
    }

    fn accumulate(&mut self, now: u64, record: Record) {
        self.out.records += 1;
        match record {
            Record::Open(slot) => self.acc.open(slot),
            Record::Settle(pixel, settle) => {
                let slot = pixel as usize % self.u.pixel_slots;
                if self.acc.settle(slot, &settle).is_some() {
                    self.unfinished.remove(&pixel);
                    self.slot_free_at[slot] = Some(now + self.u.accumulate_latency);
                    self.finished += 1;
                    self.out.cycles = now + self.u.accumulate_latency;
                }
            }
        }
    }

    /// The walk of ray `id` through the traversal unit's model; its answer kept with it.
    fn trace(&mut self, id: usize) -> Result<Vec<Step>, ScheduleError> {
        let stored = self.store[id].as_mut().expect("a queued ray is stored");
        let ray = UnitRay::of(&unit_ray(&stored.ray), id as u32);
        let mut walk = Vec::new();
        stored.hit = self
            .model
            .walk(&ray, &mut self.counters, &mut |s| walk.push(s))?;
        Ok(walk)
    }

    /// Ray `id`'s answer leaves the traversal unit: a shadow ray settles, a cast ray waits
    /// for a thread.
    fn answer(&mut self, id: usize) -> Result<(), ScheduleError> {
        let kind = self.store[id].as_ref().expect("answered").ray.kind();
        if kind == RayKind::Shadow {
            let stored = self.release(id);
            self.shaded.clear();
            let (settle, _) = thread::shade(
                self.program,
                self.c,
                &stored.ray,
                stored.hit.as_ref(),
                &mut self.shaded,
            )?;
            (self.records).push_back(Record::Settle(stored.ray.pixel, settle));
        } else {
            let ray = &self.store[id].as_ref().expect("answered").ray;
            let key = (ray.pixel, Reverse(depth(ray)), self.answered, id);
            self.answers.push(Reverse(key));
            self.answered += 1;
        }
        Ok(())
    }

    fn slot(&self, ray: &FrameRay) -> usize {
        ray.pixel as usize % self.u.pixel_slots
    }

    /// The cast ray whose thread starts next.
    fn waiting(&self) -> Option<usize> {
        self.answers.peek().map(|Reverse((.., id))| *id)
    }

    /// The rays the thread of waiting ray `id` may push.
    fn pushes(&self, id: usize) -> Pushes {
        let s = self.store[id].as_ref().expect("waiting");
        thread::input(self.program, self.c, &s.ray, s.hit.as_ref())
            .map_or(Pushes::default(), |t| self.program.pushes_from(t.entry))
    }

    /// Whether the thread of waiting ray `id` can start now (given a free context).
    fn can_start(&self, id: usize) -> bool {
        let need = self.pushes(id);
        let after = (self.available() + 1).checked_sub(need.total());
        let Some(after) = after else {
            return false;
        };
        if after >= self.escape_reserve || need.cast == 0 {
            return true;
        }
        // The escape: the oldest pixel's deepest cast ray in flight.
        let ray = &self.store[id].as_ref().expect("waiting").ray;
        let deepest = self.cast_depths[self.slot(ray)]
            .iter()
            .rposition(|&n| n > 0);
        self.unfinished.first() == Some(&ray.pixel) && deepest == Some(depth(ray) as usize)
    }

    /// The shader cores' cycle: threads whose last result is in end, each core issues, and
    /// the next waiting ray starts a thread if a context and its entries are free.
    fn shade(&mut self, now: u64) -> Result<(), ScheduleError> {
        let threads = self.u.threads as u64;
        for k in 0..self.cores.len() {
            let mut t = 0;
            while t < self.cores[k].threads.len() {
                let th = &self.cores[k].threads[t];
                if th.left > 0 || th.ready_at > now {
                    t += 1;
                    continue;
                }
                let th = self.cores[k].threads.remove(t);
                self.end(th);
            }
            let core = &mut self.cores[k];
            let n = core.threads.len();
            if n > 0 {
                let start = core.last.wrapping_add(1) % n;
                let ready = (start..n)
                    .chain(0..start)
                    .find(|&i| core.threads[i].left > 0 && core.threads[i].ready_at <= now);
                if let Some(i) = ready {
                    let th = &mut core.threads[i];
                    th.left -= 1;
                    // The last (`End`) leaves its record in the next cycle.
                    th.ready_at = now + if th.left == 0 { 1 } else { threads };
                    core.last = i;
                }
            }
        }
        self.start(now)
    }

    /// A thread's end: its pushes join the traversal unit's input in their reserved
    /// entries, the rest of its reservation is freed, its settle record goes out.
    fn end(&mut self, th: Thread) {
        self.reserved -= th.reserved;
        for ray in th.spawned {
            let id = self.take(ray);
            self.spawned.push_back(id);
        }
        self.records.push_back(Record::Settle(th.pixel, th.settle));
    }

    /// The next waiting ray's thread starts, if a core has a free context and the store
    /// the entries its pushes may need (its own entry, read now, counting).
    fn start(&mut self, now: u64) -> Result<(), ScheduleError> {
        let Some(id) = self.waiting() else {
            return Ok(());
        };
        let Some(core) = (0..self.cores.len())
            .filter(|&k| self.cores[k].threads.len() < self.u.threads)
            .min_by_key(|&k| self.cores[k].threads.len())
        else {
            return Ok(());
        };
        if !self.can_start(id) {
            return Ok(());
        }
        let reserve = self.pushes(id).total();
        self.answers.pop();
        let stored = self.release(id);
        self.shaded.clear();
        let (settle, issued) = thread::shade(
            self.program,
            self.c,
            &stored.ray,
            stored.hit.as_ref(),
            &mut self.shaded,
        )?;
        let issued = issued.expect("a cast ray runs a thread");
        self.out.threads[issued.kind.index()] += ShaderLoad {
            threads: 1,
            instructions: u64::from(issued.instructions),
        };
        self.reserved += reserve;
        self.cores[core].threads.push(Thread {
            left: issued.instructions,
            ready_at: now + 1,
            pixel: stored.ray.pixel,
            settle,
            spawned: self.shaded.spawned.clone(),
            reserved: reserve,
        });
        Ok(())
    }

    /// The first cycle from the next at which a stage can act (`None`: none ever can).
    fn next_event(&self) -> Option<u64> {
        let now = self.traversal.now();
        let soon = !self.records.is_empty()
            || (self.traversal.has_free_slot() && !self.spawned.is_empty())
            || self.waiting().is_some_and(|id| {
                self.cores.iter().any(|c| c.threads.len() < self.u.threads) && self.can_start(id)
            });
        if soon {
            return Some(now);
        }
        let primary = match self.primaries.front() {
            Some(&(ready, _)) if self.traversal.has_free_slot() => Some(ready.max(now)),
            _ => None,
        };
        let pixel = (self.next_pixel < self.out.pixels && self.available() > self.u.spawn_reserve)
            .then(|| self.slot_free_at[(self.next_pixel % self.u.pixel_slots as u64) as usize])
            .flatten()
            .map(|t| t.max(now).max(self.raygen_free_at));
        let threads = (self.cores.iter().flat_map(|c| &c.threads)).map(|t| t.ready_at.max(now));
        [primary, pixel, self.traversal.next_ready()]
            .into_iter()
            .flatten()
            .chain(threads)
            .min()
    }

    fn stalled(&self) -> ScheduleError {
        ScheduleError::Stalled {
            cycle: self.traversal.now(),
            pixels_left: self.out.pixels - self.finished,
            waiting: self.answers.len(),
            needed: self.waiting().map_or(0, |id| self.pushes(id).total()),
            free: self.available(),
            entries: self.u.ray_store,
        }
    }
}

/// A cast ray's depth (0 for a primary ray, and for a shadow ray, which never waits).
fn depth(ray: &FrameRay) -> u32 {
    match ray.load {
        Load::Cast { depth, .. } => depth,
        Load::Shadow { .. } => 0,
    }
}
