//! The shader core's programs (`hw_model::frame::shader`) against the frame model's
//! reference shading (`frame::shade::shade`), bit for bit: the settle record (contributions'
//! sum, spawned count), every spawned ray in order (all fields) and the counters, on every ray
//! of small renders of the built-in, frame test and thesis scenes (`SKIPPED` without them),
//! with the scenes' constants and with random ones, and on random threads; the instruction
//! word's encoding and its refusals; the interpreter's and the compiler's errors.

mod common;

use std::path::Path;

use hw_model::fp32::{Fp32, Vec3};
use hw_model::frame::constants::{FrameConstants, LightConstants};
use hw_model::frame::shade::{shade, Shaded};
use hw_model::frame::shader::isa::{
    word, Counter, Field, Loc, OpKind, Pred, PushKind, CODE, CONSTANTS, MATERIAL_STRIDE,
    PREDICATES, REGISTERS,
};
use hw_model::frame::shader::{
    compile, run, thread, CompileError, Instr, IsaError, Op, Program, ProgramKind, RunError, Src,
    ThreadInput,
};
use hw_model::frame::{Frame, FrameLimits, FrameRay, FrameStats, Load, RayKind, Settle};
use hw_model::traversal::TraversalEngine;
use hw_model::Format;
use rand::rngs::StdRng;
use rand::Rng;
use sw_renderer::hit::Hit;
use sw_renderer::scene::{builtin, MaterialKind, Scene};
use sw_renderer::thesis_scenes::{for_test, SCENE_DIRS};
use sw_renderer::trace::PreparedScene;

use common::says;

fn traversal() -> TraversalEngine {
    TraversalEngine::resident(Format::FP32)
}

fn test_scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/frame_scenes")
        .join(format!("{name}.toml"));
    Scene::load(path.to_str().unwrap()).unwrap()
}

/// Every material: the glass scene, its floor a mirror, and a Phong cylinder beside it.
fn every_material() -> Scene {
    let mut scene = test_scene("glass");
    let mut phong = test_scene("phong").objects[1].clone();
    phong.object_to_world.0[3][0] -= 2.5;
    scene.objects.push(phong);
    scene.objects[0].material = test_scene("mirror").objects[1].material.clone();
    scene
}

/// What the compared rays exercised.
#[derive(Debug, Default)]
struct Tally {
    threads: [u64; 5],
    shadow_rays: u64,
    past_depth: u64,
    total_internal: u64,
    zero_shadows: u64,
}

/// One returned ray shaded both ways: the same settle record, spawned rays and counters; the
/// contributions the frame's statistics count. The reference's spawned rays.
fn compare(
    c: &FrameConstants,
    program: &Program,
    ray: &FrameRay,
    hit: Option<&Hit>,
    tally: &mut Tally,
) -> Vec<FrameRay> {
    let mut want = Shaded::default();
    shade(c, ray, hit, &mut want);
    let mut got = Shaded::default();
    let (settle, issued) = thread::shade(program, c, ray, hit, &mut got)
        .unwrap_or_else(|e| panic!("{ray:?} {hit:?}: {e}"));
    let at = || format!("{ray:?} hit {hit:?}");
    let want_settle = Settle::of(&want.contributions, want.spawned.len() as u32);
    assert_eq!(settle, want_settle, "{}", at());
    assert_eq!(got.spawned, want.spawned, "{}", at());
    assert_eq!(
        (got.zero_shadows, got.past_depth, got.total_internal),
        (want.zero_shadows, want.past_depth, want.total_internal),
        "{}",
        at()
    );
    // `FrameStats::contributions` counts a miss, an unoccluded shadow ray and each ray past
    // the depth: what the reference adds.
    let mut stats = FrameStats::default();
    match ray.kind() {
        RayKind::Shadow => {
            stats.shadow_rays = 1;
            stats.occluded = u64::from(hit.is_some());
        }
        _ => {
            stats.primary_rays = 1;
            stats.hits = u64::from(hit.is_some());
        }
    }
    stats.past_depth = want.past_depth;
    assert_eq!(stats.contributions(), want.contributions.len() as u64);
    match issued {
        Some(t) => {
            assert_eq!(t.kind, thread::program_kind(c, hit));
            tally.threads[t.kind.index()] += 1;
        }
        None => {
            assert_eq!(ray.kind(), RayKind::Shadow);
            tally.shadow_rays += 1;
        }
    }
    tally.past_depth += want.past_depth;
    tally.total_internal += want.total_internal;
    tally.zero_shadows += want.zero_shadows;
    want.spawned
}

