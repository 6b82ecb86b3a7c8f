//! The traversal unit's model against independent references: brute force over every
//! triangle (random meshes and rays, proptest), the software renderer (whole renders of the
//! built-in and the thesis' scenes, fp32 images identical), the same unit in chunked passes
//! against it whole (random meshes and capacities, the thesis' scenes), and its failure
//! modes.

use hw_model::precision::{auto_scale_exp, spawn_policy, SceneRange};
use hw_model::traversal::capacity::{chunks, needs};
use hw_model::traversal::scene_image::{
    ChildBoxes, ImageNode, ImageTriangle, Link, SceneImage, UnitImage,
};
use hw_model::traversal::strategies::{mesh, ray};
use hw_model::traversal::{
    ChunkedModel, NodeFormat, SceneCapacity, SceneMemory, TraversalEngine, TraversalError,
    TraversalModel, UnitCounters, UnitRay,
};
use hw_model::{lookup, mt_model, Advance, Format, ModelIntersector};
use proptest::prelude::*;
use sw_renderer::bvh::Bvh;
use sw_renderer::compare::compare;
use sw_renderer::hit::{closest_hit, Hit, Window, NO_BOUND};
use sw_renderer::intersect::{F32Intersector, MtQuery};
use sw_renderer::math::V3;
use sw_renderer::render::{render, RenderError, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;
use sw_renderer::world::WorldTriangle;

fn fp32() -> Format {
    lookup("fp32").unwrap()
}

/// The reference: every triangle tested (shadow rays only shadow casters), reduced by the
/// renderer's rule (its window: `t_min`, `t_max`, the excluded triangle).
fn brute_force(
    format: &Format,
    tris: &[WorldTriangle],
    casts: &[bool],
    ray: &UnitRay,
) -> Option<Hit> {
    let (cands, results): (Vec<u32>, Vec<_>) = tris
        .iter()
        .enumerate()
        .filter(|(k, _)| !ray.any_hit || casts[*k])
        .map(|(k, t)| {
            let q = MtQuery {
                orig: ray.orig,
                dir: ray.dir,
                v0: t.verts[0].to_array(),
                v1: t.verts[1].to_array(),
                v2: t.verts[2].to_array(),
                t_min: ray.t_min,
            };
            (k as u32, mt_model(format, &q))
        })
        .unzip();
    let window = Window {
        t_min: ray.t_min,
        bound: ray.t_max,
        exclude: ray.exclude,
    };
    closest_hit(&cands, &results, &window)
}

/// A model holding `tris` (objects of 8 triangles; odd objects cast no shadow), with the
/// renderer's BVH, through the image's word stream, walking it in `nodes`.
fn unit_in(
    tris: &[WorldTriangle],
    format: Format,
    stack: usize,
    nodes: NodeFormat,
) -> (TraversalModel, Vec<bool>) {
    let casts: Vec<bool> = tris.iter().map(|t| t.object % 2 == 0).collect();
    let image = SceneImage::from_bvh(&Bvh::build(tris), tris, &casts);
    let image = SceneImage::from_words(&image.to_words()).unwrap();
    let unit = TraversalModel::new(format, stack, image)
        .with_nodes(nodes)
        .unwrap();
    (unit, casts)
}

fn unit(tris: &[WorldTriangle], format: Format, stack: usize) -> (TraversalModel, Vec<bool>) {
    unit_in(tris, format, stack, NodeFormat::Bvh2Fp32)
}

/// `tris` and `rays` scaled by `2^k` (directions unchanged): a tiny or a huge scene.
fn scaled(tris: &[WorldTriangle], rays: &[UnitRay], k: i32) -> (Vec<WorldTriangle>, Vec<UnitRay>) {
    let s = 2f32.powi(k);
    let tris = tris
        .iter()
        .map(|t| WorldTriangle {
            verts: t.verts.map(|v| v * s),
            ..*t
        })
        .collect();
    let rays = rays
        .iter()
        .map(|r| UnitRay {
            orig: r.orig.map(|x| x * s),
            t_max: r.t_max * s,
            t_min: r.t_min * s,
            ..*r
        })
        .collect();
    (tris, rays)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// fp32, in every node format: the unit's answer is the brute-force answer (closest-hit:
    /// the same hit, bit for bit; any-hit: occluded exactly when brute force finds a hit), in
    /// scenes of ordinary, tiny and huge size.
    #[test]
    fn fp32_answers_equal_brute_force(
        tris in mesh(),
        rays in prop::collection::vec(ray(), 1..24),
        scale in prop_oneof![Just(0), -100i32..-20, 20i32..100],
    ) {
        let (tris, rays) = scaled(&tris, &rays, scale);
        for nodes in NodeFormat::ALL {
            let (unit, casts) = unit_in(&tris, fp32(), 64, nodes);
            for r in &rays {
                let mut counters = UnitCounters::default();
                let got = unit.trace(r, &mut counters).unwrap();
                let want = brute_force(&fp32(), &tris, &casts, r);
                if r.any_hit {
                    prop_assert_eq!(got.is_some(), want.is_some(), "{} {:?}", nodes.name(), r);
                } else {
                    prop_assert_eq!(got, want, "{} {:?}", nodes.name(), r);
                }
                prop_assert!(counters.mt_tests <= tris.len() as u64);
            }
        }
    }
}

#[test]
fn rays_with_nan_or_infinite_components_end_as_misses_like_the_software() {
    let tris: Vec<WorldTriangle> = (0..50)
        .map(|k| WorldTriangle {
            verts: [
                V3::new(k as f32, 0.0, 0.0),
                V3::new(k as f32 + 1.0, 0.0, 0.0),
                V3::new(k as f32, 1.0, 0.0),
            ],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: 0,
        })
        .collect();
    let (nan, inf) = (f32::NAN, f32::INFINITY);
    for nodes in NodeFormat::ALL {
        let (unit, casts) = unit_in(&tris, fp32(), 64, nodes);
        for (orig, dir, t_max) in [
            ([nan, 0.2, 1.0], [0.0, 0.0, -1.0], NO_BOUND),
            ([0.2, 0.2, 1.0], [nan, 0.0, -1.0], NO_BOUND),
            ([inf, 0.2, 1.0], [0.0, 0.0, -1.0], NO_BOUND),
            ([0.2, 0.2, 1.0], [0.0, 0.0, -inf], NO_BOUND),
            ([0.2, 0.2, 1.0], [0.0, 0.0, -1.0], nan),
            ([0.2, 0.2, 1.0], [0.0, 0.0, 0.0], NO_BOUND),
        ] {
            for any_hit in [false, true] {
                let r = UnitRay {
                    orig,
                    dir,
                    t_max,
                    any_hit,
                    id: 7,
                    ..UnitRay::default()
                };
                let got = unit.trace(&r, &mut UnitCounters::default()).unwrap();
                assert_eq!(
                    got,
                    brute_force(&fp32(), &tris, &casts, &r),
                    "{} {r:?}",
                    nodes.name()
                );
            }
        }
    }
}

#[test]
fn t_min_and_the_excluded_triangle_remove_hits_and_exclusion_saves_its_test() {
    // Two stacked triangles under the ray, at t = 1 (index 0) and t = 2 (index 1).
    let tri = |z: f32| WorldTriangle {
        verts: [
            V3::new(0.0, 0.0, z),
            V3::new(1.0, 0.0, z),
            V3::new(0.0, 1.0, z),
        ],
        normals: [V3::new(0.0, 0.0, 1.0); 3],
        object: 0,
    };
    for nodes in NodeFormat::ALL {
        let (unit, _) = unit_in(&[tri(0.0), tri(-1.0)], fp32(), 64, nodes);
        let trace = |t_min, exclude, any_hit| {
            let r = UnitRay {
                orig: [0.25, 0.25, 1.0],
                dir: [0.0, 0.0, -1.0],
                t_max: NO_BOUND,
                t_min,
                exclude,
                any_hit,
                id: 0,
            };
            let mut counters = UnitCounters::default();
            let hit = unit.trace(&r, &mut counters).unwrap().map(|h| h.triangle);
            (hit, counters.mt_tests)
        };
        assert_eq!(trace(0.0, None, false), (Some(0), 2));
        assert_eq!(trace(1.0, None, false).0, Some(1), "t = t_min is a miss");
        assert_eq!(trace(2.0, None, false).0, None);
        assert_eq!(trace(0.0, Some(0), false), (Some(1), 1));
        assert_eq!(trace(0.0, Some(1), true).0, Some(0));
        assert_eq!(trace(1.5, Some(1), true).0, None);
    }
}

#[test]
fn a_stack_too_small_for_the_walk_is_an_error_naming_the_ray_and_sizes() {
    let tris: Vec<WorldTriangle> = (0..256)
        .map(|k| {
            let x = (k % 16) as f32;
            let y = (k / 16) as f32;
            WorldTriangle {
                verts: [
                    V3::new(x, y, 0.0),
                    V3::new(x + 0.9, y, 0.0),
                    V3::new(x, y + 0.9, 0.0),
                ],
                normals: [V3::new(0.0, 0.0, 1.0); 3],
                object: 0,
            }
        })
        .collect();
    for nodes in NodeFormat::ALL {
        let (unit, _) = unit_in(&tris, fp32(), 1, nodes);
        // A grazing ray along the grid enters many boxes at once.
        let r = UnitRay {
            orig: [-1.0, 0.3, 0.0],
            dir: [1.0, 0.4, 0.0],
            t_max: NO_BOUND,
            any_hit: false,
            id: 42,
            ..UnitRay::default()
        };
        let e = unit.trace(&r, &mut UnitCounters::default()).unwrap_err();
        assert!(matches!(
            e,
            TraversalError::StackOverflow {
                id: 42,
                capacity: 1,
                ..
            }
        ));
        let text = e.to_string();
        assert!(
            text.contains("ray 42") && text.contains("more than 1 entries"),
            "{text}"
        );
    }
}

fn small(
    scene: &Scene,
    engine: &dyn sw_renderer::rays::RayEngine,
    w: u32,
    h: u32,
) -> image::RgbImage {
    let opts = RenderOptions {
        width: Some(w),
        height: Some(h),
        ..Default::default()
    };
    render(scene, engine, &opts).unwrap().image
}

#[test]
fn fp32_renders_of_the_builtin_scenes_equal_the_software() {
    let engine = TraversalEngine {
        format: fp32(),
        stack_depth: 64,
        scale_exp: 0,
        advance: Advance::None,
        timing: None,
        memory: SceneMemory::Unbounded,
        nodes: NodeFormat::Bvh2Fp32,
    };
    for nodes in NodeFormat::ALL {
        let engine = TraversalEngine { nodes, ..engine };
        for name in sw_renderer::scene::builtin::names() {
            let scene = Scene::load(name).unwrap();
            let diff = compare(
                &small(&scene, &engine, 64, 36),
                &small(&scene, &F32Intersector, 64, 36),
            )
            .unwrap();
            assert_eq!(
                diff.differing_pixels,
                0,
                "{name} {}: {diff:?}",
                nodes.name()
            );
        }
    }
}

#[test]
fn fp32_renders_of_the_thesis_scenes_equal_the_software() {
    let Some(root) =
        thesis_scenes::for_test("traversal::fp32_renders_of_the_thesis_scenes_equal_the_software")
    else {
        return;
    };
    let engine = TraversalEngine {
        format: fp32(),
        stack_depth: 64,
        scale_exp: 0,
        advance: Advance::None,
        timing: None,
        memory: SceneMemory::Unbounded,
        nodes: NodeFormat::Bvh2Fp32,
    };
    for nodes in NodeFormat::ALL {
        let engine = TraversalEngine { nodes, ..engine };
        for name in thesis_scenes::SCENE_DIRS {
            let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
            let diff = compare(
                &small(&scene, &engine, 48, 27),
                &small(&scene, &F32Intersector, 48, 27),
            )
            .unwrap();
            assert_eq!(
                diff.differing_pixels,
                0,
                "{name} {}: {diff:?}",
                nodes.name()
            );
        }
    }
}

#[test]
fn a_render_whose_stack_overflows_fails_with_the_engines_error() {
    let scene = Scene::load("utah_teapot").unwrap();
    let engine = TraversalEngine {
        format: fp32(),
        stack_depth: 2,
        scale_exp: 0,
        advance: Advance::None,
        timing: None,
        memory: SceneMemory::Unbounded,
        nodes: NodeFormat::Bvh2Fp32,
    };
    let opts = RenderOptions {
        width: Some(16),
        height: Some(9),
        ..Default::default()
    };
    let e = render(&scene, &engine, &opts).unwrap_err();
    assert!(matches!(e, RenderError::Engine { .. }));
    assert!(e.to_string().contains("traversal stack overflow"), "{e}");
}

/// Format-aware spawning (t_min, exclusion) and scaling answer the same in the unit's model
/// as through the software BVH and the model intersector: both reduce with `hit::Window`.
#[test]
fn format_aware_renders_equal_the_bvh_path_in_a_narrow_scaled_format() {
    let fp16 = lookup("fp16").unwrap();
    for name in ["simple_plane", "glasses", "utah_teapot"] {
        let scene = Scene::load(name).unwrap();
        let scale_exp = auto_scale_exp(&fp16, &SceneRange::of(&scene).unwrap());
        let opts = RenderOptions {
            width: Some(48),
            height: Some(27),
            spawn: spawn_policy(&fp16, scale_exp),
            ..Default::default()
        };
        let unit = TraversalEngine {
            format: fp16,
            stack_depth: 64,
            scale_exp,
            advance: Advance::None,
            timing: None,
            memory: SceneMemory::Unbounded,
            nodes: NodeFormat::Bvh2Fp32,
        };
        let bvh = ModelIntersector {
            scale_exp,
            ..ModelIntersector::new(fp16)
        };
        let a = render(&scene, &unit, &opts).unwrap().image;
        let b = render(&scene, &bvh, &opts).unwrap().image;
        let diff = compare(&a, &b).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{name}: {diff:?}");
    }
}

// ---- scenes larger than the unit's scene memory: chunked passes ---------------------------

/// A capacity from a few units of the mesh's largest leaf (so most meshes split, some
/// fit whole) and up to 12 inner nodes.
fn capacity() -> impl Strategy<Value = (u32, u32, u32)> {
    (0u32..12, 0u32..4, 0u32..6)
}

fn largest_leaf(image: &SceneImage) -> u32 {
    let root = std::iter::once(image.root);
    (root.chain(image.nodes.iter().flat_map(|n| n.child)))
        .filter(|l| l.is_leaf())
        .map(|l| l.count)
        .max()
        .unwrap_or(0)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Chunks fit, load through the checking loader, hold every triangle record once with its
    /// global index; and the chunked unit answers as the unchunked one: closest-hit rays the
    /// same hit bit for bit, any-hit rays occluded exactly when it is (by a counting,
    /// shadow-casting triangle).
    #[test]
    fn chunked_passes_answer_as_the_whole_scene(
        tris in mesh(),
        rays in prop::collection::vec(ray(), 1..24),
        (nodes, leaf_units, extra) in capacity(),
    ) {
        let (whole, casts) = unit(&tris, fp32(), 64);
        let UnitImage::Binary(image) = whole.image() else { unreachable!("a binary unit") };
        let cap = SceneCapacity { nodes, triangles: largest_leaf(image) * leaf_units.max(1) + extra };
        let parts = chunks(image, SceneMemory::Chunked(cap), NodeFormat::Bvh2Fp32).unwrap();
        let fits = cap.holds(SceneCapacity::of(image));
        prop_assert_eq!(parts.len() == 1, fits);
        let mut indices = Vec::new();
        for c in &parts {
            prop_assert!(cap.holds(SceneCapacity::of(c)));
            prop_assert_eq!(&SceneImage::from_words(&c.to_words()).unwrap(), c);
            indices.extend(c.triangles.iter().map(|t| t.index));
        }
        indices.sort_unstable();
        prop_assert_eq!(indices, (0..tris.len() as u32).collect::<Vec<_>>());

        let chunked = ChunkedModel::new(fp32(), 64, 0, image, SceneMemory::Chunked(cap), NodeFormat::Bvh2Fp32).unwrap();
        prop_assert_eq!(chunked.chunks().len(), parts.len());
        for r in &rays {
            let want = whole.trace(r, &mut UnitCounters::default()).unwrap();
            let mut counters = UnitCounters::default();
            let got = chunked.trace(r, &mut counters).unwrap();
            if r.any_hit {
                prop_assert_eq!(got.is_some(), want.is_some(), "{:?}", r);
                if let Some(h) = got {
                    prop_assert!(casts[h.triangle as usize] && r.window().counts(h.triangle, &mt_model(&fp32(), &MtQuery {
                        orig: r.orig,
                        dir: r.dir,
                        v0: tris[h.triangle as usize].verts[0].to_array(),
                        v1: tris[h.triangle as usize].verts[1].to_array(),
                        v2: tris[h.triangle as usize].verts[2].to_array(),
                        t_min: r.t_min,
                    })), "{:?}: {:?}", r, h);
                }
            } else {
                prop_assert_eq!(got, want, "{:?}", r);
                // Every pass walks the ray.
                prop_assert_eq!(counters.rays, parts.len() as u64);
            }
        }

        // Chunks of wide nodes: each holds its wide nodes within the capacity (a leaf chunk
        // takes one node), and the answers are the whole scene's.
        for nodes in [NodeFormat::Bvh4Q8, NodeFormat::Bvh8Q8] {
            let cap = SceneCapacity { nodes: cap.nodes.max(1), ..cap };
            let parts = chunks(image, SceneMemory::Chunked(cap), nodes).unwrap();
            for c in &parts {
                prop_assert!(cap.holds(needs(c, nodes)), "{} {:?}", nodes.name(), needs(c, nodes));
            }
            let chunked = ChunkedModel::new(fp32(), 64, 0, image, SceneMemory::Chunked(cap), nodes).unwrap();
            for r in rays.iter().filter(|r| !r.any_hit) {
                let want = whole.trace(r, &mut UnitCounters::default()).unwrap();
                let got = chunked.trace(r, &mut UnitCounters::default()).unwrap();
                prop_assert_eq!(got, want, "{} {:?}", nodes.name(), r);
            }
        }

        // With the leaf advance in a narrow format a chunk's leaf is entered at the distance
        // the whole scene's walk enters it (a chunk's root box is its subtree's box), so the
        // answers stay the whole scene's.
        let e5m14: Format = "e5m14".parse().unwrap();
        let whole = TraversalModel::new(e5m14, 64, image.clone()).advanced(Advance::LeafBox);
        let chunked = ChunkedModel::new(e5m14, 64, 0, image, SceneMemory::Chunked(cap), NodeFormat::Bvh2Fp32)
            .unwrap()
            .advanced(Advance::LeafBox);
        for r in &rays {
            let want = whole.trace(r, &mut UnitCounters::default()).unwrap();
            let got = chunked.trace(r, &mut UnitCounters::default()).unwrap();
            if r.any_hit {
                prop_assert_eq!(got.is_some(), want.is_some(), "leaf-box {:?}", r);
            } else {
                prop_assert_eq!(got, want, "leaf-box {:?}", r);
            }
        }
    }
}

/// Two records of one triangle (equal t) in two chunks, the lower global index in the
/// later one: the carried t_max must still let it win, as the unchunked walk does.
#[test]
fn an_equally_near_hit_with_a_lower_index_in_a_later_chunk_wins() {
    let tri = |index| ImageTriangle {
        verts: [[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 1.0, 2.0]],
        index,
        casts_shadow: true,
    };
    let b = [-1.5f32, 2.5];
    let boxes = ChildBoxes {
        min: [[b[0]; 2]; 3],
        max: [[b[1]; 2]; 3],
    };
    let image = SceneImage {
        root: Link { first: 0, count: 0 },
        root_box: ([b[0]; 3], [b[1]; 3]),
        nodes: vec![ImageNode {
            boxes,
            child: [Link { first: 0, count: 1 }, Link { first: 1, count: 1 }],
        }],
        triangles: vec![tri(1), tri(0)],
        scene_triangles: 2,
    };
    let ray = UnitRay {
        orig: [0.0, 0.0, 0.0],
        dir: [0.0, 0.0, 1.0],
        t_max: NO_BOUND,
        ..UnitRay::default()
    };
    let whole = TraversalModel::new(fp32(), 8, image.clone());
    let want = whole.trace(&ray, &mut UnitCounters::default()).unwrap();
    assert_eq!(want.map(|h| (h.triangle, h.t)), Some((0, 2.0)));
    let cap = SceneCapacity {
        nodes: 0,
        triangles: 1,
    };
    let chunked = ChunkedModel::new(
        fp32(),
        8,
        0,
        &image,
        SceneMemory::Chunked(cap),
        NodeFormat::Bvh2Fp32,
    )
    .unwrap();
    assert_eq!(chunked.chunks().len(), 2);
    assert_eq!(chunked.chunks()[0].image().triangles()[0].index, 1);
    assert_eq!(
        chunked.trace(&ray, &mut UnitCounters::default()).unwrap(),
        want
    );
}

/// A unit that cannot hold a scene says what the scene needs and what it holds.
#[test]
fn a_scene_the_unit_cannot_hold_is_an_error_naming_the_sizes() {
    let scene = Scene::load("utah_teapot").unwrap();
    let prepared = sw_renderer::trace::PreparedScene::new(&scene).unwrap();
    let need = SceneCapacity::of(&SceneImage::new(&prepared));
    let holds = SceneCapacity {
        nodes: 2048,
        triangles: 4096,
    };
    let engine = fp32_unit;
    let opts = RenderOptions {
        width: Some(8),
        height: Some(6),
        ..Default::default()
    };
    let e = render(&scene, &engine(SceneMemory::Whole(holds)), &opts).unwrap_err();
    assert!(matches!(e, RenderError::Engine { .. }));
    let msg = format!(
        "scene needs {need}; this unit holds 2,048 nodes and 4,096 triangles; chunked passes are disabled"
    );
    assert!(e.to_string().contains(&msg), "{e}");
    assert!(msg.contains(&format!("{} triangles", thousand(need.triangles))));
    let tiny = SceneCapacity {
        nodes: 100,
        triangles: 1,
    };
    let e = render(&scene, &engine(SceneMemory::Chunked(tiny)), &opts).unwrap_err();
    assert!(
        e.to_string()
            .contains("this unit holds 100 nodes and 1 triangles; its BVH has a leaf of"),
        "{e}"
    );
    let none = SceneCapacity::default();
    let e = render(&scene, &engine(SceneMemory::Chunked(none)), &opts).unwrap_err();
    assert!(
        e.to_string().contains("holds 0 nodes and 0 triangles"),
        "{e}"
    );
}

/// "6322" as "6,322", independently of the library's formatting.
fn thousand(n: u32) -> String {
    match n {
        0..=999 => n.to_string(),
        _ => format!("{},{:03}", thousand(n / 1000), n % 1000),
    }
}

/// Whole renders: every thesis scene through a unit whose memory holds a third of the
/// scene (at least 3 chunks where the scene has more than one leaf) equals the unchunked
/// render, and reports its passes and chunk loads.
#[test]
fn chunked_renders_of_the_thesis_scenes_equal_the_unchunked_unit() {
    let Some(root) = thesis_scenes::for_test(
        "traversal::chunked_renders_of_the_thesis_scenes_equal_the_unchunked_unit",
    ) else {
        return;
    };
    let engine = fp32_unit;
    let opts = RenderOptions {
        width: Some(64),
        height: Some(36),
        ..Default::default()
    };
    for name in thesis_scenes::SCENE_DIRS {
        let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
        let prepared = sw_renderer::trace::PreparedScene::new(&scene).unwrap();
        let image = SceneImage::new(&prepared);
        let need = SceneCapacity::of(&image);
        let third = SceneCapacity {
            nodes: need.nodes / 3,
            triangles: (need.triangles / 3).max(largest_leaf(&image)),
        };
        let memory = SceneMemory::Chunked(third);
        let parts = chunks(&image, memory, NodeFormat::Bvh2Fp32).unwrap().len();
        if need.nodes > 0 {
            assert!(parts >= 3, "{name}: {parts} chunks");
        }
        let whole = render(&scene, &engine(SceneMemory::Unbounded), &opts).unwrap();
        let chunked = render(&scene, &engine(memory), &opts).unwrap();
        let diff = compare(&chunked.image, &whole.image).unwrap();
        assert_eq!(diff.differing_pixels, 0, "{name}: {diff:?}");
        let (c, w) = (chunked.stats.trace.cast, whole.stats.trace.cast);
        assert_eq!(w.chunk_loads, 0, "{name}: a resident scene is loaded once");
        assert_eq!(w.passes, w.batches, "{name}");
        if parts > 1 {
            assert!(c.chunk_loads >= c.batches && c.chunk_loads <= c.batches * parts as u64);
            assert!(c.loaded_bytes >= c.chunk_loads * 64, "{name}: {c:?}");
            assert!(c.ray_passes > w.ray_passes, "{name}: {c:?}");
        }
    }
}

/// The fp32 unit, untimed, with stacks deep enough for any BVH, holding scenes in `memory`.
fn fp32_unit(memory: SceneMemory) -> TraversalEngine {
    TraversalEngine {
        format: fp32(),
        stack_depth: 64,
        scale_exp: 0,
        advance: Advance::None,
        timing: None,
        memory,
        nodes: NodeFormat::Bvh2Fp32,
    }
}
