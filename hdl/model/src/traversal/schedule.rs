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
//! wavefront starts after it (the unit drains in between).

use super::Step;

/// Widths and latencies of the unit (cycles from issue to the slot's next step).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitTiming {
    pub slots: usize,
    pub lanes: usize,
    /// Ray in → first box test possible (reciprocals, padding, the far end).
    pub setup_latency: u64,
    /// Node read + box-test pipeline + the slot's update.
    pub box_latency: u64,
    /// Last triangle read issued → its answer folded into the slot's hit (read + MT lane +
    /// reduction and the far end's update).
    pub mt_latency: u64,
    /// Stack read + far-end check.
    pub pop_latency: u64,
}

/// What a schedule took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Schedule {
    pub cycles: u64,
    /// Cycles the box port issued a test.
    pub box_busy: u64,
    /// Lane-cycles that issued a test.
    pub mt_busy: u64,
}

impl std::ops::AddAssign for Schedule {
    fn add_assign(&mut self, o: Schedule) {
        self.cycles += o.cycles;
        self.box_busy += o.box_busy;
        self.mt_busy += o.mt_busy;
    }
}

#[derive(Clone, Copy)]
struct Slot {
    /// Index of the ray, and of its next step.
    ray: usize,
    step: usize,
    /// Triangles of the current leaf not issued yet.
    left: u32,
    ready_at: u64,
}

/// The cycles of one wavefront whose rays walk `walks` (in the order they enter).
pub fn schedule(t: &UnitTiming, walks: &[Vec<Step>]) -> Schedule {
    assert!(t.slots > 0 && t.lanes > 0, "a unit needs slots and lanes");
    let mut slots: Vec<Option<Slot>> = vec![None; t.slots];
    let mut next_ray = 0;
    let mut done = 0;
    let mut out = Schedule::default();
    let mut cycle = 0u64;
    // The last grant of each arbiter: box port, stack port, hit output, then one per lane.
    let mut last = vec![usize::MAX; 3 + t.lanes];
    while done < walks.len() {
        // One ray enters a free slot.
        if next_ray < walks.len() {
            if let Some(free) = slots.iter_mut().find(|s| s.is_none()) {
                *free = Some(Slot {
                    ray: next_ray,
                    step: 0,
                    left: 0,
                    ready_at: cycle + t.setup_latency,
                });
                next_ray += 1;
            }
        }
        // Steps needing no shared resource: an empty leaf.
        for s in slots.iter_mut().flatten() {
            while s.ready_at <= cycle && walks[s.ray].get(s.step) == Some(&Step::Leaf(0)) {
                s.step += 1;
            }
        }
        let wants = |s: &Slot, f: &dyn Fn(Step) -> bool| {
            s.ready_at <= cycle && walks[s.ray].get(s.step).is_some_and(|&st| f(st))
        };
        if let Some(s) = granted(&mut slots, &mut last[0], |_, s| {
            wants(s, &|st| st == Step::Box)
        }) {
            s.ready_at = cycle + t.box_latency;
            s.step += 1;
            out.box_busy += 1;
        }
        if let Some(s) = granted(&mut slots, &mut last[1], |_, s| {
            wants(s, &|st| st == Step::Pop)
        }) {
            s.ready_at = cycle + t.pop_latency;
            s.step += 1;
        }
        for lane in 0..t.lanes {
            let Some(s) = granted(&mut slots, &mut last[3 + lane], |k, s| {
                k % t.lanes == lane && wants(s, &|st| matches!(st, Step::Leaf(_)))
            }) else {
                continue;
            };
            if s.left == 0 {
                let Some(&Step::Leaf(n)) = walks[s.ray].get(s.step) else {
                    unreachable!("selected for a leaf")
                };
                s.left = n;
            }
            s.left -= 1;
            out.mt_busy += 1;
            // One triangle a cycle per slot: it is next ready in the next cycle, or when
            // its leaf's last answer is in.
            if s.left == 0 {
                s.ready_at = cycle + t.mt_latency;
                s.step += 1;
            } else {
                s.ready_at = cycle + 1;
            }
        }
        // One hit leaves the unit, freeing its slot.
        if let Some(k) = round_robin(&slots, &mut last[2], |_, s| {
            s.ready_at <= cycle && s.step == walks[s.ray].len()
        }) {
            slots[k] = None;
            done += 1;
        }
        cycle += 1;
    }
    out.cycles = cycle;
    out
}

/// The index of the first `eligible(index, slot)` slot after `last` cyclically, which
/// becomes `last`.
fn round_robin(
    slots: &[Option<Slot>],
    last: &mut usize,
    eligible: impl Fn(usize, &Slot) -> bool,
) -> Option<usize> {
    let n = slots.len();
    let start = last.wrapping_add(1) % n;
    let k = (0..n)
        .map(|i| (start + i) % n)
        .find(|&k| slots[k].as_ref().is_some_and(|s| eligible(k, s)))?;
    *last = k;
    Some(k)
}

/// The slot [`round_robin`] grants.
fn granted<'a>(
    slots: &'a mut [Option<Slot>],
    last: &mut usize,
    eligible: impl Fn(usize, &Slot) -> bool,
) -> Option<&'a mut Slot> {
    let k = round_robin(slots, last, eligible)?;
    slots[k].as_mut()
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: UnitTiming = UnitTiming {
        slots: 1,
        lanes: 1,
        setup_latency: 5,
        box_latency: 10,
        mt_latency: 20,
        pop_latency: 2,
    };

    #[test]
    fn one_slot_runs_a_walk_step_after_step() {
        // setup 5, box 10, leaf of 3: issues at 15, 16, 17, answer at 37, out at 37.
        let walk = vec![Step::Box, Step::Leaf(3)];
        let s = schedule(&T, &[walk]);
        assert_eq!((s.cycles, s.box_busy, s.mt_busy), (38, 1, 3));
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
    fn lanes_share_the_leaf_tests_of_different_slots() {
        let walks = vec![vec![Step::Leaf(8)]; 32];
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
        let walks = vec![vec![Step::Box, Step::Leaf(0), Step::Pop]];
        let s = schedule(&T, &walks);
        assert_eq!((s.cycles, s.box_busy, s.mt_busy), (5 + 10 + 2 + 1, 1, 0));
    }
}
