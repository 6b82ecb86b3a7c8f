//! The traversal unit's box test in fp32: both children of a BVH node tested against one ray
//! per cycle (II = 1), bit for bit `hw_model::traversal::box_test::box_test`.
//!
//! The dataflow, with the cycle each value is ready (the operators' latencies at `depth`,
//! see [`BoxSchedule`]):
//! ```text
//! t_diff    = sub               min − orig_lo, max − orig_hi        (per axis and child)
//! t_slab    = t_diff + mul      t0, t1 = the differences · inv_dir
//! t_ordered = t_slab + lt       lo, hi = t0, t1 ordered by lt(t0, t1) (a mux)
//! t_fold    = t_ordered + 3·lt  near = larger of 0, lo_x, lo_y, lo_z; far = smaller of
//!                               t_hi, hi_x, hi_y, hi_z, one lt and one mux per axis
//! latency   = t_fold + lt       enters = !lt(far, near) & !isnan(far); first = lt(near1, near0)
//! ```
//! The folds are sequential (x, then y, then z) as the model's are: a tree would give the
//! same larger value but could keep the other zero of a ±0 tie, and bit for bit is the spec.
//! Every other path (inv_dir, t_hi, the fold operands, valid and the tag) is padded to it with
//! flip-flop delay lines; they are short (a few cycles), so no block RAM rings as in the lane.
//!
//! Latency at depth 0..=5: 0, 7, 9, 11, 12, 13 (5 = [`max_depth`]). yosys xc7 (Yosys 0.23,
//! `cargo test --release -p hdl --test integration -- --ignored --nocapture box_test::box_test_resources`):
//! depth 1: 12791 LUT, 2751 FF, 24 DSP48E1, logic depth 26; depth 5: 10072 LUT, 5763 FF,
//! 24 DSP48E1, logic depth 10.
//!
//! rust-hdl emits only the first index of `a[i].b[j]` correctly, so every array here is flat:
//! per (axis, child) things are indexed `2·axis + child` (the order of `ChildBoxes`' fields),
//! and a fold step k of child c is `2·k + c` (step k reads axis k).

use hw_model::traversal::box_test::{BoxResult, ChildBoxes, RaySetup};
use rust_hdl::prelude::*;

use crate::formats::fp32::{self, Lt, Mul, Sub};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;
use crate::operator::Op;

/// Width of the tag that travels with a test (a ray or stack slot id of the caller's).
pub const TAG_BITS: usize = 16;
pub type Tag = Bits<TAG_BITS>;
type Word = Bits<32>;

/// When each value of the box test is ready, from the operators' latencies at a depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoxSchedule {
    /// Registers per fp32 `Sub`, `Mul`, `Lt`: `min(depth, max_stages)`.
    pub sub: usize,
    pub mul: usize,
    pub lt: usize,
    /// t0, t1.
    pub t_slab: usize,
    /// lo, hi (the ordered pair).
    pub t_ordered: usize,
    /// near, far after the three axes.
    pub t_fold: usize,
    /// Inputs to outputs.
    pub latency: usize,
}

impl BoxSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let (sub, mul, lt) = (ops.sub, ops.mul, ops.lt);
        let t_slab = sub + mul;
        let t_ordered = t_slab + lt;
        let t_fold = t_ordered + 3 * lt;
        BoxSchedule {
            sub,
            mul,
            lt,
            t_slab,
            t_ordered,
            t_fold,
            latency: t_fold + lt,
        }
    }

    /// inv_dir (an input) to the multipliers: it skips the subtraction.
    pub fn inv_to_slab(&self) -> usize {
        self.sub
    }

    /// t_hi (an input) to the first far step.
    pub fn t_hi_to_fold(&self) -> usize {
        self.t_ordered
    }

    /// lo, hi of axis `k` to fold step `k` (the steps before it).
    pub fn axis_to_step(&self, k: usize) -> usize {
        k * self.lt
    }
}

/// The block's timing at `depth`.
pub fn schedule(depth: usize) -> BoxSchedule {
    BoxSchedule::new(depth)
}

