//! The timing estimate on hand-written netlists whose critical path is known: every expected
//! delay below is summed by hand from yosys' xc7 cell delays (hdl/src/timing/xc7.rs) and the
//! test's own routing model, not from the analysis.

use hdl::timing::{analyze, CriticalPath, RoutingModel, TimingError};
use serde_json::{json, Map, Value};

/// Flat 500 ps per general net: easy sums.
const FLAT: RoutingModel = RoutingModel {
    base_ps: 500.0,
    per_fanout_doubling_ps: 0.0,
};
const FF_CLOCK_TO_Q: u64 = 303;

/// A netlist under construction: cells and named nets of module `top`.
#[derive(Default)]
struct Netlist {
    cells: Map<String, Value>,
    netnames: Map<String, Value>,
    ports: Map<String, Value>,
    next_net: u64,
}

impl Netlist {
    fn net(&mut self, name: &str) -> u64 {
        self.next_net += 1;
        let n = self.next_net + 1;
        self.netnames
            .insert(name.into(), json!({"hide_name": 0, "bits": [n]}));
        n
    }
    /// A cell: `pins` are (port, direction, bits), a bit a net number or "0". A name starting
    /// with `$` is one yosys made up (hidden).
    fn cell(&mut self, name: &str, kind: &str, params: Value, pins: &[(&str, &str, Value)]) {
        let mut dirs = Map::new();
        let mut conns = Map::new();
        for (port, dir, bits) in pins {
            dirs.insert((*port).into(), json!(dir));
            let bits = if bits.is_array() {
                bits.clone()
            } else {
                json!([bits])
            };
            conns.insert((*port).into(), bits);
        }
        self.cells.insert(
            name.into(),
            json!({"hide_name": u8::from(name.starts_with('$')), "type": kind, "parameters": params,
                   "port_directions": dirs, "connections": conns}),
        );
    }
    fn ff(&mut self, name: &str, d: Value, q: u64) {
        self.cell(
            name,
            "FDRE",
            json!({}),
            &[
                ("C", "input", json!(1)),
                ("CE", "input", json!("1")),
                ("R", "input", json!("0")),
                ("D", "input", d),
                ("Q", "output", json!(q)),
            ],
        );
    }
    fn lut1(&mut self, name: &str, i: u64, o: u64) {
        self.cell(
            name,
            "LUT1",
            json!({"INIT": "01"}),
            &[("I0", "input", json!(i)), ("O", "output", json!(o))],
        );
    }
    fn json(&self) -> String {
        let mut ports = self.ports.clone();
        ports.insert("clk".into(), json!({"direction": "input", "bits": [1]}));
        json!({"modules": {"top": {"ports": ports, "cells": self.cells, "netnames": self.netnames}}})
            .to_string()
    }
    fn path(&self, routing: &RoutingModel) -> CriticalPath {
        analyze(&self.json(), "top", routing)
            .unwrap()
            .expect("a register-to-register path")
    }
}

/// FF → `n` LUT1s → FF. The last LUT's fanout-1 net into D is the slice's own wire.
fn lut_chain(n: usize) -> Netlist {
    let mut nl = Netlist::default();
    let mut prev = nl.net("start_q");
    nl.ff("$start", json!("0"), prev);
    for i in 0..n {
        let o = nl.net(&format!("l{i}_o"));
        nl.lut1(&format!("l{i}"), prev, o);
        prev = o;
    }
    let q = nl.net("end_q");
    nl.ff("$end", json!(prev), q);
    nl
}

#[test]
fn a_chain_of_luts_costs_a_lut_and_a_net_per_level() {
    for n in [1u64, 3, 8] {
        let p = lut_chain(n as usize).path(&FLAT);
        assert_eq!(p.levels, n, "{p:?}");
        assert_eq!(p.routing_ps, 500 * n, "{p:?}");
        assert_eq!(p.cell_ps, FF_CLOCK_TO_Q + 127 * n, "{p:?}");
        assert_eq!(p.delay_ps, p.cell_ps + p.routing_ps);
        assert_eq!(p.start, "start_q (FDRE)");
        assert_eq!(p.end, "end_q (FDRE D setup)");
        assert!((p.fmax_mhz() - 1e6 / p.delay_ps as f64).abs() < 1e-9);
    }
}

