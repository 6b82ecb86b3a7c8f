//! The wide box stage: every child of a wide node tested against one ray in one beat (II = 1),
//! bit for bit `hw_model::traversal::wide::box_test::wide_box_test` (docs/wide-nodes.md
//! derives it). One block a file; [`WideBoxStage`] wires them.
//!
//! The dataflow, with the cycle each value is ready (at `depth`, see [`WideSchedule`]):
//! ```text
//! t_alpha   = sub + mul        α = (p − o)·inv per axis (the fp32 operators)
//! t_grid    = t_alpha + grid   the grid's extent E and shift 22 − E (exponents only)
//! t_scaled  = t_grid + scaled  α, pad_t, t0, t_hi and the reciprocal on the grid
//! t_axis    = t_scaled + axis  per axis: offsets and steps with their margins; the far end
//! t_slab    = t_axis + plane + code + fold
//!                              per child and plane a DSP48E1 multiply-add, the codes,
//!                              near = max of the entries, far = min of the exits
//! t_ordered = t_slab + max(order, entry)
//!                              the ranks by (near, slot) beside each child's t0' and width
//! latency   = t_ordered + select   the entered children, nearest first
//! ```
//! Every other path (the node's codes and links, τ, the extent, `valid` and the tag) is padded
//! with flip-flop delay lines (synthesis packs them into SRLs).
//!
//! Beside the stage, [`pad_in_t::PadInT`] computes the ray's `pad_t` after the fp32 ray setup.

pub mod axis;
pub mod entry;
pub mod extent;
pub mod far;
pub mod fold;
pub mod grid;
pub mod ones;
pub mod order;
pub mod pad_in_t;
pub mod plane;
pub mod scaled;
pub mod select;
pub mod slab;
pub mod stage;

use rust_hdl::prelude::*;

use crate::formats::fp32;
use crate::mt::schedule::OpLatencies;
use crate::operator::Op;

pub use stage::{
    simulate_wide_box_stage, wide_box_stage_verilog, width_word, EnteredChild, WideBoxStage,
    WideInput, WideOutput, LINK_BITS,
};

type Word = Bits<32>;
/// The grid's shift `8 − U` and its extent `E`: two's complement.
pub type Shift = Bits<11>;
/// A magnitude on the grid, saturated at `2^46` ([`scaled::SATURATED`]).
pub type Magnitude = Bits<47>;
/// Offsets and planes: the DSP48E1's 48-bit post-adder.
pub type Offset = Bits<48>;
/// Steps: the DSP48E1's 25-bit signed A port.
pub const STEP_BITS: usize = 25;
pub type Step = Bits<STEP_BITS>;
/// A child's box plane code.
pub type Code = Bits<8>;
/// Entry codes, `0..=ENTRY_MAX`.
pub type EntryCode = Bits<15>;
/// Every entry beyond the far end's limit saturates here.
pub const ENTRY_MAX: u64 = (1 << 15) - 1;
/// Exit codes and far ends, `−1..=ENTRY_MAX` (two's complement).
pub type ExitCode = Bits<16>;
/// A width exponent (two's complement; `WIDTH_UNBOUNDED` is unbounded).
pub type WidthExp = Bits<10>;
/// A child's slot in its node, and a count of children (up to [`MAX_WIDTH`]).
pub type Slot = Bits<3>;
pub type Count = Bits<4>;
/// The widest node the stage is built for.
pub const MAX_WIDTH: usize = 8;
/// A bit per slot.
pub type SlotBits = Bits<MAX_WIDTH>;

/// When each value of the stage is ready, from its blocks' registers at a depth: each block
/// has `min(depth, its cut points)` of them, as an operator has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WideSchedule {
    /// Registers per block.
    pub sub: usize,
    pub mul: usize,
    pub grid: usize,
    pub scaled: usize,
    pub axis: usize,
    pub far: usize,
    pub plane: usize,
    pub code: usize,
    pub fold: usize,
    pub order: usize,
    pub entry: usize,
    pub select: usize,
    /// α.
    pub t_alpha: usize,
    /// The grid's extent and shift.
    pub t_grid: usize,
    /// The grid-scaled values.
    pub t_scaled: usize,
    /// The axes' offsets and steps.
    pub t_axis: usize,
    /// Every child's near and far codes.
    pub t_slab: usize,
    /// The ranks and every child's entry, aligned.
    pub t_ordered: usize,
    /// Inputs to outputs.
    pub latency: usize,
}

impl WideSchedule {
    pub fn new(depth: usize) -> Self {
        let ops = OpLatencies::for_depth(depth, fp32::max_stages);
        let at = |cuts: usize| depth.min(cuts);
        let (sub, mul) = (ops.sub, ops.mul);
        let grid = at(grid::NodeGrid::CUTS);
        let scaled = at(scaled::Scaled::CUTS);
        let axis = at(axis::AxisBounds::CUTS);
        let far = at(far::FarCode::CUTS);
        let plane = at(plane::Plane::CUTS);
        let code = at(slab::AxisSlab::CODE_CUTS);
        let fold = at(fold::SlabFold::CUTS);
        let order = at(order::NearestFirst::CUTS);
        let entry = at(entry::ChildEntry::CUTS);
        let select = at(select::Select::<1>::CUTS);
        let t_alpha = sub + mul;
        let t_grid = t_alpha + grid;
        let t_scaled = t_grid + scaled;
        let t_axis = t_scaled + axis;
        let t_slab = t_axis + plane + code + fold;
        let t_ordered = t_slab + order.max(entry);
        WideSchedule {
            sub,
            mul,
            grid,
            scaled,
            axis,
            far,
            plane,
            code,
            fold,
            order,
            entry,
            select,
            t_alpha,
            t_grid,
            t_scaled,
            t_axis,
            t_slab,
            t_ordered,
            latency: t_ordered + select,
        }
    }

    /// The far end (ready at `t_scaled + far`) to the fold.
    pub fn far_to_fold(&self) -> usize {
        self.t_axis + self.plane + self.code - (self.t_scaled + self.far)
    }

    /// Whether the node is unknown (with the far end) to the ranks and the entries.
    pub fn unknown_to_slab(&self) -> usize {
        self.t_slab - (self.t_scaled + self.far)
    }
}

/// The stage's timing at `depth`.
pub fn schedule(depth: usize) -> WideSchedule {
    WideSchedule::new(depth)
}

/// Cycles from a node test at the inputs to its answer at the outputs: the one source of it.
pub fn latency(depth: usize) -> usize {
    schedule(depth).latency
}

/// The depth at which every block of the stage has all its pipeline registers.
pub fn max_depth() -> usize {
    [Op::Sub, Op::Mul]
        .into_iter()
        .map(fp32::max_stages)
        .chain([
            grid::NodeGrid::CUTS,
            scaled::Scaled::CUTS,
            axis::AxisBounds::CUTS,
            far::FarCode::CUTS,
            plane::Plane::CUTS,
            slab::AxisSlab::CODE_CUTS,
            fold::SlabFold::CUTS,
            order::NearestFirst::CUTS,
            entry::ChildEntry::CUTS,
            select::Select::<1>::CUTS,
        ])
        .max()
        .unwrap_or(0)
}
