//! The shader core (`hdl::frame::shader`) in rust-hdl's simulator, bit for bit against
//! `hw_model::frame::shader::interpret::run`.
//!
//! The datapath alone (`alu`): every operation with a result on edge words (±0, subnormals,
//! NaNs canonical or not, ±Inf, ±MAX, the smallest normals, the contribution's saturation)
//! and random words in every lane, at depth 0, 1 and full: each result and predicate exactly
//! `latency(depth)` cycles after its operands, as the interpreter computes it for a one
//! instruction program. Verilator's lint.
//!
//! The core (`core`): random programs (kernels of random instructions of every operation
//! under random predicates and masks, swizzles, abs and neg, constants and material
//! constants, pushes of every kind, a predicated End now and then, then End; a register read
//! only once written in full) run by many threads at once, their starts offered with random
//! gaps and their rays and settle records taken under random back-pressure with long stalls,
//! and again flowing: every thread's rays in order, its settle record and tag, the counters
//! and the instructions issued equal `run()`'s, at depth 0, 1 and full; registers and
//! constants from the edge words; a second program and its constants loaded over the first
//! between two frames. Programs and starts that do not fit are errors. Lint.

use crate::common::{fp32_edge_words, print_synthesis_row, Traffic, FLOWING, SYNTHESIS_COLUMNS};
use hdl::frame::shader::alu::{self, simulate_alu, AluInput};
use hw_model::frame::shader::isa::{Field, Instr, Op, OpKind, Pred, PushKind, Src};
use hw_model::frame::shader::{run, Program, ThreadInput};
use rand::{rngs::StdRng, Rng, SeedableRng};

/// The kinds the datapath computes a register's value for, and the predicate ones.
const VALUE_KINDS: [OpKind; 9] = [
    OpKind::Mov,
    OpKind::Add,
    OpKind::Mul,
    OpKind::Max,
    OpKind::Min,
    OpKind::Recip,
    OpKind::Sqrt,
    OpKind::Fix,
    OpKind::IAdd,
];
const PREDICATE_KINDS: [OpKind; 3] = [OpKind::Lt, OpKind::Le, OpKind::Nz];

/// What the interpreter computes for `kind` on a and b: the register's value (all lanes
/// written) or the predicate.
fn model(kind: OpKind, a: [u32; 3], b: [u32; 3]) -> ([u32; 3], bool) {
    let op = Op::from_fields(kind, 2, Src::reg(0), Src::reg(1)).unwrap();
    let is_predicate = PREDICATE_KINDS.contains(&kind);
    let code = if is_predicate {
        vec![
            Instr::new(op),
            Instr::new(Op::Push {
                kind: PushKind::Shadow,
            })
            .when(Pred::when(2)),
            Instr::new(Op::End { a: Src::reg(0) }),
        ]
    } else {
        vec![
            Instr::new(op),
            Instr::new(Op::Out {
                f: Field::Payload,
                a: Src::reg(2),
            }),
            Instr::new(Op::Push {
                kind: PushKind::Shadow,
            }),
            Instr::new(Op::End { a: Src::reg(0) }),
        ]
    };
    let program = Program {
        code,
        constants: vec![],
        material_entry: vec![],
        miss_entry: 0,
    };
    let mut registers = [[0; 3]; 7];
    registers[0] = a;
    registers[1] = b;
    let input = ThreadInput {
        entry: 0,
        material: 0,
        registers,
        past_depth: false,
    };
    let out = run(&program, &input).expect("a one-operation program runs");
    if is_predicate {
        ([0; 3], out.pushed.len() == 1)
    } else {
        (out.pushed[0].payload, false)
    }
}

/// Words at the edges of fp32 and of the contribution conversion.
fn edge_words() -> Vec<u32> {
    let mut words = fp32_edge_words();
    words.extend([
        1.0f32.to_bits(),
        (-1.0f32).to_bits(),
        0.5f32.to_bits(),
        2.0f32.to_bits(),
        255.0f32.to_bits(),
        // The contribution's saturation at ±2048 steps and around it.
        2047.9999f32.to_bits(),
        2048.0f32.to_bits(),
        (-2048.0f32).to_bits(),
        (-2048.0001f32).to_bits(),
        1e30f32.to_bits(),
        0x7FFF_FFFF, // integer extremes for IAdd
        0x8000_0001,
        1,
    ]);
    words.sort_unstable();
    words.dedup();
    words
}

