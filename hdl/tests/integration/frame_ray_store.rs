//! The frame engine's ray store (`hdl::frame::ray_store`) in rust-hdl's simulator: its entry
//! holds the model's ray in flight bit for bit (`StoredRay::of` and back to the same
//! `FrameRay`, every ray of 16×9 renders of the frame test scenes: primary, reflection,
//! refraction and shadow rays at every depth they reach, with their answers), and each
//! reader shows, a cycle after its id, its fields of the entry as it was before that edge's
//! writes, cycle by cycle against a model of the entries: random rays and answers written
//! at random entries while all four readers read random entries, a few entries at a time (so
//! reads meet writes to their entry at the same edge) and all 512. Entries that do not fit are
//! errors naming the sizes; Verilator's lint.

use crate::common::{frame_test_scene, print_synthesis_row, SYNTHESIS_COLUMNS};

use hdl::frame::id_queue::IDS;
use hdl::frame::ray_store::{
    ray_store_verilog, simulate_ray_store, stored_answer, StoreError, StoreInput, StoreOutput,
    StoredAnswer, StoredRay,
};
use hdl::frame::thread_start::triangles;
use hw_model::frame::shade::Shaded;
use hw_model::frame::shader::thread;
use hw_model::frame::{Frame, FrameLimits, FrameRay, Load, RayKind};
use hw_model::traversal::TraversalEngine;
use hw_model::Format;
use rand::{rngs::StdRng, seq::SliceRandom, Rng, SeedableRng};
use sw_renderer::hit::Hit;
use sw_renderer::trace::PreparedScene;

/// The triangle memory's address bits the test builds.
const TB: usize = 12;

/// Every ray of a 16×9 render of the frame test scene `name` and its answer.
fn rays(name: &str) -> Vec<(FrameRay, Option<Hit>)> {
    let scene = frame_test_scene(name);
    let prepared = PreparedScene::new(&scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = Frame::new(&scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let c = frame.constants();
    let mut queue: Vec<FrameRay> = (0..c.height)
        .flat_map(|j| (0..c.width).map(move |i| (i, j)))
        .map(|(i, j)| FrameRay::primary(c, i, j))
        .collect();
    let (mut out, mut hits, mut shaded) = (Vec::new(), Vec::new(), Shaded::default());
    while !queue.is_empty() {
        let batch = std::mem::take(&mut queue);
        frame.cast(&batch, &mut hits).unwrap();
        for (ray, hit) in batch.iter().zip(&hits) {
            out.push((*ray, *hit));
            shaded.clear();
            thread::shade(frame.program(), c, ray, hit.as_ref(), &mut shaded).unwrap();
            queue.extend_from_slice(&shaded.spawned);
        }
    }
    out
}

fn pool() -> Vec<(StoredRay, StoredAnswer)> {
    let mut pool = Vec::new();
    let mut kinds = [0; 4];
    for name in ["glass", "phong", "diffuse_point", "mirror"] {
        for (ray, hit) in rays(name) {
            let stored = StoredRay::of(&ray).unwrap();
            assert_eq!(
                stored.frame_ray(),
                ray,
                "{name}: the entry holds the model's ray"
            );
            kinds[stored.tag.kind] += 1;
            pool.push((stored, stored_answer::<TB>(hit.as_ref()).unwrap()));
        }
    }
    assert!(kinds.iter().all(|&k| k > 0), "every kind of ray: {kinds:?}");
    pool
}

/// What each reader shows of an entry.
fn shown(read: [usize; 4], at: &Entries) -> StoreOutput {
    let entry = |k: usize| at.rays[read[k]];
    let (packet, returned, start) = (entry(0), entry(1), entry(2));
    StoreOutput {
        packet: StoredRay {
            payload: [0; 3],
            ..packet
        },
        returned: StoredRay {
            tag: returned.tag,
            payload: returned.payload,
            ..StoredRay::default()
        },
        start: (StoredRay { t_max: 0, ..start }, at.answers[read[2]]),
        scan: entry(3).tag,
    }
}

struct Entries {
    rays: Vec<StoredRay>,
    answers: Vec<StoredAnswer>,
}

fn check(pool: &[(StoredRay, StoredAnswer)], span: usize, cycles: usize, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let inputs: Vec<StoreInput> = (0..cycles)
        .map(|_| {
            let (ray, answer) = *pool.choose(&mut rng).unwrap();
            StoreInput {
                ray: rng.gen_bool(0.6).then(|| (rng.gen_range(0..span), ray)),
                answer: rng.gen_bool(0.5).then(|| (rng.gen_range(0..span), answer)),
                read: std::array::from_fn(|_| rng.gen_range(0..span)),
            }
        })
        .collect();
    let mut feed = inputs.clone().into_iter();
    let runs = simulate_ray_store::<TB>(move |_| feed.next());
    let mut at = Entries {
        rays: vec![StoredRay::default(); IDS],
        answers: vec![None; IDS],
    };
    let mut want: Option<StoreOutput> = None;
    let mut met = 0;
    for (cycle, (input, out)) in runs.iter().enumerate() {
        if let Some(w) = want {
            assert_eq!(*out, w, "span {span}: the readers at cycle {cycle}");
        }
        want = Some(shown(input.read, &at));
        met += usize::from(input.ray.is_some_and(|(id, _)| input.read.contains(&id)));
        if let Some((id, ray)) = input.ray {
            at.rays[id] = ray;
        }
        if let Some((id, answer)) = input.answer {
            at.answers[id] = answer;
        }
    }
    assert!(met > 0, "span {span}: reads meet writes to their entry");
}

#[test]
fn ray_store_holds_the_models_rays() {
    let pool = pool();
    check(&pool, 6, 1500, 1);
    check(&pool, IDS, 3000, 2);
}

#[test]
fn ray_store_refuses_what_does_not_fit() {
    let (ray, _) = rays("mirror")[0];
    let far = FrameRay {
        pixel: 1 << 21,
        ..ray
    };
    assert_eq!(
        StoredRay::of(&far),
        Err(StoreError::Pixel { pixel: 1 << 21 })
    );
    let deep = FrameRay {
        load: Load::Cast {
            kind: RayKind::Reflection,
            depth: 16,
            weight: hw_model::fp32::Vec3::of([1.0; 3]),
        },
        ..ray
    };
    let e = StoredRay::of(&deep).unwrap_err();
    assert_eq!(e, StoreError::Depth { depth: 16 });
    assert!(e.to_string().contains("4 bits"), "{e}");
    let hit = Hit {
        triangle: triangles(TB) as u32,
        t: 1.0,
        u: 0.0,
        v: 0.0,
    };
    let e = stored_answer::<TB>(Some(&hit)).unwrap_err().to_string();
    assert_eq!(
        e,
        "triangle 4096: the frame engine's triangle memory holds 4096"
    );
}

#[test]
fn ray_store_verilog_passes_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&ray_store_verilog::<TB>()) {
        panic!("ray store: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_ray_store::ray_store_synthesis`.
#[test]
#[ignore]
fn ray_store_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let r = synthesize(&ray_store_verilog::<14>(), "top", &SynthOptions::default())
        .expect("yosys synth_xilinx");
    print_synthesis_row("ray store (512, TB = 14)", &r);
}
