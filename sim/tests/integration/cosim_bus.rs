//! The bus drivers on the Verilated accelerator (fp32, depth 1, one lane — the cheapest full
//! top to build, ~1 min the first time, then cached): register mode (polling and interrupt)
//! and stream mode give the same, model-exact results; back-pressure on `m_axis_tready` keeps
//! every result; register reads return the ID/CONFIG words; a bad address answers SLVERR; a
//! missing tool or a broken model build is a clear error, never a hang.

use hdl::regmap;
use hdl::top::TopConfig;
use hw_model::HwFormat;
use hw_model::{mt_model, MtQuery, MtResult};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sim::accel_model::{top_model, top_model_with, Accel};
use sim::axil_master::{AxiLiteMaster, Completion};
use sim::cosim_error::CosimError;
use sim::hw_intersector::{HwIntersector, Mode};
use sim::stream_driver::stream_batch;
use sim::BuildOptions;
use sw_renderer::intersect::Intersector;

fn config() -> TopConfig {
    TopConfig::new(HwFormat::named("fp32"), 1, 1)
}

/// Rays aimed near random triangles (about half hit), plus a few raw bit patterns.
fn queries(n: usize, seed: u64) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            if i % 10 == 9 {
                let mut bits = || [0; 3].map(|_| f32::from_bits(rng.gen()));
                return MtQuery {
                    orig: bits(),
                    dir: bits(),
                    v0: bits(),
                    v1: bits(),
                    v2: bits(),
                    t_min: 0.0,
                };
            }
            let mut p = |r: f32| [0; 3].map(|_| rng.gen_range(-r..r));
            let (v0, v1, v2, orig) = (p(2.0), p(2.0), p(2.0), p(8.0));
            let (a, b) = (rng.gen_range(-0.3..1.0f32), rng.gen_range(-0.3..1.0f32));
            // The hit is at t = 1: random lower bounds on both sides of it.
            let t_min = if i % 3 == 0 {
                rng.gen_range(0.0..2.0f32)
            } else {
                0.0
            };
            MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min)
        })
        .collect()
}

fn assert_model_exact(format: &str, qs: &[MtQuery], got: &[MtResult]) {
    let f = hw_model::lookup(format).unwrap();
    for (i, (q, g)) in qs.iter().zip(got).enumerate() {
        let want = mt_model(&f, q);
        assert!(
            g.same_bits(&want),
            "query {i} {q:?}: hardware {g:?}, model {want:?}"
        );
    }
    let hits = got.iter().filter(|r| r.hit).count();
    assert!(hits > qs.len() / 5, "only {hits} hits of {}", qs.len());
}

#[test]
fn register_and_stream_modes_agree_with_the_model() {
    let top = top_model(&config(), false).unwrap();
    let mut accel = Accel::new(&top).unwrap();
    let qs = queries(300, 1);

    let mut poll = AxiLiteMaster::new(Completion::Poll);
    assert_eq!(poll.read(&mut accel, regmap::ID).unwrap(), regmap::ID_VALUE);
    assert_eq!(
        poll.read(&mut accel, regmap::CONFIG).unwrap(),
        config().config_word().unwrap().pack()
    );
    let before = poll.stats;
    let by_poll: Vec<MtResult> = qs[..150]
        .iter()
        .map(|q| poll.test(&mut accel, q).unwrap())
        .collect();
    let per_test = (poll.stats.cycles - before.cycles) as f64 / 150.0;
    let transactions = (poll.stats.transactions() - before.transactions()) as f64 / 150.0;
    // The operands + ap_start + ≥1 poll + 4 results; each transaction takes ≥ 2 cycles.
    assert!(
        transactions >= (regmap::OPERAND_COUNT + 6) as f64 && per_test >= 2.0 * transactions,
        "{transactions} {per_test}"
    );
    println!("register mode (poll): {per_test:.1} cycles, {transactions:.1} transactions per test");

    let mut irq = AxiLiteMaster::new(Completion::Interrupt);
    let by_irq: Vec<MtResult> = qs[150..]
        .iter()
        .map(|q| irq.test(&mut accel, q).unwrap())
        .collect();
    assert_eq!(
        irq.stats.writes,
        2 + 150 * (regmap::OPERAND_COUNT as u64 + 2),
        "GIE, IER once; the operands, ap_start, ISR ack per test"
    );
    assert_eq!(irq.stats.reads, 150 * 4);

    let mut streamed = vec![MtResult::default(); qs.len()];
    let s = stream_batch(&mut accel, &qs, &mut streamed, &mut || true).unwrap();
    assert_eq!((s.tests, s.beats, s.input_stalls), (300, 300, 0));
    // One beat per cycle after the pipeline fills: latency + FIFO + handshakes on top.
    assert!(
        s.cycles >= 300 && s.cycles <= 300 + top.lane_latency as u64 + 8,
        "{s:?}"
    );

    let registers: Vec<MtResult> = by_poll.into_iter().chain(by_irq).collect();
    for (i, (r, s)) in registers.iter().zip(&streamed).enumerate() {
        assert!(r.same_bits(s), "query {i}: register {r:?}, stream {s:?}");
    }
    assert_model_exact("fp32", &qs, &streamed);
}

