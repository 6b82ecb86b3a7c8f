//! [`WideBoxStage`]: the wide node box test, one test a cycle in, its entered children out
//! nearest first [`super::latency`]`(depth)` cycles later.

use hw_model::traversal::scene_image::Link;
use hw_model::traversal::wide::box_test::{NodeEntry, WideRay};
use hw_model::traversal::wide::image::{link_of, link_word};
use hw_model::traversal::wide::WideNode;
use rust_hdl::prelude::*;

use super::axis::AxisBounds;
use super::entry::ChildEntry;
use super::far::FarCode;
use super::fold::SlabFold;
use super::grid::NodeGrid;
use super::order::NearestFirst;
use super::scaled::Scaled;
use super::select::Select;
use super::slab::AxisSlab;
use super::{
    schedule, Code, Count, Magnitude, Shift, Slot, WideSchedule, WidthExp, Word, MAX_WIDTH,
};
use crate::formats::fp32::{Mul, Sub};
use crate::harness::{built_verilog, simulate_cycles, Stepped};
use crate::mt::delay::Delay;
use crate::traversal::box_test::Tag;

/// `n` delay lines of `cycles` each.
fn lines<T: Synth>(n: usize, cycles: usize) -> Vec<Delay<T>> {
    (0..n).map(|_| Delay::new(cycles)).collect()
}

/// Bits of a child's link in the stage's simulation and reports: the scene image's link word
/// (`hw_model::traversal::wide::image::link_word`), which the stage passes through unread.
pub const LINK_BITS: usize = 32;

/// The wide box test of one node against one ray, one test a cycle (II = 1): in a ray's
/// [`WideRay`] words, where the walk entered the node ([`NodeEntry`]) and the node's record
/// (grid origin and exponents, child count, per child six codes and a link); out
/// [`super::latency`]`(depth)` cycles later how many children are entered and, nearest first
/// by (entry code, slot), each one's link and where the walk enters it (`t0` in fp32, width
/// exponent), with `valid_out` and `tag_out`. Positions from `entered` on are not meaningful.
/// `depth` is the pipeline registers per block, each saturating at its own cut points (as
/// the operators'). No reset: the valid line holds the flip-flops' power-on zeros until the
/// first test passes.
///
/// The node ports are the fields of the scene image's node record
/// (`hw_model::traversal::wide::image`, version 3), unconverted: `origin` its words 0–2, `exp`
/// the bytes 0–2 of word 3 and `children` the low 4 bits of its byte 3, `lo[3·slot + axis]`
/// and `hi[3·slot + axis]` the code bytes `6·slot + axis` and `6·slot + 3 + axis` of the
/// packed code words, `link` the link words (with `L` = [`LINK_BITS`] = 32; the stage passes
/// them through unread). The ray's words are the wide ray setup's ([`WideRay`]).
#[derive(LogicBlock)]
pub struct WideBoxStage<const L: usize> {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Tag>,
    pub orig: [Signal<In, Word>; 3],
    pub inv_dir: [Signal<In, Word>; 3],
    pub pad_t: [Signal<In, Word>; 3],
    pub t_hi: Signal<In, Word>,
    /// Where the walk entered the node.
    pub t0: Signal<In, Word>,
    pub width_exp: Signal<In, WidthExp>,
    /// The node's grid origin (fp32) and exponents (i8) per axis, its child count.
    pub origin: [Signal<In, Word>; 3],
    pub exp: [Signal<In, Bits<8>>; 3],
    pub children: Signal<In, Count>,
    pub lo: Vec<Signal<In, Code>>,
    pub hi: Vec<Signal<In, Code>>,
    pub link: Vec<Signal<In, Bits<L>>>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Tag>,
    /// Children entered.
    pub entered: Signal<Out, Count>,
    /// Per position, nearest first.
    pub entry_link: Vec<Signal<Out, Bits<L>>>,
    pub entry_t0: Vec<Signal<Out, Word>>,
    pub entry_width: Vec<Signal<Out, WidthExp>>,
    to_origin: [Sub; 3],
    alpha: [Mul; 3],
    inv_at_mul: [Delay<Word>; 3],
    inv_at_grid: [Delay<Word>; 3],
    pad_at_grid: [Delay<Word>; 3],
    exp_at_grid: [Delay<Bits<8>>; 3],
    width_at_grid: Delay<WidthExp>,
    grid: NodeGrid,
    alpha_at_scale: [Delay<Word>; 3],
    inv_at_scale: [Delay<Word>; 3],
    pad_at_scale: [Delay<Word>; 3],
    exp_at_scale: [Delay<Bits<8>>; 3],
    t0_at_scale: Delay<Word>,
    t_hi_at_scale: Delay<Word>,
    alpha_scaled: [Scaled; 3],
    pad_scaled: [Scaled; 3],
    step_scaled: [Scaled; 3],
    t0_scaled: Scaled,
    t_hi_scaled: Scaled,
    /// `τ`: t0 on the grid, 0 for a negative t0.
    tau: Signal<Local, Magnitude>,
    inv_at_axis: [Delay<Word>; 3],
    shift_at_axis: Delay<Shift>,
    axes: [AxisBounds; 3],
    bounded_at_far: Delay<Bit>,
    far: FarCode,
    far_at_fold: Delay<Bits<16>>,
    /// Per slot and axis (`3·slot + axis`).
    lo_at_slab: Vec<Delay<Code>>,
    hi_at_slab: Vec<Delay<Code>>,
    slabs: Vec<AxisSlab>,
    fold: SlabFold,
    children_at_order: Delay<Count>,
    unknown_at_slab: Delay<Bit>,
    order: NearestFirst,
    tau_at_entry: Delay<Magnitude>,
    extent_at_entry: Delay<Shift>,
    t0_at_entry: Delay<Word>,
    entries: Vec<ChildEntry>,
    slot_at_select: Vec<Delay<Slot>>,
    entered_at_out: Delay<Count>,
    t0_at_select: Vec<Delay<Word>>,
    width_at_select: Vec<Delay<WidthExp>>,
    link_at_select: Vec<Delay<Bits<L>>>,
    t0_select: Select<32>,
    width_select: Select<10>,
    link_select: Select<L>,
    valid_at_out: Delay<Bit>,
    tag_at_out: Delay<Tag>,
    no_offset: Constant<Bits<8>>,
    no_tau: Constant<Magnitude>,
}

