//! An Fmax estimate for the XC7Z020-1 from a flattened yosys `synth_xilinx` netlist: the
//! longest register-to-register path under yosys' 7-series cell delays ([`xc7`]) plus a
//! routing model ([`RoutingModel`]) calibrated against published Vivado results
//! (docs/timing.md, `scripts/timing_calibration.sh`).
//!
//! **It is an estimate, not timing closure.** Nothing here is placed or routed: every general
//! net gets the model's delay for its fanout, whatever the distance a placer would give it,
//! and Vivado's optimisations (logic restructuring, replication of high-fanout drivers,
//! retiming) are not modelled. The calibration's residuals (docs/timing.md) are the error
//! band to expect: about ±15 % on the designs it was fitted to, more on designs unlike them.
//!
//! What is timed: paths from a clocked output (flip-flop Q, SRL, distributed RAM read after
//! a write, block RAM DO, registered DSP48E1 P) through combinational cells (LUTs, MUXF7/8,
//! CARRY4, unregistered DSP48E1 arcs, distributed RAM and SRL address-to-data) to a clocked
//! input (setup of D, CE, reset, RAM write ports, DSP48E1 registered inputs). Module ports are
//! unconstrained, as Vivado leaves them without `set_input_delay`/`set_output_delay`: paths
//! from or to them are not timed. One clock is assumed.
//!
//! LUT inputs are logically equivalent pins that Vivado permutes while routing, putting the
//! latest-arriving signal on the fastest pin; the analysis does the same rather than keep the
//! pin order yosys happened to write.
//!
//! Inverters (INV cells, which yosys leaves for the vendor tool to absorb) cost nothing.
//! Dedicated connections have no routing delay: CARRY4 CO\[3\] to the next CARRY4's CI, a LUT
//! into a MUXF7 data input and a MUXF7 into a MUXF8, DSP48E1 PCOUT to PCIN, and a LUT, MUXF or
//! CARRY4 output with fanout 1 into a flip-flop's D or a CARRY4's S (the slice's own wires).

mod netlist;
mod xc7;

use std::collections::HashMap;

use serde::{Deserialize, Serialize};

use netlist::{Bit, Direction};
use xc7::{CellModel, Pin};

#[derive(Debug, thiserror::Error)]
pub enum TimingError {
    #[error("reading the yosys netlist: {detail}")]
    Netlist { detail: String },
    #[error("timing: no delay model for cell type {cell_type} (instance {instance}); hdl::timing::xc7 lists the cells synth_xilinx emits for xc7")]
    UnknownCell { cell_type: String, instance: String },
    #[error("timing: combinational loop through {instance} ({cell_type})")]
    CombinationalLoop { cell_type: String, instance: String },
}

/// Delay of a general (not dedicated) net as a function of its fanout:
/// `base_ps + per_fanout_doubling_ps · log2(fanout)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RoutingModel {
    pub base_ps: f64,
    pub per_fanout_doubling_ps: f64,
}

/// The calibrated routing model (docs/timing.md, "Calibration"; reproduce with
/// `scripts/timing_calibration.sh`).
pub const ROUTING: RoutingModel = RoutingModel {
    base_ps: 230.0,
    per_fanout_doubling_ps: 70.0,
};

impl RoutingModel {
    pub fn net_ps(&self, fanout: usize) -> u32 {
        let doublings = (fanout.max(1) as f64).log2();
        (self.base_ps + self.per_fanout_doubling_ps * doublings).round() as u32
    }
}

/// One cell of the critical path and the net into it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PathStep {
    /// The cell's name, or for a cell yosys named itself the name of the net it drives.
    pub cell: String,
    pub cell_type: String,
    /// `clock->Q` at the start, `I2->O` through a cell, `D setup` at the end.
    pub arc: String,
    pub cell_ps: u64,
    /// The net into this cell (none at the start).
    pub net: Option<String>,
    pub fanout: u64,
    pub route_ps: u64,
}

/// The longest register-to-register path.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CriticalPath {
    /// Cell delays (clock-to-out, combinational arcs, setup) plus routing.
    pub delay_ps: u64,
    pub cell_ps: u64,
    pub routing_ps: u64,
    /// Combinational cells on the path (inverters, absorbed, not counted).
    pub levels: u64,
    /// The launching cell (`name (TYPE)`).
    pub start: String,
    /// The capturing cell and pin.
    pub end: String,
    pub steps: Vec<PathStep>,
}

