//! The frame engine's queues of ray ids in rust-hdl's simulator, cycle by cycle against a
//! queue model that shows an id `SHOW_LATENCY` cycles after its write: `IdQueue` (random
//! writes and reads, filled to every id at once and drained), `TraceQueues` (spawned ids
//! before primary ones, both written in one cycle) and `WaitingQueue` (answers held until
//! taken, heads taken and some deferred back to the tail two cycles later, as the thread
//! start's decision does): every cycle's head equals the model's, every id leaves once.
//! Verilator's lint.

use std::collections::VecDeque;

use crate::common::{print_synthesis_row, Traffic, SYNTHESIS_COLUMNS};
use hdl::frame::id_queue::{id_queue_verilog, simulate_id_queue, IdQueueInput, IDS, SHOW_LATENCY};
use hdl::frame::trace_queues::{simulate_trace_queues, trace_queues_verilog, TraceInput};
use hdl::frame::waiting_queue::{
    simulate_waiting_queue, waiting_queue_verilog, WaitingInput, WaitingOutput,
};
use rand::{rngs::StdRng, seq::SliceRandom, Rng, SeedableRng};

/// The queue's model: ids in order, each shown from `SHOW_LATENCY` cycles after its write.
#[derive(Default)]
struct Model {
    ids: VecDeque<(usize, u64)>,
}

impl Model {
    fn head(&self, now: u64) -> Option<usize> {
        self.ids
            .front()
            .filter(|&&(_, at)| at <= now)
            .map(|&(id, _)| id)
    }

    fn write(&mut self, id: usize, now: u64) {
        assert!(self.ids.len() < IDS, "the test writes at most every id");
        self.ids.push_back((id, now + SHOW_LATENCY as u64));
    }

    fn read(&mut self, now: u64) -> usize {
        let id = self.head(now).expect("a read of a shown id");
        self.ids.pop_front();
        id
    }
}

const NOISY: Traffic = Traffic {
    gap: 0.4,
    stall: 0.3,
    long_stall: 0.02,
    long: 40,
};

/// Ids 0..IDS in a random order.
fn shuffled(rng: &mut StdRng) -> Vec<usize> {
    let mut ids: Vec<usize> = (0..IDS).collect();
    ids.shuffle(rng);
    ids
}

/// Replays `cycles` on the model: each cycle's head shown equals the model's; returns the
/// ids read, in order.
fn replay(what: &str, cycles: &[(Option<usize>, bool, Option<usize>)]) -> Vec<usize> {
    let mut model = Model::default();
    let mut read = Vec::new();
    for (now, &(write, take, shown)) in cycles.iter().enumerate() {
        let now = now as u64;
        assert_eq!(shown, model.head(now), "{what}: the head at cycle {now}");
        if take {
            read.push(model.read(now));
        }
        if let Some(id) = write {
            model.write(id, now);
        }
    }
    read
}

/// Cycles after the last id leaves: nothing else may show.
const TAIL: u64 = 4;

/// `IdQueue` under `traffic`; `fill`: every id written before the first read.
fn check_id_queue(traffic: Traffic, fill: bool, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let ids = shuffled(&mut rng);
    let (mut next, mut now, mut stalled, mut left, mut after) = (0, 0u64, 0, IDS, 0);
    let mut model = Model::default();
    let runs = simulate_id_queue(move |_| {
        let write = (next < IDS && !rng.gen_bool(traffic.gap)).then(|| {
            next += 1;
            ids[next - 1]
        });
        let ready = traffic.ready(&mut rng, &mut stalled) && (!fill || next == IDS);
        let read = ready && model.head(now).is_some();
        if read {
            model.read(now);
            left -= 1;
        }
        if let Some(id) = write {
            model.write(id, now);
        }
        now += 1;
        if left == 0 {
            after += 1;
        }
        (after <= TAIL).then_some(IdQueueInput { write, read })
    });
    let cycles: Vec<_> = runs.iter().map(|(i, o)| (i.write, i.read, *o)).collect();
    let written: Vec<usize> = cycles.iter().filter_map(|c| c.0).collect();
    assert_eq!(written.len(), IDS);
    assert_eq!(
        replay("id queue", &cycles),
        written,
        "every id out once, in order"
    );
    if fill {
        let most = (runs.iter().scan(0i64, |n, (i, _)| {
            *n += i64::from(i.write.is_some()) - i64::from(i.read);
            Some(*n)
        }))
        .max();
        assert_eq!(most, Some(IDS as i64), "every id held at once");
    }
}

#[test]
fn id_queue_matches_the_model() {
    check_id_queue(NOISY, false, 1);
    check_id_queue(NOISY, true, 2);
    check_id_queue(crate::common::FLOWING, false, 3);
}