/// A word: mostly an edge word, else any bits or a moderate float.
fn word(rng: &mut StdRng, edges: &[u32]) -> u32 {
    match rng.gen_range(0..10) {
        0..=4 => edges[rng.gen_range(0..edges.len())],
        5..=6 => rng.gen(),
        _ => rng.gen_range(-1000.0f32..1000.0).to_bits(),
    }
}

/// `per_kind` operations of every kind in random order, lanes from `word`; then the
/// datapath at `depth` against the model.
fn check_alu(depth: usize, per_kind: usize, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let edges = edge_words();
    let mut ops: Vec<(OpKind, [u32; 3], [u32; 3])> = Vec::new();
    for kind in VALUE_KINDS.into_iter().chain(PREDICATE_KINDS) {
        for n in 0..per_kind {
            let (a, b) = if n < edges.len() * edges.len() && n < per_kind / 2 {
                // Pairs of edge words in lane x first (in order, as many as half the
                // operations), the other lanes random.
                let (i, j) = (n / edges.len(), n % edges.len());
                let mut a = [0; 3].map(|_| word(&mut rng, &edges));
                let mut b = [0; 3].map(|_| word(&mut rng, &edges));
                a[0] = edges[i];
                b[0] = edges[j];
                (a, b)
            } else {
                (
                    [0; 3].map(|_| word(&mut rng, &edges)),
                    [0; 3].map(|_| word(&mut rng, &edges)),
                )
            };
            ops.push((kind, a, b));
        }
    }
    // Shuffled, so that every operation follows every other.
    for i in (1..ops.len()).rev() {
        ops.swap(i, rng.gen_range(0..=i));
    }
    let inputs: Vec<AluInput> = ops
        .iter()
        .map(|&(kind, a, b)| AluInput {
            op: kind.opcode(),
            a,
            b,
        })
        .collect();
    let latency = alu::latency(depth);
    let shown = simulate_alu(depth, &inputs, latency);
    for (n, &(kind, a, b)) in ops.iter().enumerate() {
        let got = shown[n + latency];
        let (y, p) = model(kind, a, b);
        if PREDICATE_KINDS.contains(&kind) {
            assert_eq!(
                got.p, p,
                "depth {depth}: {kind:?} a {a:08x?} b {b:08x?} (operation {n})"
            );
        } else {
            assert_eq!(
                got.y, y,
                "depth {depth}: {kind:?} a {a:08x?} b {b:08x?} (operation {n})"
            );
        }
    }
}

#[test]
fn shader_alu_matches_the_interpreter_at_depth_0() {
    check_alu(0, 80, 1);
}

#[test]
fn shader_alu_matches_the_interpreter_at_depth_1() {
    check_alu(1, 80, 2);
}

#[test]
fn shader_alu_matches_the_interpreter_at_full_depth() {
    check_alu(alu::full_depth(), 400, 3);
}

/// The latency grows with the depth to the square root's, every operator's stages capped.
#[test]
fn shader_alu_latency_follows_the_depth() {
    assert_eq!(alu::latency(0), 0);
    assert_eq!(alu::latency(1), 1);
    let full = alu::full_depth();
    assert!(
        alu::latency(full) >= 5,
        "full latency {}",
        alu::latency(full)
    );
    assert_eq!(alu::latency(full + 10), alu::latency(full));
}