#[test]
fn an_inverter_is_absorbed() {
    // FF → INV → LUT1 → FF costs what FF → LUT1 → FF does.
    let mut nl = Netlist::default();
    let q = nl.net("a");
    nl.ff("$a_reg", json!("0"), q);
    let inv = nl.net("a_n");
    nl.cell(
        "$inv",
        "INV",
        json!({}),
        &[("I", "input", json!(q)), ("O", "output", json!(inv))],
    );
    let o = nl.net("o");
    nl.lut1("lut", inv, o);
    let q2 = nl.net("q");
    nl.ff("$q_reg", json!(o), q2);
    let p = nl.path(&FLAT);
    assert_eq!(p.delay_ps, 303 + 500 + 127, "{p:?}");
    assert_eq!(p.levels, 1, "{p:?}");
}

#[test]
fn fanout_adds_routing_delay() {
    // One flip-flop into the CE of 16 others: log2(16) = 4 doublings of 30 ps.
    let mut nl = Netlist::default();
    let q = nl.net("en");
    nl.ff("en_reg", json!("0"), q);
    for i in 0..16 {
        let qi = nl.net(&format!("r{i}"));
        nl.cell(
            &format!("r{i}"),
            "FDRE",
            json!({}),
            &[
                ("C", "input", json!(1)),
                ("CE", "input", json!(q)),
                ("R", "input", json!("0")),
                ("D", "input", json!("0")),
                ("Q", "output", json!(qi)),
            ],
        );
    }
    let routing = RoutingModel {
        base_ps: 400.0,
        per_fanout_doubling_ps: 30.0,
    };
    let p = nl.path(&routing);
    assert_eq!(p.levels, 0);
    assert_eq!(p.routing_ps, 400 + 4 * 30, "{p:?}");
    assert_eq!(p.delay_ps, FF_CLOCK_TO_Q + 520 + 109, "{p:?}");
    assert_eq!(p.steps.last().unwrap().fanout, 16);
}

#[test]
fn the_latest_lut_input_takes_the_fastest_pin() {
    // A LUT6 whose inputs come from chains of 0…5 LUT1s: the input through five LUT1s arrives
    // last and takes I5 (127 ps); the others arrive in order and take the slower pins.
    let mut nl = Netlist::default();
    let mut inputs = Vec::new();
    for k in 0..6 {
        let mut prev = nl.net(&format!("src{k}"));
        nl.ff(&format!("src{k}"), json!("0"), prev);
        for j in 0..k {
            let o = nl.net(&format!("c{k}_{j}"));
            nl.lut1(&format!("c{k}_{j}"), prev, o);
            prev = o;
        }
        inputs.push(prev);
    }
    let o = nl.net("lut6_o");
    // Wired in the worst order for the written pins: the latest on I0 (642 ps).
    nl.cell(
        "lut6",
        "LUT6",
        json!({"INIT": "0"}),
        &[
            ("I0", "input", json!(inputs[5])),
            ("I1", "input", json!(inputs[4])),
            ("I2", "input", json!(inputs[3])),
            ("I3", "input", json!(inputs[2])),
            ("I4", "input", json!(inputs[1])),
            ("I5", "input", json!(inputs[0])),
            ("O", "output", json!(o)),
        ],
    );
    let q = nl.net("end_q");
    nl.ff("end", json!(o), q);
    let p = nl.path(&FLAT);
    // Arrival of input k at the LUT6: 303 + k·(500 + 127) + 500. Input 5 + I5 (127) =
    // 303 + 5·627 + 500 + 127; input 4 + I4 (238) is 627 − 111 earlier, and so on.
    assert_eq!(p.delay_ps, 303 + 5 * 627 + 500 + 127, "{p:?}");
    assert_eq!(p.levels, 6);
    assert_eq!(p.steps[6].arc, "I0->O", "{p:?}");
    assert_eq!(p.steps[6].cell_ps, 127);
}

