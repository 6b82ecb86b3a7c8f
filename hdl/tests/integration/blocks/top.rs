//! `hdl::top`.

use hdl::top::*;
use hw_model::HwFormat;

#[test]
fn impossible_configurations_are_refused_by_name() {
    let fp32 = HwFormat::FP32;
    assert_eq!(
        TopConfig::new(fp32, 1, 0).validate(),
        Err(TopError::NoLanes)
    );
    assert_eq!(
        TopConfig::new(fp32, 1, 9).validate(),
        Err(TopError::TooManyLanes(9))
    );
    let max = hdl::mt::max_depth(fp32);
    assert!(matches!(
        TopConfig::new(fp32, max + 1, 1).validate(),
        Err(TopError::DepthTooLarge { max: m, .. }) if m == max
    ));
    assert_eq!(TopConfig::new(fp32, max, MAX_LANES).validate(), Ok(()));
}

#[test]
fn config_word_uses_the_catalogue_index() {
    let fp16 = HwFormat::named("fp16");
    let w = TopConfig::new(fp16, 2, 3).config_word().unwrap();
    assert_eq!(hw_model::catalogue()[w.format_code as usize].name, "fp16");
    assert_eq!((w.depth, w.lanes), (2, 3));
    assert_eq!(
        TopConfig::new(HwFormat::FP32, 1, 4).dir_name(),
        "fp32_d1_l4"
    );
}

#[test]
fn the_result_fifo_covers_every_latency() {
    for name in HwFormat::all() {
        let max = hdl::mt::max_depth(name);
        let worst = (0..=max).map(|d| hdl::mt::latency(name, d)).max().unwrap();
        assert!(
            worst + 2 <= stream::FIFO_DEPTH,
            "{name}: latency {worst} leaves the FIFO short of full rate"
        );
    }
}

#[test]
fn every_hardware_format_has_an_accelerator() {
    for format in HwFormat::all() {
        // Cheapest configuration: depth 0, one lane.
        let body = with_build_stack(move || accelerator::body_verilog(format, 0, 1, 0));
        assert!(body.contains("module top"), "{format}");
    }
}

mod fit;
mod wrapper;