impl<const L: usize> WideBoxStage<L> {
    /// The stage for nodes of `width` children (2, 4 or 8) at `depth`.
    pub fn new(width: usize, depth: usize) -> Self {
        assert!(
            width.is_power_of_two() && (2..=MAX_WIDTH).contains(&width),
            "a wide box stage for {width} children: the stage is built for 2, 4 or 8"
        );
        let s: WideSchedule = schedule(depth);
        let scaled = || std::array::from_fn(|_| Scaled::new(s.scaled));
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            orig: Default::default(),
            inv_dir: Default::default(),
            pad_t: Default::default(),
            t_hi: Default::default(),
            t0: Default::default(),
            width_exp: Default::default(),
            origin: Default::default(),
            exp: Default::default(),
            children: Default::default(),
            lo: crate::defaults(3 * width),
            hi: crate::defaults(3 * width),
            link: crate::defaults(width),
            valid_out: Default::default(),
            tag_out: Default::default(),
            entered: Default::default(),
            entry_link: crate::defaults(width),
            entry_t0: crate::defaults(width),
            entry_width: crate::defaults(width),
            to_origin: std::array::from_fn(|_| Sub::new(s.sub)),
            alpha: std::array::from_fn(|_| Mul::new(s.mul)),
            inv_at_mul: Delay::lines(s.sub),
            inv_at_grid: Delay::lines(s.t_alpha),
            pad_at_grid: Delay::lines(s.t_alpha),
            exp_at_grid: Delay::lines(s.t_alpha),
            width_at_grid: Delay::new(s.t_alpha),
            grid: NodeGrid::new(s.grid),
            alpha_at_scale: Delay::lines(s.grid),
            inv_at_scale: Delay::lines(s.grid),
            pad_at_scale: Delay::lines(s.grid),
            exp_at_scale: Delay::lines(s.grid),
            t0_at_scale: Delay::new(s.t_grid),
            t_hi_at_scale: Delay::new(s.t_grid),
            alpha_scaled: scaled(),
            pad_scaled: scaled(),
            step_scaled: scaled(),
            t0_scaled: Scaled::new(s.scaled),
            t_hi_scaled: Scaled::new(s.scaled),
            tau: Default::default(),
            inv_at_axis: Delay::lines(s.scaled),
            shift_at_axis: Delay::new(s.scaled),
            axes: std::array::from_fn(|_| AxisBounds::new(s.axis)),
            bounded_at_far: Delay::new(s.scaled),
            far: FarCode::new(s.far),
            far_at_fold: Delay::new(s.far_to_fold()),
            lo_at_slab: lines(3 * width, s.t_axis),
            hi_at_slab: lines(3 * width, s.t_axis),
            slabs: (0..3 * width)
                .map(|_| AxisSlab::new(s.plane, s.code))
                .collect(),
            fold: SlabFold::new(width, s.fold),
            children_at_order: Delay::new(s.t_slab),
            unknown_at_slab: Delay::new(s.unknown_to_slab()),
            order: NearestFirst::new(width, s.order),
            tau_at_entry: Delay::new(s.t_slab - s.t_scaled),
            extent_at_entry: Delay::new(s.t_slab - s.t_grid),
            t0_at_entry: Delay::new(s.t_slab - s.t_grid),
            entries: (0..width).map(|_| ChildEntry::new(s.entry)).collect(),
            slot_at_select: lines(width, s.t_ordered - s.t_slab - s.order),
            entered_at_out: Delay::new(s.t_ordered - s.t_slab - s.order + s.select),
            t0_at_select: lines(width, s.t_ordered - s.t_slab - s.entry),
            width_at_select: lines(width, s.t_ordered - s.t_slab - s.entry),
            link_at_select: lines(width, s.t_ordered),
            t0_select: Select::new(width, s.select),
            width_select: Select::new(width, s.select),
            link_select: Select::new(width, s.select),
            valid_at_out: Delay::new(s.latency),
            tag_at_out: Delay::new(s.latency),
            no_offset: Constant::new(0.into()),
            no_tau: Constant::new(0.into()),
        }
    }

    /// Children per node.
    pub fn width(&self) -> usize {
        self.link.len()
    }
}

