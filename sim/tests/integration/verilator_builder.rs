//! The Verilator model builder against designs with known behaviour: a rust-hdl registered
//! adder + counter checked cycle by cycle against Rust, the cache, tracing, and the errors.

use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sim::verilator::{Direction, Port};
use sim::{build, run_pipelined, BuildOptions, ModelSpec, SimError};
use std::time::Instant;

/// Registered `a + b`, a counter that counts while `enable` is high, and a registered 48-bit
/// inversion (a port spanning two words with a partial top word).
#[derive(LogicBlock, Default)]
struct AddCount {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<32>>,
    pub b: Signal<In, Bits<32>>,
    pub enable: Signal<In, Bit>,
    pub c: Signal<In, Bits<48>>,
    pub sum: Signal<Out, Bits<32>>,
    pub count: Signal<Out, Bits<16>>,
    pub not_c: Signal<Out, Bits<48>>,
    sum_reg: DFF<Bits<32>>,
    count_reg: DFF<Bits<16>>,
    not_c_reg: DFF<Bits<48>>,
}

impl Logic for AddCount {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, sum_reg, count_reg, not_c_reg);
        self.sum_reg.d.next = self.a.val() + self.b.val();
        if self.enable.val() {
            self.count_reg.d.next = self.count_reg.q.val() + 1;
        }
        self.not_c_reg.d.next = !self.c.val();
        self.sum.next = self.sum_reg.q.val();
        self.count.next = self.count_reg.q.val();
        self.not_c.next = self.not_c_reg.q.val();
    }
}

fn add_count_verilog() -> String {
    let mut uut = AddCount::default();
    uut.connect_all();
    generate_verilog(&uut)
}

/// The same design in Rust: the outputs sampled at the rising edge of each cycle.
#[derive(Default)]
struct AddCountRef {
    sum: u32,
    count: u16,
    not_c: u64,
}

impl AddCountRef {
    fn cycle(&mut self, a: u32, b: u32, enable: bool, c: u64) -> [u64; 3] {
        let out = [u64::from(self.sum), u64::from(self.count), self.not_c];
        self.sum = a.wrapping_add(b);
        self.count = self.count.wrapping_add(u16::from(enable));
        self.not_c = !c & ((1 << 48) - 1);
        out
    }
}

#[test]
fn ports_are_read_from_rust_hdl_verilog() {
    let ports = sim::verilator::parse_ports(&add_count_verilog(), "top").unwrap();
    let expected = [
        ("clock", Direction::Input, 1),
        ("a", Direction::Input, 32),
        ("b", Direction::Input, 32),
        ("enable", Direction::Input, 1),
        ("c", Direction::Input, 48),
        ("sum", Direction::Output, 32),
        ("count", Direction::Output, 16),
        ("not_c", Direction::Output, 48),
    ];
    for (n, d, w) in expected {
        assert!(
            ports.contains(&Port::new(n, d, w)),
            "{n} missing from {ports:?}"
        );
    }
    assert_eq!(ports.len(), expected.len());
}

