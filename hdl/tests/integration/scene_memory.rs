//! The scene memory in rust-hdl's simulator: real images (the built-in Simple plane, a random
//! mesh with its BVH) streamed with random `tvalid` gaps and read back through both ports
//! word for word against the software image; each malformed image refused with its error code,
//! word and value, the packet drained and `s_tready` low afterwards (never a hang); a new load
//! replacing the scene; random one-word corruptions judged as the software loader judges them.
//! The Verilated memory loads a thesis scene
//! (sim/tests/integration/scene_memory_verilator.rs).

use hdl::traversal::scene_memory::{
    address_bits_for, capacity_for, LoadError, SceneMemory4x5, INDEX_BITS,
};
use hdl::traversal::scene_memory_driver::{
    check_before_load, status_result, LoadStatus, MemoryConfig, SceneMemoryError,
};
use hdl::verilog::verilator_lint;
use hw_model::traversal::scene_image::{
    SceneImage, HEADER_WORDS, NODE_WORDS, TRIANGLE_WORDS, VERSION,
};
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

struct Bench {
    uut: SceneMemory4x5,
    rng: StdRng,
    /// Chance of an idle cycle before each beat.
    gap: f64,
}

impl Bench {
    fn new(seed: u64, gap: f64) -> Self {
        let mut uut = SceneMemory4x5::new(1);
        uut.connect_all();
        let mut bench = Bench {
            uut,
            rng: StdRng::seed_from_u64(seed),
            gap,
        };
        bench.idle();
        bench
    }

    scene_loader_methods!();

    /// Reads every node and triangle back (one address a cycle, the answer the next) and the
    /// root registers: all equal the image's words (reserved words are not stored).
    fn read_back(&mut self, words: &[u32]) {
        let u = |x: Bits<32>| x.to_u64() as u32;
        let (n, t) = (words[2] as usize, words[3] as usize);
        let s = self.status();
        assert_eq!((s.nodes as usize, s.triangles as usize), (n, t));
        assert_eq!(
            [
                self.uut.root_first.val().to_u64() as u32,
                self.uut.root_count.val().to_u64() as u32
            ],
            words[4..6]
        );
        let root: Vec<u32> = (0..3)
            .map(|i| u(self.uut.root_min[i].val()))
            .chain((0..3).map(|i| u(self.uut.root_max[i].val())))
            .collect();
        assert_eq!(root, words[6..12]);
        for k in 0..n {
            self.uut.node_address.next = (k as u64).into();
            self.sample_after_edge();
            let at = HEADER_WORDS + NODE_WORDS * k;
            let mut got: Vec<u32> = (0..6).map(|i| u(self.uut.min[i].val())).collect();
            got.extend((0..6).map(|i| u(self.uut.max[i].val())));
            for c in 0..2 {
                got.push(self.uut.child_first[c].val().to_u64() as u32);
                got.push(self.uut.child_count[c].val().to_u64() as u32);
            }
            assert_eq!(got, words[at..at + NODE_WORDS], "node {k}");
        }
        for k in 0..t {
            self.uut.triangle_address[0].next = (k as u64).into();
            self.sample_after_edge();
            let at = HEADER_WORDS + NODE_WORDS * n + TRIANGLE_WORDS * k;
            let vertices = self.uut.vertices[0].val();
            let mut got: Vec<u32> = (0..9)
                .map(|i| vertices.get_bits::<32>(32 * i).to_u64() as u32)
                .collect();
            got.push(self.uut.global_index[0].val().to_u64() as u32);
            got.push(u32::from(self.uut.casts_shadow[0].val()));
            assert_eq!(got, words[at..at + 11], "triangle record {k}");
        }
    }
}

/// The built-in Simple plane: 2 triangles, no inner node.
fn simple_plane() -> Vec<u32> {
    let scene = Scene::load("simple_plane").unwrap();
    SceneImage::new(&PreparedScene::new(&scene).unwrap()).to_words()
}

/// A random mesh of 28 triangles (odd objects cast no shadow) with the renderer's BVH: a
/// tree of inner nodes and leaves within the 16 nodes and 32 triangles of the memory.
fn mesh() -> Vec<u32> {
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
    let words = SceneImage::from_bvh(&Bvh::build(&tris), &tris, &casts).to_words();
    assert!(
        words[2] >= 5,
        "the mesh has {} inner nodes: no tree to test",
        words[2]
    );
    words
}