impl<const L: usize> Logic for WideBoxStage<L> {
    #[hdl_gen]
    fn update(&mut self) {
        // α = (p − o)·inv, and what the grid reads beside it.
        for a in 0..3 {
            self.to_origin[a].clock.next = self.clock.val();
            self.alpha[a].clock.next = self.clock.val();
            self.inv_at_mul[a].clock.next = self.clock.val();
            self.inv_at_grid[a].clock.next = self.clock.val();
            self.pad_at_grid[a].clock.next = self.clock.val();
            self.exp_at_grid[a].clock.next = self.clock.val();
            self.to_origin[a].a.next = self.origin[a].val();
            self.to_origin[a].b.next = self.orig[a].val();
            self.inv_at_mul[a].d.next = self.inv_dir[a].val();
            self.alpha[a].a.next = self.to_origin[a].y.val();
            self.alpha[a].b.next = self.inv_at_mul[a].q.val();
            self.inv_at_grid[a].d.next = self.inv_dir[a].val();
            self.pad_at_grid[a].d.next = self.pad_t[a].val();
            self.exp_at_grid[a].d.next = self.exp[a].val();
            self.grid.alpha[a].next = self.alpha[a].y.val();
            self.grid.inv_dir[a].next = self.inv_at_grid[a].q.val();
            self.grid.pad_t[a].next = self.pad_at_grid[a].q.val();
            self.grid.exp[a].next = self.exp_at_grid[a].q.val();
        }
        self.width_at_grid.clock.next = self.clock.val();
        self.width_at_grid.d.next = self.width_exp.val();
        self.grid.clock.next = self.clock.val();
        self.grid.width.next = self.width_at_grid.q.val();
        // Everything onto the grid.
        for a in 0..3 {
            self.alpha_at_scale[a].clock.next = self.clock.val();
            self.inv_at_scale[a].clock.next = self.clock.val();
            self.pad_at_scale[a].clock.next = self.clock.val();
            self.exp_at_scale[a].clock.next = self.clock.val();
            self.alpha_scaled[a].clock.next = self.clock.val();
            self.pad_scaled[a].clock.next = self.clock.val();
            self.step_scaled[a].clock.next = self.clock.val();
            self.alpha_at_scale[a].d.next = self.alpha[a].y.val();
            self.inv_at_scale[a].d.next = self.inv_at_grid[a].q.val();
            self.pad_at_scale[a].d.next = self.pad_at_grid[a].q.val();
            self.exp_at_scale[a].d.next = self.exp_at_grid[a].q.val();
            self.alpha_scaled[a].x.next = self.alpha_at_scale[a].q.val();
            self.alpha_scaled[a].shift.next = self.grid.shift.val();
            self.alpha_scaled[a].offset.next = self.no_offset.val();
            self.pad_scaled[a].x.next = self.pad_at_scale[a].q.val();
            self.pad_scaled[a].shift.next = self.grid.shift.val();
            self.pad_scaled[a].offset.next = self.no_offset.val();
            self.step_scaled[a].x.next = self.inv_at_scale[a].q.val();
            self.step_scaled[a].shift.next = self.grid.shift.val();
            self.step_scaled[a].offset.next = self.exp_at_scale[a].q.val();
        }
        self.t0_at_scale.clock.next = self.clock.val();
        self.t_hi_at_scale.clock.next = self.clock.val();
        self.t0_scaled.clock.next = self.clock.val();
        self.t_hi_scaled.clock.next = self.clock.val();
        self.t0_at_scale.d.next = self.t0.val();
        self.t_hi_at_scale.d.next = self.t_hi.val();
        self.t0_scaled.x.next = self.t0_at_scale.q.val();
        self.t0_scaled.shift.next = self.grid.shift.val();
        self.t0_scaled.offset.next = self.no_offset.val();
        self.t_hi_scaled.x.next = self.t_hi_at_scale.q.val();
        self.t_hi_scaled.shift.next = self.grid.shift.val();
        self.t_hi_scaled.offset.next = self.no_offset.val();
        self.tau.next = self.t0_scaled.floor.val();
        if self.t0_scaled.negative.val() {
            self.tau.next = self.no_tau.val();
        }
        // Per axis: offsets and steps; the node's far end.
        self.shift_at_axis.clock.next = self.clock.val();
        self.shift_at_axis.d.next = self.grid.shift.val();
        for a in 0..3 {
            self.inv_at_axis[a].clock.next = self.clock.val();
            self.axes[a].clock.next = self.clock.val();
            self.inv_at_axis[a].d.next = self.inv_at_scale[a].q.val();
            self.axes[a].alpha_floor.next = self.alpha_scaled[a].floor.val();
            self.axes[a].alpha_ceil.next = self.alpha_scaled[a].ceil.val();
            self.axes[a].alpha_negative.next = self.alpha_scaled[a].negative.val();
            self.axes[a].alpha_nan.next = self.alpha_scaled[a].nan.val();
            self.axes[a].pad_ceil.next = self.pad_scaled[a].ceil.val();
            self.axes[a].pad_nan.next = self.pad_scaled[a].nan.val();
            self.axes[a].step_floor.next = self.step_scaled[a].floor.val();
            self.axes[a].step_ceil.next = self.step_scaled[a].ceil.val();
            self.axes[a].inv_dir.next = self.inv_at_axis[a].q.val();
            self.axes[a].shift.next = self.shift_at_axis.q.val();
            self.axes[a].tau.next = self.tau.val();
        }
        self.bounded_at_far.clock.next = self.clock.val();
        self.bounded_at_far.d.next = self.grid.bounded.val();
        self.far.clock.next = self.clock.val();
        self.far.t_hi_floor.next = self.t_hi_scaled.floor.val();
        self.far.t_hi_ceil.next = self.t_hi_scaled.ceil.val();
        self.far.t_hi_negative.next = self.t_hi_scaled.negative.val();
        self.far.t_hi_nan.next = self.t_hi_scaled.nan.val();
        self.far.tau.next = self.tau.val();
        self.far.t0_nan.next = self.t0_scaled.nan.val();
        self.far.bounded.next = self.bounded_at_far.q.val();
        // Per child and axis: the planes and their codes.
        for i in 0..self.slabs.len() {
            self.lo_at_slab[i].clock.next = self.clock.val();
            self.hi_at_slab[i].clock.next = self.clock.val();
            self.slabs[i].clock.next = self.clock.val();
            self.lo_at_slab[i].d.next = self.lo[i].val();
            self.hi_at_slab[i].d.next = self.hi[i].val();
            self.slabs[i].lo.next = self.lo_at_slab[i].q.val();
            self.slabs[i].hi.next = self.hi_at_slab[i].q.val();
        }
        for c in 0..self.link.len() {
            for a in 0..3 {
                self.slabs[3 * c + a].offset_lo.next = self.axes[a].offset_lo.val();
                self.slabs[3 * c + a].offset_hi.next = self.axes[a].offset_hi.val();
                self.slabs[3 * c + a].step_lo.next = self.axes[a].step_lo.val();
                self.slabs[3 * c + a].step_hi.next = self.axes[a].step_hi.val();
                self.slabs[3 * c + a].lo_inf.next = self.axes[a].lo_inf.val();
                self.slabs[3 * c + a].hi_inf.next = self.axes[a].hi_inf.val();
                self.slabs[3 * c + a].step_lo_inf.next = self.axes[a].step_lo_inf.val();
                self.slabs[3 * c + a].step_hi_inf.next = self.axes[a].step_hi_inf.val();
                self.slabs[3 * c + a].positive.next = self.axes[a].positive.val();
            }
        }
        // Per child: near and far.
        self.far_at_fold.clock.next = self.clock.val();
        self.far_at_fold.d.next = self.far.far_end.val();
        self.fold.clock.next = self.clock.val();
        self.fold.far_end.next = self.far_at_fold.q.val();
        for i in 0..self.slabs.len() {
            self.fold.entry[i].next = self.slabs[i].entry.val();
            self.fold.exit[i].next = self.slabs[i].exit.val();
        }
        // The order, and each child's entry beside it.
        self.children_at_order.clock.next = self.clock.val();
        self.unknown_at_slab.clock.next = self.clock.val();
        self.order.clock.next = self.clock.val();
        self.tau_at_entry.clock.next = self.clock.val();
        self.extent_at_entry.clock.next = self.clock.val();
        self.t0_at_entry.clock.next = self.clock.val();
        self.children_at_order.d.next = self.children.val();
        self.unknown_at_slab.d.next = self.far.unknown.val();
        self.tau_at_entry.d.next = self.tau.val();
        self.extent_at_entry.d.next = self.grid.extent.val();
        self.t0_at_entry.d.next = self.t0_at_scale.q.val();
        self.order.children.next = self.children_at_order.q.val();
        self.order.unknown.next = self.unknown_at_slab.q.val();
        for c in 0..self.link.len() {
            self.order.near[c].next = self.fold.near[c].val();
            self.order.far[c].next = self.fold.far[c].val();
            self.entries[c].clock.next = self.clock.val();
            self.entries[c].near.next = self.fold.near[c].val();
            self.entries[c].far.next = self.fold.far[c].val();
            self.entries[c].tau.next = self.tau_at_entry.q.val();
            self.entries[c].extent.next = self.extent_at_entry.q.val();
            self.entries[c].unknown.next = self.unknown_at_slab.q.val();
            self.entries[c].t0.next = self.t0_at_entry.q.val();
        }
        // Nearest first.
        self.entered_at_out.clock.next = self.clock.val();
        self.entered_at_out.d.next = self.order.entered.val();
        self.entered.next = self.entered_at_out.q.val();
        self.t0_select.clock.next = self.clock.val();
        self.width_select.clock.next = self.clock.val();
        self.link_select.clock.next = self.clock.val();
        for c in 0..self.link.len() {
            self.slot_at_select[c].clock.next = self.clock.val();
            self.t0_at_select[c].clock.next = self.clock.val();
            self.width_at_select[c].clock.next = self.clock.val();
            self.link_at_select[c].clock.next = self.clock.val();
            self.slot_at_select[c].d.next = self.order.slot[c].val();
            self.t0_at_select[c].d.next = self.entries[c].entry_t0.val();
            self.width_at_select[c].d.next = self.entries[c].entry_width.val();
            self.link_at_select[c].d.next = self.link[c].val();
            self.t0_select.word[c].next = self.t0_at_select[c].q.val();
            self.t0_select.slot[c].next = self.slot_at_select[c].q.val();
            self.width_select.word[c].next = self.width_at_select[c].q.val();
            self.width_select.slot[c].next = self.slot_at_select[c].q.val();
            self.link_select.word[c].next = self.link_at_select[c].q.val();
            self.link_select.slot[c].next = self.slot_at_select[c].q.val();
            self.entry_t0[c].next = self.t0_select.y[c].val();
            self.entry_width[c].next = self.width_select.y[c].val();
            self.entry_link[c].next = self.link_select.y[c].val();
        }
        self.valid_at_out.clock.next = self.clock.val();
        self.tag_at_out.clock.next = self.clock.val();
        self.valid_at_out.d.next = self.valid_in.val();
        self.tag_at_out.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_at_out.q.val();
        self.tag_out.next = self.tag_at_out.q.val();
    }
}