impl CriticalPath {
    /// The clock this path allows, in MHz.
    pub fn fmax_mhz(&self) -> f64 {
        1e6 / self.delay_ps as f64
    }

    /// The path cell by cell as a Markdown table: each cell's delay and arc, and the net into
    /// it with its fanout and routing delay.
    pub fn steps_markdown(&self) -> String {
        let ns = |ps: u64| format!("{:.2}", ps as f64 / 1000.0);
        let mut s = String::from(
            "| cell ns | type | arc | cell | net in | fanout | route ns |\n\
             |---:|---|---|---|---|---:|---:|\n",
        );
        for step in &self.steps {
            let (net, fanout, route) = match &step.net {
                Some(n) => (format!("`{n}`"), step.fanout.to_string(), ns(step.route_ps)),
                None => Default::default(),
            };
            s += &format!(
                "| {} | {} | {} | `{}` | {net} | {fanout} | {route} |\n",
                ns(step.cell_ps),
                step.cell_type,
                step.arc,
                step.cell
            );
        }
        s
    }
}

/// One input or output pin of a cell and the net on it.
struct Conn {
    port: String,
    bit: usize,
    net: Option<u32>,
}

struct Node {
    name: String,
    hidden: bool,
    kind: String,
    model: CellModel,
    inputs: Vec<Conn>,
    outputs: Vec<Conn>,
}

impl Node {
    fn has_arc_from(&self, c: &Conn) -> bool {
        self.model
            .arcs
            .iter()
            .any(|(f, _, _)| f.matches(&c.port, c.bit))
    }
    fn drives_by_arc(&self, c: &Conn) -> bool {
        self.model
            .arcs
            .iter()
            .any(|(_, t, _)| t.matches(&c.port, c.bit))
    }
    fn find(list: &[(Pin, u32)], c: &Conn) -> Option<u32> {
        list.iter()
            .filter(|(p, _)| p.matches(&c.port, c.bit))
            .map(|&(_, ps)| ps)
            .max()
    }
}

/// How a net got its arrival time.
#[derive(Clone, Copy)]
enum Pred {
    Launch {
        cell: usize,
        output: usize,
    },
    Through {
        cell: usize,
        input: usize,
        output: usize,
        cell_ps: u32,
    },
}

/// The critical path of module `top` of a `write_json` netlist under `routing`, or `None`
/// when it has no register-to-register path.
pub fn analyze(
    json: &str,
    top: &str,
    routing: &RoutingModel,
) -> Result<Option<CriticalPath>, TimingError> {
    Ok(TimingGraph::from_json(json, top)?.critical_path(routing))
}

/// A netlist ready for timing: cells with their delay models, nets with driver, sinks and
/// fanout, and the combinational cells in topological order. Built once, it can be timed
/// under several routing models (the calibration does).
pub struct TimingGraph {
    nodes: Vec<Node>,
    /// Width of each cell's ports, for pin names.
    widths: Vec<HashMap<String, usize>>,
    driver: Vec<Option<(usize, usize)>>,
    fanout: Vec<usize>,
    /// The cells with combinational arcs, each after the cells that drive its arc inputs.
    order: Vec<usize>,
    net_names: Vec<Option<String>>,
}