/// Cycles from a test at the inputs to its result at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    schedule(depth).latency
}

/// The depth at which every operator of the block has all its pipeline registers.
pub fn max_depth() -> usize {
    [Op::Sub, Op::Mul, Op::Lt]
        .into_iter()
        .map(fp32::max_stages)
        .max()
        .unwrap_or(0)
}

/// One axis of one child: `t0 = (min − orig_lo)·inv`, `t1 = (max − orig_hi)·inv`, and the
/// ordered pair `lo, hi` (`lt(t0, t1)` decides) `t_ordered` cycles after `orig_*`, `min`,
/// `max`. `inv` arrives `sub` cycles later than those, at the multipliers.
#[derive(LogicBlock)]
pub struct Slab {
    pub clock: Signal<In, Clock>,
    pub orig_lo: Signal<In, Word>,
    pub orig_hi: Signal<In, Word>,
    pub inv: Signal<In, Word>,
    pub min: Signal<In, Word>,
    pub max: Signal<In, Word>,
    pub lo: Signal<Out, Word>,
    pub hi: Signal<Out, Word>,
    to_min: Sub,
    to_max: Sub,
    t0: Mul,
    t1: Mul,
    ordered: Lt,
    /// t0, t1 waiting for their comparison, to be selected.
    t0_at_select: Delay<Word>,
    t1_at_select: Delay<Word>,
}

impl Slab {
    pub fn new(s: &BoxSchedule) -> Self {
        Self {
            clock: Default::default(),
            orig_lo: Default::default(),
            orig_hi: Default::default(),
            inv: Default::default(),
            min: Default::default(),
            max: Default::default(),
            lo: Default::default(),
            hi: Default::default(),
            to_min: Sub::new(s.sub),
            to_max: Sub::new(s.sub),
            t0: Mul::new(s.mul),
            t1: Mul::new(s.mul),
            ordered: Lt::new(s.lt),
            t0_at_select: Delay::new(s.lt),
            t1_at_select: Delay::new(s.lt),
        }
    }
}

impl Logic for Slab {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(
            self,
            clock,
            to_min,
            to_max,
            t0,
            t1,
            ordered,
            t0_at_select,
            t1_at_select
        );
        self.to_min.a.next = self.min.val();
        self.to_min.b.next = self.orig_lo.val();
        self.to_max.a.next = self.max.val();
        self.to_max.b.next = self.orig_hi.val();
        self.t0.a.next = self.to_min.y.val();
        self.t0.b.next = self.inv.val();
        self.t1.a.next = self.to_max.y.val();
        self.t1.b.next = self.inv.val();
        self.ordered.a.next = self.t0.y.val();
        self.ordered.b.next = self.t1.y.val();
        self.t0_at_select.d.next = self.t0.y.val();
        self.t1_at_select.d.next = self.t1.y.val();
        // Not lt(t0, t1) (also when either is NaN) swaps them, as the model does.
        if self.ordered.y.val() {
            self.lo.next = self.t0_at_select.q.val();
            self.hi.next = self.t1_at_select.q.val();
        } else {
            self.lo.next = self.t1_at_select.q.val();
            self.hi.next = self.t0_at_select.q.val();
        }
    }
}

