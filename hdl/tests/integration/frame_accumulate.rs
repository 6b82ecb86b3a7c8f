//! The frame unit's per-pixel accumulator (`hdl::frame::accumulate`) in rust-hdl's simulator,
//! bit for bit against `hw_model::frame::accumulate::Accumulator::{open, settle}`: random
//! record streams as the frame unit makes them (each pixel opened, its shaded rays settled,
//! spawning rays, until none is out) over many pixels at once, one hot pixel (a record to the
//! same slot every cycle: the forwarding path), two pixels alternating (the RAM's write read
//! back two records on), sums that go negative and beyond 255; under random gaps between
//! records and random back-pressure on the finished pixels, with long stalls: every finished
//! pixel exactly once, in the order the model finishes it, with the model's colour, none
//! before its last record plus the latency, held while not taken; `record_ready` falls when
//! the consumer stalls and never while it is always ready. Records that do not fit are
//! errors; Verilator's lint.

use crate::common::{print_synthesis_row, Traffic, FLOWING, SYNTHESIS_COLUMNS};
use hdl::frame::accumulate::{
    accumulate_verilog, latency, simulate_accumulate, AccumulateInput, AccumulateOutput, Command,
    Finished, Record, RecordError, PIXEL_SLOTS, QUEUE_DEPTH, SETTLE_BITS,
};
use hw_model::frame::accumulate::{
    max_contributions_per_ray, max_outstanding, max_spawned, Accumulator, Contribution, Settle,
    CONTRIBUTION, FRACTION_BITS,
};
use hw_model::frame::FrameLimits;
use rand::{rngs::StdRng, Rng, SeedableRng};

/// Which slots a stream's records go to.
#[derive(Clone, Copy, Debug)]
enum Pattern {
    /// Up to this many pixels in flight, in random slots, each record to a random one.
    Many(usize),
    /// One slot, every record to it; a pixel finished, the next opens there at once.
    Hot,
    /// Two slots, records alternating between them.
    Alternating,
}

/// Records and the pixels the model finishes with them: (index of the finishing record,
/// the pixel).
struct Stream {
    records: Vec<Record>,
    finished: Vec<(usize, Finished)>,
}

impl Stream {
    /// Applies `records` to the model, in order.
    fn of(records: Vec<Record>) -> Stream {
        let mut model = Accumulator::new(PIXEL_SLOTS);
        let mut finished = Vec::new();
        for (n, r) in records.iter().enumerate() {
            match r.command() {
                Command::Open => model.open(r.slot()),
                Command::Settle(s) => {
                    if let Some(rgb) = model.settle(r.slot(), &s) {
                        finished.push((
                            n,
                            Finished {
                                slot: r.slot(),
                                rgb,
                            },
                        ));
                    }
                }
            }
        }
        Stream { records, finished }
    }
}

/// A random contribution: mostly a dim colour's (a pixel sums a few hundred), some negative,
/// a few at the format's extremes or anywhere in its range.
fn contribution(rng: &mut StdRng) -> Contribution {
    let lo = -(1i32 << (CONTRIBUTION.width() - 1));
    let hi = (1i32 << (CONTRIBUTION.width() - 1)) - 1;
    Contribution(std::array::from_fn(|_| match rng.gen_range(0..1000) {
        0 => lo,
        1 => hi,
        2 => rng.gen_range(lo..=hi),
        3..=100 => -rng.gen_range(0..2 << FRACTION_BITS),
        _ => rng.gen_range(0..2 << FRACTION_BITS),
    }))
}

/// A shaded ray's record: up to the most contributions a ray adds, spawning up to `budget`
/// rays (and the most a ray spawns), mostly one.
fn settle(rng: &mut StdRng, budget: &mut u32) -> Command {
    let limits = FrameLimits::HW;
    let n = rng.gen_range(0..=max_contributions_per_ray(&limits));
    let contributions: Vec<Contribution> = (0..n).map(|_| contribution(rng)).collect();
    let most = max_spawned(&limits).min(*budget);
    let spawned = match rng.gen_range(0..4) {
        0 => rng.gen_range(0..=most),
        _ => most.min(1),
    };
    *budget -= spawned;
    Command::Settle(Settle::of(&contributions, spawned))
}