/// FF → LUT1 → CARRY4.S[0] of a chain of `n` CARRY4s → O[3] of the last → FF.
fn carry_chain(n: usize) -> Netlist {
    let mut nl = Netlist::default();
    let q = nl.net("a");
    nl.ff("a_reg", json!("0"), q);
    let s0 = nl.net("s0");
    nl.lut1("prop", q, s0);
    let mut ci = json!("0");
    let mut last_o = 0;
    for k in 0..n {
        let co: Vec<u64> = (0..4).map(|b| nl.net(&format!("co{k}_{b}"))).collect();
        let o: Vec<u64> = (0..4).map(|b| nl.net(&format!("o{k}_{b}"))).collect();
        let s = if k == 0 {
            json!([s0, "0", "0", "0"])
        } else {
            json!(["0", "0", "0", "0"])
        };
        nl.cell(
            &format!("carry{k}"),
            "CARRY4",
            json!({}),
            &[
                ("CI", "input", ci.clone()),
                ("CYINIT", "input", json!("0")),
                ("DI", "input", json!(["0", "0", "0", "0"])),
                ("S", "input", s),
                ("CO", "output", json!(co)),
                ("O", "output", json!(o)),
            ],
        );
        ci = json!(co[3]);
        last_o = o[3];
    }
    let q = nl.net("sum");
    nl.ff("sum_reg", json!(last_o), q);
    nl
}

#[test]
fn a_carry_chain_uses_the_dedicated_carry_wires() {
    // 303 + 500 (Q → LUT) + 127 (LUT) + S[0]→CO[3] 508 + CI→CO[3] 114 per middle CARRY4 +
    // CI→O[3] 313; LUT → S, CO[3] → CI and O[3] → D are dedicated.
    for n in [2u64, 4] {
        let p = carry_chain(n as usize).path(&FLAT);
        assert_eq!(p.routing_ps, 500, "{p:?}");
        assert_eq!(
            p.delay_ps,
            303 + 500 + 127 + 508 + 114 * (n - 2) + 313,
            "{p:?}"
        );
        assert_eq!(p.levels, 1 + n, "{p:?}");
    }
}

fn dsp(nl: &mut Netlist, name: &str, params: Value, a: u64, p: &[u64]) {
    nl.cell(
        name,
        "DSP48E1",
        params,
        &[
            ("CLK", "input", json!(1)),
            ("A", "input", json!([a])),
            ("B", "input", json!(["0"])),
            ("P", "output", json!(p)),
        ],
    );
}

#[test]
fn dsp_paths_follow_the_pipeline_registers() {
    let regs = |a: u32, m: u32, p: u32| {
        let bit = |b: u32| format!("{b:032b}");
        json!({"AREG": bit(a), "BREG": bit(a), "MREG": bit(m), "PREG": bit(p), "CREG": bit(0),
               "ADREG": bit(0), "DREG": bit(0), "USE_MULT": "MULTIPLY", "USE_DPORT": "FALSE"})
    };
    // Unregistered multiplier: FF → A → P (2823) → FF, two general nets.
    let mut nl = Netlist::default();
    let a = nl.net("a");
    nl.ff("a_reg", json!("0"), a);
    let p = nl.net("p");
    dsp(&mut nl, "mul", regs(0, 0, 0), a, &[p]);
    let q = nl.net("q");
    nl.ff("q_reg", json!(p), q);
    let path = nl.path(&FLAT);
    assert_eq!(path.delay_ps, 303 + 500 + 2823 + 500, "{path:?}");
    assert_eq!(path.levels, 1);

    // P registered only: A's setup is the whole multiplier (2739); P → FF is 329 + 500.
    let mut nl = Netlist::default();
    let a = nl.net("a");
    nl.ff("a_reg", json!("0"), a);
    let p = nl.net("p");
    dsp(&mut nl, "mul", regs(0, 0, 1), a, &[p]);
    let q = nl.net("q");
    nl.ff("q_reg", json!(p), q);
    let path = nl.path(&FLAT);
    assert_eq!(path.delay_ps, 303 + 500 + 2739, "{path:?}");
    assert_eq!(path.levels, 0);
    assert_eq!(path.end, "mul (DSP48E1 A setup)");
}

