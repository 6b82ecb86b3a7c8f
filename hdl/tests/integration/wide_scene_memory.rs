//! The wide scene memory in rust-hdl's simulator: wide images (version 3) of a random mesh and
//! the built-in Simple plane streamed with random `tvalid` gaps and read back through the node
//! and triangle ports field for field against the image, for 4- and 8-wide nodes; each
//! malformed image refused with its error code, word and value and the packet drained; random
//! one-word corruptions judged as the software loader (`WideImage::from_words`) judges them;
//! the driver's whole-image checks.

use hdl::traversal::scene_memory::{LoadError, VERTEX_BITS};
use hdl::traversal::scene_memory_driver::{
    check_before_load_wide, status_result_in, LoadStatus, MemoryConfig, NodeLayout,
    SceneMemoryError,
};
use hdl::traversal::wide_scene_memory::{
    WideSceneMemory, WideSceneMemory4w4x5, WideSceneMemory8w11x13, WideSceneMemory8w4x5,
};
use hdl::verilog::verilator_lint;
use hw_model::traversal::scene_image::Link;
use hw_model::traversal::scene_image::{
    SceneImage, SceneImageError, HEADER_WORDS, TRIANGLE_WORDS, VERSION,
};
use hw_model::traversal::wide::image::{link_word, node_words, WideImage};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::bvh::Bvh;
use sw_renderer::math::V3;
use sw_renderer::scene::Scene;
use sw_renderer::trace::PreparedScene;
use sw_renderer::world::WorldTriangle;

const CONFIG: MemoryConfig = MemoryConfig {
    node_bits: 4,
    triangle_bits: 5,
};

struct Bench<
    const NB: usize,
    const TB: usize,
    const LF: usize,
    const LK: usize,
    const HB: usize,
    const LB: usize,
    const NW: usize,
    const TW: usize,
> {
    uut: WideSceneMemory<NB, TB, LF, LK, HB, LB, NW, TW>,
    width: usize,
    rng: StdRng,
    /// Chance of an idle cycle before each beat.
    gap: f64,
}

impl<
        const NB: usize,
        const TB: usize,
        const LF: usize,
        const LK: usize,
        const HB: usize,
        const LB: usize,
        const NW: usize,
        const TW: usize,
    > Bench<NB, TB, LF, LK, HB, LB, NW, TW>
{
    fn new(width: usize, seed: u64, gap: f64) -> Self {
        let mut uut = WideSceneMemory::new(width, 1);
        uut.connect_all();
        let mut bench = Bench {
            uut,
            width,
            rng: StdRng::seed_from_u64(seed),
            gap,
        };
        bench.idle();
        bench
    }

    scene_loader_methods!();

    /// Reads every node and triangle back: each field equals the image's (a node's read port
    /// gives its words as the box stage takes them, the links as `first` with `count` above).
    fn read_back(&mut self, words: &[u32]) {
        let image = WideImage::from_words(words).unwrap();
        let (n, t) = (image.tree.nodes.len(), image.triangles.len());
        let s = self.status();
        assert_eq!((s.nodes as usize, s.triangles as usize), (n, t));
        let width = self.width;
        for (k, node) in image.tree.nodes.iter().enumerate() {
            self.uut.node_address.next = (k as u64).into();
            self.sample_after_edge();
            let u = &self.uut;
            let origin: Vec<u32> = (0..3).map(|a| u.origin[a].val().to_u64() as u32).collect();
            assert_eq!(origin, node.origin.map(f32::to_bits), "node {k}");
            let exp: Vec<i8> = (0..3)
                .map(|a| u.exp[a].val().to_u64() as u8 as i8)
                .collect();
            assert_eq!(exp, node.exp, "node {k}");
            assert_eq!(u.children.val().to_u64() as usize, node.children.len());
            for c in 0..width {
                let child = node.children.get(c).copied().unwrap_or_default();
                for a in 0..3 {
                    assert_eq!(u.lo[3 * c + a].val().to_u64() as u8, child.lo[a], "{k}/{c}");
                    assert_eq!(u.hi[3 * c + a].val().to_u64() as u8, child.hi[a], "{k}/{c}");
                }
                let link = u.link[c].val().to_u64();
                let got = Link {
                    first: (link & ((1 << LF) - 1)) as u32,
                    count: (link >> LF) as u32,
                };
                assert_eq!(link_word(got), link_word(child.link), "node {k} child {c}");
            }
        }
        let node_end = HEADER_WORDS + node_words(width) * n;
        for k in 0..t {
            self.uut.triangle_address[0].next = (k as u64).into();
            self.sample_after_edge();
            let at = node_end + TRIANGLE_WORDS * k;
            let vertices = self.uut.vertices[0].val();
            let mut got: Vec<u32> = (0..VERTEX_BITS / 32)
                .map(|i| vertices.get_bits::<32>(32 * i).to_u64() as u32)
                .collect();
            got.push(self.uut.global_index[0].val().to_u64() as u32);
            got.push(u32::from(self.uut.casts_shadow[0].val()));
            assert_eq!(got, words[at..at + 11], "triangle record {k}");
        }
    }
}