/// One node test at the inputs.
#[derive(Clone, Debug, PartialEq)]
pub struct WideInput {
    pub valid: bool,
    pub tag: u16,
    pub ray: WideRay,
    pub node: WideNode,
    pub at: NodeEntry,
}

impl WideInput {
    /// The idle input: not valid, every word zero, no children.
    pub fn idle() -> Self {
        WideInput {
            valid: false,
            tag: 0,
            ray: WideRay {
                orig: [0.0; 3],
                inv_dir: [0.0; 3],
                pad_t: [0.0; 3],
                pad: 0.0,
                t_hi: 0.0,
            },
            node: WideNode::default(),
            at: NodeEntry {
                t0: 0.0,
                width_exp: 0,
            },
        }
    }
}

/// An entered child at the outputs: its link and where the walk enters it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EnteredChild {
    pub link: Link,
    /// fp32 bits.
    pub t0: u32,
    pub width_exp: i16,
}

/// What the stage's outputs show in one cycle: the meaningful positions only.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WideOutput {
    pub valid: bool,
    pub tag: u16,
    pub entered: Vec<EnteredChild>,
}

/// A width exponent as the stage's 10-bit two's complement word.
pub fn width_word(w: i16) -> u64 {
    (w as u64) & ((1 << WidthExp::BITS) - 1)
}