#[test]
fn registered_adder_and_counter_match_rust_for_1m_cycles() {
    let model = build(
        &ModelSpec::rust_hdl(add_count_verilog()),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut sim = model.instantiate();
    let iface = sim.interface().clone();
    // Port order of the packed buffers is the Verilog's: find each port's value slot.
    let in_names: Vec<&str> = iface.inputs.iter().map(|p| p.name.as_str()).collect();
    let out_names: Vec<&str> = iface.outputs.iter().map(|p| p.name.as_str()).collect();
    let in_slot = |n: &str| in_names.iter().position(|x| *x == n).unwrap();
    let out_slot = |n: &str| out_names.iter().position(|x| *x == n).unwrap();

    const CYCLES: usize = 1 << 20;
    const BATCH: usize = 1 << 14;
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let mut reference = AddCountRef::default();
    let mut stimuli = Vec::with_capacity(BATCH);
    let mut in_words = Vec::with_capacity(BATCH * iface.in_words());
    let mut out_words = vec![0u32; BATCH * iface.out_words()];
    let mut simulated = std::time::Duration::ZERO;
    for _ in 0..CYCLES / BATCH {
        stimuli.clear();
        in_words.clear();
        for _ in 0..BATCH {
            let (a, b, en, c) = (
                rng.gen::<u32>(),
                rng.gen::<u32>(),
                rng.gen_bool(0.7),
                rng.gen::<u64>(),
            );
            let mut values = [0u64; 4];
            values[in_slot("a")] = a.into();
            values[in_slot("b")] = b.into();
            values[in_slot("enable")] = en.into();
            // All 64 bits are offered: the shim must drop the 16 above the port's width.
            values[in_slot("c")] = c;
            iface.pack_inputs(&values, &mut in_words).unwrap();
            stimuli.push((a, b, en, c));
        }
        let t = Instant::now();
        sim.run(&in_words, &mut out_words).unwrap();
        simulated += t.elapsed();
        for (i, (a, b, en, c)) in stimuli.iter().enumerate() {
            let mut got = [0u64; 3];
            iface
                .unpack_outputs(
                    &out_words[i * iface.out_words()..(i + 1) * iface.out_words()],
                    &mut got,
                )
                .unwrap();
            let want = reference.cycle(*a, *b, *en, *c);
            let got = [
                got[out_slot("sum")],
                got[out_slot("count")],
                got[out_slot("not_c")],
            ];
            assert_eq!(got, want, "cycle {}", sim.cycles() as usize - BATCH + i);
        }
    }
    assert_eq!(sim.cycles(), CYCLES as u64);
    println!(
        "AddCount: {CYCLES} cycles in {:.3} s of simulation = {:.1} M cycles/s (cached build: {})",
        simulated.as_secs_f64(),
        CYCLES as f64 / simulated.as_secs_f64() / 1e6,
        model.cached
    );
}

#[test]
fn run_pipelined_aligns_results_with_their_inputs() {
    let model = build(
        &ModelSpec::rust_hdl(add_count_verilog()),
        &BuildOptions::default(),
    )
    .unwrap();
    let mut sim = model.instantiate();
    let names: Vec<String> = sim
        .interface()
        .inputs
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let sum_slot = sim
        .interface()
        .outputs
        .iter()
        .position(|p| p.name == "sum")
        .unwrap();
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let vectors: Vec<[u64; 4]> = (0..10_000)
        .map(|_| {
            let mut v = [0u64; 4];
            for (slot, name) in names.iter().enumerate() {
                v[slot] = if name == "enable" {
                    0
                } else {
                    rng.gen::<u32>().into()
                };
            }
            v
        })
        .collect();
    let a = names.iter().position(|n| n == "a").unwrap();
    let b = names.iter().position(|n| n == "b").unwrap();
    let results: Vec<[u64; 3]> = run_pipelined(&mut sim, &vectors, 1).unwrap();
    assert_eq!(results.len(), vectors.len());
    for (v, r) in vectors.iter().zip(&results) {
        assert_eq!(r[sum_slot], (v[a] as u32).wrapping_add(v[b] as u32) as u64);
    }
    // The wrong number of ports is an error, not a panic.
    let err = run_pipelined::<2, 3>(&mut sim, &[[0, 0]], 1).unwrap_err();
    assert!(matches!(err, SimError::Interface(_)), "{err}");
}

#[test]
fn second_build_is_cached() {
    // A unique comment gives a key no earlier run has built.
    let nonce: u64 = rand::random();
    let verilog = format!("// cache test {nonce}\n{}", add_count_verilog());
    let first = build(
        &ModelSpec::rust_hdl(verilog.clone()),
        &BuildOptions::default(),
    )
    .unwrap();
    let second = build(&ModelSpec::rust_hdl(verilog), &BuildOptions::default()).unwrap();
    assert!(!first.cached);
    assert!(second.cached);
    assert_eq!(first.path(), second.path());
    let entry = first.path().parent().unwrap().to_path_buf();
    drop((first, second));
    std::fs::remove_dir_all(entry).unwrap();
}

/// Every model's C++ starts with a precompiled `verilated.h` from the cache; one that does not
/// match the compiler (another GCC, a damaged file) must cost time, not the build.
#[test]
fn a_precompiled_header_that_does_not_match_falls_back_to_the_header() {
    let spec = |verilog: String| ModelSpec {
        verilog,
        top: "wide".into(),
        ports: None,
        clock: None,
    };
    // The shared cache's runtime and precompiled headers, copied into a cache of our own.
    let shared = build(&spec(WIDE.into()), &BuildOptions::default()).unwrap();
    let shared_root = shared.path().parent().unwrap().parent().unwrap();
    let own = tempfile::tempdir().unwrap();
    let mut damaged = 0;
    for entry in std::fs::read_dir(shared_root).unwrap().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !(name.starts_with("runtime-") || name.starts_with("pch-")) {
            continue;
        }
        let to = own.path().join(&name);
        std::fs::create_dir(&to).unwrap();
        for file in std::fs::read_dir(entry.path()).unwrap().flatten() {
            let target = to.join(file.file_name());
            if file.path().extension().is_some_and(|e| e == "gch") {
                std::fs::write(&target, b"not a precompiled header").unwrap();
                damaged += 1;
            } else {
                std::fs::copy(file.path(), &target).unwrap();
            }
        }
    }
    // Two headers a set of compiler flags (one for the evaluation, one for the rest); the
    // shared cache holds the untraced set just used, and a traced one if a test built with
    // tracing first: all are damaged alike.
    assert!(
        damaged >= 2 && damaged % 2 == 0,
        "{damaged} precompiled headers: two a set of flags expected"
    );
    let options = BuildOptions {
        cache_dir: Some(own.path().to_path_buf()),
        ..BuildOptions::default()
    };
    let model = build(
        &spec(format!("// {}\n{WIDE}", own.path().display())),
        &options,
    )
    .unwrap();
    assert!(!model.cached);
    let mut out = [0u32; 5];
    model
        .instantiate()
        .eval(&[1, 2, 3, 4, 5], &mut out)
        .unwrap();
    assert_eq!(out, [!1, !2, !3, !4 & 0xF, 6]);
}

