use hw_model::traversal::schedule::UnitTiming;
use hw_model::traversal::{NodeFormat, SceneMemory, TraversalEngine};
use hw_model::{lookup, Advance};
use sw_renderer::compare::compare;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;

#[test]
#[ignore]
fn explore() {
    let w: u32 = std::env::var("W")
        .map(|s| s.parse().unwrap())
        .unwrap_or(160);
    let h = w * 9 / 16;
    let boxlat: u64 = std::env::var("BOXLAT")
        .map(|s| s.parse().unwrap())
        .unwrap_or(0);
    let root = std::path::Path::new("/work/shared/scenes/thesis");
    let all = [
        "Utah_teapot_scene",
        "Glass_pen_scene",
        "Glasses_scene",
        "Glasses_point_scene",
        "Simple_plane_scene",
        "All_materials_scene",
    ];
    let only = std::env::var("SCENES").unwrap_or_default();
    let scenes: Vec<&str> = all
        .into_iter()
        .filter(|s| only.is_empty() || only.split(',').any(|o| s.starts_with(o)))
        .collect();
    let formats: Vec<NodeFormat> = std::env::var("NODES")
        .map(|n| n.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(NodeFormat::ALL.to_vec());
    for name in scenes {
        let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
        let opts = RenderOptions {
            width: Some(w),
            height: Some(h),
            ..Default::default()
        };
        let reference = render(&scene, &F32Intersector, &opts).unwrap().image;
        for &nodes in &formats {
            let wide = nodes.width().is_some();
            let slots: usize = std::env::var("SLOTS")
                .map(|s| s.parse().unwrap())
                .unwrap_or(32);
            let box_ports: usize = std::env::var("PORTS")
                .map(|s| s.parse().unwrap())
                .unwrap_or(1);
            let timing = UnitTiming {
                slots,
                lanes: 1,
                box_ports,
                setup_latency: 14,
                box_latency: if wide { 15 + boxlat } else { 15 },
                mt_latency: 56,
                pop_latency: 3,
            };
            let engine = TraversalEngine {
                format: lookup("fp32").unwrap(),
                stack_depth: std::env::var("STACK")
                    .map(|s| s.parse().unwrap())
                    .unwrap_or(64),
                scale_exp: 0,
                advance: Advance::None,
                timing: Some(timing),
                memory: SceneMemory::Unbounded,
                nodes,
            };
            let out = render(&scene, &engine, &opts).unwrap();
            let c = out.stats.trace.cast;
            let rays = out.stats.trace.rays() as f64;
            let diff = compare(&out.image, &reference).unwrap();
            println!("{name:22} {:9} box/ray {:6.2} visits/ray {:6.2} mt/ray {:5.2} cycles/ray {:6.2} diff {}", nodes.name(), c.box_tests as f64 / rays, c.node_visits as f64 / rays, c.mt_tests as f64 / rays, c.cycles as f64 / rays, diff.differing_pixels);
        }
    }
}