/// The binary image of a random mesh of 28 triangles (odd objects cast no shadow) with the
/// renderer's BVH.
fn mesh() -> SceneImage {
    let mut rng = StdRng::seed_from_u64(5);
    let mut v = || {
        V3::new(
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
            rng.gen_range(-4.0..4.0),
        )
    };
    let tris: Vec<WorldTriangle> = (0..28)
        .map(|k| WorldTriangle {
            verts: [v(), v(), v()],
            normals: [V3::new(0.0, 0.0, 1.0); 3],
            object: k / 4,
        })
        .collect();
    let casts: Vec<bool> = tris.iter().map(|t| t.object % 2 == 0).collect();
    SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts)
}

/// The wide image's words of `image` at `width`.
fn wide(image: &SceneImage, width: usize) -> Vec<u32> {
    let words = WideImage::of(image, width).unwrap().to_words();
    assert!(
        words[2] >= 2,
        "{width}-wide mesh of {} nodes: no tree",
        words[2]
    );
    words
}

fn simple_plane() -> SceneImage {
    let scene = Scene::load("simple_plane").unwrap();
    SceneImage::new(&PreparedScene::new(&scene).unwrap())
}

fn last(words: &[u32]) -> Option<usize> {
    Some(words.len() - 1)
}

fn with(words: &[u32], i: usize, value: u32) -> Vec<u32> {
    let mut w = words.to_vec();
    w[i] = value;
    w
}

/// Loads the mesh, the plane and the empty scene at `width` and reads them back.
macro_rules! loads_and_reads_back {
    ($memory:ty, $width:literal) => {{
        let mut bench = Bench::new($width, 1, 0.3);
        let _: &$memory = &bench.uut;
        let layout = NodeLayout::Wide($width);
        for binary in [mesh(), simple_plane()] {
            let words = WideImage::of(&binary, $width).unwrap().to_words();
            check_before_load_wide(&words, CONFIG, $width).unwrap();
            let status = bench.load(&words, last(&words));
            status_result_in(&status, &words, CONFIG, layout).unwrap();
            assert!(status.loaded && !status.loading, "{status:?}");
            assert!(!bench.cycle(), "s_tready must be low once loaded");
            bench.read_back(&words);
        }
        let empty = SceneImage::from_bvh(&Bvh::build(&[]), &[], &[]);
        let words = WideImage::of(&empty, $width).unwrap().to_words();
        let status = bench.load(&words, last(&words));
        status_result_in(&status, &words, CONFIG, layout).unwrap();
        // Back to back, one word a cycle.
        bench.gap = 0.0;
        let words = wide(&mesh(), $width);
        let status = bench.load(&words, last(&words));
        status_result_in(&status, &words, CONFIG, layout).unwrap();
        bench.read_back(&words);
    }};
}

#[test]
fn four_wide_images_load_and_read_back_field_for_field() {
    loads_and_reads_back!(WideSceneMemory4w4x5, 4);
}

#[test]
fn eight_wide_images_load_and_read_back_field_for_field() {
    loads_and_reads_back!(WideSceneMemory8w4x5, 8);
}