/// The box test of both children of a node: one test a cycle in (a ray's [`RaySetup`] words,
/// the node's [`ChildBoxes`] words, `valid_in`, `tag_in`), its [`BoxResult`] out exactly
/// [`latency`]`(depth)` cycles later with `valid_out` and `tag_out`. `depth` is the pipeline
/// registers per operator, each saturating at its own `max_stages()` (as in the MT lane).
/// No reset: the valid line holds the flip-flops' power-on zeros until the first test passes.
///
/// `min` and `max` are indexed `2·axis + child` (`ChildBoxes::min[axis][child]`).
#[derive(LogicBlock)]
pub struct BoxTest {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Tag>,
    pub orig_lo: [Signal<In, Word>; 3],
    pub orig_hi: [Signal<In, Word>; 3],
    pub inv_dir: [Signal<In, Word>; 3],
    pub t_hi: Signal<In, Word>,
    pub min: [Signal<In, Word>; 6],
    pub max: [Signal<In, Word>; 6],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Tag>,
    pub enters: [Signal<Out, Bit>; 2],
    pub near: [Signal<Out, Word>; 2],
    /// 1: child 1 first (entered strictly nearer; meaningful when both are entered).
    pub first: Signal<Out, Bit>,
    /// Per axis and child (`2·axis + child`).
    slabs: [Slab; 6],
    inv_at_slab: [Delay<Word>; 3],
    t_hi_at_fold: Delay<Word>,
    /// Per fold step and child (`2·step + child`): lo, hi waiting for their step …
    lo_at_step: [Delay<Word>; 6],
    hi_at_step: [Delay<Word>; 6],
    /// … the step's comparison, lt(near, lo) and lt(hi, far) …
    near_step: [Lt; 6],
    far_step: [Lt; 6],
    /// … and both candidates waiting for it, to be selected.
    lo_at_keep: [Delay<Word>; 6],
    hi_at_keep: [Delay<Word>; 6],
    near_at_keep: [Delay<Word>; 6],
    far_at_keep: [Delay<Word>; 6],
    /// The running near and far before step k (`2·k + child`; k = 3: the results).
    running_near: [Signal<Local, Word>; 8],
    running_far: [Signal<Local, Word>; 8],
    /// lt(far, near) per child, lt(near1, near0).
    far_before_near: [Lt; 2],
    near_order: Lt,
    near_at_out: [Delay<Word>; 2],
    far_nan: [Signal<Local, Bit>; 2],
    far_nan_at_out: [Delay<Bit>; 2],
    valid_at_out: Delay<Bit>,
    tag_at_out: Delay<Tag>,
    zero: Constant<Word>,
    exp_mask: Constant<Word>,
    frac_mask: Constant<Word>,
}

impl BoxTest {
    pub fn new(depth: usize) -> Self {
        let s = schedule(depth);
        // Step k of either child (index 2k + c) waits for the k steps before it.
        let to_step = || std::array::from_fn(|i| Delay::new(s.axis_to_step(i / 2)));
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            orig_lo: Default::default(),
            orig_hi: Default::default(),
            inv_dir: Default::default(),
            t_hi: Default::default(),
            min: Default::default(),
            max: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            enters: Default::default(),
            near: Default::default(),
            first: Default::default(),
            slabs: std::array::from_fn(|_| Slab::new(&s)),
            inv_at_slab: Delay::lines(s.inv_to_slab()),
            t_hi_at_fold: Delay::new(s.t_hi_to_fold()),
            lo_at_step: to_step(),
            hi_at_step: to_step(),
            near_step: std::array::from_fn(|_| Lt::new(s.lt)),
            far_step: std::array::from_fn(|_| Lt::new(s.lt)),
            lo_at_keep: Delay::lines(s.lt),
            hi_at_keep: Delay::lines(s.lt),
            near_at_keep: Delay::lines(s.lt),
            far_at_keep: Delay::lines(s.lt),
            running_near: Default::default(),
            running_far: Default::default(),
            far_before_near: std::array::from_fn(|_| Lt::new(s.lt)),
            near_order: Lt::new(s.lt),
            near_at_out: Delay::lines(s.lt),
            far_nan: Default::default(),
            far_nan_at_out: Delay::lines(s.lt),
            valid_at_out: Delay::new(s.latency),
            tag_at_out: Delay::new(s.latency),
            zero: Constant::new(0.into()),
            exp_mask: Constant::new(0x7F80_0000u64.into()),
            frac_mask: Constant::new(0x007F_FFFFu64.into()),
        }
    }

    /// Cycles from a test at the inputs to its result at the outputs ([`latency`]).
    pub fn latency(depth: usize) -> usize {
        latency(depth)
    }
}

impl Stepped for BoxTest {
    type Input = BoxInput;
    type Output = BoxOutput;

