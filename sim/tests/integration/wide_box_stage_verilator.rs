//! The wide box stage (`hdl::traversal::wide`), Verilated and streamed one node test per cycle
//! (II = 1, `valid_in` low every seventh cycle), bit for bit against
//! `hw_model::traversal::wide::box_test::wide_box_test`, with `valid_out` and the tag
//! following `valid_in` and `tag_in` by `latency(depth)`. The tests are random and adversarial
//! (`hw_model::traversal::wide::cases::random_test`, 20k per width and depth) and the thesis
//! scenes' own: every node test of the rays of a small render of each scene, recorded by
//! descending the scene's wide tree along the model's answers (tests/wide_box_stage.rs in hdl
//! runs the rust-hdl simulation of the same stage at every width and depth).
//! Each width and depth is its own Verilator model, so `make test` builds one — the widest
//! stage at the maximum depth, where the thesis tests run — and the rest of the matrix (nodes
//! of 2, 4 and 8 children at depth 1 and at the maximum, every thesis test at each width) is
//! ignored:
//! `cargo test --release -p sim --test integration wide_box_stage_verilator:: -- --include-ignored --nocapture`

use std::sync::Mutex;

use hdl::traversal::wide::{latency, max_depth, wide_box_stage_verilog, WideInput, WideOutput};
use hw_model::traversal::scene_image::SceneImage;
use hw_model::traversal::wide::box_test::{wide_box_test, NodeEntry, WideRay};
use hw_model::traversal::wide::cases::{random_test, NodeTest};
use hw_model::traversal::wide::image::WideImage;
use hw_model::traversal::wide::{NodeFormat, WideTree};
use hw_model::traversal::UnitRay;
use rand::rngs::StdRng;
use rand::SeedableRng;
use sim::{build, run_pipelined, BuildOptions, ModelSpec};
use sw_renderer::hit::Hit;
use sw_renderer::intersect::F32Intersector;
use sw_renderer::rays::{CastStats, EngineError, Ray, RayCaster, RayEngine};
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;
use sw_renderer::trace::PreparedScene;

/// Node tests per node width and depth.
const RANDOM_TESTS: usize = 20_000;
/// The thesis scenes' renders: pixels across and down.
const RENDER: (u32, u32) = (24, 14);

/// Input and output ports of a stage of `width` children.
const fn input_ports(width: usize) -> usize {
    21 + 7 * width
}
const fn output_ports(width: usize) -> usize {
    3 + 3 * width
}

/// Streams `tests` through the Verilated stage of `width` children at `depth` and checks
/// every answer; returns how many tests entered several children.
fn run<const N: usize, const M: usize>(width: usize, depth: usize, tests: &[NodeTest]) -> usize {
    assert_eq!((N, M), (input_ports(width), output_ports(width)));
    let lat = latency(depth);
    let built = build(
        &ModelSpec::rust_hdl(wide_box_stage_verilog(width, depth)),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut model = built.instantiate();
    let names = |ports: &[sim::verilator::Port]| -> Vec<String> {
        ports.iter().map(|p| p.name.clone()).collect()
    };
    let inputs = names(&model.interface().inputs);
    assert_eq!(inputs.len(), N, "{inputs:?}");
    assert_eq!(
        [&inputs[..3], &inputs[N - 1..]].concat(),
        [
            "valid_in",
            "tag_in",
            "orig$0",
            &format!("link${}", width - 1)
        ]
    );
    let outputs = names(&model.interface().outputs);
    assert_eq!(outputs.len(), M, "{outputs:?}");
    assert_eq!(
        [&outputs[..4], &outputs[M - 1..]].concat(),
        [
            "valid_out",
            "tag_out",
            "entered",
            "entry_link$0",
            &format!("entry_width${}", width - 1)
        ]
    );
    let stream: Vec<WideInput> = tests
        .iter()
        .enumerate()
        .map(|(i, t)| WideInput {
            valid: i % 7 != 6,
            tag: (i as u16).wrapping_mul(0x9E37),
            ray: t.ray,
            node: t.node.clone(),
            at: t.at,
        })
        .collect();
    let words: Vec<[u64; N]> = stream
        .iter()
        .map(|x| x.port_words(width).try_into().unwrap())
        .collect();
    let start = std::time::Instant::now();
    let out: Vec<[u64; M]> = run_pipelined(&mut model, &words, lat).unwrap();
    eprintln!(
        "wide box stage, {width} children, depth {depth} (latency {lat}): {} tests, {:.2} M tests/s",
        tests.len(),
        tests.len() as f64 / start.elapsed().as_secs_f64() / 1e6
    );
    let mut several = 0;
    for (x, o) in stream.iter().zip(&out) {
        let got = WideOutput::from_port_words(o, width);
        assert_eq!(
            (got.valid, got.tag),
            (x.valid, x.tag),
            "width {width} depth {depth}"
        );
        if !x.valid {
            continue;
        }
        let want = WideOutput::of_model(x);
        assert_eq!(
            got.entered, want,
            "width {width} depth {depth}: {x:?}\n stage {got:?}\n model {want:?}"
        );
        several += usize::from(want.len() >= 2);
    }
    several
}

fn run_width(width: usize, depth: usize, tests: &[NodeTest]) -> usize {
    match width {
        2 => run::<{ input_ports(2) }, { output_ports(2) }>(2, depth, tests),
        4 => run::<{ input_ports(4) }, { output_ports(4) }>(4, depth, tests),
        8 => run::<{ input_ports(8) }, { output_ports(8) }>(8, depth, tests),
        _ => unreachable!("a stage for {width} children"),
    }
}

fn random_tests(width: usize, seed: u64) -> Vec<NodeTest> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..RANDOM_TESTS)
        .map(|_| random_test(&mut rng, width))
        .collect()
}