fn last(words: &[u32]) -> Option<usize> {
    Some(words.len() - 1)
}

#[test]
fn images_load_and_read_back_word_for_word_with_gaps() {
    let mut bench = Bench::new(1, 0.3);
    for words in [simple_plane(), mesh()] {
        check_before_load(&words, CONFIG).unwrap();
        let status = bench.load(&words, last(&words));
        status_result(&status, &words, CONFIG).unwrap();
        assert!(status.loaded && !status.loading, "{status:?}");
        assert!(!bench.cycle(), "s_tready must be low once loaded");
        bench.read_back(&words);
    }
    // The empty scene (N = T = 0, root (0, 0)) loads.
    let empty = SceneImage::from_bvh(&Bvh::build(&[]), &[], &[]).to_words();
    let status = bench.load(&empty, last(&empty));
    status_result(&status, &empty, CONFIG).unwrap();
}

/// A chunk of a larger scene (`hw_model::traversal::capacity`) keeps its scene's global
/// indices, which reach beyond this memory's own triangle capacity: they load and read back.
#[test]
fn a_chunks_global_indices_beyond_the_capacity_load() {
    let mesh = mesh();
    let (n, t) = (mesh[2] as usize, mesh[3] as usize);
    let tri = |k: usize, w: usize| HEADER_WORDS + NODE_WORDS * n + TRIANGLE_WORDS * k + w;
    let scene = 100_000;
    let mut words = with(&mesh, 12, scene);
    for k in 0..t {
        words[tri(k, 9)] += scene - t as u32;
    }
    SceneImage::from_words(&words).unwrap();
    let mut bench = Bench::new(8, 0.1);
    let status = bench.load(&words, last(&words));
    status_result(&status, &words, CONFIG).unwrap();
    bench.read_back(&words);
}

#[test]
fn back_to_back_beats_load_at_one_word_a_cycle() {
    let mut bench = Bench::new(2, 0.0);
    let words = mesh();
    let status = bench.load(&words, last(&words));
    status_result(&status, &words, CONFIG).unwrap();
    bench.read_back(&words);
}

/// `words` with word `i` replaced by `value`.
fn with(words: &[u32], i: usize, value: u32) -> Vec<u32> {
    let mut w = words.to_vec();
    w[i] = value;
    w
}

