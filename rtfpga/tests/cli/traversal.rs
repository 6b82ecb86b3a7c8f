//! `render --engine traversal` (the traversal unit's bit-accurate model, timed by its
//! schedule model) and `scene-image` (the unit's scene memory).

use hw_model::precision::spawn_policy;
use hw_model::traversal::{SceneMemory, TraversalEngine, DEFAULT_STACK_DEPTH};
use hw_model::Advance;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::RenderOptions;

use crate::common::*;

#[test]
fn an_fp32_traversal_render_is_the_software_image_and_reports_the_units_schedule() {
    let dir = tmp();
    let png = at(&dir, "t.png");
    let out = render("glass_pen", 40, 24, &png)
        .args(&["--engine", "traversal", "--slots", "16"])
        .ok();
    assert_eq!(
        read_png(&png),
        library_render("glass_pen", 40, 24, &F32Intersector),
        "an fp32 traversal render is the software image"
    );
    let schedule = last_line(&out);
    assert!(
        schedule.starts_with("unit_schedule nodes=bvh2-fp32 slots=16 box_ports=1 lanes=1 "),
        "{out}"
    );
    for key in [
        "cycles_per_ray",
        "box_tests_per_ray",
        "mt_tests_per_ray",
        "box_utilisation",
        "lane_utilisation",
    ] {
        assert!(value(schedule, key).is_some(), "no {key}: {out}");
    }
}

#[test]
fn a_format_without_hardware_renders_but_has_no_lane_to_time() {
    let dir = tmp();
    let png = at(&dir, "t.png");
    let out = render("glass_pen", 8, 6, &png)
        .args(&["--engine", "traversal", "--format", "e8m14"])
        .ok();
    assert!(!out.contains("unit_schedule"), "{out}");
}

#[test]
fn the_leaf_advance_reaches_the_units_model() {
    let dir = tmp();
    let png = at(&dir, "leaf.png");
    let out = render("glass_pen", 32, 18, &png)
        .args(&["--engine", "traversal", "--format", "e5m14"])
        .args(&["--advance", "leaf-box", "--scene-memory", "100000,100000"])
        .ok();
    assert_eq!(value(&out, "advance").as_deref(), Some("leaf-box"), "{out}");
    assert_eq!(
        value(&out, "spawn").as_deref(),
        Some("format-aware"),
        "{out}"
    );
    let e5m14: hw_model::Format = "e5m14".parse().unwrap();
    let engine = TraversalEngine {
        format: e5m14,
        stack_depth: DEFAULT_STACK_DEPTH,
        scale_exp: 0,
        advance: Advance::LeafBox,
        timing: None,
        memory: SceneMemory::Unbounded,
        nodes: hw_model::traversal::NodeFormat::Bvh2Fp32,
    };
    let opts = RenderOptions {
        spawn: spawn_policy(&e5m14, 0),
        ..Default::default()
    };
    assert_eq!(
        read_png(&png),
        library_render_with("glass_pen", 32, 18, &engine, opts)
    );
}

/// A scene memory smaller than the scene renders in chunked passes (the same image), and is
/// refused with --no-chunks naming both sizes in the units typed.
#[test]
fn a_small_scene_memory_chunks_the_scene_or_names_the_sizes() {
    let dir = tmp();
    let png = at(&dir, "t.png");
    let unit = || render("utah_teapot", 24, 16, &png).args(&["--engine", "traversal"]);
    let out = unit().args(&["--scene-memory", "1000,2000"]).ok();
    assert_eq!(
        read_png(&png),
        library_render("utah_teapot", 24, 16, &F32Intersector)
    );
    let loads: u64 = value(labelled(&out, "unit_memory"), "chunk_loads")
        .unwrap()
        .parse()
        .unwrap();
    assert!(loads >= 4, "a teapot in 1,000-node chunks: {out}");
    unit()
        .args(&["--scene-memory", "2048,4096", "--no-chunks"])
        .fails(
            1,
            &["nodes and 6,322 triangles; this unit holds 2,048 nodes and 4,096 triangles"],
        );
    unit().args(&["--scene-memory", "100,1"]).fails(
        1,
        &["holds 100 nodes and 1 triangles; its BVH has a leaf of"],
    );
    unit()
        .args(&["--scene-memory", "2048"])
        .fails(2, &["NODES,TRIANGLES"]);
    unit()
        .args(&["--scene-memory", "2048,-1"])
        .fails(2, &["--scene-memory"]);
}

