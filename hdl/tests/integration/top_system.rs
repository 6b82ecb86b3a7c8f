//! The whole accelerator, Verilated through `rtfpga_top`'s port names: register-mode tests
//! driven over AXI4-Lite channel by channel, and stream batches with random gaps on
//! `s_axis_tvalid` and random back-pressure on `m_axis_tready`; every result is checked bit
//! for bit against `hw_model::mt_model`.

use hdl::mt::query_words;
use hdl::regmap;
use hdl::top::stream::{CTRL_VALID, FIFO_DEPTH, FLAG_HIT, FLAG_VALID, IN_LANE_BITS, TAG_SHIFT};
use hdl::top::TopConfig;
use hw_model::HwFormat;
use hw_model::{mt_model, MtQuery, MtResult};
use rand::{rngs::StdRng, Rng, SeedableRng};
use sim::accel_model::top_model;
use sim::verilator::{Direction, VerilatedModel};

/// Words of input and output ports of the Verilated top, by name.
struct Top {
    sim: VerilatedModel,
    inputs: Vec<u32>,
    outputs: Vec<u32>,
    in_at: Vec<(String, usize, usize)>,
    out_at: Vec<(String, usize, usize)>,
}

fn layout(ports: &[sim::verilator::Port]) -> Vec<(String, usize, usize)> {
    let mut at = 0;
    ports
        .iter()
        .map(|p| {
            let entry = (p.name.clone(), at, p.words());
            at += p.words();
            entry
        })
        .collect()
}

impl Top {
    fn new(config: &TopConfig) -> Self {
        // The process-wide model of `config`, the one `HwIntersector` and `rtfpga cosim` use:
        // a configuration other tests build too costs no second Verilator build.
        let model = top_model(config, false).unwrap();
        let sim = model.model.instantiate();
        let iface = sim.interface().clone();
        assert!(iface.inputs.iter().all(|p| p.direction == Direction::Input));
        let mut top = Top {
            inputs: vec![0; iface.in_words()],
            outputs: vec![0; iface.out_words()],
            in_at: layout(&iface.inputs),
            out_at: layout(&iface.outputs),
            sim,
        };
        top.set("ap_rst_n", 0);
        for _ in 0..4 {
            top.step();
        }
        top.set("ap_rst_n", 1);
        top
    }

    fn slot(at: &[(String, usize, usize)], name: &str) -> (usize, usize) {
        let (_, o, w) = at
            .iter()
            .find(|(n, ..)| n == name)
            .unwrap_or_else(|| panic!("no port {name}"));
        (*o, *w)
    }

    fn set(&mut self, name: &str, value: u32) {
        let (o, w) = Self::slot(&self.in_at, name);
        self.inputs[o..o + w].fill(0);
        self.inputs[o] = value;
    }

    fn set_words(&mut self, name: &str, words: &[u32]) {
        let (o, w) = Self::slot(&self.in_at, name);
        assert_eq!(words.len(), w, "{name}");
        self.inputs[o..o + w].copy_from_slice(words);
    }

    fn get(&self, name: &str) -> u32 {
        self.outputs[Self::slot(&self.out_at, name).0]
    }

    fn get_words(&self, name: &str) -> &[u32] {
        let (o, w) = Self::slot(&self.out_at, name);
        &self.outputs[o..o + w]
    }

    /// One clock: outputs are sampled before the edge (what the handshakes of this edge see).
    fn step(&mut self) {
        self.sim.step(&self.inputs, &mut self.outputs).unwrap();
    }

