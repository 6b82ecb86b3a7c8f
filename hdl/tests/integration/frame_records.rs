//! The accumulator's sources (`hdl::frame::records`) in rust-hdl's simulator, cycle by cycle
//! against a model of the arbiter (one record register; a thread's settle first, then a
//! shadow answer, then an open), each shadow answer's record bit for bit
//! `thread::shade` of its shadow ray: the shadow rays of 16×9 renders of the built-in scenes
//! and the frame test scenes (occluded and not) and random contributions at the format's
//! extremes, beside random opens and thread settles (sums at the settle's extremes), under
//! random gaps and back-pressure with long stalls, and flowing. Verilator's lint.

use std::collections::VecDeque;

use crate::common::{
    frame_test_scene, print_synthesis_row, Traffic, FLOWING, FRAME_TEST_SCENES, SYNTHESIS_COLUMNS,
};
use hdl::frame::accumulate::{Command, Record, PIXEL_SLOTS, SETTLE_BITS};
use hdl::frame::records::{
    records_verilog, simulate_records, RecordsInput, RecordsOutput, ShadowAnswer,
};
use hw_model::frame::accumulate::{Contribution, Settle, CONTRIBUTION};
use hw_model::frame::shade::Shaded;
use hw_model::frame::shader::thread;
use hw_model::frame::{Frame, FrameLimits, FrameRay, Load, RayKind};
use hw_model::traversal::TraversalEngine;
use hw_model::Format;
use rand::{rngs::StdRng, Rng, SeedableRng};
use sw_renderer::hit::Hit;
use sw_renderer::scene::{builtin, Scene};
use sw_renderer::trace::PreparedScene;

/// A shadow answer and the record the model makes of it.
type ShadowCase = (ShadowAnswer, Record);

fn shadow_case(ray: &FrameRay, settle: Settle, occluded: bool) -> ShadowCase {
    let Load::Shadow { contribution } = ray.load else {
        unreachable!("a shadow ray")
    };
    let slot = ray.pixel as usize % PIXEL_SLOTS;
    (
        ShadowAnswer {
            slot,
            occluded,
            payload: contribution.0.map(|x| x as u32),
        },
        Record::new(slot, Command::Settle(settle)).unwrap(),
    )
}

/// The model's record of a shadow ray and its answer.
fn shade_shadow(frame: &Frame, ray: &FrameRay, hit: Option<&Hit>) -> ShadowCase {
    let mut shaded = Shaded::default();
    let (settle, issued) =
        thread::shade(frame.program(), frame.constants(), ray, hit, &mut shaded).unwrap();
    assert!(issued.is_none() && shaded.spawned.is_empty());
    shadow_case(ray, settle, hit.is_some())
}

/// Every shadow ray of a 16×9 render of `scene`, a wavefront at a time, with its record.
fn shadow_cases(scene: &Scene) -> Vec<ShadowCase> {
    let prepared = PreparedScene::new(scene).unwrap();
    let unit = TraversalEngine::resident(Format::FP32);
    let frame = Frame::new(scene, &prepared, &unit, 16, 9, &FrameLimits::HW).unwrap();
    let c = frame.constants();
    let mut queue: Vec<FrameRay> = (0..c.height)
        .flat_map(|j| (0..c.width).map(move |i| (i, j)))
        .map(|(i, j)| FrameRay::primary(c, i, j))
        .collect();
    let (mut cases, mut hits, mut shaded) = (Vec::new(), Vec::new(), Shaded::default());
    while !queue.is_empty() {
        let batch = std::mem::take(&mut queue);
        frame.cast(&batch, &mut hits).unwrap();
        for (ray, hit) in batch.iter().zip(&hits) {
            if ray.kind() == RayKind::Shadow {
                cases.push(shade_shadow(&frame, ray, hit.as_ref()));
            } else {
                shaded.clear();
                thread::shade(frame.program(), c, ray, hit.as_ref(), &mut shaded).unwrap();
                queue.extend_from_slice(&shaded.spawned);
            }
        }
    }
    // Random contributions, the format's extremes among them, occluded or not.
    let ray = FrameRay::primary(c, 0, 0);
    let (lo, hi) = (
        -(1i32 << (CONTRIBUTION.width() - 1)),
        (1i32 << (CONTRIBUTION.width() - 1)) - 1,
    );
    let mut rng = StdRng::seed_from_u64(cases.len() as u64);
    for _ in 0..40 {
        let contribution = Contribution(std::array::from_fn(|_| match rng.gen_range(0..4) {
            0 => lo,
            1 => hi,
            _ => rng.gen_range(lo..=hi),
        }));
        let shadow = FrameRay {
            pixel: rng.gen_range(0..1 << 21),
            load: Load::Shadow { contribution },
            ..ray
        };
        let hit = rng.gen_bool(0.3).then_some(Hit {
            triangle: 0,
            t: 1.0,
            u: 0.0,
            v: 0.0,
        });
        cases.push(shade_shadow(&frame, &shadow, hit.as_ref()));
    }
    cases
}

/// Random thread settles: sums at the settle's extremes and between, 0 to 8 spawned.
fn settles(rng: &mut StdRng, n: usize) -> Vec<Record> {
    let limit = 1i64 << (SETTLE_BITS - 1);
    (0..n)
        .map(|_| {
            let sum = std::array::from_fn(|_| match rng.gen_range(0..4) {
                0 => -limit,
                1 => limit - 1,
                _ => rng.gen_range(-limit..limit),
            });
            let spawned = rng.gen_range(0..=8);
            Record::new(
                rng.gen_range(0..PIXEL_SLOTS),
                Command::Settle(Settle { sum, spawned }),
            )
            .unwrap()
        })
        .collect()
}