    fn idle() -> BoxInput {
        BoxInput::idle()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, x: &BoxInput) {
        let (ray, boxes) = (&x.ray, &x.boxes);
        let word = |x: f32| Word::from(u64::from(x.to_bits()));
        self.valid_in.next = x.valid;
        self.tag_in.next = u64::from(x.tag).into();
        for a in 0..3 {
            self.orig_lo[a].next = word(ray.orig_lo[a]);
            self.orig_hi[a].next = word(ray.orig_hi[a]);
            self.inv_dir[a].next = word(ray.inv_dir[a]);
            for c in 0..2 {
                self.min[2 * a + c].next = word(boxes.min[a][c]);
                self.max[2 * a + c].next = word(boxes.max[a][c]);
            }
        }
        self.t_hi.next = word(ray.t_hi);
    }

    fn observe(&self) -> BoxOutput {
        let word = |s: &Signal<Out, Word>| s.val().to_u64() as u32;
        BoxOutput {
            valid: self.valid_out.val(),
            tag: self.tag_out.val().to_u64() as u16,
            enters: [self.enters[0].val(), self.enters[1].val()],
            near: [word(&self.near[0]), word(&self.near[1])],
            first: self.first.val(),
        }
    }
}

impl Logic for BoxTest {
    #[hdl_gen]
    fn update(&mut self) {
        for a in 0..3 {
            clock!(self, clock, inv_at_slab[a]);
            self.inv_at_slab[a].d.next = self.inv_dir[a].val();
            for c in 0..2 {
                clock!(self, clock, slabs[2 * a + c]);
                self.slabs[2 * a + c].orig_lo.next = self.orig_lo[a].val();
                self.slabs[2 * a + c].orig_hi.next = self.orig_hi[a].val();
                self.slabs[2 * a + c].inv.next = self.inv_at_slab[a].q.val();
                self.slabs[2 * a + c].min.next = self.min[2 * a + c].val();
                self.slabs[2 * a + c].max.next = self.max[2 * a + c].val();
            }
        }
        // The folds start from near = +0 and far = t_hi.
        clock!(self, clock, t_hi_at_fold);
        self.t_hi_at_fold.d.next = self.t_hi.val();
        for c in 0..2 {
            self.running_near[c].next = self.zero.val();
            self.running_far[c].next = self.t_hi_at_fold.q.val();
        }
        // Step k takes axis k: slab 2k + c is step 2k + c. A NaN candidate loses its lt, so
        // the running value keeps it out, and a tie keeps the running value, as in the model.
        for k in 0..3 {
            for c in 0..2 {
                clock!(
                    self,
                    clock,
                    lo_at_step[2 * k + c],
                    hi_at_step[2 * k + c],
                    near_step[2 * k + c],
                    far_step[2 * k + c],
                    lo_at_keep[2 * k + c],
                    hi_at_keep[2 * k + c],
                    near_at_keep[2 * k + c],
                    far_at_keep[2 * k + c]
                );
                self.lo_at_step[2 * k + c].d.next = self.slabs[2 * k + c].lo.val();
                self.hi_at_step[2 * k + c].d.next = self.slabs[2 * k + c].hi.val();
                self.near_step[2 * k + c].a.next = self.running_near[2 * k + c].val();
                self.near_step[2 * k + c].b.next = self.lo_at_step[2 * k + c].q.val();
                self.far_step[2 * k + c].a.next = self.hi_at_step[2 * k + c].q.val();
                self.far_step[2 * k + c].b.next = self.running_far[2 * k + c].val();
                self.lo_at_keep[2 * k + c].d.next = self.lo_at_step[2 * k + c].q.val();
                self.hi_at_keep[2 * k + c].d.next = self.hi_at_step[2 * k + c].q.val();
                self.near_at_keep[2 * k + c].d.next = self.running_near[2 * k + c].val();
                self.far_at_keep[2 * k + c].d.next = self.running_far[2 * k + c].val();
                if self.near_step[2 * k + c].y.val() {
                    self.running_near[2 * k + c + 2].next = self.lo_at_keep[2 * k + c].q.val();
                } else {
                    self.running_near[2 * k + c + 2].next = self.near_at_keep[2 * k + c].q.val();
                }
                if self.far_step[2 * k + c].y.val() {
                    self.running_far[2 * k + c + 2].next = self.hi_at_keep[2 * k + c].q.val();
                } else {
                    self.running_far[2 * k + c + 2].next = self.far_at_keep[2 * k + c].q.val();
                }
            }
        }
        // near ≤ far, and a NaN far (from a NaN t_hi: no product is a NaN that gets kept)
        // enters nothing; the NaN test is two masks, no operator.
        for c in 0..2 {
            clock!(
                self,
                clock,
                far_before_near[c],
                near_at_out[c],
                far_nan_at_out[c]
            );
            self.far_before_near[c].a.next = self.running_far[6 + c].val();
            self.far_before_near[c].b.next = self.running_near[6 + c].val();
            self.far_nan[c].next = ((self.running_far[6 + c].val() & self.exp_mask.val())
                == self.exp_mask.val())
                & ((self.running_far[6 + c].val() & self.frac_mask.val()) != self.zero.val());
            self.far_nan_at_out[c].d.next = self.far_nan[c].val();
            self.near_at_out[c].d.next = self.running_near[6 + c].val();
            self.enters[c].next =
                !self.far_before_near[c].y.val() & !self.far_nan_at_out[c].q.val();
            self.near[c].next = self.near_at_out[c].q.val();
        }
        clock!(self, clock, near_order);
        self.near_order.a.next = self.running_near[7].val();
        self.near_order.b.next = self.running_near[6].val();
        self.first.next = self.near_order.y.val();
        clock!(self, clock, valid_at_out, tag_at_out);
        self.valid_at_out.d.next = self.valid_in.val();
        self.tag_at_out.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_at_out.q.val();
        self.tag_out.next = self.tag_at_out.q.val();
    }
}