    /// An AXI4-Lite write: address and data together, then the response. Returns bresp.
    fn write(&mut self, addr: usize, data: u32) -> u32 {
        self.set("s_axi_control_awaddr", addr as u32);
        self.set("s_axi_control_wdata", data);
        self.set("s_axi_control_wstrb", 0xF);
        self.set("s_axi_control_awvalid", 1);
        self.set("s_axi_control_wvalid", 1);
        self.set("s_axi_control_bready", 1);
        let (mut aw, mut w) = (false, false);
        for _ in 0..100 {
            self.step();
            aw |= self.get("s_axi_control_awready") == 1;
            w |= self.get("s_axi_control_wready") == 1;
            let done = self.get("s_axi_control_bvalid") == 1;
            if aw {
                self.set("s_axi_control_awvalid", 0);
            }
            if w {
                self.set("s_axi_control_wvalid", 0);
            }
            if done {
                self.set("s_axi_control_bready", 0);
                return self.get("s_axi_control_bresp");
            }
        }
        panic!("AXI-Lite write to {addr:#x} got no response");
    }

    /// An AXI4-Lite read. Returns (rdata, rresp).
    fn read(&mut self, addr: usize) -> (u32, u32) {
        self.set("s_axi_control_araddr", addr as u32);
        self.set("s_axi_control_arvalid", 1);
        self.set("s_axi_control_rready", 1);
        for _ in 0..100 {
            self.step();
            if self.get("s_axi_control_arready") == 1 {
                self.set("s_axi_control_arvalid", 0);
            }
            if self.get("s_axi_control_rvalid") == 1 {
                self.set("s_axi_control_rready", 0);
                return (
                    self.get("s_axi_control_rdata"),
                    self.get("s_axi_control_rresp"),
                );
            }
        }
        panic!("AXI-Lite read of {addr:#x} got no response");
    }
}

/// Random queries, about half of them aimed through their triangle (hits at t = 1), every
/// third with a lower bound on either side of that.
fn queries(n: usize, seed: u64) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let mut p = || {
                [
                    rng.gen_range(-4.0f32..4.0),
                    rng.gen_range(-4.0f32..4.0),
                    rng.gen_range(-4.0f32..4.0),
                ]
            };
            let (orig, v0, v1, v2, other) = (p(), p(), p(), p(), p());
            let t_min = if i % 3 == 0 {
                rng.gen_range(0.0..2.0)
            } else {
                0.0
            };
            let target = if i % 2 == 0 {
                // A point inside the triangle: weights 0.2, 0.3, 0.5 of the vertices.
                std::array::from_fn(|k| 0.2 * v0[k] + 0.3 * v1[k] + 0.5 * v2[k])
            } else {
                other
            };
            MtQuery {
                orig,
                dir: std::array::from_fn(|k| target[k] - orig[k]),
                v0,
                v1,
                v2,
                t_min,
            }
        })
        .collect()
}

fn model(config: &TopConfig, q: &MtQuery) -> MtResult {
    mt_model(&config.format.format(), q)
}

fn assert_same(what: &str, got: MtResult, want: MtResult) {
    assert!(
        got.same_bits(&want),
        "{what}: hardware {got:?}, model {want:?}"
    );
}

fn register_mode(top: &mut Top, config: &TopConfig, qs: &[MtQuery]) {
    assert_eq!(top.read(regmap::ID), (regmap::ID_VALUE, regmap::RESP_OKAY));
    assert_eq!(
        top.read(regmap::CONFIG).0,
        config.config_word().unwrap().pack()
    );
    let mut hits = 0;
    for (i, q) in qs.iter().enumerate() {
        for (off, word) in regmap::OPERANDS.iter().zip(query_words(q)) {
            assert_eq!(top.write(*off, word), regmap::RESP_OKAY);
        }
        assert_eq!(
            top.write(regmap::CONTROL, regmap::AP_START),
            regmap::RESP_OKAY
        );
        let mut polls = 0;
        while top.read(regmap::CONTROL).0 & regmap::AP_DONE == 0 {
            polls += 1;
            assert!(polls < 1000, "query {i}: ap_done never rose");
        }
        let got = MtResult {
            hit: top.read(regmap::RESULT).0 & regmap::RESULT_HIT != 0,
            t: f32::from_bits(top.read(regmap::T).0),
            u: f32::from_bits(top.read(regmap::U).0),
            v: f32::from_bits(top.read(regmap::V).0),
        };
        hits += got.hit as usize;
        assert_same(&format!("register mode, query {i}"), got, model(config, q));
    }
    assert!(
        hits > 0 && hits < qs.len(),
        "{hits} hits of {}: no coverage",
        qs.len()
    );
}