fn width_of(word: u64) -> i16 {
    ((word << 6) as u16 as i16) >> 6
}

impl Stepped for WideBoxStage<LINK_BITS> {
    type Input = WideInput;
    type Output = WideOutput;

    fn idle() -> WideInput {
        WideInput::idle()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    /// Drives the inputs with one test (the simulator's side of the ports, from
    /// [`WideInput::port_words`]): a node's missing children are zero words.
    fn apply(&mut self, x: &WideInput) {
        let width = self.width();
        assert!(
            x.node.children.len() <= width,
            "{} children",
            x.node.children.len()
        );
        let w = x.port_words(width);
        let mut next = w.into_iter();
        let mut take = || next.next().expect("a word per input port");
        self.valid_in.next = take() != 0;
        self.tag_in.next = take().into();
        for field in [&mut self.orig, &mut self.inv_dir, &mut self.pad_t] {
            for s in field.iter_mut() {
                s.next = take().into();
            }
        }
        self.t_hi.next = take().into();
        self.t0.next = take().into();
        self.width_exp.next = take().into();
        for s in &mut self.origin {
            s.next = take().into();
        }
        for s in &mut self.exp {
            s.next = take().into();
        }
        self.children.next = take().into();
        for s in self.lo.iter_mut().chain(self.hi.iter_mut()) {
            s.next = take().into();
        }
        for s in &mut self.link {
            s.next = take().into();
        }
    }

    /// What the outputs show ([`WideOutput::from_port_words`]).
    fn observe(&self) -> WideOutput {
        let mut w = vec![
            u64::from(self.valid_out.val()),
            self.tag_out.val().to_u64(),
            self.entered.val().to_u64(),
        ];
        w.extend(self.entry_link.iter().map(|s| s.val().to_u64()));
        w.extend(self.entry_t0.iter().map(|s| s.val().to_u64()));
        w.extend(self.entry_width.iter().map(|s| s.val().to_u64()));
        WideOutput::from_port_words(&w, self.width())
    }
}

impl WideInput {
    /// The input ports' words in port order (`valid_in`, `tag_in`, `orig`, `inv_dir`, `pad_t`,
    /// `t_hi`, `t0`, `width_exp`, `origin`, `exp`, `children`, `lo`, `hi`, `link`) for a stage
    /// of `width` children with [`LINK_BITS`]-bit links: what the Verilated stage takes.
    pub fn port_words(&self, width: usize) -> Vec<u64> {
        let word = |v: f32| u64::from(v.to_bits());
        let child = |slot: usize| self.node.children.get(slot).copied().unwrap_or_default();
        let mut w = vec![u64::from(self.valid), u64::from(self.tag)];
        for field in [self.ray.orig, self.ray.inv_dir, self.ray.pad_t] {
            w.extend(field.map(word));
        }
        w.extend([
            word(self.ray.t_hi),
            word(self.at.t0),
            width_word(self.at.width_exp),
        ]);
        w.extend(self.node.origin.map(word));
        w.extend(self.node.exp.map(|e| u64::from(e as u8)));
        w.push(self.node.children.len() as u64);
        w.extend((0..3 * width).map(|i| u64::from(child(i / 3).lo[i % 3])));
        w.extend((0..3 * width).map(|i| u64::from(child(i / 3).hi[i % 3])));
        w.extend((0..width).map(|slot| u64::from(link_word(child(slot).link))));
        w
    }
}

impl WideOutput {
    /// The output ports' words in port order (`valid_out`, `tag_out`, `entered`,
    /// `entry_link`, `entry_t0`, `entry_width`) of a stage of `width` children.
    pub fn from_port_words(w: &[u64], width: usize) -> WideOutput {
        let entered = (w[2] as usize).min(width);
        WideOutput {
            valid: w[0] != 0,
            tag: w[1] as u16,
            entered: (0..entered)
                .map(|p| EnteredChild {
                    link: link_of(w[3 + p] as u32),
                    t0: w[3 + width + p] as u32,
                    width_exp: width_of(w[3 + 2 * width + p]),
                })
                .collect(),
        }
    }

