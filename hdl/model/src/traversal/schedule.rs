//! The traversal unit's schedule model: how many cycles a wavefront of rays takes on the
//! planned microarchitecture, given each ray's walk ([`Step`]s from the bit-accurate model).
//!
//! The unit holds `slots` rays at once. Shared resources take one request a cycle each: the
//! ray setup (one ray enters the lowest free slot), the box port (node read + box-test
//! pipeline, both children per test), the stack's read port (a pop and its far-end check),
//! each of the `lanes` Möller-Trumbore lanes (slot `s` uses lane `s mod lanes`, issuing one
//! triangle of its leaf a cycle) and the hit output. A slot waits for the answer of each
//! step before its next one (a leaf: until its last test's answer is folded in). Each
//! resource grants round robin among the slots ready for it, from the slot after its last
//! grant (`hdl::traversal::arbiter::RoundRobin`). Rays are independent, so a wavefront's time
//! is this schedule from the first ray in to the last hit out; the renderer's next
//! wavefront starts after it (the unit drains in between). [`Unit`] is the same unit stepped
//! a cycle at a time, fed rays as they come (the frame schedule, `crate::frame::schedule`);
//! [`schedule`] feeds it a wavefront.

use super::Step;

/// Widths and latencies of the unit (cycles from issue to the slot's next step).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitTiming {
    pub slots: usize,
    pub lanes: usize,
    /// Box ports: slot `s` uses port `s mod box_ports` (each its own node read and box test).
    pub box_ports: usize,
    /// Ray in → first box test possible (reciprocals, padding, the far end).
    pub setup_latency: u64,
    /// Node read + box-test pipeline + the slot's update.
    pub box_latency: u64,
    /// Last triangle read issued → its answer folded into the slot's hit (read + MT lane +
    /// reduction and the far end's update).
    pub mt_latency: u64,
    /// Of `mt_latency`, the part only a leaf that made the hit nearer takes (the far end's
    /// recomputation); any other leaf's slot is ready `far_latency` cycles sooner.
    pub far_latency: u64,
    /// Stack read + far-end check.
    pub pop_latency: u64,
}

/// A unit the schedule model cannot time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TimingError {
    #[error("a unit of {0} ray slots: it needs at least one")]
    NoSlots(usize),
    #[error("{lanes} Möller-Trumbore lanes for {slots} ray slots: each lane serves its own slots, so 1 to {slots}")]
    Lanes { lanes: usize, slots: usize },
    #[error(
        "{ports} box ports for {slots} ray slots: each port serves its own slots, so 1 to {slots}"
    )]
    BoxPorts { ports: usize, slots: usize },
    #[error("a {what} step that takes no cycle: every step keeps its slot busy for at least one")]
    Latency { what: &'static str },
}

impl UnitTiming {
    /// Whether the schedule model can time this unit: a slot, 1 lane (box port) to one per
    /// slot, and every step taking at least a cycle.
    pub fn check(&self) -> Result<(), TimingError> {
        if self.slots == 0 {
            return Err(TimingError::NoSlots(self.slots));
        }
        if !(1..=self.slots).contains(&self.lanes) {
            return Err(TimingError::Lanes {
                lanes: self.lanes,
                slots: self.slots,
            });
        }
        if !(1..=self.slots).contains(&self.box_ports) {
            return Err(TimingError::BoxPorts {
                ports: self.box_ports,
                slots: self.slots,
            });
        }
        for (what, cycles) in [
            ("box test", self.box_latency),
            ("pop", self.pop_latency),
            ("leaf", self.mt_latency.saturating_sub(self.far_latency)),
        ] {
            if cycles == 0 {
                return Err(TimingError::Latency { what });
            }
        }
        Ok(())
    }
}

/// What a schedule took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Schedule {
    pub cycles: u64,
    /// Cycles the box port issued a test.
    pub box_busy: u64,
    /// Lane-cycles that issued a triangle (tested or skipped).
    pub mt_busy: u64,
}

impl std::ops::AddAssign for Schedule {
    fn add_assign(&mut self, o: Schedule) {
        self.cycles += o.cycles;
        self.box_busy += o.box_busy;
        self.mt_busy += o.mt_busy;
    }
}

/// What a slot waits to be granted.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Want {
    Free,
    Box,
    Pop,
    /// Triangles of its leaf not issued yet; whether the leaf makes the hit nearer.
    Leaf(u32, bool),
    /// Its answer to the hit output.
    Out,
}