#[test]
fn scene_image_lists_the_chunks_of_a_scene_memory() {
    let out = rtfpga(&[
        "scene-image",
        "--scene",
        "utah_teapot",
        "--scene-memory",
        "1000,2000",
    ])
    .ok();
    let chunks = out.lines().filter(|l| l.starts_with("chunk=")).count();
    assert!(chunks >= 4, "{out}");
    assert_eq!(value(&out, "chunks"), Some(chunks.to_string()), "{out}");
}

#[test]
fn scene_image_writes_the_words_it_reports() {
    let dir = tmp();
    let file = at(&dir, "new/teapot.rtsi");
    let out = rtfpga(&["scene-image", "--scene", "utah_teapot", "--out", s(&file)]).ok();
    let bytes = std::fs::read(&file).unwrap();
    assert_eq!(value(&out, "bytes"), Some(bytes.len().to_string()), "{out}");
    assert_eq!(value(&out, "triangles").as_deref(), Some("6322"), "{out}");
    assert_eq!(value(&out, "out").as_deref(), Some(s(&file)), "{out}");
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|w| u32::from_le_bytes(w.try_into().unwrap()))
        .collect();
    let image = hw_model::traversal::scene_image::SceneImage::from_words(&words).unwrap();
    assert_eq!(image.triangles.len(), 6322);
}

#[test]
fn scene_image_writes_wide_nodes_and_their_record_sizes() {
    let dir = tmp();
    let binary = rtfpga(&["scene-image", "--scene", "utah_teapot"]).ok();
    assert_eq!(value(&binary, "node_format").as_deref(), Some("bvh2-fp32"));
    assert_eq!(
        value(&binary, "node_bytes").as_deref(),
        Some("64"),
        "{binary}"
    );
    assert_eq!(
        value(&binary, "triangle_bytes").as_deref(),
        Some("48"),
        "{binary}"
    );
    let count = |out: &str| value(out, "nodes").unwrap().parse::<usize>().unwrap();
    let mut fewer = count(&binary);
    for (nodes, width) in [("bvh4-q8", 4), ("bvh8-q8", 8)] {
        let file = at(&dir, &format!("{nodes}.rtsi"));
        let out = rtfpga(&[
            "scene-image",
            "--scene",
            "utah_teapot",
            "--nodes",
            nodes,
            "--out",
            s(&file),
        ])
        .ok();
        let words: Vec<u32> = std::fs::read(&file)
            .unwrap()
            .chunks_exact(4)
            .map(|w| u32::from_le_bytes(w.try_into().unwrap()))
            .collect();
        assert_eq!(
            value(&out, "bytes"),
            Some((4 * words.len()).to_string()),
            "{out}"
        );
        let image = hw_model::traversal::wide::image::WideImage::from_words(&words).unwrap();
        assert_eq!(image.tree.width, width);
        assert_eq!(count(&out), image.tree.nodes.len(), "{out}");
        assert!(count(&out) < fewer, "{nodes}: {out}");
        fewer = count(&out);
        let node_bytes = 4 * hw_model::traversal::wide::image::node_words(width);
        assert_eq!(value(&out, "node_bytes"), Some(node_bytes.to_string()));
    }
    let chunked = rtfpga(&[
        "scene-image",
        "--scene",
        "utah_teapot",
        "--nodes",
        "bvh8-q8",
        "--scene-memory",
        "100,2000",
    ])
    .ok();
    assert!(
        value(&chunked, "chunks").unwrap().parse::<usize>().unwrap() >= 4,
        "{chunked}"
    );
}