/// `TraceQueues`: ids 0..IDS split at random between the spawned and the primary queue,
/// under `traffic`: every cycle's id is the spawned model's head, else the primary's.
fn check_trace_queues(traffic: Traffic, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let ids = shuffled(&mut rng);
    let split = rng.gen_range(IDS / 4..3 * IDS / 4);
    let (spawned_ids, primary_ids) = (ids[..split].to_vec(), ids[split..].to_vec());
    let (mut s, mut p, mut now, mut stalled, mut left, mut after) = (0, 0, 0u64, 0, IDS, 0);
    let mut models = [Model::default(), Model::default()];
    let runs = simulate_trace_queues(move |_| {
        let mut input = TraceInput::default();
        if s < spawned_ids.len() && !rng.gen_bool(traffic.gap) {
            input.spawned = Some(spawned_ids[s]);
            s += 1;
        }
        if p < primary_ids.len() && !rng.gen_bool(traffic.gap) {
            input.primary = Some(primary_ids[p]);
            p += 1;
        }
        input.out_ready = traffic.ready(&mut rng, &mut stalled);
        if input.out_ready {
            if models[0].head(now).is_some() {
                models[0].read(now);
                left -= 1;
            } else if models[1].head(now).is_some() {
                models[1].read(now);
                left -= 1;
            }
        }
        for (m, id) in models.iter_mut().zip([input.spawned, input.primary]) {
            if let Some(id) = id {
                m.write(id, now);
            }
        }
        now += 1;
        if left == 0 {
            after += 1;
        }
        (after <= TAIL).then_some(input)
    });
    // Replay: the head shown is the spawned model's, else the primary's.
    let mut models = [Model::default(), Model::default()];
    let mut out = Vec::new();
    let mut both = 0;
    for (now, (input, shown)) in runs.iter().enumerate() {
        let now = now as u64;
        let heads = [models[0].head(now), models[1].head(now)];
        both += usize::from(heads[0].is_some() && heads[1].is_some());
        assert_eq!(
            *shown,
            heads[0].or(heads[1]),
            "trace queues: the id at cycle {now}"
        );
        if input.out_ready && shown.is_some() {
            out.push(models[usize::from(heads[0].is_none())].read(now));
        }
        for (m, id) in models.iter_mut().zip([input.spawned, input.primary]) {
            if let Some(id) = id {
                m.write(id, now);
            }
        }
    }
    assert!(both > 0, "spawned and primary ids waiting at once");
    out.sort_unstable();
    assert_eq!(out, (0..IDS).collect::<Vec<_>>(), "every id out once");
}

#[test]
fn trace_queues_send_spawned_rays_first() {
    check_trace_queues(NOISY, 4);
    check_trace_queues(
        Traffic {
            gap: 0.1,
            stall: 0.6,
            long_stall: 0.01,
            long: 100,
        },
        5,
    );
    check_trace_queues(crate::common::FLOWING, 6);
}

/// Cycles from a head taken to its start decided (the thread start's latency).
const DECIDED: usize = hdl::frame::thread_start::LATENCY;

/// `WaitingQueue`: ids 0..IDS answered under `traffic`, each held until `answer_ready`;
/// heads taken when ready, a share `defer` of them back to the tail `DECIDED` cycles later.
fn check_waiting_queue(traffic: Traffic, defer: f64, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let ids = shuffled(&mut rng);
    let (mut next, mut now, mut stalled, mut started, mut after) = (0, 0u64, 0, 0, 0);
    let mut offered: Option<usize> = None;
    let mut deciding: VecDeque<Option<usize>> = vec![None; DECIDED].into();
    let mut model = Model::default();
    let runs = simulate_waiting_queue(move |_| {
        let mut input = WaitingInput {
            deferred: deciding.pop_front().flatten(),
            ..WaitingInput::default()
        };
        if offered.is_none() && next < IDS && !rng.gen_bool(traffic.gap) {
            offered = Some(ids[next]);
            next += 1;
        }
        input.answer = offered;
        input.out_ready = traffic.ready(&mut rng, &mut stalled);
        let taken = (input.out_ready && model.head(now).is_some()).then(|| model.read(now));
        if let Some(id) = input.deferred {
            model.write(id, now);
        } else if let Some(id) = offered.take() {
            model.write(id, now);
        }
        match taken {
            Some(id) if rng.gen_bool(defer) => deciding.push_back(Some(id)),
            Some(_) => {
                started += 1;
                deciding.push_back(None);
            }
            None => deciding.push_back(None),
        }
        now += 1;
        if started == IDS {
            after += 1;
        }
        (after <= TAIL).then_some(input)
    });
    let mut model = Model::default();
    let (mut deferred, mut out) = (0, Vec::new());
    for (now, (input, shown)) in runs.iter().enumerate() {
        let now = now as u64;
        let want = WaitingOutput {
            answer_ready: input.deferred.is_none(),
            head: model.head(now),
        };
        assert_eq!(*shown, want, "waiting queue at cycle {now}");
        if input.out_ready && shown.head.is_some() {
            out.push(model.read(now));
        }
        if let Some(id) = input.deferred {
            deferred += 1;
            model.write(id, now);
        } else if let Some(id) = input.answer {
            model.write(id, now);
        }
    }
    let answered: Vec<usize> = (runs.iter().enumerate())
        .filter(|(_, (i, o))| i.answer.is_some() && o.answer_ready)
        .map(|(_, (i, _))| i.answer.unwrap())
        .collect();
    assert_eq!(answered.len(), IDS, "every answer taken once");
    assert!(deferred > IDS / 10, "starts deferred: {deferred}");
    assert_eq!(out.len(), IDS + deferred, "every id out once a wait");
}

#[test]
fn waiting_queue_sends_deferred_starts_to_the_tail() {
    check_waiting_queue(NOISY, 0.3, 7);
    check_waiting_queue(crate::common::FLOWING, 0.5, 8);
}

#[test]
fn id_queues_pass_verilator_lint() {
    for (what, v) in [
        ("id queue", id_queue_verilog()),
        ("trace queues", trace_queues_verilog()),
        ("waiting queue", waiting_queue_verilog()),
    ] {
        if let Err(e) = hdl::verilog::verilator_lint(&v) {
            panic!("{what}: verilator lint failed:\n{e}");
        }
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_queues::queues_synthesis`.
#[test]
#[ignore]
fn queues_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (what, v) in [
        ("id queue (512)", id_queue_verilog()),
        ("trace queues", trace_queues_verilog()),
        ("waiting queue", waiting_queue_verilog()),
    ] {
        let r = synthesize(&v, "top", &SynthOptions::default()).expect("yosys synth_xilinx");
        print_synthesis_row(what, &r);
    }
}