/// A malformed image: its words, the beat with `tlast`, the error, its word and value, and
/// words of the driver's message.
type Case = (Vec<u32>, usize, LoadError, usize, u32, &'static str);

#[test]
fn malformed_images_are_refused_with_their_code_word_and_value() {
    let mesh = mesh();
    let (n, t) = (mesh[2] as usize, mesh[3] as usize);
    let node = |k: usize, w: usize| HEADER_WORDS + NODE_WORDS * k + w;
    let tri = |k: usize, w: usize| HEADER_WORDS + NODE_WORDS * n + TRIANGLE_WORDS * k + w;
    let (max_nodes, max_triangles) = capacity_for(CONFIG.node_bits, CONFIG.triangle_bits);
    // A node child that is an inner node, and one that is a leaf.
    let inner = (0..n)
        .flat_map(|k| [(k, 0), (k, 1)])
        .find(|&(k, c)| mesh[node(k, 13 + 2 * c)] == 0)
        .unwrap();
    let leaf = (0..n)
        .flat_map(|k| [(k, 0), (k, 1)])
        .find(|&(k, c)| mesh[node(k, 13 + 2 * c)] != 0)
        .unwrap();
    let leaf_first = mesh[node(leaf.0, 12 + 2 * leaf.1)];
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
            with(&mesh, 1, VERSION + 1),
            mesh.len() - 1,
            LoadError::BadVersion,
            1,
            VERSION + 1,
            "this memory reads version",
        ),
        // The scene's triangle count S: at least T, at most what a global index can name.
        (
            with(&mesh, 12, t as u32 - 1),
            mesh.len() - 1,
            LoadError::SceneTriangles,
            12,
            t as u32 - 1,
            "at least the image's 28 triangles",
        ),
        (
            with(&mesh, 12, (1 << INDEX_BITS) + 1),
            mesh.len() - 1,
            LoadError::SceneTriangles,
            12,
            (1 << INDEX_BITS) + 1,
            "at most 16777216",
        ),
        (
            with(&mesh, 2, max_nodes as u32 + 1),
            mesh.len() - 1,
            LoadError::TooManyNodes,
            2,
            max_nodes as u32 + 1,
            "17 inner nodes, but this memory holds 16",
        ),
        (
            with(&mesh, 3, max_triangles as u32 + 1),
            mesh.len() - 1,
            LoadError::TooManyTriangles,
            3,
            max_triangles as u32 + 1,
            "33 triangles, but this memory holds 32",
        ),
        (
            with(&mesh, node(inner.0, 12 + 2 * inner.1), n as u32),
            mesh.len() - 1,
            LoadError::NodeLink,
            node(inner.0, 13 + 2 * inner.1),
            0,
            "links to inner node",
        ),
        (
            with(
                &mesh,
                node(leaf.0, 13 + 2 * leaf.1),
                t as u32 - leaf_first + 1,
            ),
            mesh.len() - 1,
            LoadError::LeafLink,
            node(leaf.0, 13 + 2 * leaf.1),
            t as u32 - leaf_first + 1,
            "but there are 28 triangles",
        ),
        // The root's link is checked too.
        (
            with(&mesh, 4, n as u32),
            mesh.len() - 1,
            LoadError::NodeLink,
            5,
            0,
            "header word 5",
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
            with(&mesh, tri(5, 11), 7),
            mesh.len() - 1,
            LoadError::Reserved,
            tri(5, 11),
            7,
            "reserved",
        ),
        (
            with(&mesh, 13, 1),
            mesh.len() - 1,
            LoadError::Reserved,
            13,
            1,
            "header word 13",
        ),
        (
            mesh.clone(),
            tri(2, 4),
            LoadError::EarlyLast,
            tri(2, 4),
            mesh[tri(2, 4)],
            "tlast before",
        ),
        // No tlast on the last word: the next packet's words are drained up to its tlast.
        (
            [mesh.clone(), vec![1, 2, 3]].concat(),
            mesh.len() + 2,
            LoadError::MissingLast,
            mesh.len() - 1,
            *mesh.last().unwrap(),
            "no tlast",
        ),
    ];
    let mut bench = Bench::new(3, 0.2);
    for (words, tlast, error, word, value, message) in cases {
        let status = bench.load(&words, Some(tlast));
        let what = format!("{error:?}: {status:?}");
        assert!(!status.loading && !status.loaded, "{what}");
        assert_eq!(status.error_code, error.code(), "{what}");
        assert_eq!(
            (status.error_word as usize, status.error_value),
            (word, value),
            "{what}"
        );
        // The packet was drained to its tlast: the memory takes nothing more.
        assert!(!bench.cycle(), "{what}: s_tready high after the packet");
        let err = status_result(&status, &words, CONFIG).unwrap_err();
        assert!(err.to_string().contains(message), "{what}: {err}");
        assert!(matches!(err, SceneMemoryError::Refused { error: e, .. } if e == error));
    }
    // After all that, a good image loads again and replaces whatever was there.
    let status = bench.load(&mesh, last(&mesh));
    status_result(&status, &mesh, CONFIG).unwrap();
    bench.read_back(&mesh);
}

/// One word of the mesh changed at random (random bits, one bit flipped, ±1, 0; every other
/// case a word that is not a float), 60 times:
/// the memory's verdict against the software loader's (`SceneImage::from_words`, the
/// independent reference). What the memory refuses the software refuses; what the software
/// refuses the memory refuses too, unless only the whole tree shows it (a node reached twice,
/// a duplicate global index: the driver's checks); what both accept reads back.
#[test]
fn random_corruptions_get_the_software_loaders_verdict() {
    use hw_model::traversal::scene_image::SceneImageError;
    let mesh = mesh();
    let mut rng = StdRng::seed_from_u64(6);
    let mut bench = Bench::new(7, 0.0);
    // Every word but the floats: header fields, links, indices, flags, reserved words.
    let n = mesh[2] as usize;
    let structure: Vec<usize> = (0..mesh.len())
        .filter(|&i| match i.checked_sub(HEADER_WORDS) {
            None => !(6..12).contains(&i),
            Some(j) if j < NODE_WORDS * n => j % NODE_WORDS >= 12,
            Some(j) => (j - NODE_WORDS * n) % TRIANGLE_WORDS >= 9,
        })
        .collect();
    let (mut refused, mut whole_tree) = (0, 0);
    for case in 0..60 {
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
        let software = SceneImage::from_words(&words);
        let status = bench.load(&words, last(&words));
        let hardware = status_result(&status, &words, CONFIG);
        let what = format!("word {at}: {old:#x} -> {value:#x}: {software:?} / {hardware:?}");
        match (&software, &hardware) {
            (Ok(_), Ok(())) => bench.read_back(&words),
            (
                Err(SceneImageError::ReachedTwice { .. } | SceneImageError::DuplicateIndex { .. }),
                Ok(()),
            ) => whole_tree += 1,
            (Err(_), Err(_)) => refused += 1,
            // A global index has INDEX_BITS bits; the software loader has no such limit.
            (Ok(_), Err(SceneMemoryError::Refused { error, .. }))
                if *error == LoadError::SceneTriangles && words[12] > 1 << INDEX_BITS =>
            {
                refused += 1
            }
            _ => panic!("{what}"),
        }
    }
    assert!(refused >= 20, "only {refused} of 60 corruptions refused");
    eprintln!("{refused} refused by both, {whole_tree} left to the driver's whole-tree checks");
}

