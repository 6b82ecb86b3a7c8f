//! The frame engine's thread start (`hdl::frame::thread_start`) in rust-hdl's simulator, bit
//! for bit against `hw_model::frame::shader::thread::input` and `Program::pushes_from`: the
//! returned cast rays of 16×9 renders of the built-in scenes and of the frame test scenes
//! (hits and misses, every depth the scene reaches), and random rays under random depths
//! and max depths (past depth either side of its edge) on random triangles with raw words;
//! under random gaps and random back-pressure with long stalls: every start exactly once, in
//! order, held while not taken, and, flowing, exactly `LATENCY` cycles after its ray; the
//! normals' codes at the grid's edges converted to exactly their `normal_value`s.
//! Constants and rays that do not fit are errors naming the sizes; Verilator's lint.

use crate::common::{frame_test_scene, print_synthesis_row, FRAME_TEST_SCENES, SYNTHESIS_COLUMNS};
use hdl::frame::id_queue::IDS;
use hdl::frame::ray_store::StoreError;
use hdl::frame::thread_start::{
    loads, simulate_thread_start, thread_start_verilog, triangles, Decision, Returned,
    ReturnedError, StartConstants, StartInput, StartLoadError, StartOutput, Started, LATENCY,
    OBJECTS,
};
use hw_model::fp32::{Fp32, Vec3};
use hw_model::frame::constants::{normal_code, normal_value, NORMAL_BITS};
use hw_model::frame::shade::Shaded;
use hw_model::frame::shader::{compile, thread, Program};
use hw_model::frame::{Frame, FrameConstants, FrameLimits, FrameRay, Load, RayKind};
use hw_model::traversal::TraversalEngine;
use hw_model::Format;
use rand::{rngs::StdRng, Rng, SeedableRng};
use sw_renderer::hit::Hit;
use sw_renderer::scene::{builtin, Scene};
use sw_renderer::trace::PreparedScene;

/// The triangle memory's address bits the tests build: 4,096 triangles. Scenes with more
/// (the built-in Utah teapot's 6,322, All materials') run at `FrameLimits::HW`'s, `TB_HW`.
const TB: usize = 12;
const TB_HW: usize = 14;
const _: () = assert!(1 << TB_HW == FrameLimits::HW.triangles);

fn traversal() -> TraversalEngine {
    TraversalEngine::resident(Format::FP32)
}

/// A ray the block takes and the start the model makes of it.
struct Case {
    ray: Returned,
    want: Started,
}

fn case(c: &FrameConstants, program: &Program, ray: &FrameRay, hit: Option<&Hit>) -> Case {
    let input = thread::input(program, c, ray, hit).expect("a cast ray runs a thread");
    let Load::Cast { depth, .. } = ray.load else {
        unreachable!("a cast ray")
    };
    Case {
        ray: Returned::of::<TB_HW>(ray, hit).unwrap_or_else(|e| panic!("{ray:?}: {e}")),
        want: Started {
            input,
            pixel: ray.pixel,
            depth,
            casts: program.pushes_from(input.entry).cast > 0,
        },
    }
}

