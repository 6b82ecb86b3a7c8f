//! The frame engine (`hdl::frame::engine`): its constants for a frame (the load port's
//! words, the held inputs, the reserves) and what does not fit; Verilator's lint. Its frames
//! are co-simulated against the frame model in sim (`frame_engine_verilator::`).

use hdl::frame::engine::{
    frame_engine_verilog, EngineError, EngineFrame, LoadTarget, CAMERA_WORDS, LOAD_DATA_WORDS,
};
use hdl::frame::id_queue::IDS;
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::frame::shader::isa::CONSTANTS;
use hw_model::frame::{Frame, FrameLimits};
use hw_model::traversal::TraversalEngine;
use hw_model::Format;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;

use crate::common::frame_test_scene;

const TB: usize = 12;

fn frame_of<'a>(
    scene: &Scene,
    prepared: &'a PreparedScene,
    unit: &'a TraversalEngine,
) -> Frame<'a> {
    Frame::new(scene, prepared, unit, 16, 9, &FrameLimits::HW).unwrap()
}

#[test]
fn engine_frame_holds_the_blocks_words_and_the_reserves() {
    let scene = frame_test_scene("glass");
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = frame_of(&scene, &prepared, &unit);
    let (c, program) = (frame.constants(), frame.program());
    let e = EngineFrame::new::<TB>(c, program, None).unwrap();
    let count = |t: LoadTarget| e.loads.iter().filter(|w| w.target == t).count();
    assert_eq!(count(LoadTarget::Program), program.code.len());
    assert_eq!(count(LoadTarget::Constant), CONSTANTS);
    assert_eq!(count(LoadTarget::Triangle), c.triangles.len());
    assert_eq!(count(LoadTarget::Object), c.materials.len());
    assert!(e.loads.iter().all(|w| w.data.len() == LOAD_DATA_WORDS));
    // Each triangle and object once, at its index.
    for target in [LoadTarget::Triangle, LoadTarget::Object] {
        let mut at: Vec<u64> = (e.loads.iter().filter(|w| w.target == target))
            .map(|w| w.address)
            .collect();
        at.sort_unstable();
        assert!(
            at.iter().enumerate().all(|(k, &a)| a == k as u64),
            "{target:?}"
        );
    }
    let k = &c.camera;
    assert_eq!(e.camera.len(), CAMERA_WORDS);
    assert_eq!(e.camera[..4], [k.dx, k.x0, k.dy, k.y0].map(|x| x.bits()));
    assert_eq!(e.camera[13..], k.origin.components().map(|x| x.bits()));
    // Glass pushes 2 cast rays (C) of at most 2 (M) under max depth 5: C·D + M = 12.
    assert_eq!(
        (e.reservation, e.escape_reserve, e.spawn_reserve),
        (2, 12, IDS / 4)
    );
    let least = EngineFrame::new::<TB>(c, program, Some(13)).unwrap();
    assert_eq!(
        (least.spawn_reserve, least.escape_reserve),
        (IDS - 1, IDS - 1)
    );
}

#[test]
fn engine_frame_refuses_what_does_not_fit() {
    let scene = frame_test_scene("glass");
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = frame_of(&scene, &prepared, &unit);
    let (c, program) = (frame.constants(), frame.program());
    let e = EngineFrame::new::<TB>(c, program, Some(12)).unwrap_err();
    assert!(
        matches!(
            e,
            EngineError::Store {
                entries: 12,
                needed: 13,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("a ray store of 12 entries"), "{e}");
    assert!(EngineFrame::new::<TB>(c, program, Some(IDS + 1)).is_err());
    let teapot = Scene::load("utah_teapot").unwrap();
    let prepared = PreparedScene::new(&teapot).unwrap();
    let frame = frame_of(&teapot, &prepared, &unit);
    let e = EngineFrame::new::<TB>(frame.constants(), frame.program(), None).unwrap_err();
    assert!(e.to_string().contains("triangle memory holds 4096"), "{e}");
}

#[test]
fn frame_engine_verilog_passes_verilator_lint() {
    let verilog = frame_engine_verilog::<TB>(1);
    if let Err(e) = verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS) {
        panic!("frame engine: verilator lint failed:\n{e}");
    }
}

/// yosys `synth_xilinx` of the engine, operators at depth 5, 4,096 triangles (slow, the
/// whole engine flattened): `cargo test --release -p hdl --test integration -- --ignored
/// --nocapture frame_engine::engine_synthesis`.
#[test]
#[ignore]
fn engine_synthesis() {
    use crate::common::{print_synthesis_row, SYNTHESIS_COLUMNS};
    use hdl::synth::{synthesize, SynthOptions};
    let verilog = frame_engine_verilog::<TB>(5);
    let r = synthesize(&verilog, "top", &SynthOptions::default()).expect("yosys synth_xilinx");
    println!(
        "| block | {SYNTHESIS_COLUMNS} |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    print_synthesis_row("frame engine, depth 5, 4,096 triangles", &r);
}