/// A combinational design with ports wider than 64 bits and `$` in names (as rust-hdl emits for
/// interface fields).
const WIDE: &str = "module wide(input wire [99:0] x$in, input wire [6:0] k, output wire [99:0] y$out, output wire [7:0] k1);\n\
                    assign y$out = ~x$in;\n  assign k1 = k + 8'd1;\nendmodule\n";

#[test]
fn wide_combinational_ports_and_independent_instances() {
    let spec = ModelSpec {
        verilog: WIDE.into(),
        top: "wide".into(),
        ports: None,
        clock: None,
    };
    let model = build(&spec, &BuildOptions::default()).unwrap();
    assert_eq!(
        (model.interface().in_words(), model.interface().out_words()),
        (5, 5)
    );
    let run_one = |seed: u32| {
        let mut sim = model.instantiate();
        let input = [seed, !seed, seed ^ 0x5555_5555, 0xFFFF_FFF5, 0xFFFF_FFFF];
        let mut out = [0u32; 5];
        sim.eval(&input, &mut out).unwrap();
        // 100 bits: the top word holds 4 (0x5 → !0x5 = 0xA); `k` is 7 bits, so 0xFFFFFFFF is 127.
        assert_eq!(out, [!seed, seed, !(seed ^ 0x5555_5555), 0xA, 128]);
        let err = sim.eval(&input[..4], &mut out).unwrap_err();
        assert!(matches!(err, SimError::Interface(_)));
    };
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..2u32)
            .map(|i| s.spawn(move || run_one(i * 0x1234_5679)))
            .collect();
        handles.into_iter().for_each(|h| h.join().unwrap());
    });
    // Instances move between threads.
    let sim = model.instantiate();
    std::thread::spawn(move || drop(sim)).join().unwrap();
}