/// What the block's outputs show in one cycle (near as fp32 bits).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BoxOutput {
    pub valid: bool,
    pub tag: u16,
    pub enters: [bool; 2],
    pub near: [u32; 2],
    pub first: bool,
}

impl BoxOutput {
    pub fn result(&self) -> BoxResult {
        BoxResult {
            enters: self.enters,
            near: self.near.map(f32::from_bits),
            first: usize::from(self.first),
        }
    }

    /// Whether the result is `want` bit for bit (near compared as words, not as floats).
    pub fn same_bits(&self, want: &BoxResult) -> bool {
        self.enters == want.enters
            && self.near == want.near.map(f32::to_bits)
            && usize::from(self.first) == want.first
    }
}

/// One test at the inputs: valid, tag, the ray and the node's boxes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxInput {
    pub valid: bool,
    pub tag: u16,
    pub ray: RaySetup,
    pub boxes: ChildBoxes,
}

impl BoxInput {
    /// The idle input: not valid, every word zero.
    pub fn idle() -> Self {
        BoxInput {
            valid: false,
            tag: 0,
            ray: RaySetup {
                orig_lo: [0.0; 3],
                orig_hi: [0.0; 3],
                inv_dir: [0.0; 3],
                pad: 0.0,
                t_hi: 0.0,
            },
            boxes: ChildBoxes::default(),
        }
    }
}

/// Runs a freshly built block at `depth` in rust-hdl's simulator for `inputs.len() + flush`
/// cycles, feeding `inputs[c]` in cycle `c` (then idle inputs) and returning what the
/// outputs show in every cycle.
pub fn simulate_box_test(depth: usize, inputs: &[BoxInput], flush: usize) -> Vec<BoxOutput> {
    simulate_cycles(move || BoxTest::new(depth), inputs, flush)
}

/// Verilog of the block at `depth`, top module `top` (built on a thread with room for it).
pub fn box_test_verilog(depth: usize) -> String {
    built_verilog(move || BoxTest::new(depth))
}
