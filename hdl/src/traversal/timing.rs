//! The planned unit's timing at a configuration, from its blocks' own latency functions:
//! what the schedule model (`hw_model::traversal::schedule`) times a walk with, until the
//! unit's RTL is co-simulated.

use hw_model::traversal::schedule::UnitTiming;
use hw_model::traversal::NodeFormat;
use hw_model::{Advance, HwFormat};

use super::{box_test, far_end, leaf_advance, ray_setup, stack_port, wide};
use crate::formats::fp32;
use crate::mt::schedule::OpLatencies;

/// Ray slots unless configured otherwise: enough for the box port to be 96 % busy on the
/// Utah teapot at depth 5 in the schedule model (16 slots: 68 %; 64 slots: 98 %).
pub const DEFAULT_SLOTS: usize = 32;

/// A block RAM read (node, triangle, stack entry): the RAM's read register.
pub const MEMORY_READ: usize = 1;
/// The slot's state register, written from a step's answer.
pub const SLOT_UPDATE: usize = 1;

/// The unit with `lanes` MT lanes in `format` and `slots` ray slots, every operator built
/// with `depth` pipeline registers (at most its maximum), starting a leaf's queries where
/// `advance` says (`None` or `LeafBox`).
pub fn unit_timing(
    format: HwFormat,
    depth: usize,
    lanes: usize,
    slots: usize,
    advance: Advance,
) -> UnitTiming {
    let lt = OpLatencies::for_depth(depth, fp32::max_stages).lt;
    let cycles = |c: usize| c as u64;
    let around_lane = match advance {
        Advance::LeafBox => leaf_advance::around_lane_latency(depth),
        // triangle-box is the model engine's alone: the unit's plain lane.
        Advance::None | Advance::TriangleBox => 0,
    };
    UnitTiming {
        slots,
        lanes,
        box_ports: 1,
        setup_latency: cycles(ray_setup::latency(depth) + SLOT_UPDATE),
        box_latency: box_port_latency(NodeFormat::Bvh2Fp32, depth),
        // Triangle read, the lane (behind the leaf advance, `t + t0` after it), the (t,
        // index) comparison with the slot's nearest hit (its registers are the leaf port's
        // before the far end), then the far end of the new bound.
        mt_latency: cycles(
            MEMORY_READ
                + crate::mt::latency(format, depth)
                + around_lane
                + lt
                + far_end::latency(depth)
                + SLOT_UPDATE,
        ),
        // A leaf that leaves the hit as it was steps on from the answer (`LeafPort`'s pop).
        far_latency: cycles(lt + far_end::latency(depth)),
        // The stack port (its grant register, the stack read and the entry's distance against
        // the far end), then the slot's update.
        pop_latency: cycles(stack_port::LATENCY + SLOT_UPDATE),
    }
}

/// `t` with its inner nodes stored as `nodes` and `box_ports` box ports: for wide nodes the
/// ray setup is followed by its padding in t (`wide::pad_in_t::PadInT`).
pub fn node_timing(t: UnitTiming, nodes: NodeFormat, depth: usize, box_ports: usize) -> UnitTiming {
    let pad_in_t = match nodes.width() {
        Some(_) => wide::pad_in_t::PadInT::latency(depth),
        None => 0,
    };
    UnitTiming {
        box_ports,
        setup_latency: t.setup_latency + pad_in_t as u64,
        box_latency: box_port_latency(nodes, depth),
        ..t
    }
}

/// Node read, the box test (the fp32 one of both children, or the wide stage testing all of a
/// wide node's children: [`wide::latency`]) and the slot's update.
fn box_port_latency(nodes: NodeFormat, depth: usize) -> u64 {
    let test = match nodes.width() {
        Some(_) => wide::latency(depth),
        None => box_test::latency(depth),
    };
    (MEMORY_READ + test + SLOT_UPDATE) as u64
}