#[derive(Clone, Copy)]
struct Slot {
    /// The caller's id of the ray, and the index of its next step.
    ray: usize,
    step: usize,
    want: Want,
    ready_at: u64,
}

impl Slot {
    /// Moves to the next step that needs a resource (an empty leaf needs none).
    fn advance(&mut self, walk: &[Step]) {
        while matches!(walk.get(self.step), Some(Step::Leaf { triangles: 0, .. })) {
            self.step += 1;
        }
        self.want = match walk.get(self.step) {
            None => Want::Out,
            Some(Step::Box) => Want::Box,
            Some(Step::Pop) => Want::Pop,
            Some(&Step::Leaf { triangles, nearer }) => Want::Leaf(triangles, nearer),
        };
    }
}

/// The unit stepped a cycle at a time: rays enter when a slot is free ([`Unit::enter`]),
/// [`Unit::cycle`] grants the cycle's resources and lets at most one answer out. `W` holds a
/// ray's walk while it is in the unit (`&[Step]` or `Vec<Step>`).
pub struct Unit<W> {
    t: UnitTiming,
    slots: Vec<Slot>,
    /// The walk of each slot's ray.
    walks: Vec<Option<W>>,
    /// The last grant of each arbiter: stack port, hit output, one per lane, one per box port.
    last: Vec<usize>,
    /// Per slot, its lane's and its box port's arbiter.
    serves: Vec<(usize, usize)>,
    /// The current cycle's grant of each arbiter so far: (distance after its last grant, slot).
    grant: Vec<(usize, usize)>,
    free_slots: usize,
    cycle: u64,
    busy: Schedule,
}

/// The arbiters' order in `Unit::last`: stack port, hit output, lanes, then box ports.
/// No grant: the distance no slot has.
const NO_GRANT: (usize, usize) = (usize::MAX, 0);
const POP: usize = 0;
const OUT: usize = 1;
const LANES: usize = 2;

impl<W: AsRef<[Step]>> Unit<W> {
    /// An empty unit at cycle 0, for a timing that passes [`UnitTiming::check`] (its callers
    /// check it where the timing enters).
    pub fn new(t: UnitTiming) -> Unit<W> {
        debug_assert!(t.check().is_ok(), "{t:?}: {:?}", t.check());
        let free = Slot {
            ray: 0,
            step: 0,
            want: Want::Free,
            ready_at: 0,
        };
        Unit {
            t,
            slots: vec![free; t.slots],
            walks: (0..t.slots).map(|_| None).collect(),
            last: vec![usize::MAX; LANES + t.lanes + t.box_ports],
            serves: (0..t.slots)
                .map(|k| (LANES + k % t.lanes, LANES + t.lanes + k % t.box_ports))
                .collect(),
            grant: vec![NO_GRANT; LANES + t.lanes + t.box_ports],
            free_slots: t.slots,
            cycle: 0,
            busy: Schedule::default(),
        }
    }

    /// The current cycle.
    pub fn now(&self) -> u64 {
        self.cycle
    }

    /// What the unit has done so far; `cycles` is the current cycle.
    pub fn schedule(&self) -> Schedule {
        Schedule {
            cycles: self.cycle,
            ..self.busy
        }
    }

    pub fn has_free_slot(&self) -> bool {
        self.free_slots > 0
    }

    /// Ray `id` walking `walk` enters the lowest free slot in the current cycle (one ray a
    /// cycle: call it at most once between [`Unit::cycle`]s); `false` if no slot is free.
    pub fn enter(&mut self, id: usize, walk: W) -> bool {
        let Some(k) = self.slots.iter().position(|s| s.want == Want::Free) else {
            return false;
        };
        let s = &mut self.slots[k];
        *s = Slot {
            ray: id,
            step: 0,
            want: Want::Free,
            ready_at: self.cycle + self.t.setup_latency,
        };
        s.advance(walk.as_ref());
        self.walks[k] = Some(walk);
        self.free_slots -= 1;
        true
    }