#[test]
fn shader_alu_verilog_passes_verilator_lint() {
    for depth in [0, 1, alu::full_depth()] {
        if let Err(e) = hdl::verilog::verilator_lint(&alu::alu_verilog(depth)) {
            panic!("shader datapath at depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// Many more random operations at more depths (a few CPU-minutes):
/// `cargo test --release -p hdl --test integration -- --ignored frame_shader::shader_alu_long`.
#[test]
#[ignore]
fn shader_alu_long() {
    for depth in [0, 1, 2, 3, 5, 10, alu::full_depth()] {
        check_alu(depth, 1000, 100 + depth as u64);
    }
}

// The core.

use hdl::frame::shader::core::{
    self as shader_core, core_verilog, loads, simulate_core, CoreInput, CoreOutput, Load,
    LoadError, RayOut, SettleOut, Start, StartError, THREAD_BITS,
};
use hdl::verilog::{verilator_lint_waiving, UNIT_VERILATOR_WAIVERS};
use hw_model::frame::shader::isa::{Loc, CODE, CONSTANTS, MATERIAL_STRIDE, REGISTERS};
use hw_model::frame::shader::ThreadOutput;

/// A random source operand: a register already written in full (`defined`), a constant or a
/// material constant; any swizzle, sometimes abs or neg.
fn source(rng: &mut StdRng, defined: &[u8]) -> Src {
    let loc = match rng.gen_range(0..10) {
        0..=5 => Loc::Reg(defined[rng.gen_range(0..defined.len())]),
        6..=7 => Loc::Const(rng.gen_range(0..CONSTANTS as u16)),
        _ => Loc::MatConst(rng.gen_range(0..MATERIAL_STRIDE as u8)),
    };
    Src {
        loc,
        swizzle: [0; 3].map(|_| rng.gen_range(0..3)),
        abs: rng.gen_bool(0.15),
        neg: rng.gen_bool(0.2),
    }
}

/// An operation of a random kind reading `a` and `b`, its destination (register, predicate,
/// field, push kind or counter) drawn until the machine has it.
fn random_op(rng: &mut StdRng, a: Src, b: Src) -> Op {
    let kind = OpKind::ALL[rng.gen_range(0..OpKind::ALL.len())];
    loop {
        let dest = rng.gen_range(0..REGISTERS as u64);
        if let Ok(op) = Op::from_fields(kind, dest, a, b) {
            if Instr::new(op).check().is_ok() {
                return op;
            }
        }
    }
}

/// A random kernel: `length` instructions of every operation, under random predicates and
/// masks, at most `max_pushes` pushes, then End. A register is read only once an
/// unconditional full-mask write has defined it (the others are unspecified at a start).
fn kernel(rng: &mut StdRng, length: usize, max_pushes: usize) -> Vec<Instr> {
    let mut defined: Vec<u8> = (0..7).collect();
    let mut pushes = 0;
    let mut code = Vec::new();
    for _ in 0..length {
        let d = rng.gen_range(0..REGISTERS as u8);
        let a = source(rng, &defined);
        let b = source(rng, &defined);
        let op = random_op(rng, a, b);
        let op = match op {
            Op::Push { .. } if pushes < max_pushes => {
                pushes += 1;
                op
            }
            // Now and then an End that may not run.
            Op::End { .. } if rng.gen_bool(0.2) => op,
            Op::Push { .. } | Op::End { .. } => Op::Mov { d, a },
            _ => op,
        };
        let pred = match rng.gen_range(0..10) {
            0..=5 => Pred::ALWAYS,
            6 => Pred::when(1),
            7 => Pred::unless(rng.gen_range(0..8)),
            _ => Pred::when(rng.gen_range(0..8)),
        };
        let pred = if matches!(op, Op::End { .. }) && pred == Pred::ALWAYS {
            Pred::unless(0)
        } else {
            pred
        };
        let mask = if rng.gen_bool(0.6) {
            0b111
        } else {
            rng.gen_range(0..8)
        };
        let instr = Instr { op, pred, mask };
        if let Some(d) = op.written_register() {
            if pred == Pred::ALWAYS && mask == 0b111 && !defined.contains(&d) {
                defined.push(d);
            }
        }
        code.push(instr);
    }
    code.push(Instr::new(Op::End {
        a: source(rng, &defined),
    }));
    code
}

/// Kernels side by side in one program (their entries), random constants of edge and
/// moderate words.
fn random_program(rng: &mut StdRng, kernels: usize, length: usize) -> (Program, Vec<u16>) {
    let edges = edge_words();
    let mut code = Vec::new();
    let mut entries = Vec::new();
    for _ in 0..kernels {
        entries.push(code.len() as u16);
        let n = rng.gen_range(length / 2..=length);
        code.extend(kernel(rng, n, 8));
    }
    let constants = (0..CONSTANTS)
        .map(|_| [0; 3].map(|_| word(rng, &edges)))
        .collect();
    let program = Program {
        code,
        constants,
        material_entry: vec![],
        miss_entry: 0,
    };
    (program, entries)
}

/// A thread per start, its pixel its index.
fn random_starts(rng: &mut StdRng, entries: &[u16], count: usize) -> Vec<Start> {
    let edges = edge_words();
    (0..count)
        .map(|n| {
            let input = ThreadInput {
                entry: entries[rng.gen_range(0..entries.len())],
                material: rng.gen_range(0..(CONSTANTS / MATERIAL_STRIDE) as u32),
                registers: [[0; 3]; 7].map(|_| [0; 3].map(|_| word(rng, &edges))),
                past_depth: rng.gen_bool(0.5),
            };
            Start::new(input, n as u32, rng.gen_range(0..16)).expect("a start that fits")
        })
        .collect()
}

const NOISY: Traffic = Traffic {
    gap: 0.3,
    stall: 0.4,
    long_stall: 0.005,
    long: 150,
};

/// Loads the program, then offers the starts in order (each held until taken) and takes
/// rays and settle records as `traffic` says, until every thread has settled and every ray
/// is taken.
struct Bench {
    /// Per frame its loads and the starts up to its last (an index into `starts`).
    frames: Vec<(Vec<Load>, usize)>,
    starts: Vec<Start>,
    frame: usize,
    traffic: Traffic,
    rng: StdRng,
    loaded: usize,
    next: usize,
    offered: bool,
    stalled: [usize; 2],
    settled: usize,
    last: Option<CoreInput>,
    cycles_left: usize,
}

impl Bench {
    fn drive(&mut self, shown: Option<&CoreOutput>) -> Option<CoreInput> {
        if let (Some(last), Some(out)) = (self.last, shown) {
            if last.start.is_some() && out.start_ready {
                self.next += 1;
                self.offered = false;
            }
            if last.settle_ready && out.settle.is_some() {
                self.settled += 1;
            }
        }
        // A frame is done when its every thread has settled and no ray waits; the next is
        // loaded then.
        let drained = shown.is_some_and(|out| out.ray.is_none());
        if self.settled == self.frames[self.frame].1 && drained {
            if self.frame + 1 == self.frames.len() {
                return None;
            }
            self.frame += 1;
            self.loaded = 0;
        }
        if self.cycles_left == 0 {
            return None;
        }
        self.cycles_left -= 1;
        let loads = &self.frames[self.frame].0;
        if self.loaded < loads.len() {
            self.loaded += 1;
            let input = CoreInput {
                load: Some(loads[self.loaded - 1]),
                ..CoreInput::default()
            };
            self.last = Some(input);
            return Some(input);
        }
        if !self.offered && self.next < self.frames[self.frame].1 {
            self.offered = !self.rng.gen_bool(self.traffic.gap);
        }
        let mut ready = [false; 2];
        for (ready, stalled) in ready.iter_mut().zip(&mut self.stalled) {
            *ready = self.traffic.ready(&mut self.rng, stalled);
        }
        let input = CoreInput {
            load: None,
            start: self.offered.then(|| self.starts[self.next]),
            ray_ready: ready[0],
            settle_ready: ready[1],
        };
        self.last = Some(input);
        Some(input)
    }
}

/// Runs frames (a program loaded, then its starts) through one core at `depth` and checks
/// every thread against `run()` on its frame's program: its rays in order, its settle
/// record, and the counters summed over the threads. The starts' pixels index all the
/// frames' starts. Returns the simulated cycles.
fn check_core(
    what: &str,
    depth: usize,
    frames: &[(Program, Vec<Start>)],
    traffic: Traffic,
    seed: u64,
) -> usize {
    let starts: Vec<Start> = frames.iter().flat_map(|(_, s)| s.clone()).collect();
    let models: Vec<ThreadOutput> = (frames.iter())
        .flat_map(|(program, starts)| {
            (starts.iter()).map(|s| run(program, &s.input).expect("a random program runs"))
        })
        .collect();
    let mut end = 0;
    let frame_loads: Vec<(Vec<Load>, usize)> = (frames.iter())
        .map(|(program, starts)| {
            end += starts.len();
            (loads(program).expect("the program fits"), end)
        })
        .collect();
    let work: u32 = models.iter().map(|m| m.instructions).sum();
    let limit = frame_loads.iter().map(|(l, _)| l.len()).sum::<usize>()
        + 40 * (work as usize + starts.len()) * shader_core::threads(depth)
        + 5000;
    let mut bench = Bench {
        frames: frame_loads,
        starts: starts.clone(),
        frame: 0,
        traffic,
        rng: StdRng::seed_from_u64(seed),
        loaded: 0,
        next: 0,
        offered: false,
        stalled: [0; 2],
        settled: 0,
        last: None,
        cycles_left: limit,
    };
    let cycles = simulate_core(depth, move |shown| bench.drive(shown));
    let mut rays: Vec<Vec<RayOut>> = vec![Vec::new(); starts.len()];
    let mut settles: Vec<Vec<SettleOut>> = vec![Vec::new(); starts.len()];
    let mut taken = 0;
    for (c, (input, out)) in cycles.iter().enumerate() {
        if input.start.is_some() && out.start_ready {
            assert_eq!(input.start, Some(starts[taken]), "{what}: starts in order");
            taken += 1;
        }
        if let Some(ray) = out.ray {
            if input.ray_ready {
                rays[ray.pixel as usize].push(ray);
            } else {
                assert_eq!(
                    cycles.get(c + 1).and_then(|(_, o)| o.ray),
                    Some(ray),
                    "{what}: a ray changed before taken (cycle {c})"
                );
            }
        }
        if let Some(settle) = out.settle {
            if input.settle_ready {
                settles[settle.pixel as usize].push(settle);
            }
        }
    }
    assert_eq!(
        taken,
        starts.len(),
        "{what}: starts taken in {} cycles (limit {limit})",
        cycles.len()
    );
    for (n, (s, m)) in starts.iter().zip(&models).enumerate() {
        let got: Vec<_> = rays[n].iter().map(|r| r.pushed).collect();
        assert_eq!(got, m.pushed, "{what}: thread {n}'s rays ({:?})", s.input);
        for r in &rays[n] {
            assert_eq!(r.depth, s.depth, "{what}: thread {n}'s tag");
        }
        assert_eq!(
            settles[n],
            vec![SettleOut {
                pixel: n as u32,
                depth: s.depth,
                sum: m.sum,
                spawned: m.pushed.len() as u32,
            }],
            "{what}: thread {n}'s settle record ({:?})",
            s.input
        );
    }
    let (_, last) = cycles.last().expect("cycles");
    let counters: [u32; 3] = std::array::from_fn(|c| models.iter().map(|m| m.counters[c]).sum());
    assert_eq!(last.counters, counters, "{what}: counters");
    assert_eq!(last.instructions, work, "{what}: instructions issued");
    assert!(
        work <= last.busy_cycles && last.busy_cycles as usize <= cycles.len(),
        "{what}: {} busy cycles for {work} instructions in {} cycles",
        last.busy_cycles,
        cycles.len()
    );
    cycles.len()
}

/// Random programs over many threads at once, noisy and flowing.
fn check_random(depth: usize, threads: usize, length: usize, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let (program, entries) = random_program(&mut rng, 4, length);
    let starts = random_starts(&mut rng, &entries, threads);
    let pushed: usize = (starts.iter())
        .map(|s| run(&program, &s.input).expect("runs").pushed.len())
        .sum();
    assert!(
        pushed >= threads / 2,
        "{pushed} rays pushed by {threads} threads"
    );
    let frames = [(program, starts)];
    check_core(
        &format!("depth {depth}, noisy"),
        depth,
        &frames,
        NOISY,
        seed,
    );
    check_core(
        &format!("depth {depth}, flowing"),
        depth,
        &frames,
        FLOWING,
        seed,
    );
}

/// Two frames on one core: the second program and its constants loaded over the first's
/// once its threads have settled, its threads running the new code.
#[test]
fn shader_core_reloads_between_frames() {
    let mut rng = StdRng::seed_from_u64(13);
    let frames: Vec<(Program, Vec<Start>)> = (0..2)
        .map(|f| {
            let (program, entries) = random_program(&mut rng, 3, 20);
            let starts = random_starts(&mut rng, &entries, 8)
                .into_iter()
                .map(|s| Start::new(s.input, s.pixel + 8 * f, s.depth).expect("fits"))
                .collect();
            (program, starts)
        })
        .collect();
    check_core("two frames, noisy", 1, &frames, NOISY, 13);
}

#[test]
fn shader_core_runs_random_programs_at_depth_0() {
    check_random(0, 16, 24, 10);
}

#[test]
fn shader_core_runs_random_programs_at_depth_1() {
    check_random(1, 24, 24, 11);
}

#[test]
fn shader_core_runs_random_programs_at_full_depth() {
    check_random(alu::full_depth(), 48, 24, 12);
}

/// Threads per depth: the loop latency, within the thread index at full depth.
#[test]
fn shader_core_threads_follow_the_depth() {
    assert_eq!(shader_core::threads(1), 4);
    assert_eq!(shader_core::threads(5), 8);
    let full = shader_core::threads(alu::full_depth());
    assert!(full <= 1 << THREAD_BITS, "{full} threads");
}

#[test]
fn shader_core_rejects_what_does_not_fit() {
    let program = |code: Vec<Instr>, constants: usize| Program {
        code,
        constants: vec![[0; 3]; constants],
        material_entry: vec![],
        miss_entry: 0,
    };
    let end = Instr::new(Op::End { a: Src::reg(0) });
    assert!(loads(&program(vec![end; CODE], CONSTANTS)).is_ok());
    let err = loads(&program(vec![end; CODE + 1], 0)).unwrap_err();
    assert_eq!(err, LoadError::Code { len: CODE + 1 });
    assert_eq!(
        err.to_string(),
        format!(
            "a program of {} instructions: the program memory holds {CODE}",
            CODE + 1
        )
    );
    assert_eq!(
        loads(&program(vec![end], CONSTANTS + 1)),
        Err(LoadError::Constants { len: CONSTANTS + 1 })
    );
    let bad = Instr::new(Op::Mov {
        d: 40,
        a: Src::reg(0),
    });
    assert!(matches!(
        loads(&program(vec![bad], 0)),
        Err(LoadError::Isa(_))
    ));
    let input = ThreadInput {
        entry: 0,
        material: 0,
        registers: [[0; 3]; 7],
        past_depth: false,
    };
    assert!(Start::new(input, 0, 0).is_ok());
    assert_eq!(
        Start::new(
            ThreadInput {
                entry: CODE as u16,
                ..input
            },
            0,
            0
        ),
        Err(StartError::Entry { entry: CODE as u16 })
    );
    let materials = (CONSTANTS / MATERIAL_STRIDE) as u32;
    let err = Start::new(
        ThreadInput {
            material: materials,
            ..input
        },
        0,
        0,
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        format!("material {materials}: the constant memory holds {materials} materials")
    );
    assert_eq!(
        Start::new(input, 1 << 21, 0),
        Err(StartError::Pixel { pixel: 1 << 21 })
    );
    assert_eq!(
        Start::new(input, 0, 16),
        Err(StartError::Depth { depth: 16 })
    );
}

#[test]
fn shader_core_verilog_passes_verilator_lint() {
    for depth in [1, alu::full_depth()] {
        let verilog = core_verilog(depth);
        if let Err(e) = verilator_lint_waiving(&verilog, UNIT_VERILATOR_WAIVERS) {
            panic!("shader core at depth {depth}: verilator lint failed:\n{e}");
        }
    }
}

/// One row of yosys `synth_xilinx` figures for `verilog`.
fn synthesis_row(what: &str, verilog: &str) {
    use hdl::synth::{synthesize, SynthOptions};
    let r = synthesize(verilog, "top", &SynthOptions::default()).expect("yosys synth_xilinx");
    print_synthesis_row(what, &r);
}

/// yosys `synth_xilinx` of the datapath and the core at depth 5 and full (slow):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// frame_shader::shader_synthesis`.
#[test]
#[ignore]
fn shader_synthesis() {
    println!(
        "| block | {SYNTHESIS_COLUMNS} |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for depth in [5, alu::full_depth()] {
        synthesis_row(
            &format!("datapath, depth {depth} (latency {})", alu::latency(depth)),
            &alu::alu_verilog(depth),
        );
        synthesis_row(
            &format!(
                "core, depth {depth} ({} threads)",
                shader_core::threads(depth)
            ),
            &core_verilog(depth),
        );
    }
}

/// More threads, longer kernels, more depths and seeds (a few CPU-minutes):
/// `cargo test --release -p hdl --test integration -- --ignored frame_shader::shader_core_long`.
#[test]
#[ignore]
fn shader_core_long() {
    for (n, depth) in [0, 1, 2, 5, alu::full_depth()].into_iter().enumerate() {
        for seed in 0..3 {
            check_random(depth, 96, 48, 1000 + 10 * n as u64 + seed);
        }
    }
}