/// A malformed image: its words, the beat with `tlast`, the error, its word and value, and
/// words of the driver's message.
type Case = (Vec<u32>, usize, LoadError, usize, u32, &'static str);

#[test]
fn malformed_wide_images_are_refused_with_their_code_word_and_value() {
    const WIDTH: usize = 4;
    let mesh = wide(&mesh(), WIDTH);
    let image = WideImage::from_words(&mesh).unwrap();
    let (n, t) = (mesh[2] as usize, mesh[3] as usize);
    let words = node_words(WIDTH);
    let node = |k: usize, w: usize| HEADER_WORDS + words * k + w;
    let links = words - WIDTH;
    let tri = |k: usize, w: usize| node(n, 0) + TRIANGLE_WORDS * k + w;
    // A node with a free slot, an inner child and a leaf child.
    let nodes = &image.tree.nodes;
    let short = nodes.iter().position(|x| x.children.len() < WIDTH).unwrap();
    let used = nodes[short].children.len();
    let inner = (0..n)
        .flat_map(|k| (0..nodes[k].children.len()).map(move |c| (k, c)))
        .find(|&(k, c)| !nodes[k].children[c].link.is_leaf())
        .unwrap();
    let leaf = (0..n)
        .flat_map(|k| (0..nodes[k].children.len()).map(move |c| (k, c)))
        .find(|&(k, c)| nodes[k].children[c].link.is_leaf())
        .unwrap();
    // A leaf of 4 ending one beyond the triangles.
    let long_leaf = link_word(Link {
        first: t as u32 - 3,
        count: 4,
    });
    let count_word = |k: usize, count: u32| (mesh[node(k, 3)] & 0x00FF_FFFF) | count << 24;
    // The first code byte beyond the used children's, and its word.
    let unused_byte = 6 * used;
    let unused_code = node(short, 4 + unused_byte / 4);
    let unused_value = mesh[unused_code] | 1 << (8 * (unused_byte % 4));
    let cases: Vec<Case> = vec![
        (
            with(&mesh, 0, 0xDEAD),
            mesh.len() - 1,
            LoadError::BadMagic,
            0,
            0xDEAD,
            "magic",
        ),
        (
            with(&mesh, 1, VERSION),
            mesh.len() - 1,
            LoadError::BadVersion,
            1,
            VERSION,
            "this memory reads version 3",
        ),
        (
            with(&mesh, 2, 17),
            mesh.len() - 1,
            LoadError::TooManyNodes,
            2,
            17,
            "17 inner nodes, but this memory holds 16",
        ),
        (
            with(&mesh, 3, 33),
            mesh.len() - 1,
            LoadError::TooManyTriangles,
            3,
            33,
            "33 triangles, but this memory holds 32",
        ),
        (
            with(&mesh, 4, 1),
            mesh.len() - 1,
            LoadError::NodeLink,
            4,
            1,
            "the root of a wide image is node 0",
        ),
        (
            with(&mesh, 5, 3),
            mesh.len() - 1,
            LoadError::NodeLink,
            5,
            3,
            "header word 5",
        ),
        (
            with(&mesh, 13, 8),
            mesh.len() - 1,
            LoadError::Width,
            13,
            8,
            "nodes of 8 children; this memory holds 4-wide nodes",
        ),
        (
            with(&mesh, 15, 2),
            mesh.len() - 1,
            LoadError::Reserved,
            15,
            2,
            "header word 15",
        ),
        (
            with(&mesh, node(1, 3), count_word(1, 0)),
            mesh.len() - 1,
            LoadError::ChildCount,
            node(1, 3),
            count_word(1, 0),
            "0 children; a node of this memory has 1 to 4",
        ),
        (
            with(&mesh, node(1, 3), count_word(1, 5)),
            mesh.len() - 1,
            LoadError::ChildCount,
            node(1, 3),
            count_word(1, 5),
            "node 1 word 3: exponents and child count",
        ),
        (
            with(&mesh, unused_code, unused_value),
            mesh.len() - 1,
            LoadError::Reserved,
            unused_code,
            unused_value,
            "child box codes",
        ),
        (
            with(&mesh, node(short, links + used), 5),
            mesh.len() - 1,
            LoadError::Reserved,
            node(short, links + used),
            5,
            "link of child",
        ),
        (
            with(&mesh, node(inner.0, links + inner.1), n as u32),
            mesh.len() - 1,
            LoadError::NodeLink,
            node(inner.0, links + inner.1),
            n as u32,
            "links to inner node",
        ),
        (
            with(&mesh, node(leaf.0, links + leaf.1), long_leaf),
            mesh.len() - 1,
            LoadError::LeafLink,
            node(leaf.0, links + leaf.1),
            long_leaf,
            "but there are 28 triangles",
        ),
        (
            with(&mesh, tri(3, 9), t as u32),
            mesh.len() - 1,
            LoadError::GlobalIndex,
            tri(3, 9),
            t as u32,
            "global index 28",
        ),
        (
            with(&mesh, tri(4, 10), 2),
            mesh.len() - 1,
            LoadError::BadFlags,
            tri(4, 10),
            2,
            "flags 0x2",
        ),
        (
            mesh.clone(),
            tri(2, 4),
            LoadError::EarlyLast,
            tri(2, 4),
            mesh[tri(2, 4)],
            "tlast before",
        ),
        (
            [mesh.clone(), vec![1, 2, 3]].concat(),
            mesh.len() + 2,
            LoadError::MissingLast,
            mesh.len() - 1,
            *mesh.last().unwrap(),
            "no tlast",
        ),
    ];
    let mut bench: Bench<4, 5, 5, 9, 320, 36, 356, 313> = Bench::new(WIDTH, 3, 0.2);
    let _: &WideSceneMemory4w4x5 = &bench.uut;
    for (words, tlast, error, word, value, message) in cases {
        // The software loader refuses each too.
        assert!(WideImage::from_words(&words[..=tlast.min(words.len() - 1)]).is_err());
        let status = bench.load(&words, Some(tlast));
        let what = format!("{error:?}: {status:?}");
        assert!(!status.loading && !status.loaded, "{what}");
        assert_eq!(status.error_code, error.code(), "{what}");
        assert_eq!(
            (status.error_word as usize, status.error_value),
            (word, value),
            "{what}"
        );
        assert!(!bench.cycle(), "{what}: s_tready high after the packet");
        let err = status_result_in(&status, &words, CONFIG, NodeLayout::Wide(WIDTH)).unwrap_err();
        assert!(err.to_string().contains(message), "{what}: {err}");
        assert!(matches!(err, SceneMemoryError::Refused { error: e, .. } if e == error));
    }
    let status = bench.load(&mesh, last(&mesh));
    status_result_in(&status, &mesh, CONFIG, NodeLayout::Wide(WIDTH)).unwrap();
    bench.read_back(&mesh);
}

/// One word of the 4-wide mesh changed at random, 80 times: the memory's verdict against the
/// software loader's. What the memory refuses the software refuses; what the software refuses
/// the memory refuses too, unless only the whole tree shows it (a node reached twice, a box
/// not enclosing its triangles, inverted codes, a duplicate global index: the driver's
/// checks); what both accept reads back.
#[test]
fn random_corruptions_get_the_software_loaders_verdict() {
    const WIDTH: usize = 4;
    let mesh = wide(&mesh(), WIDTH);
    let mut rng = StdRng::seed_from_u64(6);
    let mut bench: Bench<4, 5, 5, 9, 320, 36, 356, 313> = Bench::new(WIDTH, 7, 0.0);
    // Every word but the floats and codes: header fields, child counts, links, indices,
    // flags, reserved words.
    let (n, words) = (mesh[2] as usize, node_words(WIDTH));
    let structure: Vec<usize> = (0..mesh.len())
        .filter(|&i| match i.checked_sub(HEADER_WORDS) {
            None => !(6..12).contains(&i),
            Some(j) if j < words * n => j % words == 3 || j % words >= words - WIDTH,
            Some(j) => (j - words * n) % TRIANGLE_WORDS >= 9,
        })
        .collect();
    let (mut refused, mut whole_tree) = (0, 0);
    for case in 0..80 {
        let at = match case % 2 {
            0 => rng.gen_range(0..mesh.len()),
            _ => structure[rng.gen_range(0..structure.len())],
        };
        let old = mesh[at];
        let value = match case % 5 {
            0 => rng.gen(),
            1 => old ^ (1 << rng.gen_range(0..32)),
            2 => old.wrapping_add(1),
            3 => old.wrapping_sub(1),
            _ => 0,
        };
        let words = with(&mesh, at, value);
        let software = WideImage::from_words(&words);
        let status = bench.load(&words, last(&words));
        let hardware = status_result_in(&status, &words, CONFIG, NodeLayout::Wide(WIDTH));
        let what = format!("word {at}: {old:#x} -> {value:#x}: {software:?} / {hardware:?}");
        match (&software, &hardware) {
            (Ok(_), Ok(())) => bench.read_back(&words),
            (
                Err(
                    SceneImageError::ReachedTwice { .. }
                    | SceneImageError::DuplicateIndex { .. }
                    | SceneImageError::Wide(_),
                ),
                Ok(()),
            ) => whole_tree += 1,
            (Err(_), Err(_)) => refused += 1,
            _ => panic!("{what}"),
        }
    }
    assert!(refused >= 20, "only {refused} of 80 corruptions refused");
    eprintln!("{refused} refused by both, {whole_tree} left to the driver's whole-tree checks");
}

#[test]
fn the_driver_rejects_another_width_a_cycle_and_what_does_not_fit() {
    let binary = mesh();
    let eight = wide(&binary, 8);
    let err = check_before_load_wide(&eight, CONFIG, 4).unwrap_err();
    assert_eq!(
        err,
        SceneMemoryError::Width {
            image: 8,
            memory: 4
        }
    );
    // A link back to the root passes the memory's range checks, not the software's.
    let four = wide(&binary, 4);
    let image = WideImage::from_words(&four).unwrap();
    let (k, c) = (0..image.tree.nodes.len())
        .flat_map(|k| (0..image.tree.nodes[k].children.len()).map(move |c| (k, c)))
        .find(|&(k, c)| !image.tree.nodes[k].children[c].link.is_leaf())
        .unwrap();
    let at = HEADER_WORDS + node_words(4) * k + node_words(4) - 4 + c;
    assert!(matches!(
        check_before_load_wide(&with(&four, at, 0), CONFIG, 4),
        Err(SceneMemoryError::Image(_))
    ));
    let small = MemoryConfig {
        node_bits: 1,
        triangle_bits: 5,
    };
    let err = check_before_load_wide(&four, small, 4).unwrap_err();
    assert!(
        err.to_string().contains("2 nodes and 32 triangles"),
        "{err}"
    );
}

/// The 8-wide memory of the XC7Z020 (2,048 nodes, 8,192 triangles, 3 triangle ports).
#[test]
fn the_zynq_wide_memory_passes_verilator_lint() {
    let mut memory = WideSceneMemory8w11x13::new(8, 3);
    memory.connect_all();
    let v = generate_verilog(&memory);
    assert!(v.contains("node_ram") && v.contains("link$7"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("wide scene memory: {e}"));
}

/// yosys xc7 resources of the 8-wide XC7Z020 memory with one triangle port (block RAM
/// primitives by kind, LUT, FF, logic depth):
/// `cargo test --release -p hdl --test wide_scene_memory -- --ignored --nocapture resources`.
#[test]
#[ignore]
fn wide_scene_memory_resources() {
    use hdl::synth::{synthesize, SynthOptions};
    let mut memory = WideSceneMemory8w11x13::new(8, 1);
    memory.connect_all();
    let v = generate_verilog(&memory);
    let r = synthesize(&v, hdl::verilog::TOP, &SynthOptions::default()).unwrap();
    let cell = |c: &str| r.cells.get(c).copied().unwrap_or(0);
    println!("| memory | nodes | triangles | RAMB36 | RAMB18 | LUT | LUTRAM | FF | logic depth |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    println!(
        "| 8-wide, 11/13 | 2048 | 8192 | {} | {} | {} | {} | {} | {} |",
        cell("RAMB36E1"),
        cell("RAMB18E1"),
        r.lut,
        r.lutram,
        r.ff,
        r.logic_depth
    );
}