/// Streams `qs` (`lanes` per beat; every 7th lane slot left invalid) with random input gaps
/// and output back-pressure (`ready_percent`), optionally holding `m_axis_tready` low for the
/// first `stall` cycles. Checks every result and returns the cycles taken.
fn stream(
    top: &mut Top,
    config: &TopConfig,
    qs: &[MtQuery],
    ready_percent: u32,
    stall: usize,
    seed: u64,
) -> usize {
    let lanes = config.lanes;
    let mut rng = StdRng::seed_from_u64(seed);
    // Beats: per lane Some(query index) or None (invalid slot).
    let mut beats: Vec<Vec<Option<usize>>> = Vec::new();
    let mut next = 0;
    let mut slot = 0;
    while next < qs.len() {
        let beat = (0..lanes)
            .map(|_| {
                slot += 1;
                if slot % 7 == 0 || next >= qs.len() {
                    None
                } else {
                    next += 1;
                    Some(next - 1)
                }
            })
            .collect();
        beats.push(beat);
    }
    let tag = |b: usize, lane: usize| ((b * lanes + lane) as u32) & 0xFF_FFFF;
    let beat_words = |b: usize| -> Vec<u32> {
        let mut w = Vec::with_capacity(IN_LANE_BITS / 32 * lanes);
        for (lane, q) in beats[b].iter().enumerate() {
            match q {
                Some(i) => {
                    w.extend(query_words(&qs[*i]));
                    w.push(CTRL_VALID | tag(b, lane) << TAG_SHIFT);
                }
                None => {
                    w.extend([0x3f80_0000; regmap::OPERAND_COUNT]);
                    w.push(tag(b, lane) << TAG_SHIFT);
                }
            }
        }
        w
    };
    let (mut sent, mut received, mut cycles) = (0, 0, 0);
    let mut max_accepted_while_stalled = 0;
    while received < beats.len() {
        cycles += 1;
        assert!(
            cycles < 100 * beats.len() + stall + 10_000,
            "stream stuck: {sent} sent, {received} received"
        );
        let offer = sent < beats.len() && rng.gen_range(0..100) < 90;
        if offer {
            top.set_words("s_axis_tdata", &beat_words(sent));
            top.set("s_axis_tlast", (sent + 1 == beats.len()) as u32);
        }
        top.set("s_axis_tvalid", offer as u32);
        let ready = cycles > stall && rng.gen_range(0..100) < ready_percent;
        top.set("m_axis_tready", ready as u32);
        top.step();
        if offer && top.get("s_axis_tready") == 1 {
            sent += 1;
            if cycles <= stall {
                max_accepted_while_stalled = sent;
            }
        }
        if ready && top.get("m_axis_tvalid") == 1 {
            let data = top.get_words("m_axis_tdata").to_vec();
            let b = received;
            for lane in 0..lanes {
                let w = &data[4 * lane..4 * lane + 4];
                let what = format!("stream beat {b} lane {lane}");
                assert_eq!(w[0] >> TAG_SHIFT, tag(b, lane), "{what}: tag");
                match beats[b][lane] {
                    Some(i) => {
                        assert_ne!(w[0] & FLAG_VALID, 0, "{what}: valid flag");
                        let got = MtResult {
                            hit: w[0] & FLAG_HIT != 0,
                            t: f32::from_bits(w[1]),
                            u: f32::from_bits(w[2]),
                            v: f32::from_bits(w[3]),
                        };
                        assert_same(&what, got, model(config, &qs[i]));
                    }
                    None => assert_eq!(
                        w[0] & (FLAG_VALID | FLAG_HIT),
                        0,
                        "{what}: invalid slot flags"
                    ),
                }
            }
            assert_eq!(
                top.get("m_axis_tlast"),
                (b + 1 == beats.len()) as u32,
                "beat {b}: tlast"
            );
            received += 1;
        }
    }
    top.set("s_axis_tvalid", 0);
    top.set("m_axis_tready", 0);
    if stall > 0 {
        assert_eq!(
            max_accepted_while_stalled,
            FIFO_DEPTH.min(beats.len()),
            "beats taken while the output stalled"
        );
    }
    cycles
}