impl TimingGraph {
    pub fn from_json(json: &str, top: &str) -> Result<Self, TimingError> {
        let module = netlist::parse(json, top)?;

        // Cells, in name order so that ties resolve the same way every run.
        let mut names: Vec<&String> = module.cells.keys().collect();
        names.sort();
        let mut nodes = Vec::with_capacity(names.len());
        let mut widths = Vec::with_capacity(names.len());
        for name in names {
            let cell = &module.cells[name];
            let model = xc7::model(cell, name)?;
            let (mut inputs, mut outputs) = (Vec::new(), Vec::new());
            let mut ports: Vec<(&String, &Vec<Bit>)> = cell.connections.iter().collect();
            ports.sort_by(|a, b| a.0.cmp(b.0));
            let mut width = HashMap::new();
            for (port, bits) in ports {
                width.insert(port.clone(), bits.len());
                let dir = cell.port_directions.get(port).copied();
                for (bit, b) in bits.iter().enumerate() {
                    let conn = Conn {
                        port: port.clone(),
                        bit,
                        net: match b {
                            Bit::Net(n) => Some(*n),
                            Bit::Const => None,
                        },
                    };
                    match dir {
                        Some(Direction::Output) => outputs.push(conn),
                        Some(Direction::Input) => inputs.push(conn),
                        // Bidirectional pins (none in the cells modelled) are not timed.
                        _ => {}
                    }
                }
            }
            nodes.push(Node {
                name: name.clone(),
                hidden: cell.hide_name != 0,
                kind: cell.kind.clone(),
                model,
                inputs,
                outputs,
            });
            widths.push(width);
        }

        // Nets: driver, sinks (cell, input index), fanout (sinks plus output-port bits).
        let port_nets = || {
            module.ports.values().flat_map(|p| {
                p.bits.iter().filter_map(move |b| match b {
                    Bit::Net(n) => Some((p.direction, *n)),
                    Bit::Const => None,
                })
            })
        };
        let nets = nodes
            .iter()
            .flat_map(|n| n.inputs.iter().chain(&n.outputs))
            .filter_map(|c| c.net)
            .chain(port_nets().map(|(_, n)| n))
            .max()
            .map_or(0, |n| n as usize + 1);
        let mut driver = vec![None; nets];
        let mut sinks = vec![Vec::new(); nets];
        let mut fanout = vec![0usize; nets];
        for (ci, node) in nodes.iter().enumerate() {
            for (oi, c) in node.outputs.iter().enumerate() {
                if let Some(n) = c.net {
                    driver[n as usize] = Some((ci, oi));
                }
            }
            for (ii, c) in node.inputs.iter().enumerate() {
                if let Some(n) = c.net {
                    sinks[n as usize].push((ci, ii));
                    fanout[n as usize] += 1;
                }
            }
        }
        for (dir, n) in port_nets() {
            if dir != Direction::Input {
                fanout[n as usize] += 1;
            }
        }

        // Topological order of the combinational cells (Kahn): a cell is ready when every
        // arc input driven through an arc of another cell is done.
        let through_arc = |n: u32| {
            driver[n as usize]
                .is_some_and(|(di, oi)| nodes[di].drives_by_arc(&nodes[di].outputs[oi]))
        };
        let mut pending = vec![0usize; nodes.len()];
        let mut ready = Vec::new();
        for (ci, node) in nodes.iter().enumerate() {
            if node.model.arcs.is_empty() {
                continue;
            }
            pending[ci] = node
                .inputs
                .iter()
                .filter(|c| node.has_arc_from(c) && c.net.is_some_and(through_arc))
                .count();
            if pending[ci] == 0 {
                ready.push(ci);
            }
        }
        let mut order = Vec::new();
        while let Some(ci) = ready.pop() {
            order.push(ci);
            for out in nodes[ci]
                .outputs
                .iter()
                .filter(|o| nodes[ci].drives_by_arc(o))
            {
                let Some(n) = out.net else { continue };
                for &(si, sii) in &sinks[n as usize] {
                    if nodes[si].has_arc_from(&nodes[si].inputs[sii]) {
                        pending[si] -= 1;
                        if pending[si] == 0 {
                            ready.push(si);
                        }
                    }
                }
            }
        }
        if let Some(ci) = (0..nodes.len()).find(|&ci| pending[ci] > 0) {
            return Err(TimingError::CombinationalLoop {
                cell_type: nodes[ci].kind.clone(),
                instance: nodes[ci].name.clone(),
            });
        }

        // A net bit's name: its shortest public name, else a name yosys made up.
        let mut named: Vec<Option<(bool, String)>> = vec![None; nets];
        let mut netnames: Vec<(&String, &netlist::NetName)> = module.netnames.iter().collect();
        netnames.sort_by(|a, b| a.0.cmp(b.0));
        for (name, net) in netnames {
            let hidden = net.hide_name != 0;
            for (i, b) in net.bits.iter().enumerate() {
                let Bit::Net(n) = b else { continue };
                let Some(slot) = named.get_mut(*n as usize) else {
                    continue;
                };
                let full = if net.bits.len() > 1 {
                    format!("{name}[{i}]")
                } else {
                    name.to_string()
                };
                let better = match slot {
                    None => true,
                    Some((was_hidden, old)) => {
                        (*was_hidden && !hidden)
                            || (*was_hidden == hidden && full.len() < old.len())
                    }
                };
                if better {
                    *slot = Some((hidden, full));
                }
            }
        }
        let net_names = named.into_iter().map(|n| n.map(|(_, s)| s)).collect();

        Ok(TimingGraph {
            nodes,
            widths,
            driver,
            fanout,
            order,
            net_names,
        })
    }