/// Every ray of `frame`'s render with constants `c` (the frame's own or others on the same
/// geometry), a wavefront at a time, compared.
fn compare_frame(frame: &Frame, c: &FrameConstants, tally: &mut Tally) {
    let program = compile(c).unwrap_or_else(|e| panic!("{e}"));
    let mut queue: Vec<FrameRay> = (0..c.height)
        .flat_map(|j| (0..c.width).map(move |i| FrameRay::primary(c, i, j)))
        .collect();
    let mut hits = Vec::new();
    while !queue.is_empty() {
        let batch = std::mem::take(&mut queue);
        frame.cast(&batch, &mut hits).unwrap();
        for (ray, hit) in batch.iter().zip(&hits) {
            queue.extend(compare(c, &program, ray, hit.as_ref(), tally));
        }
    }
}

fn compare_scene(scene: &Scene, tally: &mut Tally) {
    let prepared = PreparedScene::new(scene).unwrap();
    let unit = traversal();
    let frame = Frame::new(scene, &prepared, &unit, 40, 24, &FrameLimits::HW).unwrap();
    assert_eq!(
        frame.program(),
        &compile(frame.constants()).unwrap(),
        "the frame's programs"
    );
    compare_frame(&frame, frame.constants(), tally);
}

fn all_kinds(tally: &Tally, what: &str) {
    for kind in ProgramKind::ALL {
        assert!(
            tally.threads[kind.index()] > 0,
            "{what}: no {kind:?} thread"
        );
    }
    assert!(
        tally.shadow_rays > 0
            && tally.past_depth > 0
            && tally.total_internal > 0
            && tally.zero_shadows > 0,
        "{what}: {tally:?}"
    );
}

#[test]
fn programs_shade_the_builtin_and_test_scenes_as_the_model() {
    let mut tally = Tally::default();
    for name in builtin::names() {
        compare_scene(&Scene::load(name).unwrap(), &mut tally);
    }
    for name in [
        "diffuse_distant",
        "diffuse_point",
        "mirror",
        "glass",
        "phong",
    ] {
        compare_scene(&test_scene(name), &mut tally);
    }
    compare_scene(&every_material(), &mut tally);
    all_kinds(&tally, "built-in and test scenes");
}

#[test]
fn programs_shade_the_thesis_scenes_as_the_model() {
    let Some(dir) = for_test("programs_shade_the_thesis_scenes_as_the_model") else {
        return;
    };
    let mut tally = Tally::default();
    for d in SCENE_DIRS {
        compare_scene(
            &Scene::load(dir.join(d).to_str().unwrap()).unwrap(),
            &mut tally,
        );
    }
    eprintln!("thesis scenes at 40×24: {tally:?}");
}

fn vec3(rng: &mut StdRng, lo: f32, hi: f32) -> Vec3 {
    Vec3::of([(); 3].map(|_| rng.gen_range(lo..hi)))
}

/// A value of an awkward kind now and then: zero of either sign, tiny, huge.
fn scalar(rng: &mut StdRng, lo: f32, hi: f32) -> Fp32 {
    Fp32::new(match rng.gen_range(0..12) {
        0 => 0.0,
        1 => -0.0,
        2 => 1e-30,
        3 => 1e30,
        _ => rng.gen_range(lo..hi),
    })
}