#[test]
fn start_load_restarts_a_load_and_replaces_the_scene() {
    let mut bench = Bench::new(4, 0.1);
    let (plane, mesh) = (simple_plane(), mesh());
    bench.load(&mesh, last(&mesh));
    // Half a load of the plane (no tlast), then the whole plane: the plane is the scene.
    bench.load(&plane[..20], None);
    let status = bench.load(&plane, last(&plane));
    status_result(&status, &plane, CONFIG).unwrap();
    bench.read_back(&plane);
}

#[test]
fn the_driver_rejects_what_the_memory_cannot_see_and_what_does_not_fit() {
    let mesh = mesh();
    let n = mesh[2] as usize;
    // Child 0 of node 1 links back to node 0: a cycle, which passes the memory's link
    // checks but not the software loader.
    let at = HEADER_WORDS + NODE_WORDS + 12;
    let cycle = with(&with(&mesh, at, 0), at + 1, 0);
    assert!(matches!(
        check_before_load(&cycle, CONFIG),
        Err(SceneMemoryError::Image(_))
    ));
    let small = MemoryConfig {
        node_bits: 2,
        triangle_bits: 5,
    };
    let err = check_before_load(&mesh, small).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains(&format!("{n} inner nodes and 28 triangles"))
            && text.contains("4 nodes and 32 triangles"),
        "{text}"
    );
    assert_eq!(address_bits_for(n, 28), (address_bits_for(n, 1).0, 5));
    assert_eq!(address_bits_for(0, 0), (1, 1));
    assert_eq!(address_bits_for(16, 17), (4, 5));
}

#[test]
fn the_memory_passes_verilator_lint() {
    let mut uut = SceneMemory4x5::new(1);
    uut.connect_all();
    let v = generate_verilog(&uut);
    assert!(v.contains("s_tready") && v.contains("error_code"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("scene memory: {e}"));
}

/// yosys xc7 resources of three capacities (block RAM primitives by kind, LUT, FF, logic
/// depth): `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// scene_memory::scene_memory_resources`.
#[test]
#[ignore]
fn scene_memory_resources() {
    use hdl::synth::{synthesize, SynthOptions};
    use hdl::traversal::scene_memory::{SceneMemory11x12, SceneMemory12x13, SceneMemory9x10};
    fn verilog<T: Block>(mut uut: T) -> String {
        uut.connect_all();
        generate_verilog(&uut)
    }
    let designs = [
        ((9, 10), verilog(SceneMemory9x10::new(1))),
        ((11, 12), verilog(SceneMemory11x12::new(1))),
        ((12, 13), verilog(SceneMemory12x13::new(1))),
    ];
    println!(
        "| address bits | nodes | triangles | RAMB36 | RAMB18 | LUT | LUTRAM | FF | logic depth |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for ((nb, tb), v) in designs {
        let start = std::time::Instant::now();
        let r = synthesize(&v, hdl::verilog::TOP, &SynthOptions::default()).unwrap();
        let cell = |c: &str| r.cells.get(c).copied().unwrap_or(0);
        let (nodes, triangles) = capacity_for(nb, tb);
        println!(
            "| {nb}/{tb} | {nodes} | {triangles} | {} | {} | {} | {} | {} | {} |",
            cell("RAMB36E1"),
            cell("RAMB18E1"),
            r.lut,
            r.lutram,
            r.ff,
            r.logic_depth
        );
        eprintln!(
            "{nb}/{tb}: {:.0} s, cells {:?}",
            start.elapsed().as_secs_f64(),
            r.cells
        );
    }
}