    /// The current cycle's grants (box ports, stack port, lanes) and hit output: the id of
    /// the ray whose answer leaves, if one does (its slot is free from the next cycle). Then
    /// the next cycle.
    pub fn cycle(&mut self) -> Option<usize> {
        let (t, cycle, n) = (self.t, self.cycle, self.slots.len());
        // Every arbiter's grant in one pass over the slots: the first ready slot it serves
        // after its last grant, cyclically. The grants of a cycle are independent: a slot
        // wants one resource, and a grant keeps it busy for at least a cycle
        // (`UnitTiming::check`).
        self.grant.fill(NO_GRANT);
        for (k, s) in self.slots.iter().enumerate() {
            if s.want == Want::Free || s.ready_at > cycle {
                continue;
            }
            let a = match s.want {
                Want::Pop => POP,
                Want::Out => OUT,
                Want::Leaf(..) => self.serves[k].0,
                Want::Box => self.serves[k].1,
                Want::Free => unreachable!("skipped"),
            };
            let start = self.last[a].wrapping_add(1) % n;
            let distance = if k >= start { k - start } else { k + n - start };
            if distance < self.grant[a].0 {
                self.grant[a] = (distance, k);
            }
        }
        let mut out = None;
        for (a, &(distance, k)) in self.grant.iter().enumerate() {
            if distance == NO_GRANT.0 {
                continue;
            }
            self.last[a] = k;
            let s = &mut self.slots[k];
            match s.want {
                Want::Box => {
                    s.ready_at = cycle + t.box_latency;
                    s.step += 1;
                    s.advance(walk_of(&self.walks, k));
                    self.busy.box_busy += 1;
                }
                Want::Pop => {
                    s.ready_at = cycle + t.pop_latency;
                    s.step += 1;
                    s.advance(walk_of(&self.walks, k));
                }
                Want::Leaf(left, nearer) => {
                    self.busy.mt_busy += 1;
                    // One triangle a cycle per slot: it is next ready in the next cycle, or
                    // when its leaf's last answer is in (and a nearer hit's far end).
                    if left == 1 {
                        s.ready_at = cycle + t.mt_latency - if nearer { 0 } else { t.far_latency };
                        s.step += 1;
                        s.advance(walk_of(&self.walks, k));
                    } else {
                        s.want = Want::Leaf(left - 1, nearer);
                        s.ready_at = cycle + 1;
                    }
                }
                // One hit leaves the unit, freeing its slot.
                Want::Out => {
                    s.want = Want::Free;
                    self.walks[k] = None;
                    self.free_slots += 1;
                    out = Some(s.ray);
                }
                Want::Free => unreachable!("granted a free slot"),
            }
        }
        self.cycle += 1;
        out
    }

    /// The first cycle from now at which a ray in the unit can be granted anything (`None`
    /// if the unit is empty): the cycles before it would do nothing.
    pub fn next_ready(&self) -> Option<u64> {
        (self.slots.iter())
            .filter(|s| s.want != Want::Free)
            .map(|s| s.ready_at.max(self.cycle))
            .min()
    }

    /// Moves to `cycle` (not backwards), skipping cycles in which nothing enters; they would
    /// grant nothing before [`Unit::next_ready`].
    pub fn skip_to(&mut self, cycle: u64) {
        self.cycle = self.cycle.max(cycle);
    }
}

fn walk_of<W: AsRef<[Step]>>(walks: &[Option<W>], k: usize) -> &[Step] {
    walks[k]
        .as_ref()
        .expect("an occupied slot holds its walk")
        .as_ref()
}

