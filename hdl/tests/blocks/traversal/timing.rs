//! `hdl::traversal::timing`.

use hdl::traversal::box_test;
use hdl::traversal::timing::*;
use hw_model::HwFormat;

#[test]
fn deeper_pipelines_take_longer_and_every_step_takes_a_cycle() {
    let fp32 = HwFormat::FP32;
    let shallow = unit_timing(fp32, 0, 1, 32);
    let deep = unit_timing(fp32, 5, 1, 32);
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
}