/// A pixel in flight in the generator: its slot, its rays out, the rays it may still spawn.
struct Pixel {
    slot: usize,
    out: u32,
    budget: u32,
}

/// `length` records in `pattern`, then the records that finish every pixel still in flight.
fn stream(pattern: Pattern, length: usize, seed: u64) -> Stream {
    let mut rng = StdRng::seed_from_u64(seed);
    let slots: Vec<usize> = match pattern {
        Pattern::Many(_) => (0..PIXEL_SLOTS).collect(),
        Pattern::Hot => vec![rng.gen_range(0..PIXEL_SLOTS)],
        Pattern::Alternating => {
            let a = rng.gen_range(0..PIXEL_SLOTS);
            vec![a, (a + rng.gen_range(1..PIXEL_SLOTS)) % PIXEL_SLOTS]
        }
    };
    let most = match pattern {
        Pattern::Many(n) => n,
        _ => slots.len(),
    };
    // Slots without a pixel in flight (`Many` opens in one of them), pixels in flight.
    let mut free = slots.clone();
    let mut flying: Vec<Pixel> = Vec::new();
    let mut records = Vec::new();
    for turn in 0.. {
        let opening = records.len() < length;
        if !opening && flying.is_empty() {
            break;
        }
        let slot = match pattern {
            Pattern::Many(_) => {
                if opening && flying.len() < most && (flying.is_empty() || rng.gen_bool(0.3)) {
                    free.swap_remove(rng.gen_range(0..free.len()))
                } else {
                    flying[rng.gen_range(0..flying.len())].slot
                }
            }
            Pattern::Hot | Pattern::Alternating => slots[turn % slots.len()],
        };
        let command = match flying.iter().position(|p| p.slot == slot) {
            Some(k) => {
                let p = &mut flying[k];
                let command = settle(&mut rng, &mut p.budget);
                if let Command::Settle(s) = command {
                    p.out = p.out + s.spawned - 1;
                }
                if p.out == 0 {
                    free.push(flying.swap_remove(k).slot);
                }
                command
            }
            None if opening => {
                free.retain(|&s| s != slot);
                flying.push(Pixel {
                    slot,
                    out: 1,
                    budget: rng.gen_range(0..60),
                });
                Command::Open
            }
            // Finishing: this slot's pixel is done.
            None => continue,
        };
        records.push(Record::new(slot, command).expect("the generator's records fit"));
    }
    Stream::of(records)
}

const NOISY: Traffic = Traffic {
    gap: 0.2,
    stall: 0.3,
    long_stall: 0.003,
    long: 80,
};

/// Offers the records in order (each held until taken, as a stream's sender must) and takes
/// pixels as `traffic` says, until every record is taken and every pixel too; then
/// `latency() + QUEUE_DEPTH` cycles taking whatever comes.
struct Bench {
    records: Vec<Record>,
    pixels: usize,
    traffic: Traffic,
    rng: StdRng,
    next: usize,
    offered: bool,
    stalled: usize,
    taken: usize,
    last: Option<AccumulateInput>,
    tail: usize,
    cycles_left: usize,
}

impl Bench {
    fn drive(&mut self, shown: Option<&AccumulateOutput>) -> Option<AccumulateInput> {
        if let (Some(last), Some(out)) = (self.last, shown) {
            if last.record.is_some() && out.record_ready {
                self.next += 1;
                self.offered = false;
            }
            if last.pixel_ready && out.pixel.is_some() {
                self.taken += 1;
            }
        }
        let done = self.next == self.records.len() && self.taken >= self.pixels;
        if done {
            if self.tail == 0 {
                return None;
            }
            self.tail -= 1;
        }
        if self.cycles_left == 0 {
            return None;
        }
        self.cycles_left -= 1;
        if !self.offered && self.next < self.records.len() {
            self.offered = !self.rng.gen_bool(self.traffic.gap);
        }
        // (Past the end the draws change nothing: no record is left to offer.)
        let ready = self.traffic.ready(&mut self.rng, &mut self.stalled);
        let input = AccumulateInput {
            record: self.offered.then(|| self.records[self.next]),
            pixel_ready: done || ready,
        };
        self.last = Some(input);
        Some(input)
    }
}

