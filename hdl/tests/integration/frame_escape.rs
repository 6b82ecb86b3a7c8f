//! The frame engine's escape pixel (`hdl::frame::escape`) in rust-hdl's simulator against
//! the ray store as `hw_model::frame::schedule` keeps it (`cast_depths` of a pixel slot, its
//! deepest depth in flight): random cast rays entering and leaving a store of every entry,
//! of a few pixel slots at every depth, the test answering the census's tag reads as the
//! store's RAM does (a write at an edge unseen by the read at that edge); one pixel at a time
//! draining and finishing when none of its rays is left, the waiting head's pixel offered as
//! the candidate. Every
//! designation's census takes `CENSUS_CYCLES` and is exact whatever entered or left during it
//! (a third of the events at the entry read at the last edge, at this one or the next); then the escape pixel's deepest depth in flight
//! equals the store's every cycle until it finishes. Verilator's lint.

use crate::common::{print_synthesis_row, SYNTHESIS_COLUMNS};
use hdl::frame::escape::{
    escape_verilog, simulate_escape, EscapeInput, EscapeOutput, Tag, CENSUS_CYCLES, DEPTHS,
};
use hdl::frame::ray_ids::IDS;
use rand::{rngs::StdRng, Rng, SeedableRng};

/// The store's cast rays and the designation as the model sees them.
struct Model {
    rng: StdRng,
    store: Vec<Option<Tag>>,
    slots: usize,
    /// Cycles each pixel slot in turn drains.
    phase: usize,
    /// The designated slot and the cycle it was designated in.
    designated: Option<(usize, usize)>,
    last: Option<EscapeInput>,
    cycle: usize,
    cycles: usize,
    /// Designations whose census finished, and cycles an escape was shown with a ray.
    censuses: usize,
    shown: usize,
}

impl Model {
    /// The deepest depth of `slot`'s rays in the store.
    fn deepest(&self, slot: usize) -> Option<usize> {
        (self.store.iter().flatten())
            .filter(|t| t.slot == slot)
            .map(|t| t.depth)
            .max()
    }

    fn drive(&mut self, shown: Option<&EscapeOutput>) -> Option<EscapeInput> {
        let mut scanned = None;
        // The entries about the census's address this cycle: read at the last edge, at
        // this one, and the next.
        let near: Vec<usize> = shown.map_or(vec![], |o| {
            (o.scan_address..o.scan_address + 3)
                .filter(|&i| i < IDS)
                .collect()
        });
        if let (Some(input), Some(out)) = (self.last.take(), shown) {
            // The cycle those inputs and outputs were of.
            let then = self.cycle - 1;
            let at = format!("cycle {then}: {input:?} {out:?}");
            // The tag RAM's word at the address read at the last edge: before its writes.
            scanned = self.store[out.scan_address];
            let want = self.designated.and_then(|(slot, since)| {
                (then >= since + CENSUS_CYCLES).then(|| (slot, self.deepest(slot)))
            });
            assert_eq!(out.escape, want, "{at}");
            if let Some((slot, since)) = self.designated {
                if then == since + CENSUS_CYCLES {
                    self.censuses += 1;
                }
                if want.is_some_and(|(_, d)| d.is_some()) {
                    self.shown += 1;
                }
                if input.finish == Some(slot) {
                    self.designated = None;
                }
            } else if let Some(slot) = input.candidate {
                self.designated = Some((slot, then));
            }
            if let Some((id, _)) = input.leave {
                self.store[id] = None;
            }
            if let Some((id, tag)) = input.enter {
                self.store[id] = Some(tag);
            }
        }
        if self.cycle == self.cycles {
            return None;
        }
        let empty: Vec<usize> = (0..self.slots)
            .filter(|&s| self.deepest(s).is_none())
            .collect();
        let rng = &mut self.rng;
        let used: Vec<usize> = (0..IDS).filter(|&i| self.store[i].is_some()).collect();
        let free: Vec<usize> = (0..IDS).filter(|&i| self.store[i].is_none()).collect();
        let mut input = EscapeInput {
            scanned,
            ..EscapeInput::default()
        };
        // Fill to about half the store, deep trees of a few pixels; one pixel at a time
        // gets no new rays and drains (half the leaving rays are its), so pixels finish.
        let retiring = (self.cycle / self.phase) % self.slots;
        if !free.is_empty() && rng.gen_bool(if used.len() < IDS / 2 { 0.7 } else { 0.4 }) {
            let mut slot = rng.gen_range(0..self.slots - 1);
            slot += usize::from(slot >= retiring);
            let tag = Tag {
                slot,
                depth: rng.gen_range(0..DEPTHS),
            };
            let near_free: Vec<usize> = (near.iter().copied())
                .filter(|&i| self.store[i].is_none())
                .collect();
            let id = if !near_free.is_empty() && rng.gen_bool(0.3) {
                near_free[rng.gen_range(0..near_free.len())]
            } else {
                free[rng.gen_range(0..free.len())]
            };
            input.enter = Some((id, tag));
        }
        let draining: Vec<usize> = (used.iter().copied())
            .filter(|&i| self.store[i].is_some_and(|t| t.slot == retiring))
            .collect();
        let near_used: Vec<usize> = (near.iter().copied())
            .filter(|&i| self.store[i].is_some() && input.enter.is_none_or(|(e, _)| e != i))
            .collect();
        let leaving = if !near_used.is_empty() && rng.gen_bool(0.3) {
            &near_used
        } else if !draining.is_empty() && rng.gen_bool(0.5) {
            &draining
        } else {
            &used
        };
        if !leaving.is_empty() && rng.gen_bool(0.5) {
            let id = leaving[rng.gen_range(0..leaving.len())];
            input.leave = Some((id, self.store[id].expect("used")));
        }
        // A pixel with no ray left finishes now and then.
        if !empty.is_empty() && rng.gen_bool(0.3) {
            let slot = empty[rng.gen_range(0..empty.len())];
            if input.enter.is_none_or(|(_, t)| t.slot != slot) {
                input.finish = Some(slot);
            }
        }
        if !used.is_empty() {
            input.candidate = self.store[used[rng.gen_range(0..used.len())]].map(|t| t.slot);
        }
        self.cycle += 1;
        self.last = Some(input);
        Some(input)
    }
}

fn check(slots: usize, phase: usize, cycles: usize, seed: u64) -> (usize, usize) {
    let model = Model {
        rng: StdRng::seed_from_u64(seed),
        store: vec![None; IDS],
        slots,
        phase,
        designated: None,
        last: None,
        cycle: 0,
        cycles,
        censuses: 0,
        shown: 0,
    };
    let model = std::sync::Arc::new(std::sync::Mutex::new(model));
    let driven = model.clone();
    simulate_escape(move |shown| driven.lock().unwrap().drive(shown));
    let m = model.lock().unwrap();
    (m.censuses, m.shown)
}

#[test]
fn escape_pixel_counts_its_rays_as_the_store_holds_them() {
    let (censuses, shown) = check(3, 700, 20_000, 1);
    assert!(censuses >= 3, "{censuses} censuses");
    assert!(shown > 5000, "{shown} cycles with an escape ray");
    let (censuses, _) = check(12, 400, 12_000, 2);
    assert!(censuses >= 2, "{censuses} censuses");
}

#[test]
fn escape_verilog_passes_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&escape_verilog()) {
        panic!("escape pixel: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_escape::escape_synthesis`.
#[test]
#[ignore]
fn escape_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    let r =
        synthesize(&escape_verilog(), "top", &SynthOptions::default()).expect("yosys synth_xilinx");
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    print_synthesis_row("escape pixel", &r);
}
