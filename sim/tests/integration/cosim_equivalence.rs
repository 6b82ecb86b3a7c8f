//! fp16 and the thesis' ap_fixed<32,16>: the Verilated accelerator answers 100% of the
//! queries of real renders exactly like `hw_model::mt_model` — a trace recorded from the
//! renders, written to a file, read back and replayed into both: fp16 at depths 1 and 2 with
//! one and two lanes, ap_fixed<32,16> at depth 2 with two lanes, and fp16 at depth 0
//! (combinational lanes: a result comes in its beat's accept cycle). Four model builds (~1–2
//! min each the first time, then cached), which hdl/tests/integration/top_system.rs and the CLI's cosim
//! contracts share; the ignored test adds three more configurations.

use hdl::top::TopConfig;
use hw_model::ModelIntersector;
use hw_model::{HwFormat, MtQuery};
use sim::hw_intersector::{HwIntersector, Mode};
use sim::trace::{first_difference, read_trace, replay, write_trace, Recorder};
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

/// The queries of two built-in scenes rendered at 40×22, through a trace file.
fn recorded_queries() -> Vec<MtQuery> {
    let rec = Recorder::new(&F32Intersector);
    let opts = RenderOptions {
        width: Some(40),
        height: Some(22),
        ..RenderOptions::default()
    };
    let mut expected = 0;
    for name in ["simple_plane", "glasses"] {
        expected += render(&Scene::load(name).unwrap(), &rec, &opts)
            .unwrap()
            .stats
            .trace
            .cast
            .mt_tests;
    }
    let queries = rec.into_queries();
    assert_eq!(queries.len() as u64, expected);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("renders.trace");
    write_trace(&path, &queries).unwrap();
    read_trace(&path).unwrap()
}

fn check(format: &str, configs: &[(usize, usize)], queries: &[MtQuery]) {
    let model = ModelIntersector::new(hw_model::lookup(format).unwrap());
    let want = replay(&model, queries, &|_| {}).unwrap();
    for &(depth, lanes) in configs {
        let hw = HwIntersector::new(
            &TopConfig::new(format.parse().unwrap(), depth, lanes),
            Mode::Stream,
        )
        .unwrap();
        let got = replay(&hw, queries, &|_| {})
            .unwrap_or_else(|e| panic!("{format} d{depth} l{lanes}: {e}"));
        assert_eq!(hw.stats().tests, queries.len() as u64);
        if let Some(d) = first_difference(&got, &want) {
            panic!("{format} d{depth} l{lanes}: hardware vs model differ at {d}");
        }
        println!(
            "{format} d{depth} l{lanes}: {} queries identical, {:.0} tests/s per core",
            queries.len(),
            hw.stats().tests_per_sec()
        );
    }
    assert!(
        want.iter().filter(|r| r.hit).count() > queries.len() / 50,
        "too few hits to mean anything"
    );
}

/// Builds shared with the CLI's spawn test (fp16 d1 l1) and hdl's `top_system` (d2 l2).
#[test]
fn fp16_hardware_equals_the_model_on_real_render_queries() {
    let max = hdl::mt::max_depth(HwFormat::named("fp16"));
    check("fp16", &[(1, 1), (max.min(2), 2)], &recorded_queries());
}

/// One lane, the smallest build of a fixed-format top (more: the ignored test at the end).
#[test]
fn fixed_32_16_hardware_equals_the_model_on_real_render_queries() {
    check("fx32_16", &[(1, 1)], &recorded_queries());
}

/// Depth 0 (combinational lanes): a result arrives in its beat's accept cycle; the stream
/// front end must still keep every result, in order.
#[test]
fn depth_0_stream_keeps_every_result() {
    check("fp16", &[(0, 2)], &recorded_queries());
}

/// Further depths and lane counts (a Verilator build each, about a minute):
/// `cargo test --release -p sim --test integration cosim_equivalence:: -- --ignored`.
#[test]
#[ignore]
fn more_configurations_equal_the_model_on_real_render_queries() {
    let queries = recorded_queries();
    let fx_max = hdl::mt::max_depth(HwFormat::named("fx32_16"));
    check("fx32_16", &[(1, 2), (2, 1), (fx_max.min(2), 2)], &queries);
    check("fp16", &[(0, 1)], &queries);
}
