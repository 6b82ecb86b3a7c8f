//! `hdl::traversal::timing`.

use hdl::traversal::box_test;
use hdl::traversal::timing::*;
use hw_model::{Advance, HwFormat};

#[test]
fn deeper_pipelines_take_longer_and_every_step_takes_a_cycle() {
    let fp32 = HwFormat::FP32;
    let shallow = unit_timing(fp32, 0, 1, 32, Advance::None);
    let deep = unit_timing(fp32, 5, 1, 32, Advance::None);
    for (a, b) in [
        (shallow.setup_latency, deep.setup_latency),
        (shallow.box_latency, deep.box_latency),
        (shallow.mt_latency, deep.mt_latency),
    ] {
        assert!(a >= 1 && a < b, "{shallow:?} vs {deep:?}");
    }
    assert_eq!(
        deep.box_latency,
        (MEMORY_READ + box_test::latency(5) + SLOT_UPDATE) as u64
    );
    // The far end a nearer hit recomputes is part of the leaf's latency (none at depth 0).
    for t in [shallow, deep] {
        assert!(t.far_latency < t.mt_latency, "{t:?}");
    }
    assert!(shallow.far_latency < deep.far_latency);
}

/// The leaf advance lengthens only the lane's answer path, by its block and its adder.
#[test]
fn the_leaf_advance_lengthens_the_leaf_step_by_its_block_and_adder() {
    use hdl::traversal::leaf_advance::{around_lane_latency, AdvanceSchedule};
    for depth in [0, 1, 5] {
        let plain = unit_timing(HwFormat::FP32, depth, 1, 32, Advance::None);
        let advanced = unit_timing(HwFormat::FP32, depth, 1, 32, Advance::LeafBox);
        let s = AdvanceSchedule::new(depth);
        let extra = (s.mul + s.add + s.add) as u64;
        assert_eq!(around_lane_latency(depth) as u64, extra);
        assert_eq!(
            advanced.mt_latency,
            plain.mt_latency + extra,
            "depth {depth}"
        );
        assert_eq!(
            (
                advanced.box_latency,
                advanced.pop_latency,
                advanced.setup_latency
            ),
            (plain.box_latency, plain.pop_latency, plain.setup_latency)
        );
    }
}