#[test]
fn trace_build_writes_a_vcd_window() {
    let options = BuildOptions {
        trace: true,
        ..BuildOptions::default()
    };
    let model = build(&ModelSpec::rust_hdl(add_count_verilog()), &options).unwrap();
    let mut sim = model.instantiate();
    let iface = sim.interface().clone();
    let enable = iface
        .inputs
        .iter()
        .position(|p| p.name == "enable")
        .unwrap();
    let mut values = [0u64; 4];
    values[enable] = 1;
    let mut words = Vec::new();
    iface.pack_inputs(&values, &mut words).unwrap();
    let mut out = vec![0u32; iface.out_words()];
    sim.step(&words, &mut out).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let vcd = dir.path().join("window.vcd");
    sim.open_trace(&vcd).unwrap();
    for _ in 0..5 {
        sim.step(&words, &mut out).unwrap();
    }
    sim.close_trace();
    let text = std::fs::read_to_string(&vcd).unwrap();
    assert!(
        text.contains("$var") && text.contains(" count_reg"),
        "{}",
        &text[..text.len().min(2000)]
    );
    // Ten time steps (clock low/high per cycle) in the window.
    let stamps = text.lines().filter(|l| l.starts_with('#')).count();
    assert_eq!(stamps, 10, "{text}");

    let plain = build(
        &ModelSpec::rust_hdl(add_count_verilog()),
        &BuildOptions::default(),
    )
    .unwrap();
    let err = plain
        .instantiate()
        .open_trace(&vcd)
        .unwrap_err()
        .to_string();
    assert!(err.contains("without tracing"), "{err}");
}

#[test]
fn missing_verilator_is_a_clear_error() {
    let empty = tempfile::tempdir().unwrap();
    let options = BuildOptions {
        search_path: Some(empty.path().as_os_str().to_owned()),
        ..BuildOptions::default()
    };
    let err = build(&ModelSpec::rust_hdl(add_count_verilog()), &options)
        .err()
        .expect("must fail");
    assert_eq!(
        err.to_string(),
        "verilator not found on PATH: install it with `apt-get install verilator` (or run `make setup`)"
    );
}

#[test]
fn invalid_verilog_is_an_error_with_verilators_message() {
    let verilog =
        "module top(clock, a, q);\ninput wire clock;\ninput wire [3:0] a;\noutput reg [3:0] q;\n\
                   always @(posedge clock) q <= a +;\nendmodule\n";
    let err = build(&ModelSpec::rust_hdl(verilog), &BuildOptions::default())
        .err()
        .expect("must fail");
    let text = err.to_string();
    assert!(matches!(err, SimError::ToolFailed { .. }), "{text}");
    assert!(
        text.contains("%Error") && text.contains("top.v:5"),
        "{text}"
    );

    let err = build(
        &ModelSpec::rust_hdl("module top(clock, q);\ninput wire clock;\nendmodule"),
        &BuildOptions::default(),
    )
    .err()
    .expect("must fail");
    assert!(
        err.to_string()
            .contains("port `q` has no input/output declaration"),
        "{err}"
    );
}

/// Ports named after words Verilator reserves (`delete` a C++ keyword, `interrupt` a common
/// word) are renamed `__SYM__…` in its C++; the shim follows.
const RESERVED: &str = "module reserved(input wire [7:0] delete, input wire [7:0] x, output wire interrupt, output wire [7:0] y);\n\
                        assign interrupt = delete == x;\n  assign y = delete + x;\nendmodule\n";

#[test]
fn ports_named_like_reserved_words_work() {
    let spec = ModelSpec {
        verilog: RESERVED.into(),
        top: "reserved".into(),
        ports: None,
        clock: None,
    };
    let model = build(&spec, &BuildOptions::default()).unwrap();
    let mut sim = model.instantiate();
    let mut out = [0u32; 2];
    for (delete, x) in [(3u32, 3u32), (200, 100), (0, 255)] {
        sim.eval(&[delete, x], &mut out).unwrap();
        assert_eq!(
            out,
            [u32::from(delete == x), (delete + x) & 0xFF],
            "delete={delete} x={x}"
        );
    }
}
