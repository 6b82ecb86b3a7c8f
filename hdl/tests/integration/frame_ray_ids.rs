//! The frame engine's ray ids (`hdl::frame::ray_ids`) in rust-hdl's simulator against the
//! ray store of `hw_model::frame::schedule` as the engine keeps it: rays taken by ray
//! generation (above the spawn reserve) and by pushes (from their thread's reservation),
//! freed by shadow answers and by thread starts (which reserve M), reservations given back
//! by settles. Random traffic: the store filled to the spawn reserve, then both freeing
//! sources at once with takes past the fresh ids into the FIFOs, then drained: every id taken is free
//! (never one in use) and below the store's size; the available count, `fits`,
//! `fits_above_reserve` and `primary_ready` equal the model's every cycle (a freed id
//! counted `FREE_LATENCY` cycles after its free); all ids available again at the end.
//! Verilator's lint.

use std::collections::{BTreeSet, VecDeque};

use crate::common::{print_synthesis_row, SYNTHESIS_COLUMNS};
use hdl::frame::ray_ids::{
    ray_ids_verilog, simulate_ray_ids, IdsInput, IdsOutput, FREE_LATENCY, IDS,
};
use rand::{rngs::StdRng, Rng, SeedableRng};

/// A running thread: the rays it will push, and those it has.
struct Thread {
    spawns: usize,
    pushed: usize,
}

/// The store as the model keeps it, and the traffic's choices.
struct Model {
    rng: StdRng,
    spawn_reserve: usize,
    escape_reserve: usize,
    m: usize,
    held: BTreeSet<usize>,
    reserved: usize,
    /// Ids freed in each of the last cycles (not yet counted).
    recent: VecDeque<usize>,
    threads: Vec<Thread>,
    cycle: usize,
    cycles: usize,
    /// The inputs and the model's expectations of the cycle before.
    last: Option<(IdsInput, usize)>,
    idle: usize,
}

impl Model {
    fn available(&self) -> usize {
        IDS - self.held.len() - self.reserved - self.recent.iter().sum::<usize>()
    }

    /// Checks what the block showed for the cycle before, applies it, picks this cycle's
    /// inputs.
    fn drive(&mut self, shown: Option<&IdsOutput>) -> Option<IdsInput> {
        if let (Some((input, available)), Some(out)) = (self.last.take(), shown) {
            let at = format!("cycle {}: {input:?} {out:?}", self.cycle - 1);
            assert_eq!(out.available, available, "{at}");
            assert_eq!(out.fits, available >= self.m, "{at}");
            assert_eq!(
                out.fits_above_reserve,
                available >= self.m + self.escape_reserve,
                "{at}"
            );
            let ready = !input.push && input.start.is_none() && available > self.spawn_reserve;
            assert_eq!(out.primary_ready, ready, "{at}");
            let mut freed = 0;
            for id in input.shadow_free.into_iter().chain(input.start) {
                assert!(self.held.remove(&id), "{at}: {id} freed twice");
                freed += 1;
            }
            if input.push || (input.primary_valid && out.primary_ready) {
                assert!(out.id < IDS, "{at}: id {}", out.id);
                assert!(self.held.insert(out.id), "{at}: id {} is in use", out.id);
            }
            if input.push {
                self.reserved -= 1;
            }
            if input.start.is_some() {
                self.reserved += self.m;
            }
            if let Some(spawned) = input.settle {
                self.reserved -= self.m - spawned;
            }
            self.recent.push_back(freed);
            while self.recent.len() > FREE_LATENCY - 1 {
                self.recent.pop_front();
            }
        }
        let available = self.available();
        let rng = &mut self.rng;
        // A third of the run filling the store, then churn, then draining it.
        let filling = self.cycle < self.cycles / 3;
        let ending = self.cycle >= self.cycles;
        let mut input = IdsInput {
            spawn_reserve: self.spawn_reserve,
            escape_reserve: self.escape_reserve,
            reservation: self.m,
            primary_valid: !ending && rng.gen_bool(0.7),
            ..IdsInput::default()
        };
        // A push, from a thread with rays left to push.
        let pushing: Vec<usize> = (0..self.threads.len())
            .filter(|&t| self.threads[t].pushed < self.threads[t].spawns)
            .collect();
        if !pushing.is_empty() && rng.gen_bool(0.6) {
            let t = pushing[rng.gen_range(0..pushing.len())];
            self.threads[t].pushed += 1;
            input.push = true;
        }
        // A settle, of a thread that has pushed all it will.
        let done = (0..self.threads.len()).find(|&t| {
            let th = &self.threads[t];
            th.pushed == th.spawns
        });
        if let Some(t) = done.filter(|_| rng.gen_bool(0.5)) {
            input.settle = Some(self.threads.remove(t).spawns);
        }
        let held: Vec<usize> = self.held.iter().copied().collect();
        let pick = |rng: &mut StdRng, not: Option<usize>| {
            let choices: Vec<usize> = held.iter().copied().filter(|&i| Some(i) != not).collect();
            (!choices.is_empty()).then(|| choices[rng.gen_range(0..choices.len())])
        };
        // A thread start: its own entry freed, M reserved.
        let starts = if filling { 0.1 } else { 0.5 };
        if !ending && available >= self.m && self.threads.len() < 16 && rng.gen_bool(starts) {
            if let Some(id) = pick(rng, None) {
                input.start = Some(id);
                self.threads.push(Thread {
                    spawns: rng.gen_range(0..=self.m),
                    pushed: 0,
                });
            }
        }
        // A shadow answer.
        let frees = match (filling, ending) {
            (true, _) => 0.05,
            (_, true) => 0.9,
            _ => 0.4,
        };
        if rng.gen_bool(frees) {
            input.shadow_free = pick(rng, input.start);
        }
        if ending && self.held.is_empty() && self.threads.is_empty() {
            self.idle += 1;
        }
        self.cycle += 1;
        self.last = Some((input, available));
        (self.idle <= FREE_LATENCY + 1).then_some(input)
    }
}

fn check(m: usize, spawn_reserve: usize, escape_reserve: usize, cycles: usize, seed: u64) {
    let mut model = Model {
        rng: StdRng::seed_from_u64(seed),
        spawn_reserve,
        escape_reserve,
        m,
        held: BTreeSet::new(),
        reserved: 0,
        recent: VecDeque::new(),
        threads: Vec::new(),
        cycle: 0,
        cycles,
        last: None,
        idle: 0,
    };
    let run = simulate_ray_ids(move |shown| model.drive(shown));
    let (_, last) = run.last().expect("cycles");
    assert_eq!(last.available, IDS, "every id free at the end");
    let takes = run
        .iter()
        .filter(|(i, o)| i.push || (i.primary_valid && o.primary_ready))
        .count();
    assert!(takes > 2 * IDS, "{takes} takes: past the fresh ids");
    let starved = run
        .iter()
        .filter(|(i, o)| i.primary_valid && !i.push && i.start.is_none() && !o.primary_ready)
        .count();
    assert!(starved > 0, "the spawn reserve never held generation back");
}

#[test]
fn ray_ids_match_the_model_under_random_traffic() {
    check(8, 128, 28, 3000, 1);
    check(2, 13, 12, 3000, 2);
}

#[test]
fn ray_ids_verilog_passes_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&ray_ids_verilog()) {
        panic!("ray ids: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_ray_ids::ray_ids_synthesis`.
#[test]
#[ignore]
fn ray_ids_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    let r = synthesize(&ray_ids_verilog(), "top", &SynthOptions::default())
        .expect("yosys synth_xilinx");
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    print_synthesis_row("ray ids", &r);
}
