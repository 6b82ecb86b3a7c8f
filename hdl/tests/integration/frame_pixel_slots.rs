//! The frame engine's pixel slots (`hdl::frame::pixel_slots`) in rust-hdl's simulator, cycle
//! by cycle against a model of the slots (pixel p opens once pixel p − `PIXEL_SLOTS` has
//! left, the schedule model's `slot_free_at`) and of the one-pixel output buffer: three
//! frames one after the other (3,000, 37 and 2,300 pixels: the parity tables carry over),
//! pixels finishing in a random order among those in flight, under random gaps and
//! back-pressure with long stalls, and flowing: `pixel_ready` exactly when the model's slot
//! is free and the tables were read for it, every pixel out once with its index and colour,
//! held while not taken. Verilator's lint.

use crate::common::{print_synthesis_row, Traffic, FLOWING, SYNTHESIS_COLUMNS};
use hdl::frame::accumulate::PIXEL_SLOTS;
use hdl::frame::pixel_slots::{pixel_slots_verilog, simulate_pixel_slots, SlotsInput};
use rand::{rngs::StdRng, Rng, SeedableRng};

const FRAMES: [u32; 3] = [3000, 37, 2300];

fn colour(frame: usize, pixel: u32) -> [u8; 3] {
    let h = (pixel as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40 ^ frame as u64;
    [h as u8, (h >> 8) as u8, (h >> 16) as u8]
}

fn slot(pixel: u32) -> usize {
    pixel as usize % PIXEL_SLOTS
}

fn check(what: &str, traffic: Traffic, finish: f64, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    // The driver: the frame, its next pixel and the pixels of it yet to leave, the pixels in
    // flight in the accumulator, the last cycle's inputs.
    let (mut frame, mut next, mut left) = (0usize, 0u32, FRAMES[0]);
    let mut in_flight: Vec<u32> = Vec::new();
    let (mut last, mut stalled, mut after) = (SlotsInput::default(), 0, 0);
    let runs = simulate_pixel_slots(move |shown| {
        let mut input = SlotsInput::default();
        if let Some(o) = shown {
            if let (Some(p), true) = (last.pixel, o.pixel_ready) {
                in_flight.push(p);
                next += 1;
            } else {
                input.pixel = last.pixel;
            }
            if !o.in_ready {
                input.finished = last.finished;
            }
            if last.out_ready && o.pixel.is_some() {
                left -= 1;
            }
        }
        if frame < FRAMES.len() && left == 0 {
            frame += 1;
            next = 0;
            left = FRAMES.get(frame).copied().unwrap_or(0);
        }
        if input.pixel.is_none()
            && frame < FRAMES.len()
            && next < FRAMES[frame]
            && !rng.gen_bool(traffic.gap)
        {
            input.pixel = Some(next);
        }
        if input.finished.is_none() && !in_flight.is_empty() && rng.gen_bool(finish) {
            let p = in_flight.swap_remove(rng.gen_range(0..in_flight.len()));
            input.finished = Some((slot(p), colour(frame, p)));
        }
        input.out_ready = traffic.ready(&mut rng, &mut stalled);
        last = input;
        if frame == FRAMES.len() {
            after += 1;
        }
        (after <= 3).then_some(input)
    });

    // The model: each slot's pixel from its open until it leaves; the output buffer; the
    // open side's read of the cycle before (its slot, free then, no leaving at its edge).
    let mut occupant: Vec<Option<u32>> = vec![None; PIXEL_SLOTS];
    let mut buffer: Option<(u32, [u8; 3])> = None;
    let (mut read, mut read_free, mut fresh) = (0usize, false, false);
    let (mut out, mut blocked) = (Vec::new(), 0);
    for (cycle, (input, shown)) in runs.iter().enumerate() {
        let pixel = input.pixel.unwrap_or(0);
        let ready = read == slot(pixel) && read_free && fresh;
        assert_eq!(
            shown.pixel_ready, ready,
            "{what}: pixel_ready at cycle {cycle}"
        );
        assert_eq!(
            shown.pixel, buffer,
            "{what}: the pixel shown at cycle {cycle}"
        );
        assert_eq!(
            shown.in_ready,
            buffer.is_none() || input.out_ready,
            "{what}: in_ready at cycle {cycle}"
        );
        let open = input.pixel.is_some() && ready;
        blocked += usize::from(input.pixel.is_some() && occupant[slot(pixel)].is_some());
        read = (slot(pixel) + usize::from(open)) % PIXEL_SLOTS;
        read_free = occupant[read].is_none();
        fresh = true;
        if let (Some((index, rgb)), true) = (buffer, input.out_ready) {
            fresh = slot(index) != read;
            occupant[slot(index)] = None;
            out.push((index, rgb));
            buffer = None;
        }
        if let (Some((s, rgb)), true) = (input.finished, shown.in_ready) {
            let index = occupant[s].expect("a finished slot holds its pixel");
            buffer = Some((index, rgb));
        }
        if open {
            assert_eq!(
                occupant[slot(pixel)],
                None,
                "{what}: pixel {pixel} opened over its slot's"
            );
            occupant[slot(pixel)] = Some(pixel);
        }
    }
    assert!(blocked > 0, "{what}: pixels waited for their slots");
    // Every pixel of every frame out once, with its colour, frame after frame.
    let mut want = Vec::new();
    for (f, &n) in FRAMES.iter().enumerate() {
        let mut pixels: Vec<(u32, [u8; 3])> = (0..n).map(|p| (p, colour(f, p))).collect();
        let start = want.len();
        want.append(&mut pixels);
        let mut got = out[start..start + n as usize].to_vec();
        got.sort_unstable();
        assert_eq!(got, want[start..], "{what}: frame {f}'s pixels");
    }
    assert_eq!(out.len(), want.len(), "{what}: pixels out");
}

#[test]
fn pixel_slots_match_the_model() {
    check(
        "noisy",
        Traffic {
            gap: 0.2,
            stall: 0.2,
            long_stall: 0.005,
            long: 60,
        },
        0.5,
        1,
    );
    check("flowing", FLOWING, 0.7, 2);
}

#[test]
fn pixel_slots_pass_verilator_lint() {
    if let Err(e) = hdl::verilog::verilator_lint(&pixel_slots_verilog()) {
        panic!("pixel slots: verilator lint failed:\n{e}");
    }
}

/// yosys figures (BENCHMARKS.md "Frame unit blocks"):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture frame_pixel_slots::pixel_slots_synthesis`.
#[test]
#[ignore]
fn pixel_slots_synthesis() {
    use hdl::synth::{synthesize, SynthOptions};
    println!("| block | {SYNTHESIS_COLUMNS} |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let r = synthesize(&pixel_slots_verilog(), "top", &SynthOptions::default())
        .expect("yosys synth_xilinx");
    print_synthesis_row("pixel slots", &r);
}