#[test]
fn ram_paths_start_at_the_ram_clock() {
    // Block RAM without output register: clock → DO 2454 → LUT1 → FF.
    let mut nl = Netlist::default();
    let dout = nl.net("ram_dout");
    nl.cell(
        "ram",
        "RAMB18E1",
        json!({"DOA_REG": "0"}),
        &[
            ("CLKARDCLK", "input", json!(1)),
            ("DOADO", "output", json!([dout])),
        ],
    );
    let o = nl.net("lut_o");
    nl.lut1("lut", dout, o);
    let q = nl.net("q");
    nl.ff("q_reg", json!(o), q);
    let p = nl.path(&FLAT);
    assert_eq!(p.delay_ps, 2454 + 500 + 127, "{p:?}");
    assert_eq!(p.start, "ram (RAMB18E1)");

    // Distributed RAM read: FF → ADDRA[0] (642) → DOA → FF, two general nets.
    let mut nl = Netlist::default();
    let a = nl.net("addr");
    nl.ff("addr_reg", json!("0"), a);
    let d = nl.net("doa");
    nl.cell(
        "lutram",
        "RAM32M",
        json!({}),
        &[
            ("WCLK", "input", json!(1)),
            ("ADDRA", "input", json!([a, "0", "0", "0", "0"])),
            ("DOA", "output", json!([d, "0"])),
        ],
    );
    let q = nl.net("q");
    nl.ff("q_reg", json!(d), q);
    let p = nl.path(&FLAT);
    assert_eq!(p.delay_ps, 303 + 500 + 642 + 500, "{p:?}");
    assert_eq!(p.steps[1].arc, "ADDRA[0]->DOA[0]");
}

#[test]
fn ports_are_unconstrained() {
    let mut nl = Netlist::default();
    let i = nl.net("in");
    nl.ports
        .insert("in".into(), json!({"direction": "input", "bits": [i]}));
    let o = nl.net("o");
    nl.lut1("lut", i, o);
    let q = nl.net("q");
    nl.ff("q_reg", json!(o), q);
    assert_eq!(analyze(&nl.json(), "top", &FLAT).unwrap(), None);
}

#[test]
fn public_names_are_preferred() {
    let mut nl = lut_chain(2);
    // A made-up alias of the start net, shorter than its public name.
    let start = nl.netnames["start_q"]["bits"][0].clone();
    nl.netnames
        .insert("$x".into(), json!({"hide_name": 1, "bits": [start]}));
    let p = nl.path(&FLAT);
    assert_eq!(p.start, "start_q (FDRE)");
}

#[test]
fn a_combinational_loop_is_an_error() {
    let mut nl = Netlist::default();
    let (a, b) = (nl.net("a"), nl.net("b"));
    nl.lut1("x", a, b);
    nl.lut1("y", b, a);
    let err = analyze(&nl.json(), "top", &FLAT).unwrap_err();
    assert!(
        matches!(err, TimingError::CombinationalLoop { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("LUT1"), "{err}");
}

#[test]
fn an_unknown_cell_is_an_error() {
    let mut nl = lut_chain(1);
    nl.cell("pll", "PLLE2_ADV", json!({}), &[]);
    let err = analyze(&nl.json(), "top", &FLAT).unwrap_err();
    assert_eq!(
        err.to_string(),
        "timing: no delay model for cell type PLLE2_ADV (instance pll); hdl::timing::xc7 lists the cells synth_xilinx emits for xc7"
    );
}

#[test]
fn a_missing_module_is_an_error() {
    let err = analyze(&lut_chain(1).json(), "other", &FLAT).unwrap_err();
    assert!(err.to_string().contains("no module `other`"), "{err}");
}