/// `c` with random materials (any kind, any exponent), lights (1 to 8 of both kinds),
/// background, bias and max depth.
fn random_constants(rng: &mut StdRng, c: &FrameConstants) -> FrameConstants {
    let mut c = c.clone();
    let kinds = [
        MaterialKind::Diffuse,
        MaterialKind::Phong,
        MaterialKind::Reflection,
        MaterialKind::ReflectionRefraction,
    ];
    for m in &mut c.materials {
        m.kind = kinds[rng.gen_range(0..4)];
        m.ior = Fp32::new(rng.gen_range(0.5..2.5));
        m.inv_ior = m.ior.recip();
        m.albedo = vec3(rng, -0.2, 1.5);
        m.kd = scalar(rng, 0.0, 1.2);
        m.ks = scalar(rng, 0.0, 1.2);
        m.exponent = if m.kind == MaterialKind::Phong {
            rng.gen_range(0..=FrameLimits::HW.phong_exponent)
        } else {
            0
        };
    }
    c.lights = (0..rng.gen_range(1..=FrameLimits::HW.lights))
        .map(|_| {
            if rng.gen_bool(0.5) {
                LightConstants::Distant {
                    dir: vec3(rng, -1.0, 1.0).normalized(),
                    intensity: vec3(rng, 0.0, 3.0),
                }
            } else {
                LightConstants::Point {
                    pos: vec3(rng, -6.0, 6.0),
                    intensity_over_4pi: vec3(rng, 0.0, 100.0),
                }
            }
        })
        .collect();
    c.background = vec3(rng, -0.5, 1.5);
    c.bias = Fp32::new(rng.gen_range(0.0..0.01));
    c.max_depth = rng.gen_range(0..=4);
    c
}