/// Full-rate streaming: with data always offered and results always taken, one beat enters
/// per cycle (after the post-reset flush) — every lane busy every cycle.
fn throughput(top: &mut Top, config: &TopConfig) {
    let lanes = config.lanes;
    let q = queries(1, 99)[0];
    let mut words = Vec::new();
    for _ in 0..lanes {
        words.extend(query_words(&q));
        words.push(CTRL_VALID);
    }
    top.set_words("s_axis_tdata", &words);
    top.set("s_axis_tvalid", 1);
    top.set("s_axis_tlast", 0);
    top.set("m_axis_tready", 1);
    let (mut accepted, mut results) = (0, 0);
    let cycles = 1000;
    for _ in 0..cycles {
        top.step();
        accepted += top.get("s_axis_tready") as usize;
        results += top.get("m_axis_tvalid") as usize;
    }
    top.set("s_axis_tvalid", 0);
    let latency = config.lane_latency().unwrap() + 2;
    assert_eq!(accepted, cycles, "input beats accepted in {cycles} cycles");
    assert_eq!(results, cycles - latency, "result beats in {cycles} cycles");
    // Drain.
    for _ in 0..latency + 2 {
        top.step();
    }
    assert_eq!(top.get("m_axis_tvalid"), 0);
}

fn system(config: &TopConfig, seed: u64) {
    let mut top = Top::new(config);
    // Flush after reset: the lanes may hold queries from before it.
    for _ in 0..config.lane_latency().unwrap() + 2 {
        top.step();
    }
    register_mode(&mut top, config, &queries(12, seed));
    let qs = queries(700 * config.lanes, seed + 1);
    let cycles = stream(&mut top, config, &qs, 70, 0, seed + 2);
    println!(
        "{}: {} queries in {cycles} cycles with 90 % input / 70 % output duty",
        config.dir_name(),
        qs.len()
    );
    // Output held off until the FIFO is full: exactly FIFO_DEPTH beats are taken, none lost.
    stream(&mut top, config, &qs, 50, FIFO_DEPTH + 200, seed + 3);
    // Register mode still works after streaming.
    register_mode(&mut top, config, &queries(4, seed + 4));
    throughput(&mut top, config);
}

// The configurations are ones `make test` builds anyway (sim/tests/integration/cosim_equivalence.rs,
// rtfpga/tests/cli/cosim.rs): a cold Verilator build of the top costs about a minute each.

#[test]
fn fp32_one_lane_register_and_stream_modes_match_the_model() {
    system(&TopConfig::new(HwFormat::named("fp32"), 1, 1), 0x7e57);
}

#[test]
fn fp16_two_lanes_register_and_stream_modes_match_the_model() {
    system(&TopConfig::new(HwFormat::named("fp16"), 2, 2), 0xf16);
}

/// Depth 0: the lanes are combinational, so a result appears in the cycle its beat is taken.
#[test]
fn fp16_depth_zero_register_and_stream_modes_match_the_model() {
    system(&TopConfig::new(HwFormat::named("fp16"), 0, 2), 0xd0);
}

/// More formats and lane counts (a Verilator build each, about a minute):
/// `cargo test --release -p hdl --test integration top_system:: -- --ignored`.
#[test]
#[ignore]
fn more_configurations_register_and_stream_modes_match_the_model() {
    for (format, depth, lanes, seed) in [
        ("fp32", 1, 2, 0x7e52),
        ("fp16", 2, 3, 0xf163),
        ("bf16", 0, 1, 0xb16),
    ] {
        system(&TopConfig::new(HwFormat::named(format), depth, lanes), seed);
    }
}