    /// The model's answer to `x` as the outputs show it.
    pub fn of_model(x: &WideInput) -> Vec<EnteredChild> {
        hw_model::traversal::wide::box_test::wide_box_test(&x.ray, &x.node, x.at)
            .iter()
            .map(|e| EnteredChild {
                link: x.node.children[e.slot].link,
                t0: e.entry.t0.to_bits(),
                width_exp: e.entry.width_exp,
            })
            .collect()
    }
}

/// Runs a freshly built stage of `width` children at `depth` in rust-hdl's simulator for
/// `inputs.len() + flush` cycles, feeding `inputs[c]` in cycle `c` (then idle inputs), and
/// returns what the outputs show in every cycle.
pub fn simulate_wide_box_stage(
    width: usize,
    depth: usize,
    inputs: &[WideInput],
    flush: usize,
) -> Vec<WideOutput> {
    simulate_cycles(
        move || WideBoxStage::<LINK_BITS>::new(width, depth),
        inputs,
        flush,
    )
}

/// Verilog of the stage of `width` children at `depth` ([`LINK_BITS`]-bit links), top
/// module `top`.
pub fn wide_box_stage_verilog(width: usize, depth: usize) -> String {
    built_verilog(move || WideBoxStage::<LINK_BITS>::new(width, depth))
}
