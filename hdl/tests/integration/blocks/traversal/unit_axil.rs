//! `hdl::traversal::unit_axil`.

use hdl::regmap::unit as map;
use hdl::traversal::config::UnitConfig;
use hdl::traversal::unit_axil::*;
use hw_model::{Advance, HwFormat};

#[test]
fn a_reset_outlasts_every_step_in_flight() {
    for format in HwFormat::all() {
        for depth in 0..=hdl::mt::max_depth(format) {
            for advance in [Advance::None, Advance::LeafBox] {
                let timing = UnitConfig {
                    advance,
                    ..UnitConfig::new(format, depth, 1)
                }
                .timing();
                assert!(
                    longest_step(&timing) < u64::from(map::RESET_CYCLES),
                    "{format} depth {depth} {advance:?}: {timing:?}"
                );
            }
        }
    }
}

#[test]
fn config_and_memory_words() {
    let mut c = UnitConfig::new(HwFormat::FP32, 1000, 1);
    let w = config_word(&c);
    assert_eq!(w.depth as usize, hdl::mt::max_depth(HwFormat::FP32));
    assert_eq!((w.format_code, w.lanes), (HwFormat::FP32.code(), 1));
    c.memory.node_bits = 4;
    c.memory.triangle_bits = 5;
    let m = memory_word(&c);
    assert_eq!((m.node_bits, m.triangle_bits), (4, 5));
    assert_eq!(m.slots as usize, hdl::traversal::config::UNIT_SLOTS);
}