/// The cycles of one wavefront whose rays walk `walks` (in the order they enter), for a
/// unit that passes [`UnitTiming::check`] (its callers check it where the timing enters).
pub fn schedule(t: &UnitTiming, walks: &[Vec<Step>]) -> Schedule {
    let mut unit = Unit::new(*t);
    let mut next_ray = 0;
    let mut done = 0;
    while done < walks.len() {
        if next_ray < walks.len() && unit.enter(next_ray, walks[next_ray].as_slice()) {
            next_ray += 1;
        }
        if unit.cycle().is_some() {
            done += 1;
        }
        // Nothing can happen before the next slot is ready: skip the idle cycles.
        if !(next_ray < walks.len() && unit.has_free_slot()) {
            if let Some(next) = unit.next_ready() {
                unit.skip_to(next);
            }
        }
    }
    unit.schedule()
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: UnitTiming = UnitTiming {
        slots: 1,
        lanes: 1,
        box_ports: 1,
        setup_latency: 5,
        box_latency: 10,
        mt_latency: 20,
        far_latency: 4,
        pop_latency: 2,
    };

    #[test]
    fn one_slot_runs_a_walk_step_after_step() {
        // setup 5, box 10, leaf of 3 with a nearer hit: issues at 15, 16, 17, answer and
        // far end at 37, out at 37.
        let walk = vec![
            Step::Box,
            Step::Leaf {
                triangles: 3,
                nearer: true,
            },
        ];
        let s = schedule(&T, &[walk]);
        assert_eq!((s.cycles, s.box_busy, s.mt_busy), (38, 1, 3));
    }

    #[test]
    fn a_leaf_that_leaves_the_hit_as_it_was_skips_the_far_end() {
        let walk = |nearer| {
            vec![
                Step::Box,
                Step::Leaf {
                    triangles: 3,
                    nearer,
                },
                Step::Pop,
            ]
        };
        let nearer = schedule(&T, &[walk(true)]).cycles;
        let same = schedule(&T, &[walk(false)]).cycles;
        assert_eq!(nearer - same, T.far_latency);
    }

    #[test]
    fn slots_overlap_rays_until_the_box_port_is_the_limit() {
        let walk = vec![Step::Box; 4];
        let walks = vec![walk; 64];
        let one = schedule(&T, &walks);
        let many = schedule(&UnitTiming { slots: 16, ..T }, &walks);
        assert_eq!(one.box_busy, 256);
        assert!(one.cycles > 64 * 40, "{one:?}");
        // 16 slots keep the box port busy: about one box test a cycle.
        assert!(many.cycles < 256 + 64, "{many:?}");
    }

    #[test]
    fn a_unit_without_slots_or_with_more_lanes_than_slots_is_refused() {
        assert_eq!(T.check(), Ok(()));
        assert_eq!(
            UnitTiming { slots: 0, ..T }.check(),
            Err(TimingError::NoSlots(0))
        );
        assert_eq!(
            UnitTiming { lanes: 0, ..T }.check(),
            Err(TimingError::Lanes { lanes: 0, slots: 1 })
        );
        let e = UnitTiming {
            lanes: 3,
            slots: 2,
            ..T
        }
        .check()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "3 Möller-Trumbore lanes for 2 ray slots: each lane serves its own slots, so 1 to 2"
        );
    }

    #[test]
    fn lanes_share_the_leaf_tests_of_different_slots() {
        let leaf = Step::Leaf {
            triangles: 8,
            nearer: false,
        };
        let walks = vec![vec![leaf]; 32];
        let one_lane = schedule(&UnitTiming { slots: 32, ..T }, &walks);
        let two_lanes = schedule(
            &UnitTiming {
                slots: 32,
                lanes: 2,
                ..T
            },
            &walks,
        );
        assert_eq!(one_lane.mt_busy, 256);
        assert!(one_lane.cycles >= 256 && two_lanes.cycles < one_lane.cycles * 6 / 10);
    }

    #[test]
    fn empty_leaves_and_pops_take_no_box_or_lane() {
        let empty = Step::Leaf {
            triangles: 0,
            nearer: false,
        };
        let walks = vec![vec![Step::Box, empty, Step::Pop]];
        let s = schedule(&T, &walks);
        assert_eq!((s.cycles, s.box_busy, s.mt_busy), (5 + 10 + 2 + 1, 1, 0));
    }

    /// The first slot after `last` (cyclically) that is ready at `cycle` and `eligible(index,
    /// want)`; it becomes `last`.
    fn round_robin(
        slots: &[Slot],
        last: &mut usize,
        cycle: u64,
        eligible: impl Fn(usize, Want) -> bool,
    ) -> Option<usize> {
        let n = slots.len();
        let start = last.wrapping_add(1) % n;
        let k = (start..n).chain(0..start).find(|&k| {
            let s = &slots[k];
            s.want != Want::Free && s.ready_at <= cycle && eligible(k, s.want)
        })?;
        *last = k;
        Some(k)
    }

    /// `schedule` as it was before the unit was stepped incrementally ([`Unit`]): the oracle
    /// the wrapper must equal.
    fn wavefront_reference(t: &UnitTiming, walks: &[Vec<Step>]) -> Schedule {
        debug_assert!(t.check().is_ok(), "{t:?}: {:?}", t.check());
        let free = Slot {
            ray: 0,
            step: 0,
            want: Want::Free,
            ready_at: 0,
        };
        let mut slots = vec![free; t.slots];
        let mut next_ray = 0;
        let mut done = 0;
        let mut out = Schedule::default();
        let mut cycle = 0u64;
        // The last grant of each arbiter: stack port, hit output, one per lane, one per box port.
        let mut last = vec![usize::MAX; 2 + t.lanes + t.box_ports];
        let box_arbiter = 2 + t.lanes;
        while done < walks.len() {
            // One ray enters the lowest free slot.
            if next_ray < walks.len() {
                if let Some(s) = slots.iter_mut().find(|s| s.want == Want::Free) {
                    *s = Slot {
                        ray: next_ray,
                        step: 0,
                        want: Want::Free,
                        ready_at: cycle + t.setup_latency,
                    };
                    s.advance(&walks[next_ray]);
                    next_ray += 1;
                }
            }
            for port in 0..t.box_ports {
                let Some(k) = round_robin(&slots, &mut last[box_arbiter + port], cycle, |k, w| {
                    k % t.box_ports == port && w == Want::Box
                }) else {
                    continue;
                };
                let s = &mut slots[k];
                s.ready_at = cycle + t.box_latency;
                s.step += 1;
                s.advance(&walks[s.ray]);
                out.box_busy += 1;
            }
            if let Some(k) = round_robin(&slots, &mut last[0], cycle, |_, w| w == Want::Pop) {
                let s = &mut slots[k];
                s.ready_at = cycle + t.pop_latency;
                s.step += 1;
                s.advance(&walks[s.ray]);
            }
            for lane in 0..t.lanes {
                let Some(k) = round_robin(&slots, &mut last[2 + lane], cycle, |k, w| {
                    k % t.lanes == lane && matches!(w, Want::Leaf(..))
                }) else {
                    continue;
                };
                let s = &mut slots[k];
                let Want::Leaf(left, nearer) = s.want else {
                    unreachable!("granted for a leaf")
                };
                out.mt_busy += 1;
                // One triangle a cycle per slot: it is next ready in the next cycle, or when
                // its leaf's last answer is in (and a nearer hit's far end).
                if left == 1 {
                    s.ready_at = cycle + t.mt_latency - if nearer { 0 } else { t.far_latency };
                    s.step += 1;
                    s.advance(&walks[s.ray]);
                } else {
                    s.want = Want::Leaf(left - 1, nearer);
                    s.ready_at = cycle + 1;
                }
            }
            // One hit leaves the unit, freeing its slot.
            if let Some(k) = round_robin(&slots, &mut last[1], cycle, |_, w| w == Want::Out) {
                slots[k].want = Want::Free;
                done += 1;
            }
            cycle += 1;
            // Nothing can happen before the next slot is ready: skip the idle cycles.
            let entering = next_ray < walks.len() && slots.iter().any(|s| s.want == Want::Free);
            if !entering {
                let next = slots
                    .iter()
                    .filter(|s| s.want != Want::Free)
                    .map(|s| s.ready_at)
                    .min();
                if let Some(next) = next {
                    cycle = cycle.max(next);
                }
            }
        }
        out.cycles = cycle;
        out
    }

    #[test]
    fn the_stepped_unit_times_random_wavefronts_as_the_wavefront_loop_did() {
        use rand::{rngs::StdRng, Rng, SeedableRng};
        let mut rng = StdRng::seed_from_u64(40);
        for case in 0..300 {
            let slots = rng.gen_range(1..=40);
            let t = UnitTiming {
                slots,
                lanes: rng.gen_range(1..=slots.min(3)),
                box_ports: rng.gen_range(1..=slots.min(2)),
                setup_latency: rng.gen_range(0..30),
                box_latency: rng.gen_range(1..30),
                mt_latency: rng.gen_range(10..40),
                far_latency: rng.gen_range(0..10),
                pop_latency: rng.gen_range(1..6),
            };
            let walks: Vec<Vec<Step>> = (0..rng.gen_range(0..200))
                .map(|_| {
                    (0..rng.gen_range(0..30))
                        .map(|_| match rng.gen_range(0..3) {
                            0 => Step::Box,
                            1 => Step::Pop,
                            _ => Step::Leaf {
                                triangles: rng.gen_range(0..5),
                                nearer: rng.gen(),
                            },
                        })
                        .collect()
                })
                .collect();
            assert_eq!(
                schedule(&t, &walks),
                wavefront_reference(&t, &walks),
                "case {case}: {t:?}"
            );
        }
    }
}
