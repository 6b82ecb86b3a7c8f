//! The scene memory Verilated: the thesis' Glasses scene image (425 nodes, 720 triangles,
//! 15,456 words) streamed with random `tvalid` gaps into a memory of 512 nodes and 1,024
//! triangles, then every node and triangle read back through both ports == the image's words;
//! a refused image (a flag word) and a reload in the same instance. Utah teapot into 4,096
//! nodes and 8,192 triangles likewise with `-- --ignored`. The rust-hdl simulation
//! (hdl/tests/integration/scene_memory.rs) carries the malformed images one by one.

use hdl::traversal::scene_memory::{SceneMemory12x13, SceneMemory9x10, VERTEX_BITS};
use hdl::traversal::scene_memory_driver::{
    check_before_load, status_result, LoadStatus, MemoryConfig,
};
use hw_model::traversal::scene_image::{SceneImage, HEADER_WORDS, NODE_WORDS, TRIANGLE_WORDS};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rust_hdl::prelude::*;
use sim::verilator::Direction;
use sim::{build, BuildOptions, ModelSpec, VerilatedModel};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;
use sw_renderer::trace::PreparedScene;

/// Cycles of input values by port name, run at once, outputs looked up by name in each
/// cycle's packed output words.
struct Run<'a> {
    sim: &'a mut VerilatedModel,
    inputs: Vec<String>,
    cycles: Vec<Vec<u64>>,
}

impl<'a> Run<'a> {
    fn new(sim: &'a mut VerilatedModel) -> Self {
        let inputs = sim
            .interface()
            .inputs
            .iter()
            .map(|p| p.name.clone())
            .collect();
        Run {
            sim,
            inputs,
            cycles: Vec::new(),
        }
    }

    /// Appends a cycle: these inputs, the others 0.
    fn push(&mut self, set: &[(&str, u64)]) {
        let mut values = vec![0; self.inputs.len()];
        for (name, v) in set {
            let i = self.inputs.iter().position(|n| n == name).unwrap();
            values[i] = *v;
        }
        self.cycles.push(values);
    }

    /// Runs the cycles so far; per cycle, the packed output words.
    fn run(&mut self) -> Vec<Vec<u32>> {
        let iface = self.sim.interface().clone();
        let mut words = Vec::new();
        for c in &self.cycles {
            iface.pack_inputs(c, &mut words).unwrap();
        }
        let mut out = vec![0; self.cycles.len() * iface.out_words()];
        self.sim.run(&words, &mut out).unwrap();
        self.cycles.clear();
        out.chunks(iface.out_words()).map(<[u32]>::to_vec).collect()
    }

    /// Where output `name` (at most 32 bits) is in a cycle's words.
    fn out(&self, name: &str) -> usize {
        self.out_wide(name, None)
    }

    /// Where output `name` of `bits` bits starts in a cycle's words.
    fn out_wide(&self, name: &str, bits: Option<u32>) -> usize {
        let iface = self.sim.interface();
        iface.word_offset(Direction::Output, name, bits).unwrap()
    }
}

/// Streams `words` after `start_load` with random gaps (`tlast` on the last word); checks
/// every beat is taken; returns the status a few cycles later.
fn load(run: &mut Run, words: &[u32], rng: &mut StdRng) -> LoadStatus {
    run.push(&[("start_load", 1)]);
    let mut beats = Vec::new();
    for (i, &w) in words.iter().enumerate() {
        while rng.gen_bool(0.25) {
            run.push(&[]);
        }
        beats.push(run.cycles.len());
        let last = u64::from(i + 1 == words.len());
        run.push(&[
            ("s_tdata", u64::from(w)),
            ("s_tvalid", 1),
            ("s_tlast", last),
        ]);
    }
    run.push(&[]);
    run.push(&[]);
    let out = run.run();
    let ready = run.out("s_tready");
    assert!(
        beats.iter().all(|&c| out[c][ready] == 1),
        "a beat was not taken"
    );
    let s = out.last().unwrap();
    let get = |name: &str| s[run.out(name)];
    LoadStatus {
        loading: get("loading") != 0,
        loaded: get("loaded") != 0,
        error_code: u64::from(get("error_code")),
        error_word: get("error_word"),
        error_value: get("error_value"),
        nodes: get("nodes"),
        triangles: get("triangles"),
    }
}