    /// Routing delay of the connection from net `n` into input `ii` of cell `ci`.
    fn route(&self, routing: &RoutingModel, n: u32, ci: usize, ii: usize) -> u32 {
        let sink = &self.nodes[ci];
        let pin = &sink.inputs[ii];
        let fo = self.fanout[n as usize];
        if let Some((di, oi)) = self.driver[n as usize] {
            let (d, out) = (&self.nodes[di], &self.nodes[di].outputs[oi]);
            let local = match (sink.kind.as_str(), pin.port.as_str()) {
                // Absorbed into what it drives (xc7::model).
                ("INV", _) => true,
                ("CARRY4", "CI") => d.kind == "CARRY4" && out.port == "CO" && out.bit == 3,
                ("MUXF7", "I0" | "I1") => d.model.lut,
                ("MUXF8", "I0" | "I1") => d.kind == "MUXF7",
                ("DSP48E1", "PCIN") => d.kind == "DSP48E1" && out.port == "PCOUT",
                ("CARRY4", "S") => d.model.lut && fo == 1,
                (k, "D") if k.starts_with("FD") => {
                    fo == 1
                        && (d.model.lut || matches!(d.kind.as_str(), "MUXF7" | "MUXF8" | "CARRY4"))
                }
                _ => false,
            };
            if local {
                return 0;
            }
        }
        routing.net_ps(fo)
    }

    fn net_name(&self, n: u32) -> String {
        self.net_names[n as usize]
            .clone()
            .unwrap_or_else(|| format!("net {n}"))
    }

    /// A cell's own name, or for a cell yosys named the name of the net it drives.
    fn cell_name(&self, ci: usize) -> String {
        let node = &self.nodes[ci];
        if !node.hidden {
            return node.name.clone();
        }
        node.outputs
            .iter()
            .find_map(|c| c.net)
            .map_or_else(|| node.name.clone(), |n| self.net_name(n))
    }

    fn pin(&self, ci: usize, c: &Conn) -> String {
        if self.widths[ci][&c.port] > 1 {
            format!("{}[{}]", c.port, c.bit)
        } else {
            c.port.clone()
        }
    }