#[test]
fn back_pressure_and_odd_batches_lose_nothing() {
    let top = top_model(&config(), false).unwrap();
    let mut accel = Accel::new(&top).unwrap();
    let qs = queries(3000, 2);
    let mut rng = StdRng::seed_from_u64(3);
    let mut got = vec![MtResult::default(); qs.len()];
    // Mostly stalled sink: the FIFO fills, s_axis_tready must fall and rise again.
    let s = stream_batch(&mut accel, &qs, &mut got, &mut || rng.gen_range(0..4) == 0).unwrap();
    assert!(s.input_stalls > 0, "{s:?}");
    assert_model_exact("fp32", &qs, &got);
    // Batches of 0 and 1 queries, back to back on the same instance.
    stream_batch(&mut accel, &[], &mut [], &mut || true).unwrap();
    let mut one = [MtResult::default()];
    stream_batch(&mut accel, &qs[..1], &mut one, &mut || true).unwrap();
    assert!(one[0].same_bits(&got[0]));
}

/// The front end's wait after reset is the reset's, not the first batch's: otherwise each
/// simulated instance charged it once and a render's cycles depended on rayon's threads.
#[test]
fn a_fresh_instance_streams_a_batch_in_the_cycles_of_a_used_one() {
    let top = top_model(&config(), false).unwrap();
    let qs = queries(200, 5);
    let mut got = vec![MtResult::default(); qs.len()];
    let mut accel = Accel::new(&top).unwrap();
    let fresh = stream_batch(&mut accel, &qs, &mut got, &mut || true).unwrap();
    let used = stream_batch(&mut accel, &qs, &mut got, &mut || true).unwrap();
    assert_eq!(fresh, used);
    assert_model_exact("fp32", &qs, &got);
}

#[test]
fn bus_errors_are_reported_not_ignored() {
    let top = top_model(&config(), false).unwrap();
    let mut accel = Accel::new(&top).unwrap();
    let mut bus = AxiLiteMaster::new(Completion::Poll);
    assert_eq!(
        bus.write_resp(&mut accel, 0x68, 1).unwrap(),
        regmap::RESP_SLVERR
    );
    let e = bus.write(&mut accel, regmap::T, 1).unwrap_err().to_string();
    assert!(
        e.contains("AXI4-Lite protocol") && e.contains("0x54"),
        "{e}"
    );
    let e = bus.read(&mut accel, 0x7C).unwrap_err().to_string();
    assert!(e.contains("read of 0x7c"), "{e}");
}

#[test]
fn intersector_counts_its_work_in_every_mode() {
    let qs = queries(500, 4);
    for mode in [
        Mode::Stream,
        Mode::Register(Completion::Poll),
        Mode::Register(Completion::Interrupt),
    ] {
        let hw = HwIntersector::new(&config(), mode).unwrap();
        let mut got = vec![MtResult::default(); qs.len()];
        hw.intersect_batch(&qs, &mut got).unwrap();
        assert_model_exact("fp32", &qs, &got);
        let s = hw.stats();
        assert_eq!((s.tests, s.busy_lane_cycles), (500, 500));
        assert_eq!(s.lane_cycles, s.cycles);
        // Linux tells the simulating thread's CPU time; it cannot exceed the batches' wall time.
        assert!(
            !s.sim_cpu_time.is_zero()
                && s.sim_cpu_time <= s.sim_time + std::time::Duration::from_millis(5),
            "{s:?}"
        );
        match mode {
            Mode::Stream => assert!(s.lane_utilisation() > 0.8 && s.transactions == 500, "{s:?}"),
            Mode::Register(Completion::Poll) => {
                assert!(
                    s.cycles_per_test() > 40.0
                        && s.transactions >= 500 * (regmap::OPERAND_COUNT as u64 + 6),
                    "{s:?}"
                )
            }
            // The operands, ap_start, ISR acknowledge, 4 result reads per test; GIE and IER once.
            Mode::Register(Completion::Interrupt) => {
                assert!(
                    s.cycles_per_test() > 40.0
                        && s.transactions == 500 * (regmap::OPERAND_COUNT as u64 + 6) + 2,
                    "{s:?}"
                )
            }
        }
        assert_eq!(hw.name(), format!("hw fp32 d1 l1 {mode}"));
    }
}

#[test]
fn missing_tools_and_broken_builds_are_clear_errors() {
    let empty = tempfile::tempdir().unwrap();
    let no_tools = BuildOptions {
        search_path: Some(empty.path().into()),
        ..BuildOptions::default()
    };
    let e = top_model_with(&config(), &no_tools)
        .err()
        .expect("no verilator on an empty PATH")
        .to_string();
    assert!(e.contains("verilator not found"), "{e}");

    let broken = BuildOptions {
        verilator_args: vec!["--no-such-verilator-option".into()],
        ..BuildOptions::default()
    };
    let e = top_model_with(&config(), &broken)
        .err()
        .expect("a bad option must fail the build");
    assert!(matches!(e, CosimError::Sim(_)), "{e}");
    assert!(e.to_string().contains("verilator failed"), "{e}");

    // An impossible configuration is refused before anything is built.
    let e = top_model(&TopConfig::new(HwFormat::FP32, 1, 0), false)
        .err()
        .unwrap();
    assert!(matches!(e, CosimError::Config(_)), "{e}");
    assert!(e.to_string().contains("lanes = 0"), "{e}");
}
