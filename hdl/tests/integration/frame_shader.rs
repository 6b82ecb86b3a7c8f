//! The shader core (`hdl::frame::shader`) in rust-hdl's simulator, bit for bit against
//! `hw_model::frame::shader::interpret::run`.
//!
//! The datapath alone (`alu`): every operation with a result on edge words (±0, subnormals,
//! NaNs canonical or not, ±Inf, ±MAX, the smallest normals, the contribution's saturation)
//! and random words in every lane, at depth 0, 1 and full: each result and predicate exactly
//! `latency(depth)` cycles after its operands, as the interpreter computes it for a one
//! instruction program. Verilator's lint.

use hdl::frame::shader::alu::{self, simulate_alu, AluInput};
use hdl::frame::shader::{opcode, Kind};
use hw_model::frame::shader::isa::{Field, Instr, Op, Pred, PushKind, Src};
use hw_model::frame::shader::{run, Program, ThreadInput};
use rand::{rngs::StdRng, Rng, SeedableRng};

/// The kinds the datapath computes a register's value for, and the predicate ones.
const VALUE_KINDS: [Kind; 9] = [
    Kind::Mov,
    Kind::Add,
    Kind::Mul,
    Kind::Max,
    Kind::Min,
    Kind::Recip,
    Kind::Sqrt,
    Kind::Fix,
    Kind::IAdd,
];
const PREDICATE_KINDS: [Kind; 3] = [Kind::Lt, Kind::Le, Kind::Nz];

/// What the interpreter computes for `kind` on a and b: the register's value (all lanes
/// written) or the predicate.
fn model(kind: Kind, a: [u32; 3], b: [u32; 3]) -> ([u32; 3], bool) {
    let op = kind.sample();
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
    let mut words = vec![
        0x0000_0000, // ±0
        0x8000_0000,
        0x0000_0001, // subnormals
        0x007F_FFFF,
        0x8000_0001,
        0x8040_0000,
        0x7FC0_0000, // NaNs: canonical, signalling, negative
        0x7F80_0001,
        0xFFFF_FFFF,
        f32::INFINITY.to_bits(),
        f32::NEG_INFINITY.to_bits(),
        f32::MAX.to_bits(),
        f32::MIN.to_bits(),
        f32::MIN_POSITIVE.to_bits(),
        (-f32::MIN_POSITIVE).to_bits(),
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
    ];
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
    let mut ops: Vec<(Kind, [u32; 3], [u32; 3])> = Vec::new();
    for kind in VALUE_KINDS.into_iter().chain(PREDICATE_KINDS) {
        for n in 0..per_kind {
            let (a, b) = if n < edges.len() * edges.len() && n < per_kind / 2 {
                // Every pair of edge words in lane x first, the other lanes random.
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
            op: opcode(kind),
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
    check_alu(0, 300, 1);
}

#[test]
fn shader_alu_matches_the_interpreter_at_depth_1() {
    check_alu(1, 300, 2);
}

#[test]
fn shader_alu_matches_the_interpreter_at_full_depth() {
    check_alu(alu::full_depth(), 300, 3);
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

/// Many more random operations at every depth (about a minute):
/// `cargo test --release -p hdl --test integration -- --ignored frame_shader::shader_alu_long`.
#[test]
#[ignore]
fn shader_alu_long() {
    for depth in 0..=alu::full_depth() {
        check_alu(depth, 2000, 100 + depth as u64);
    }
}