    /// The longest register-to-register path under `routing`, or `None` when there is none.
    pub fn critical_path(&self, routing: &RoutingModel) -> Option<CriticalPath> {
        let nodes = &self.nodes;
        let mut arrival: Vec<Option<u32>> = vec![None; self.driver.len()];
        let mut pred: Vec<Option<Pred>> = vec![None; self.driver.len()];
        for (ci, node) in nodes.iter().enumerate() {
            for (oi, c) in node.outputs.iter().enumerate() {
                let (Some(n), Some(ps)) = (c.net, Node::find(&node.model.clock_to_out, c)) else {
                    continue;
                };
                if arrival[n as usize].is_none_or(|a| ps > a) {
                    arrival[n as usize] = Some(ps);
                    pred[n as usize] = Some(Pred::Launch {
                        cell: ci,
                        output: oi,
                    });
                }
            }
        }
        for &ci in &self.order {
            let node = &nodes[ci];
            // Each timed input's arrival at the pin.
            let at_pin: Vec<Option<u32>> = node
                .inputs
                .iter()
                .enumerate()
                .map(|(ii, c)| {
                    let n = c.net?;
                    Some(arrival[n as usize]? + self.route(routing, n, ci, ii))
                })
                .collect();
            for (oi, out) in node.outputs.iter().enumerate() {
                let Some(n) = out.net else { continue };
                let mut best: Option<(u32, usize, u32)> = None;
                let mut consider = |ii: usize, ps: u32| {
                    if let Some(a) = at_pin[ii] {
                        if best.is_none_or(|(b, _, _)| a + ps > b) {
                            best = Some((a + ps, ii, ps));
                        }
                    }
                };
                if node.model.lut {
                    // The latest input on the fastest pin: the inputs by arrival, latest
                    // first, take the pin delays fastest first.
                    let mut timed: Vec<usize> = (0..node.inputs.len())
                        .filter(|&ii| at_pin[ii].is_some())
                        .collect();
                    timed.sort_by_key(|&ii| std::cmp::Reverse(at_pin[ii]));
                    let mut pins: Vec<u32> = node.model.arcs.iter().map(|&(_, _, ps)| ps).collect();
                    pins.sort();
                    for (rank, ii) in timed.into_iter().enumerate() {
                        consider(ii, pins[rank]);
                    }
                } else {
                    for &(from, to, ps) in &node.model.arcs {
                        if !to.matches(&out.port, out.bit) {
                            continue;
                        }
                        for (ii, c) in node.inputs.iter().enumerate() {
                            if from.matches(&c.port, c.bit) {
                                consider(ii, ps);
                            }
                        }
                    }
                }
                if let Some((a, ii, ps)) = best {
                    if arrival[n as usize].is_none_or(|old| a > old) {
                        arrival[n as usize] = Some(a);
                        pred[n as usize] = Some(Pred::Through {
                            cell: ci,
                            input: ii,
                            output: oi,
                            cell_ps: ps,
                        });
                    }
                }
            }
        }

        // The worst endpoint.
        let mut worst: Option<(u32, usize, usize, u32, u32)> = None;
        for (ci, node) in nodes.iter().enumerate() {
            for (ii, c) in node.inputs.iter().enumerate() {
                let (Some(n), Some(setup)) = (c.net, Node::find(&node.model.setup, c)) else {
                    continue;
                };
                let Some(a) = arrival[n as usize] else {
                    continue;
                };
                let r = self.route(routing, n, ci, ii);
                let total = a + r + setup;
                if worst.is_none_or(|(w, ..)| total > w) {
                    worst = Some((total, ci, ii, r, setup));
                }
            }
        }
        let (total, end_cell, end_input, end_route, setup) = worst?;

        // Walk back from the endpoint.
        let end_node = &nodes[end_cell];
        let end_pin = &end_node.inputs[end_input];
        let end_net = end_pin.net.expect("timed input");
        let mut steps = vec![PathStep {
            cell: self.cell_name(end_cell),
            cell_type: end_node.kind.clone(),
            arc: format!("{} setup", self.pin(end_cell, end_pin)),
            cell_ps: setup as u64,
            net: Some(self.net_name(end_net)),
            fanout: self.fanout[end_net as usize] as u64,
            route_ps: end_route as u64,
        }];
        let mut n = end_net;
        loop {
            match pred[n as usize].expect("a timed net has a predecessor") {
                Pred::Launch { cell, output } => {
                    let node = &nodes[cell];
                    let out = &node.outputs[output];
                    steps.push(PathStep {
                        cell: self.cell_name(cell),
                        cell_type: node.kind.clone(),
                        arc: format!("clock->{}", self.pin(cell, out)),
                        cell_ps: Node::find(&node.model.clock_to_out, out).unwrap_or(0) as u64,
                        net: None,
                        fanout: 0,
                        route_ps: 0,
                    });
                    break;
                }
                Pred::Through {
                    cell,
                    input,
                    output,
                    cell_ps,
                } => {
                    let node = &nodes[cell];
                    let (inp, out) = (&node.inputs[input], &node.outputs[output]);
                    let from = inp.net.expect("timed input");
                    steps.push(PathStep {
                        cell: self.cell_name(cell),
                        cell_type: node.kind.clone(),
                        arc: format!("{}->{}", self.pin(cell, inp), self.pin(cell, out)),
                        cell_ps: cell_ps as u64,
                        net: Some(self.net_name(from)),
                        fanout: self.fanout[from as usize] as u64,
                        route_ps: self.route(routing, from, cell, input) as u64,
                    });
                    n = from;
                }
            }
        }
        steps.reverse();
        let cell_ps: u64 = steps.iter().map(|s| s.cell_ps).sum();
        let routing_ps: u64 = steps.iter().map(|s| s.route_ps).sum();
        debug_assert_eq!(cell_ps + routing_ps, total as u64);
        let (first, last) = (&steps[0], &steps[steps.len() - 1]);
        let levels = steps[1..steps.len() - 1]
            .iter()
            .filter(|s| s.cell_type != "INV")
            .count() as u64;
        Some(CriticalPath {
            delay_ps: total as u64,
            cell_ps,
            routing_ps,
            levels,
            start: format!("{} ({})", first.cell, first.cell_type),
            end: format!("{} ({} {})", last.cell, last.cell_type, last.arc),
            steps,
        })
    }
}