fn settle_of(r: &Record) -> (usize, Settle) {
    let Command::Settle(s) = r.command() else {
        unreachable!("a settle")
    };
    (r.slot(), s)
}

/// A source's items, each offered until taken.
struct Source<T> {
    items: VecDeque<T>,
    offered: bool,
}

impl<T: Copy> Source<T> {
    fn new(items: Vec<T>) -> Self {
        Source {
            items: items.into(),
            offered: false,
        }
    }

    fn offer(&mut self, rng: &mut StdRng, gap: f64) -> Option<T> {
        if !self.offered && !self.items.is_empty() && !rng.gen_bool(gap) {
            self.offered = true;
        }
        self.offered.then(|| self.items[0])
    }

    fn taken(&mut self, ready: bool) {
        if self.offered && ready {
            self.offered = false;
            self.items.pop_front();
        }
    }
}

/// Streams opens, shadow answers and settles through the block under `traffic`, checking
/// every cycle against the arbiter's model.
fn run(what: &str, shadows: Vec<ShadowCase>, traffic: Traffic, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let n = shadows.len();
    let opens: Vec<usize> = (0..n).map(|_| rng.gen_range(0..PIXEL_SLOTS)).collect();
    let thread_settles = settles(&mut rng, n);
    let want_shadow: Vec<Record> = shadows.iter().map(|c| c.1).collect();
    let mut sources = (
        Source::new(opens),
        Source::new(shadows.iter().map(|c| c.0).collect()),
        Source::new(thread_settles.iter().map(settle_of).collect()),
    );
    let (mut stalled, mut after, mut out, mut was_ready) = (0, 0, 0, false);
    let (mut cycles, what_) = (0usize, what.to_string());
    let runs = simulate_records(move |shown: Option<&RecordsOutput>| {
        if let Some(o) = shown {
            sources.0.taken(o.open_ready);
            sources.1.taken(o.shadow_ready);
            sources.2.taken(o.settle_ready);
            out += usize::from(was_ready && o.record.is_some());
        }
        let input = RecordsInput {
            open: sources.0.offer(&mut rng, traffic.gap),
            shadow: sources.1.offer(&mut rng, traffic.gap),
            settle: sources.2.offer(&mut rng, traffic.gap),
            record_ready: traffic.ready(&mut rng, &mut stalled),
        };
        was_ready = input.record_ready;
        if out == 3 * n {
            after += 1;
        }
        cycles += 1;
        assert!(
            cycles < 100 * n + 1000,
            "{what_}: records still out after {cycles} cycles"
        );
        (after <= 3).then_some(input)
    });
    // The model: one record register; a free register takes the settle, else the shadow
    // answer's record (the model's), else the open.
    let mut register: Option<Record> = None;
    let mut taken = [0; 3];
    for (cycle, (input, out)) in runs.iter().enumerate() {
        let free = register.is_none() || input.record_ready;
        let want = RecordsOutput {
            settle_ready: free,
            shadow_ready: free && input.settle.is_none(),
            open_ready: free && input.settle.is_none() && input.shadow.is_none(),
            record: register,
        };
        assert_eq!(*out, want, "{what}: cycle {cycle}");
        if free {
            register = if let Some((slot, s)) = input.settle {
                assert_eq!(
                    thread_settles[taken[2]],
                    Record::new(slot, Command::Settle(s)).unwrap()
                );
                taken[2] += 1;
                thread_settles.get(taken[2] - 1).copied()
            } else if input.shadow.is_some() {
                taken[1] += 1;
                Some(want_shadow[taken[1] - 1])
            } else {
                input.open.map(|slot| {
                    taken[0] += 1;
                    Record::new(slot, Command::Open).unwrap()
                })
            };
        }
    }
    assert_eq!(taken, [n; 3], "{what}: every source's records taken");
    let records = (runs.iter())
        .filter(|(i, o)| i.record_ready && o.record.is_some())
        .count();
    assert_eq!(records, 3 * n, "{what}: every record out once");
}

const NOISY: Traffic = Traffic {
    gap: 0.5,
    stall: 0.3,
    long_stall: 0.02,
    long: 30,
};

#[test]
fn records_match_the_model_on_the_scenes_shadow_rays() {
    let mut scenes: Vec<(String, Scene)> = (builtin::names().into_iter())
        .map(|name| (name.to_string(), Scene::load(name).unwrap()))
        .collect();
    for name in FRAME_TEST_SCENES {
        scenes.push((name.to_string(), frame_test_scene(name)));
    }
    for (k, (name, scene)) in scenes.iter().enumerate() {
        let mut cases = shadow_cases(scene);
        let settled =
            |c: &&ShadowCase| matches!(c.1.command(), Command::Settle(s) if s.sum != [0; 3]);
        assert!(
            cases.iter().any(|c| c.0.occluded) && cases.iter().any(|c| settled(&c)),
            "{name}: occluded and unoccluded shadow answers"
        );
        let flowing = cases.split_off(cases.len() / 2);
        run(name, cases, NOISY, 100 + k as u64);
        run(name, flowing, FLOWING, 200 + k as u64);
    }
}

#[test]
fn records_pass_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&records_verilog()) {
        panic!("records: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_records::records_synthesis`.
#[test]
#[ignore]
fn records_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let r = synthesize(&records_verilog(), "top", &SynthOptions::default())
        .expect("yosys synth_xilinx");
    print_synthesis_row("records", &r);
}