/// Runs `stream` through the block under `traffic` and checks it against the model: the
/// pixels taken are the model's finished pixels in order, each first shown no sooner than
/// `latency()` cycles after its last record was taken (exactly then if `exact`), held until
/// taken, and nothing else is shown. Returns the simulated cycles.
fn run(
    what: &str,
    stream: &Stream,
    traffic: Traffic,
    seed: u64,
) -> Vec<(AccumulateInput, AccumulateOutput)> {
    let pixels = stream.finished.len();
    let limit = 20 * (stream.records.len() + pixels) + 1000;
    let mut bench = Bench {
        records: stream.records.clone(),
        pixels,
        traffic,
        rng: StdRng::seed_from_u64(seed),
        next: 0,
        offered: false,
        stalled: 0,
        taken: 0,
        last: None,
        tail: latency() + QUEUE_DEPTH,
        cycles_left: limit,
    };
    let cycles = simulate_accumulate(move |shown| bench.drive(shown));
    // The cycle each record was taken in, and the pixels taken with the cycle first shown.
    let mut accepted = Vec::new();
    let mut taken: Vec<(usize, Finished)> = Vec::new();
    let mut shown_since: Option<usize> = None;
    for (c, (input, out)) in cycles.iter().enumerate() {
        if let Some(r) = input.record {
            if out.record_ready {
                assert_eq!(
                    r,
                    stream.records[accepted.len()],
                    "{what}: records in order"
                );
                accepted.push(c);
            }
        }
        if let Some(pixel) = out.pixel {
            let since = *shown_since.get_or_insert(c);
            if input.pixel_ready {
                taken.push((since, pixel));
                shown_since = None;
            } else {
                let next = cycles.get(c + 1).and_then(|(_, then)| then.pixel);
                assert_eq!(
                    next,
                    Some(pixel),
                    "{what}: pixel changed before taken (cycle {c})"
                );
            }
        }
    }
    assert_eq!(
        accepted.len(),
        stream.records.len(),
        "{what}: records taken in {} cycles (limit {limit})",
        cycles.len()
    );
    let got: Vec<Finished> = taken.iter().map(|&(_, p)| p).collect();
    let want: Vec<Finished> = stream.finished.iter().map(|&(_, p)| p).collect();
    if got != want {
        let first = (got.iter().zip(&want))
            .position(|(a, b)| a != b)
            .unwrap_or(got.len().min(want.len()));
        panic!(
            "{what}: {} pixels taken, the model finished {}; first difference at pixel {first}: \
             {:?} against the model's {:?}",
            got.len(),
            want.len(),
            got.get(first),
            want.get(first)
        );
    }
    for (&(since, pixel), &(record, _)) in taken.iter().zip(&stream.finished) {
        let earliest = accepted[record] + latency();
        assert!(
            since >= earliest,
            "{what}: pixel {pixel:?} shown in cycle {since}, its last record taken in cycle {}",
            accepted[record]
        );
    }
    cycles
}