/// Every returned cast ray of a 16×9 render of `scene`, a wavefront at a time.
fn rendered(scene: &Scene) -> (FrameConstants, Program, Vec<Case>) {
    let prepared = PreparedScene::new(scene).unwrap();
    let unit = traversal();
    let frame = Frame::new(scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let (c, program) = (frame.constants().clone(), frame.program().clone());
    let mut queue: Vec<FrameRay> = (0..c.height)
        .flat_map(|j| (0..c.width).map(move |i| (i, j)))
        .map(|(i, j)| FrameRay::primary(&c, i, j))
        .collect();
    let mut cases = Vec::new();
    let mut hits = Vec::new();
    let mut shaded = Shaded::default();
    while !queue.is_empty() {
        let batch = std::mem::take(&mut queue);
        frame.cast(&batch, &mut hits).unwrap();
        for (ray, hit) in batch.iter().zip(&hits) {
            if ray.kind() != RayKind::Shadow {
                cases.push(case(&c, &program, ray, hit.as_ref()));
            }
            shaded.clear();
            thread::shade(&program, &c, ray, hit.as_ref(), &mut shaded).unwrap();
            queue.extend_from_slice(&shaded.spawned);
        }
    }
    (c, program, cases)
}

/// Random cast rays of `c`'s triangles: raw words, any depth the tag holds.
fn random_cases(rng: &mut StdRng, c: &FrameConstants, program: &Program, n: usize) -> Vec<Case> {
    let word3 = |rng: &mut StdRng| {
        hw_model::fp32::Vec3::new(
            hw_model::fp32::Fp32::from_bits(rng.gen()),
            hw_model::fp32::Fp32::from_bits(rng.gen()),
            hw_model::fp32::Fp32::from_bits(rng.gen()),
        )
    };
    (0..n)
        .map(|_| {
            let hit = rng.gen_bool(0.8).then(|| Hit {
                triangle: rng.gen_range(0..c.triangles.len() as u32),
                t: f32::from_bits(rng.gen()),
                u: f32::from_bits(rng.gen()),
                v: f32::from_bits(rng.gen()),
            });
            let ray = FrameRay {
                pixel: rng.gen_range(0..1 << 21),
                orig: word3(rng),
                dir: word3(rng),
                t_max: hw_model::fp32::Fp32::MAX,
                load: Load::Cast {
                    kind: RayKind::ALL[rng.gen_range(0..3)],
                    depth: rng.gen_range(0..16),
                    weight: word3(rng),
                },
            };
            case(c, program, &ray, hit.as_ref())
        })
        .collect()
}

/// Back-pressure and gaps of a run.
#[derive(Clone, Copy)]
struct Traffic {
    /// Chance of a cycle without a ray offered (once none is shown).
    gap: f64,
    /// Chance of a stall starting (`out_ready` low), lasting up to `stall_len` cycles.
    stall: f64,
    stall_len: usize,
}

const FLOWING: Traffic = Traffic {
    gap: 0.0,
    stall: 0.0,
    stall_len: 0,
};

/// Loads `k` and streams `cases` through the block: every start in order, equal to the
/// model's, held while not taken; flowing, each `LATENCY` cycles after its ray.
fn run<const TB: usize>(
    what: &str,
    k: &StartConstants,
    cases: Vec<Case>,
    traffic: Traffic,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    let base = StartInput {
        miss_entry: k.miss_entry,
        miss_casts: k.miss_casts,
        max_depth: k.max_depth,
        decision: Decision::GO,
        ..StartInput::default()
    };
    let mut load_words = k.loads.clone().into_iter();
    let rays: Vec<Returned> = cases.iter().map(|c| c.ray).collect();
    let n = rays.len();
    let mut next = 0;
    let mut offered: Option<Returned> = None;
    let mut stalled = 0usize;
    // Starts taken, whether the cycle before was ready, cycles since the last was taken.
    let (mut taken, mut was_ready, mut after) = (0, false, 0);
    let cycles = simulate_thread_start::<TB>(move |shown: Option<&StartOutput>| {
        let mut input = base.clone();
        if let Some(w) = load_words.next() {
            input.load = Some(w);
            return Some(input);
        }
        if was_ready && shown.is_some_and(|s| s.start.is_some()) {
            taken += 1;
        }
        if offered.is_some() && shown.is_some_and(|s| s.in_ready) {
            offered = None;
            next += 1;
        }
        if offered.is_none() && next < n && !rng.gen_bool(traffic.gap) {
            offered = Some(rays[next]);
        }
        input.ray = offered;
        input.id = next % IDS;
        if stalled == 0 && rng.gen_bool(traffic.stall) {
            stalled = rng.gen_range(1..=traffic.stall_len.max(1));
        }
        input.out_ready = stalled == 0;
        was_ready = input.out_ready;
        stalled = stalled.saturating_sub(1);
        if taken == n {
            after += 1;
        }
        // A few cycles more: nothing else may come out.
        (after <= LATENCY + 1).then_some(input)
    });
    let mut got = Vec::new();
    let mut taken_at = Vec::new();
    let mut held: Option<Started> = None;
    for (cycle, (input, out)) in cycles.iter().enumerate() {
        if let Some(h) = held {
            assert_eq!(
                out.start,
                Some(h),
                "{what}: a start not taken changed at {cycle}"
            );
        }
        if input.ray.is_some() && out.in_ready {
            taken_at.push(cycle);
        }
        held = None;
        if let Some(s) = out.start {
            if input.out_ready {
                if traffic.stall == 0.0 {
                    assert_eq!(
                        cycle,
                        taken_at[got.len()] + LATENCY,
                        "{what}: start {} shown at {cycle}",
                        got.len()
                    );
                }
                got.push(s);
            } else {
                held = Some(s);
            }
        }
    }
    assert_eq!(got.len(), cases.len(), "{what}: starts");
    let started = cycles.iter().filter(|(_, o)| o.started).count();
    assert_eq!(started, cases.len(), "{what}: every start committed once");
    assert!(
        cycles.iter().all(|(_, o)| !o.deferred),
        "{what}: nothing deferred"
    );
    let ids: Vec<usize> = (cycles.iter())
        .filter(|(_, o)| o.started)
        .map(|(_, o)| o.id)
        .collect();
    assert!(
        ids.iter().enumerate().all(|(k, &id)| id == k % IDS),
        "{what}: each start's id"
    );
    for (k, (g, c)) in got.iter().zip(&cases).enumerate() {
        assert_eq!(*g, c.want, "{what}: start {k} of {:?}", c.ray);
    }
}

const NOISY: Traffic = Traffic {
    gap: 0.3,
    stall: 0.1,
    stall_len: 12,
};

fn check_scene(what: &str, scene: &Scene, seed: u64) {
    let (c, program, mut cases) = rendered(scene);
    let mut rng = StdRng::seed_from_u64(seed);
    let misses = cases.iter().filter(|k| k.ray.hit.is_none()).count();
    assert!(
        misses > 0 && misses < cases.len(),
        "{what}: hits and misses"
    );
    cases.extend(random_cases(&mut rng, &c, &program, 60));
    let flowing = cases.split_off(cases.len() / 2);
    if c.triangles.len() <= triangles(TB) {
        let k = loads::<TB>(&c, &program).unwrap();
        run::<TB>(what, &k, cases, NOISY, seed);
        run::<TB>(what, &k, flowing, FLOWING, seed + 1);
    } else {
        let k = loads::<TB_HW>(&c, &program).unwrap();
        run::<TB_HW>(what, &k, cases, NOISY, seed);
        run::<TB_HW>(what, &k, flowing, FLOWING, seed + 1);
    }
}

#[test]
fn thread_start_matches_the_model_on_the_builtin_scenes() {
    for (n, name) in builtin::names().into_iter().enumerate() {
        check_scene(name, &Scene::load(name).unwrap(), 10 + n as u64);
    }
}

#[test]
fn thread_start_matches_the_model_on_the_frame_test_scenes() {
    for (n, name) in FRAME_TEST_SCENES.iter().enumerate() {
        check_scene(name, &frame_test_scene(name), 30 + n as u64);
    }
}

/// Past depth on either side of its edge: max depth 0, 1, 7 and 15 against depths around it.
#[test]
fn thread_start_sets_past_depth_at_the_max_depth() {
    let scene = frame_test_scene("glass");
    let (mut c, _, _) = rendered(&scene);
    let mut rng = StdRng::seed_from_u64(5);
    for max_depth in [0, 1, 7, 15] {
        c.max_depth = max_depth;
        let program = compile(&c).unwrap();
        let cases = random_cases(&mut rng, &c, &program, 40);
        let past = cases.iter().filter(|k| k.want.input.past_depth).count();
        assert!(past > 0, "max depth {max_depth}: past");
        assert!(
            past < cases.len() || max_depth == 0,
            "max depth {max_depth}: not past"
        );
        let k = loads::<TB>(&c, &program).unwrap();
        run::<TB>(
            &format!("max depth {max_depth}"),
            &k,
            cases,
            NOISY,
            50 + max_depth as u64,
        );
    }
}

/// The start decision under random decision inputs: every start at stage B committed or
/// deferred exactly once per arrival, as `Decision::allows` says (the schedule model's
/// `can_start` with the ray ids' M), a deferred ray offered again later (as the waiting
/// queue's tail gives it back), a committed start held for the core until taken whatever
/// the inputs do; starts by the escape alone (casting programs below the reserve) happen.
#[test]
fn thread_start_decides_starts() {
    let scene = frame_test_scene("glass");
    let (c, program, mut cases) = rendered(&scene);
    let mut rng = StdRng::seed_from_u64(61);
    cases.truncate(300);
    // A few pixels and depths, so the escape matches often.
    for case in &mut cases {
        let pixel = rng.gen_range(0..4) * 1024 + rng.gen_range(0..3);
        case.ray.pixel = pixel;
        case.want.pixel = pixel;
    }
    assert!(cases.iter().any(|k| k.want.casts) && cases.iter().any(|k| !k.want.casts));
    let k = loads::<TB>(&c, &program).unwrap();
    let base = StartInput {
        miss_entry: k.miss_entry,
        miss_casts: k.miss_casts,
        max_depth: k.max_depth,
        ..StartInput::default()
    };
    let mut load_words = k.loads.clone().into_iter();
    let rays: Vec<Returned> = cases.iter().map(|c| c.ray).collect();
    let n = rays.len();
    let mut pending: std::collections::VecDeque<usize> = (0..n).collect();
    let (mut offered, mut stalled, mut done, mut after) = (None::<usize>, 0usize, 0, 0);
    let mut last = base.clone();
    let cycles = simulate_thread_start::<TB>(move |shown: Option<&StartOutput>| {
        let mut input = base.clone();
        if let Some(w) = load_words.next() {
            input.load = Some(w);
            last = input.clone();
            return Some(input);
        }
        if let Some(o) = shown {
            if o.in_ready {
                offered = None;
            }
            if o.deferred {
                pending.push_back(o.id);
            }
            if o.offered && last.out_ready {
                done += 1;
            }
        }
        if offered.is_none() && !rng.gen_bool(0.3) {
            offered = pending.pop_front();
        }
        input.ray = offered.map(|id| rays[id]);
        input.id = offered.unwrap_or(0);
        // Decision inputs: often the escape of the start shown the cycle before.
        let escape = match shown.and_then(|o| o.start) {
            Some(s) if rng.gen_bool(0.5) => Some((
                s.pixel as usize % 1024,
                rng.gen_bool(0.75).then_some(s.depth),
            )),
            _ => rng.gen_bool(0.5).then(|| {
                (
                    rng.gen_range(0..3),
                    rng.gen_bool(0.8).then(|| rng.gen_range(0..4)),
                )
            }),
        };
        input.decision = Decision {
            fits: rng.gen_bool(0.8),
            fits_above_reserve: rng.gen_bool(0.3),
            escape,
        };
        if stalled == 0 && rng.gen_bool(0.1) {
            stalled = rng.gen_range(1..=10);
        }
        input.out_ready = stalled == 0;
        stalled = stalled.saturating_sub(1);
        last = input.clone();
        if done == n {
            after += 1;
        }
        (after <= LATENCY + 1 && after + done < 100_000).then_some(input)
    });
    let (mut committed, mut deferred, mut by_escape) = (false, 0, 0);
    let mut started = vec![0; n];
    for (cycle, (input, out)) in cycles.iter().enumerate() {
        let Some(s) = out.start else {
            assert!(!committed && !out.started && !out.deferred && !out.offered);
            continue;
        };
        assert_eq!(
            s, cases[out.id].want,
            "cycle {cycle}: the start of ray {}",
            out.id
        );
        if committed {
            assert!(
                out.offered && !out.started && !out.deferred,
                "cycle {cycle}: held"
            );
        } else {
            let d = input.decision;
            let allowed = d.allows(s.casts, s.pixel, s.depth);
            assert_eq!(
                (out.started, out.deferred),
                (allowed, !allowed),
                "cycle {cycle}: the decision on {s:?} under {d:?}"
            );
            deferred += usize::from(out.deferred);
            if out.started {
                started[out.id] += 1;
                by_escape += usize::from(s.casts && !d.fits_above_reserve);
            }
        }
        committed = out.offered && !input.out_ready;
    }
    assert!(
        started.iter().all(|&k| k == 1),
        "every start committed once"
    );
    assert!(deferred > n / 4, "starts deferred: {deferred}");
    assert!(by_escape > 0, "starts by the escape");
}

/// Normal components at the grid's edges, snapped as `FrameConstants::load` snaps them, through
/// the triangle memory's codes and their conversion: every start's r4..r6 the exact
/// `normal_value` of the component's code, the model's start bit for bit. ±1 and beyond
/// clamp to the top code; −0 and values nearer 0 than half a step are code 0, +0 (the
/// model's snap); half a step rounds away from 0 to ±1 code.
#[test]
fn thread_start_converts_normal_codes_at_the_grid_edges() {
    let scene = frame_test_scene("glass");
    let (mut c, program, _) = rendered(&scene);
    let top = (1 << (NORMAL_BITS - 1)) - 1;
    let step = normal_value(1).f32();
    let edges = [
        1.0,
        -1.0,
        1.5,
        -7.0,
        1.0 - step,
        -(1.0 - step),
        1.0 - 2.5 * step,
        0.0,
        -0.0,
        step,
        -step,
        step / 2.0,
        -step / 2.0,
        step * 0.49,
        -1e-30,
        0.5,
        -0.5 - step,
        0.707_106_77,
    ];
    let component =
        |t: usize, corner: usize, axis: usize| edges[(9 * t + 3 * corner + axis) % edges.len()];
    let snap = |x: f32| normal_value(normal_code(Fp32::new(x)));
    for (t, tri) in c.triangles.iter_mut().enumerate() {
        for (corner, n) in tri.normals.iter_mut().enumerate() {
            let [x, y, z] = [0, 1, 2].map(|axis| snap(component(t, corner, axis)));
            *n = Vec3::new(x, y, z);
        }
    }
    let count = c.triangles.len().min(edges.len() * 2);
    assert!(9 * count >= edges.len(), "every edge on some triangle");
    let codes: Vec<i32> = edges.iter().map(|&x| normal_code(Fp32::new(x))).collect();
    for want in [top, -top, 0, 1, -1, top - 1] {
        assert!(codes.contains(&want), "code {want} tested");
    }
    let primary = FrameRay::primary(&c, 0, 0);
    let cases: Vec<Case> = (0..count)
        .map(|t| {
            let hit = Hit {
                triangle: t as u32,
                t: 2.0,
                u: 0.25,
                v: 0.5,
            };
            let k = case(&c, &program, &primary, Some(&hit));
            for corner in 0..3 {
                let want = [0, 1, 2].map(|axis| {
                    normal_value(normal_code(Fp32::new(component(t, corner, axis)))).bits()
                });
                assert_eq!(k.want.input.registers[4 + corner], want, "triangle {t}");
            }
            k
        })
        .collect();
    let plus_zero = cases
        .iter()
        .flat_map(|k| k.want.input.registers[4..].iter().flatten());
    assert!(plus_zero.clone().any(|&w| w == 0) && plus_zero.clone().all(|&w| w != 1 << 31));
    let k = loads::<TB>(&c, &program).unwrap();
    run::<TB>("normal codes", &k, cases, NOISY, 70);
}

#[test]
fn thread_start_refuses_what_does_not_fit() {
    let scene = frame_test_scene("glass");
    let (c, program, cases) = rendered(&scene);
    // The Utah teapot's 6,322 triangles in a memory of 4,096.
    let teapot = Scene::load("utah_teapot").unwrap();
    let prepared = PreparedScene::new(&teapot).unwrap();
    let unit = traversal();
    let frame = Frame::new(&teapot, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let count = frame.constants().triangles.len();
    assert!(count > triangles(TB) && count <= triangles(TB_HW));
    let e = loads::<TB>(frame.constants(), frame.program()).unwrap_err();
    assert_eq!(
        e,
        StartLoadError::Triangles {
            count,
            capacity: 4096
        }
    );
    assert_eq!(
        e.to_string(),
        format!("{count} triangles: the frame engine's triangle memory holds 4096")
    );
    assert!(loads::<TB_HW>(frame.constants(), frame.program()).is_ok());
    let mut many = c.clone();
    many.materials = vec![c.materials[0]; OBJECTS + 1];
    let e = loads::<TB>(&many, &program).unwrap_err();
    assert!(
        e.to_string().contains(&format!("{} objects", OBJECTS + 1)),
        "{e}"
    );
    assert!(e.to_string().contains(&OBJECTS.to_string()), "{e}");
    let mut stray = c.clone();
    stray.triangles[0].object = c.materials.len() as u32;
    let e = loads::<TB>(&stray, &program).unwrap_err().to_string();
    assert!(e.contains("triangle 0 has object"), "{e}");
    for bits in [0.1f32.to_bits(), (-0.0f32).to_bits()] {
        let mut off = c.clone();
        off.triangles[1].normals[2] = Vec3::new(Fp32::ZERO, Fp32::ZERO, Fp32::from_bits(bits));
        let e = loads::<TB>(&off, &program).unwrap_err();
        assert_eq!(
            e,
            StartLoadError::NormalOffGrid {
                triangle: 1,
                corner: 2,
                axis: 2,
                bits
            }
        );
        let e = e.to_string();
        assert!(
            e.contains("triangle 1 corner 2") && e.contains("16-bit grid"),
            "{e}"
        );
    }
    let mut deep = c.clone();
    deep.max_depth = 16;
    let e = loads::<TB>(&deep, &program).unwrap_err().to_string();
    assert!(e.contains("max depth 16") && e.contains("15"), "{e}");

    let primary = FrameRay::primary(&c, 0, 0);
    let shadow = FrameRay {
        load: Load::Shadow {
            contribution: Default::default(),
        },
        ..primary
    };
    assert_eq!(
        Returned::of::<TB>(&shadow, None),
        Err(ReturnedError::Shadow)
    );
    let far = Hit {
        triangle: triangles(TB) as u32,
        t: 1.0,
        u: 0.0,
        v: 0.0,
    };
    let e = Returned::of::<TB>(&primary, Some(&far))
        .unwrap_err()
        .to_string();
    assert!(e.contains(&triangles(TB).to_string()), "{e}");
    let deep_ray = FrameRay {
        load: Load::Cast {
            kind: RayKind::Reflection,
            depth: 16,
            weight: hw_model::fp32::Vec3::of([1.0; 3]),
        },
        ..primary
    };
    assert_eq!(
        Returned::of::<TB>(&deep_ray, None),
        Err(ReturnedError::Store(StoreError::Depth { depth: 16 }))
    );
    assert!(!cases.is_empty());
}

#[test]
fn thread_start_verilog_passes_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&thread_start_verilog::<TB>()) {
        panic!("thread start: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks") at the XC7Z020's 4,096 triangles
/// (`TB`) and `FrameLimits::HW`'s 16,384 (`TB_HW`):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_thread_start::thread_start_synthesis`.
#[test]
#[ignore]
fn thread_start_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (verilog, what) in [
        (
            thread_start_verilog::<TB>(),
            "thread start (4,096 triangles)",
        ),
        (
            thread_start_verilog::<TB_HW>(),
            "thread start (16,384 triangles)",
        ),
    ] {
        let r = synthesize(&verilog, "top", &SynthOptions::default()).expect("yosys synth_xilinx");
        print_synthesis_row(what, &r);
    }
}