/// Reads every node and triangle back, both ports at once, one address a cycle.
fn read_back(run: &mut Run, words: &[u32]) {
    let (n, t) = (words[2] as usize, words[3] as usize);
    for k in 0..=n.max(t) {
        run.push(&[("node_address", k as u64), ("triangle_address$0", k as u64)]);
    }
    let out = run.run();
    let port = |name: &str, i: usize| run.out(&format!("{name}${i}"));
    for k in 0..n {
        let o = &out[k + 1];
        let mut got: Vec<u32> = (0..6).map(|i| o[port("min", i)]).collect();
        got.extend((0..6).map(|i| o[port("max", i)]));
        for c in 0..2 {
            got.push(o[port("child_first", c)]);
            got.push(o[port("child_count", c)]);
        }
        let at = HEADER_WORDS + NODE_WORDS * k;
        assert_eq!(got, words[at..at + NODE_WORDS], "node {k}");
    }
    for k in 0..t {
        let o = &out[k + 1];
        let at = run.out_wide("vertices$0", Some(VERTEX_BITS as u32));
        let mut got = o[at..at + VERTEX_BITS / 32].to_vec();
        got.push(o[run.out("global_index$0")]);
        got.push(o[run.out("casts_shadow$0")]);
        let at = HEADER_WORDS + NODE_WORDS * n + TRIANGLE_WORDS * k;
        assert_eq!(got, words[at..at + 11], "triangle record {k}");
    }
}

/// Loads the thesis scene `name` (its image `bytes` long) into the Verilated `uut` of
/// `config` with gaps, reads it back, has a flag word refused, reloads and reads it back.
fn load_and_read_back<T: Block>(mut uut: T, config: MemoryConfig, name: &str, bytes: usize) {
    let Some(dir) = thesis_scenes::for_test(&format!("scene_memory_verilator::{name}")) else {
        return;
    };
    let scene = Scene::load(dir.join(name).to_str().unwrap()).unwrap();
    let words = SceneImage::new(&PreparedScene::new(&scene).unwrap()).to_words();
    assert_eq!(words.len() * 4, bytes);
    check_before_load(&words, config).unwrap();

    uut.connect_all();
    let verilog = generate_verilog(&uut);
    hdl::verilog::verilator_lint(&verilog).unwrap();
    let model = build(&ModelSpec::rust_hdl(verilog), &BuildOptions::default()).unwrap();
    let mut sim = model.instantiate();
    let mut run = Run::new(&mut sim);
    let mut rng = StdRng::seed_from_u64(7);

    let status = load(&mut run, &words, &mut rng);
    status_result(&status, &words, config).unwrap();
    read_back(&mut run, &words);

    // A flag word of 2 in the last triangle: refused there, the scene is not loaded.
    let bad_at = words.len() - 2;
    let mut bad = words.clone();
    bad[bad_at] = 2;
    let status = load(&mut run, &bad, &mut rng);
    assert!(
        !status.loaded && status.error_word as usize == bad_at,
        "{status:?}"
    );
    let err = status_result(&status, &bad, config).unwrap_err();
    let last = words[3] - 1;
    assert!(
        err.to_string()
            .contains(&format!("triangle record {last} word 10: flags")),
        "{err}"
    );

    let status = load(&mut run, &words, &mut rng);
    status_result(&status, &words, config).unwrap();
    read_back(&mut run, &words);
}

#[test]
fn glasses_loads_with_gaps_and_reads_back_word_for_word() {
    let config = MemoryConfig {
        node_bits: 9,
        triangle_bits: 10,
    };
    load_and_read_back(SceneMemory9x10::new(1), config, "Glasses_scene", 61_824);
}

/// 4,096 nodes and 8,192 triangles:
/// `cargo test --release -p sim --test integration scene_memory_verilator:: -- --ignored`.
#[test]
#[ignore]
fn utah_teapot_loads_with_gaps_and_reads_back_word_for_word() {
    let config = MemoryConfig {
        node_bits: 12,
        triangle_bits: 13,
    };
    load_and_read_back(
        SceneMemory12x13::new(1),
        config,
        "Utah_teapot_scene",
        551_584,
    );
}