/// The record stream in `pattern`, under noisy traffic and flowing (a record every cycle, the
/// consumer always ready: no record waits, every pixel exactly `latency()` after its last
/// record).
fn noisy_and_flowing(what: &str, pattern: Pattern, length: usize, seed: u64) {
    let s = stream(pattern, length, seed);
    assert!(
        s.finished.len() >= 10,
        "{what}: {} pixels",
        s.finished.len()
    );
    run(&format!("{what}, noisy"), &s, NOISY, seed);
    let what = format!("{what}, flowing");
    let cycles = run(&what, &s, FLOWING, seed);
    for (c, (input, out)) in cycles.iter().enumerate().take(s.records.len()) {
        assert!(
            input.record.is_some() && out.record_ready,
            "{what}: record {c} waited"
        );
    }
    let mut shown = cycles
        .iter()
        .enumerate()
        .filter(|(_, (_, out))| out.pixel.is_some());
    for &(record, pixel) in &s.finished {
        let (c, (_, out)) = shown.next().expect("every pixel shown");
        assert_eq!((c, out.pixel), (record + latency(), Some(pixel)), "{what}");
    }
}

#[test]
fn accumulate_matches_the_model_on_many_pixels() {
    noisy_and_flowing("48 pixels in flight", Pattern::Many(48), 1500, 1);
}

/// One slot, a record to it every cycle: each takes the word the record before wrote in
/// stage 1 (forwarded), and a finished pixel's slot opens at once.
#[test]
fn accumulate_forwards_on_a_hot_pixel() {
    noisy_and_flowing("one hot pixel", Pattern::Hot, 600, 2);
}

/// Two slots alternating: each record reads the RAM's word written two records before.
#[test]
fn accumulate_alternates_two_pixels() {
    noisy_and_flowing("two pixels alternating", Pattern::Alternating, 600, 3);
}

/// The consumer stalled for long stretches: `record_ready` falls (the queue's credits run
/// out) and no finished pixel is lost.
#[test]
fn accumulate_holds_its_pixels_under_long_stalls() {
    let s = stream(Pattern::Many(4), 600, 4);
    let starved = Traffic {
        stall: 0.5,
        long_stall: 0.02,
        long: 400,
        ..NOISY
    };
    let cycles = run("4 pixels, long stalls", &s, starved, 4);
    assert!(
        cycles
            .iter()
            .any(|(input, out)| input.record.is_some() && !out.record_ready),
        "record_ready never fell"
    );
}

/// Sums below 0, within [0, 256) steps at the byte's edges, and far above: the bytes are
/// 0 below, `sum >> 16` within, 255 above, as the model's.
#[test]
fn accumulate_clamps_negative_and_large_sums() {
    let step = 1i64 << FRACTION_BITS;
    let most = (1i64 << (SETTLE_BITS - 1)) - 1;
    let least = -(1i64 << (SETTLE_BITS - 1));
    // Per pixel, its settles' sums (one channel's; the others are the same shifted).
    let pixels: Vec<Vec<i64>> = vec![
        vec![-1],
        vec![0],
        vec![step - 1],
        vec![step],
        vec![255 * step + step - 1],
        vec![256 * step],
        vec![most, most, most, 5],
        vec![least, least, least],
        vec![most; 40],
        vec![least; 40],
        vec![least, most, 1],
        vec![most, least, -1],
        vec![200 * step, 100 * step, -100 * step],
    ];
    let mut records = Vec::new();
    for (p, sums) in pixels.iter().enumerate() {
        let slot = 17 * p;
        records.push(Record::new(slot, Command::Open).unwrap());
        for (k, &sum) in sums.iter().enumerate() {
            let spawned = u32::from(k + 1 < sums.len());
            let settle = Settle {
                sum: [sum, sum.saturating_add(7 * step).min(most), -sum.max(-most)],
                spawned,
            };
            records.push(Record::new(slot, Command::Settle(settle)).unwrap());
        }
    }
    let s = Stream::of(records);
    assert_eq!(s.finished.len(), pixels.len());
    let channels: Vec<u8> = s.finished.iter().flat_map(|(_, p)| p.rgb).collect();
    for byte in [0, 1, 255] {
        assert!(channels.contains(&byte), "no channel at {byte}");
    }
    run("edge sums, flowing", &s, FLOWING, 5);
    run("edge sums, noisy", &s, NOISY, 5);
}