/// Random constants on the every-material scene's geometry, every ray of 16×9 renders.
#[test]
fn programs_shade_as_the_model_under_random_materials_and_lights() {
    let mut rng = common::rng(40);
    let scene = every_material();
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = traversal();
    let frame = Frame::new(&scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let mut tally = Tally::default();
    for _ in 0..40 {
        let c = random_constants(&mut rng, frame.constants());
        compare_frame(&frame, &c, &mut tally);
    }
    all_kinds(&tally, "random constants");
}

/// Random threads: any triangle, t, u, v, direction, weight (zeros, negatives, huge) and
/// depth, under random constants; and shadow rays, hit or not.
#[test]
fn programs_shade_random_rays_as_the_model() {
    let mut rng = common::rng(41);
    let scene = every_material();
    let prepared = PreparedScene::new(&scene).unwrap();
    let base = FrameConstants::load(&scene, &prepared, 16, 9, &FrameLimits::HW).unwrap();
    let mut tally = Tally::default();
    for _ in 0..20 {
        let c = random_constants(&mut rng, &base);
        let program = compile(&c).unwrap();
        for _ in 0..500 {
            let hit = rng.gen_bool(0.9).then(|| Hit {
                triangle: rng.gen_range(0..c.triangles.len() as u32),
                t: scalar(&mut rng, 0.0, 20.0).f32(),
                u: scalar(&mut rng, -0.1, 1.0).f32(),
                v: scalar(&mut rng, -0.1, 1.0).f32(),
            });
            let load = if rng.gen_bool(0.1) {
                Load::Shadow {
                    contribution: hw_model::frame::Contribution::of(vec3(&mut rng, -1.0, 2.0)),
                }
            } else {
                Load::Cast {
                    kind: RayKind::ALL[rng.gen_range(0..3)],
                    depth: rng.gen_range(0..=c.max_depth),
                    weight: Vec3::new(
                        scalar(&mut rng, -0.5, 1.0),
                        scalar(&mut rng, 0.0, 1.0),
                        scalar(&mut rng, 0.0, 1.0),
                    ),
                }
            };
            // Now and then a direction along the surface (d·N = 0 on a flat triangle): glass
            // where Fresnel's and the refraction's eta differ.
            let dir = match hit {
                Some(h) if rng.gen_bool(0.3) => {
                    let n = c.triangles[h.triangle as usize].normals[0];
                    Vec3::new(n.y, -n.x, Fp32::ZERO)
                }
                _ => vec3(&mut rng, -1.0, 1.0),
            };
            let ray = FrameRay {
                pixel: rng.gen_range(0..c.width * c.height),
                orig: vec3(&mut rng, -5.0, 5.0),
                dir: dir.normalized(),
                t_max: Fp32::MAX,
                load,
            };
            compare(&c, &program, &ray, hit.as_ref(), &mut tally);
        }
    }
    all_kinds(&tally, "random rays");
}

fn random_src(rng: &mut StdRng) -> Src {
    let loc = match rng.gen_range(0..3) {
        0 => Loc::Reg(rng.gen_range(0..REGISTERS as u8)),
        1 => Loc::Const(rng.gen_range(0..CONSTANTS as u16)),
        _ => Loc::MatConst(rng.gen_range(0..MATERIAL_STRIDE as u8)),
    };
    Src {
        loc,
        swizzle: [(); 3].map(|_| rng.gen_range(0..3)),
        abs: rng.gen(),
        neg: rng.gen(),
    }
}

/// A random instruction the machine has: every operation, field and operand in range.
fn random_instr(rng: &mut StdRng) -> Instr {
    let (a, b) = (random_src(rng), random_src(rng));
    let kind = OpKind::ALL[rng.gen_range(0..OpKind::ALL.len())];
    // The destination (register, predicate, field, push kind or counter) drawn until the
    // machine has it.
    let op = loop {
        let dest = rng.gen_range(0..REGISTERS as u64);
        if let Ok(op) = Op::from_fields(kind, dest, a, b) {
            if Instr::new(op).check().is_ok() {
                break op;
            }
        }
    };
    Instr {
        op,
        pred: Pred {
            index: rng.gen_range(0..PREDICATES as u8),
            invert: rng.gen(),
        },
        mask: rng.gen_range(0..8),
    }
}

#[test]
fn instruction_words_round_trip() {
    let mut rng = common::rng(42);
    let mut opcodes = std::collections::HashSet::new();
    for _ in 0..20_000 {
        let instr = random_instr(&mut rng);
        let w = instr.encode().unwrap_or_else(|e| panic!("{instr:?}: {e}"));
        assert_eq!(w >> word::BITS, 0, "{instr:?}");
        assert_eq!(Instr::decode(w), Ok(instr), "{w:#x}");
        opcodes.insert(w & ((1 << word::OPCODE.1) - 1));
    }
    assert_eq!(opcodes.len(), 17);
}

fn refused(w: u64) -> String {
    match Instr::decode(w) {
        Ok(i) => panic!("{w:#x} decoded as {i:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_instruction_words_are_refused_naming_the_field() {
    let field = |(lo, _): (u32, u32), v: u64| v << lo;
    let end = Instr::new(Op::End { a: Src::reg(0) }).encode().unwrap();
    for opcode in 17..32 {
        let w = (end & !field(word::OPCODE, 31)) | field(word::OPCODE, opcode);
        says(
            &refused(w),
            &[&format!("opcode {opcode} is not an operation")],
        );
    }
    for bit in word::BITS..64 {
        says(&refused(end | 1 << bit), &["unused bits"]);
    }
    // Operand a's kind 3.
    says(
        &refused(end | field(word::SRC_KIND, 3) << word::SRC_A),
        &["operand kind 3", "at most 2"],
    );
    // A swizzle component 3.
    says(
        &refused(end | field(word::SRC_SWIZZLE, 3) << word::SRC_A),
        &["swizzle component 3", "at most 2"],
    );
    // A material constant past the stride.
    let mat = field(word::SRC_KIND, 2) | field(word::SRC_INDEX, MATERIAL_STRIDE as u64);
    says(
        &refused(end | mat << word::SRC_A),
        &[&format!("material constant {MATERIAL_STRIDE}")],
    );
    let with = |op: Op, dest: u64| {
        let w = Instr::new(op).encode().unwrap();
        (w & !field(word::DEST, 31)) | field(word::DEST, dest)
    };
    let out = Op::Out {
        f: Field::Origin,
        a: Src::reg(0),
    };
    says(&refused(with(out, 4)), &["output field 4", "at most 3"]);
    let push = Op::Push {
        kind: PushKind::Shadow,
    };
    says(&refused(with(push, 3)), &["push kind 3", "at most 2"]);
    let count = Op::Count {
        counter: Counter::ZeroShadow,
    };
    says(&refused(with(count, 5)), &["counter 5", "at most 2"]);
    let lt = Op::Lt {
        p: 2,
        a: Src::reg(0),
        b: Src::reg(1),
    };
    for p in [0, 1] {
        says(
            &refused(with(lt, p)),
            &[&format!("predicate {p} is read-only")],
        );
    }
    says(&refused(with(lt, 8)), &["written predicate 8", "at most 7"]);
    // An operand an operation does not read, or a destination it does not write.
    let nop = Instr::new(Op::Nop).encode().unwrap();
    says(
        &refused(nop | field(word::SRC_INDEX, 1) << word::SRC_B),
        &["bits the operation does not use"],
    );
    says(
        &refused(with(Op::End { a: Src::reg(0) }, 1)),
        &["bits the operation does not use"],
    );
    // And instructions outside the machine are not encoded.
    for (instr, parts) in [
        (
            Instr::new(Op::Mov {
                d: REGISTERS as u8,
                a: Src::reg(0),
            }),
            vec!["register 32", "at most 31"],
        ),
        (
            Instr::new(Op::Mov {
                d: 0,
                a: Src::of(Loc::Const(CONSTANTS as u16)),
            }),
            vec!["constant 512", "at most 511"],
        ),
        (
            Instr::new(Op::Nop).when(Pred::when(PREDICATES as u8)),
            vec!["predicate 8", "at most 7"],
        ),
        (Instr::new(Op::Nop).lanes(8), vec!["write mask 8"]),
    ] {
        match instr.encode() {
            Ok(w) => panic!("{instr:?} encoded as {w:#x}"),
            Err(e @ IsaError::Operand { .. }) => says(&e.to_string(), &parts),
            Err(e) => panic!("{e}"),
        }
    }
}

#[test]
fn the_interpreter_refuses_a_thread_without_end_or_entry() {
    let program = Program {
        code: vec![Instr::new(Op::Nop), Instr::new(Op::End { a: Src::reg(0) })],
        constants: vec![],
        material_entry: vec![0],
        miss_entry: 0,
    };
    let input = ThreadInput {
        entry: 0,
        material: 0,
        registers: [[7; 3]; 7],
        past_depth: false,
    };
    let out = run(&program, &input).unwrap();
    assert_eq!((out.sum, out.instructions), ([7; 3], 2));
    let no_end = Program {
        code: vec![Instr::new(Op::Nop); 3],
        ..program.clone()
    };
    let e = run(&no_end, &input).unwrap_err();
    assert_eq!(e, RunError::NoEnd { pc: 3, len: 3 });
    says(&e.to_string(), &["without End", "3 instructions"]);
    let e = run(&program, &ThreadInput { entry: 2, ..input }).unwrap_err();
    says(&e.to_string(), &["entry point 2", "2 instructions"]);
    let material = (CONSTANTS / MATERIAL_STRIDE) as u32;
    let e = run(&program, &ThreadInput { material, ..input }).unwrap_err();
    says(
        &e.to_string(),
        &[&format!("material {material}"), "512 entries"],
    );
    // A predicated-off End does not end the thread.
    let skipped = Program {
        code: vec![Instr::new(Op::End { a: Src::reg(0) }).when(Pred::unless(0))],
        ..program
    };
    assert!(matches!(
        run(&skipped, &input),
        Err(RunError::NoEnd { pc: 1, .. })
    ));
}

#[test]
fn scenes_beyond_the_shader_core_are_errors_naming_the_sizes() {
    let scene = test_scene("phong");
    let prepared = PreparedScene::new(&scene).unwrap();
    let base = FrameConstants::load(&scene, &prepared, 16, 9, &FrameLimits::HW).unwrap();
    let phong = *base
        .materials
        .iter()
        .find(|m| m.kind == MaterialKind::Phong)
        .unwrap();
    // Many Phong exponents under 8 lights: more code than the program memory holds.
    let mut code = base.clone();
    code.lights = (0..8).map(|k| base.lights[k % base.lights.len()]).collect();
    code.materials = (0..64)
        .map(|e| hw_model::frame::constants::MaterialConstants {
            exponent: 255 - e,
            ..phong
        })
        .collect();
    match compile(&code) {
        Err(e @ CompileError::Code { used, limit }) => {
            assert!(used > CODE && limit == CODE);
            says(
                &e.to_string(),
                &[&format!("{used} instructions"), &format!("holds {CODE}")],
            );
        }
        other => panic!("{other:?}"),
    }
    // More materials than the constant memory holds.
    let mut constants = base.clone();
    constants.materials = vec![phong; CONSTANTS / MATERIAL_STRIDE];
    match compile(&constants) {
        Err(e @ CompileError::Constants { used, .. }) => {
            assert!(used > CONSTANTS);
            says(
                &e.to_string(),
                &[&format!("{used} entries"), &format!("holds {CONSTANTS}")],
            );
        }
        other => panic!("{other:?}"),
    }
}

/// A scene whose programs do not fit is a load error of the frame naming the scene and the
/// sizes (what `rtfpga render --engine frame` reports).
#[test]
fn a_frame_whose_programs_do_not_fit_is_a_load_error() {
    let mut scene = test_scene("phong");
    let cylinder = scene.objects[1].clone();
    for e in 0..40 {
        let mut o = cylinder.clone();
        o.material.n = (200 + e) as f32;
        scene.objects.push(o);
    }
    while scene.lights.len() < 8 {
        scene.lights.push(scene.lights[1].clone());
    }
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = traversal();
    let loaded = Frame::new(&scene, &prepared, &unit, 16, 9, &FrameLimits::HW);
    match loaded {
        Ok(_) => panic!("loaded"),
        Err(e) => says(
            &e.to_string(),
            &[
                "scene `phong`: the shader core: the shading programs take",
                "program memory holds 2048",
            ],
        ),
    };
}

/// The thesis scenes at 320×180 through the frame engine (the shader core's programs):
/// code and constants per scene; per program kind the instructions issued per thread and
/// the threads (`kind=instructions×threads`); all the instructions, the rays traced and the
/// instructions per traced ray (docs/frame.md, "Shading programs").
#[test]
#[ignore]
fn shader_load_of_the_thesis_scenes() {
    let Some(dir) = for_test("shader_load_of_the_thesis_scenes") else {
        return;
    };
    let unit = traversal();
    for d in SCENE_DIRS {
        let scene = Scene::load(dir.join(d).to_str().unwrap()).unwrap();
        let prepared = PreparedScene::new(&scene).unwrap();
        let frame = Frame::new(&scene, &prepared, &unit, 320, 180, &FrameLimits::HW).unwrap();
        let out = frame
            .render(32, hw_model::frame::WAVEFRONT, &|| {})
            .unwrap();
        let p = frame.program();
        let mut line = format!("{d}: code={} constants={}", p.code.len(), p.constants.len());
        let (mut threads, mut instructions) = (0, 0);
        for kind in ProgramKind::ALL {
            let load = out.stats.shader(kind);
            if load.threads > 0 {
                line += &format!(
                    " {}={:.1}×{}",
                    kind.name(),
                    load.instructions as f64 / load.threads as f64,
                    load.threads
                );
            }
            threads += load.threads;
            instructions += load.instructions;
        }
        println!(
            "{line} all={:.1}×{threads} instructions={instructions} rays={} per_ray={:.1}",
            instructions as f64 / threads as f64,
            out.stats.rays(),
            instructions as f64 / out.stats.rays() as f64,
        );
    }
}