/// The width and depth `make test` checks: the widest stage at the maximum depth.
fn default_configurations() -> [(NodeFormat, usize); 1] {
    [(NodeFormat::Bvh8Q8, max_depth())]
}

/// Every node format with wide nodes at depth 1 and at the maximum.
fn every_configuration() -> Vec<(NodeFormat, usize)> {
    [NodeFormat::Bvh2Q8, NodeFormat::Bvh4Q8, NodeFormat::Bvh8Q8]
        .into_iter()
        .flat_map(|nodes| [(nodes, 1), (nodes, max_depth())])
        .collect()
}

fn check_random_tests(configurations: &[(NodeFormat, usize)]) {
    for &(nodes, depth) in configurations {
        let width = nodes.width().expect("wide nodes");
        let several = run_width(width, depth, &random_tests(width, 40 + width as u64));
        assert!(several > RANDOM_TESTS / 20, "{several} of {RANDOM_TESTS}");
    }
}

#[test]
fn wide_stage_matches_the_model_on_random_tests() {
    check_random_tests(&default_configurations());
}

#[test]
#[ignore = "five more Verilator models: every width at depth 1 and at the maximum"]
fn wide_stage_matches_the_model_on_random_tests_at_every_width_and_depth() {
    check_random_tests(&every_configuration());
}

/// Records every wide node test of the rays it is asked to cast: from the root, each node
/// whose box test entered it, entered where that test said (a descent of every entered
/// child, not the walk's nearest-first order with its shrinking far end: the same kind of
/// tests, more of them); the hits come from the software renderer's caster, so that the
/// render spawns its secondary and shadow rays.
struct Recorder {
    nodes: NodeFormat,
    tests: Mutex<Vec<NodeTest>>,
}

struct RecordingCaster<'a> {
    tree: WideTree,
    hits: Box<dyn RayCaster + 'a>,
    tests: &'a Mutex<Vec<NodeTest>>,
}

impl RayEngine for Recorder {
    fn name(&self) -> String {
        "wide node test recorder".into()
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a PreparedScene,
    ) -> Result<Box<dyn RayCaster + 'a>, EngineError> {
        let width = self.nodes.width().expect("wide nodes");
        let image = WideImage::of(&SceneImage::new(scene), width)
            .expect("the thesis scenes' wide trees are written");
        Ok(Box::new(RecordingCaster {
            tree: image.tree,
            hits: F32Intersector.prepare(scene)?,
            tests: &self.tests,
        }))
    }
}

impl RayCaster for RecordingCaster<'_> {
    fn cast(&self, rays: &[Ray], hits: &mut [Option<Hit>]) -> Result<CastStats, EngineError> {
        let tree = &self.tree;
        let mut tests = Vec::new();
        for ray in rays {
            let r = UnitRay::of(ray, 0);
            let wide = WideRay::new(r.orig, r.dir, r.t_max);
            let mut todo = vec![(tree.root, NodeEntry::ROOT)];
            while let Some((link, at)) = todo.pop() {
                if link.is_leaf() {
                    continue;
                }
                let node = &tree.nodes[link.first as usize];
                for e in wide_box_test(&wide, node, at) {
                    todo.push((node.children[e.slot].link, e.entry));
                }
                tests.push(NodeTest {
                    ray: wide,
                    node: node.clone(),
                    at,
                });
            }
        }
        self.tests.lock().unwrap().extend(tests);
        self.hits.cast(rays, hits)
    }
}

/// Every node test of the thesis scenes' small renders through the stage of each of `formats`
/// at the maximum depth.
fn check_thesis_tests(test: &str, formats: &[NodeFormat]) {
    let Some(root) = thesis_scenes::for_test(test) else {
        return;
    };
    for &nodes in formats {
        let width = nodes.width().expect("wide nodes");
        let recorder = Recorder {
            nodes,
            tests: Mutex::new(Vec::new()),
        };
        for name in thesis_scenes::SCENE_DIRS {
            let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
            let opts = RenderOptions {
                width: Some(RENDER.0),
                height: Some(RENDER.1),
                ..Default::default()
            };
            render(&scene, &recorder, &opts).unwrap();
        }
        let tests = recorder.tests.into_inner().unwrap();
        let several = run_width(width, max_depth(), &tests);
        eprintln!(
            "{}: {} node tests of the thesis scenes, {several} entering several children",
            nodes.name(),
            tests.len()
        );
        assert!(several > tests.len() / 20, "{several} of {}", tests.len());
    }
}

#[test]
fn wide_stage_matches_the_model_on_the_thesis_scenes_node_tests() {
    check_thesis_tests(
        "wide_box_stage_verilator::wide_stage_matches_the_model_on_the_thesis_scenes_node_tests",
        &[NodeFormat::Bvh8Q8],
    );
}

#[test]
#[ignore = "two more Verilator models: the thesis tests through the stages of 2 and 4 children"]
fn wide_stage_matches_the_model_on_the_thesis_scenes_node_tests_at_every_width() {
    check_thesis_tests(
        "wide_box_stage_verilator::wide_stage_matches_the_model_on_the_thesis_scenes_node_tests_at_every_width",
        &[NodeFormat::Bvh2Q8, NodeFormat::Bvh4Q8],
    );
}