/// The widest ray tree at `FrameLimits::HW`, shaded breadth first (glass down to depth 15,
/// a diffuse hit under 8 lights at every leaf): its pixel has `max_outstanding` = 2^18 rays
/// out, which the 19-bit count holds; the pixel finishes at its last shadow ray, summed.
#[test]
fn accumulate_counts_the_widest_ray_tree() {
    let limits = FrameLimits::HW;
    let slot = 700;
    let mut records = vec![Record::new(slot, Command::Open).unwrap()];
    let mut level = 1u64;
    for depth in 0..=limits.max_depth {
        let spawned = if depth < limits.max_depth {
            2
        } else {
            max_spawned(&limits)
        };
        let settle = Settle {
            sum: [0; 3],
            spawned,
        };
        records.extend((0..level).map(|_| Record::new(slot, Command::Settle(settle)).unwrap()));
        level *= u64::from(spawned);
    }
    assert_eq!(level, max_outstanding(&limits));
    // Each shadow ray adds 2^-16 of a step to red and takes it from blue.
    let shadow = Settle {
        sum: [1, 0, -1],
        spawned: 0,
    };
    records.extend((0..level).map(|_| Record::new(slot, Command::Settle(shadow)).unwrap()));
    let s = Stream::of(records);
    assert_eq!(
        s.finished,
        [(
            s.records.len() - 1,
            Finished {
                slot,
                rgb: [4, 0, 0]
            }
        )]
    );
    run("the widest ray tree", &s, FLOWING, 6);
}

#[test]
fn accumulate_rejects_records_that_do_not_fit() {
    let settle = |sum: [i64; 3], spawned| Record::new(0, Command::Settle(Settle { sum, spawned }));
    let limit = 1i64 << (SETTLE_BITS - 1);
    let most = max_spawned(&FrameLimits::HW);
    assert!(Record::new(PIXEL_SLOTS - 1, Command::Open).is_ok());
    assert!(settle([-limit, limit - 1, 0], most).is_ok());
    assert_eq!(
        Record::new(PIXEL_SLOTS, Command::Open),
        Err(RecordError::Slot { slot: PIXEL_SLOTS })
    );
    assert_eq!(
        settle([0, limit, 0], 0),
        Err(RecordError::Sum {
            channel: 1,
            sum: limit
        })
    );
    assert_eq!(
        settle([0, 0, -limit - 1], 0),
        Err(RecordError::Sum {
            channel: 2,
            sum: -limit - 1
        })
    );
    let err = settle([0; 3], most + 1).unwrap_err();
    assert_eq!(err, RecordError::Spawned { spawned: most + 1 });
    assert_eq!(
        err.to_string(),
        format!(
            "a settle spawning {} rays: a shaded ray spawns at most {most}",
            most + 1
        )
    );
}

#[test]
fn accumulate_verilog_passes_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&accumulate_verilog()) {
        panic!("accumulator: verilator lint failed:\n{e}");
    }
}

/// Longer streams, 30 seeds (about 20 CPU-s):
/// `cargo test --release -p hdl --test integration -- --ignored frame_accumulate::accumulate_long_streams`.
#[test]
#[ignore]
fn accumulate_long_streams() {
    for seed in 10..40 {
        noisy_and_flowing("256 pixels in flight", Pattern::Many(256), 6000, seed);
        noisy_and_flowing("one hot pixel", Pattern::Hot, 3000, seed);
        noisy_and_flowing("two pixels alternating", Pattern::Alternating, 3000, seed);
    }
}

/// yosys `synth_xilinx` of the accumulator (slow):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture
/// frame_accumulate::accumulate_synthesis`.
#[test]
#[ignore]
fn accumulate_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    let r = synthesize(&accumulate_verilog(), "top", &SynthOptions::default())
        .expect("yosys synth_xilinx");
    println!("| latency | {SYNTHESIS_COLUMNS} |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    print_synthesis_row(&latency().to_string(), &r);
}
