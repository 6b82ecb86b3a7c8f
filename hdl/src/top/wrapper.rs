//! The generated Verilog top `rtfpga_top`: Vitis/Vivado port names around rust-hdl's body.
//!
//! rust-hdl names the body `top` and flattens its ports with `$` (`axi$awvalid`,
//! `s_tdata$0`). The body's modules are renamed `rtfpga_core…` (so two generated IPs, or
//! another design's `top`, do not clash) and `rtfpga_top` maps the ports: `ap_clk`,
//! `ap_rst_n`, `s_axi_control_*`, `interrupt`, and the lanes' slots concatenated into
//! `s_axis_tdata` (lane i at `[512·i +: 512]`) and `m_axis_tdata` (lane i at `[128·i +: 128]`).
use std::fmt::Write;

use crate::regmap::ADDR_BITS;
use crate::top::stream::{IN_LANE_BITS, OUT_LANE_BITS};

/// Module name of the wrapper (what constraints/ and Vivado expect).
pub const TOP: &str = "rtfpga_top";
/// Module name the body's top `top` is renamed to (its submodules keep their `$…` suffixes).
pub const CORE: &str = "rtfpga_core";
/// rust-hdl's name of the generated top module.
const RUST_HDL_TOP: &str = "top";

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    Input,
    Output,
}

/// One port of `rtfpga_top`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TopPort {
    pub name: String,
    pub direction: Direction,
    pub width: usize,
}

/// The AXI4-Lite signals: name, direction seen from the slave, width.
const AXIL_SIGNALS: [(&str, Direction, usize); 17] = {
    use Direction::{Input as I, Output as O};
    [
        ("awvalid", I, 1),
        ("awready", O, 1),
        ("awaddr", I, ADDR_BITS),
        ("wvalid", I, 1),
        ("wready", O, 1),
        ("wdata", I, 32),
        ("wstrb", I, 4),
        ("bvalid", O, 1),
        ("bready", I, 1),
        ("bresp", O, 2),
        ("arvalid", I, 1),
        ("arready", O, 1),
        ("araddr", I, ADDR_BITS),
        ("rvalid", O, 1),
        ("rready", I, 1),
        ("rdata", O, 32),
        ("rresp", O, 2),
    ]
};

/// How a wrapper port reaches the body.
enum Body {
    /// One body port of the same width.
    Port(String),
    /// Slices of `slice` bits, body ports `<prefix>$0`, `<prefix>$1`, … from the LSB.
    Lanes { prefix: &'static str, slice: usize },
}

fn connections(lanes: usize) -> Vec<(TopPort, Body)> {
    use Direction::{Input, Output};
    let port = |name: &str, direction, width| TopPort {
        name: name.to_string(),
        direction,
        width,
    };
    let mut v = vec![
        (port("ap_clk", Input, 1), Body::Port("clock".into())),
        (port("ap_rst_n", Input, 1), Body::Port("reset_n".into())),
    ];
    for (signal, dir, width) in AXIL_SIGNALS {
        v.push((
            port(&format!("s_axi_control_{signal}"), dir, width),
            Body::Port(format!("axi${signal}")),
        ));
    }
    v.push((port("interrupt", Output, 1), Body::Port("interrupt".into())));
    for (side, data_dir, ctrl_dir, slice) in [
        ("s", Input, Output, IN_LANE_BITS),
        ("m", Output, Input, OUT_LANE_BITS),
    ] {
        let prefix = if side == "s" { "s_tdata" } else { "m_tdata" };
        v.push((
            port(&format!("{side}_axis_tdata"), data_dir, slice * lanes),
            Body::Lanes { prefix, slice },
        ));
        v.push((
            port(&format!("{side}_axis_tvalid"), data_dir, 1),
            Body::Port(format!("{side}_tvalid")),
        ));
        v.push((
            port(&format!("{side}_axis_tready"), ctrl_dir, 1),
            Body::Port(format!("{side}_tready")),
        ));
        v.push((
            port(&format!("{side}_axis_tlast"), data_dir, 1),
            Body::Port(format!("{side}_tlast")),
        ));
    }
    v
}

/// The ports of `rtfpga_top` with `lanes` lanes, in declaration order.
pub fn ports(lanes: usize) -> Vec<TopPort> {
    connections(lanes).into_iter().map(|(p, _)| p).collect()
}

/// Renames rust-hdl's module `top` (and its submodules `top$…`) to [`CORE`].
pub fn rename_body(body: &str) -> String {
    let mut out = String::with_capacity(body.len() + body.len() / 50);
    for line in body.lines() {
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        let renamed = if let Some(rest) = trimmed.strip_prefix("module ") {
            format!("module {}", rename_module(rest))
        } else if let Some(rest) = trimmed.strip_prefix("endmodule // ") {
            format!("endmodule // {}", rename_module(rest))
        } else if trimmed.starts_with("top$") && trimmed.ends_with('(') {
            // A submodule instance: `top$a$b name(`.
            rename_module(trimmed)
        } else {
            trimmed.to_string()
        };
        writeln!(out, "{indent}{renamed}").unwrap();
    }
    out
}

fn rename_module(text: &str) -> String {
    match text.strip_prefix(RUST_HDL_TOP) {
        Some(rest) if rest.starts_with(['$', '(', ' ']) || rest.is_empty() => {
            format!("{CORE}{rest}")
        }
        _ => text.to_string(),
    }
}

/// The wrapper module for `lanes` lanes (instantiates [`CORE`]).
pub fn wrapper_verilog(lanes: usize) -> String {
    let conns = connections(lanes);
    let mut s = String::new();
    writeln!(s, "// {TOP}: Vitis-style port names around the rust-hdl body {CORE} (generated by hdl::top::wrapper; do not edit).").unwrap();
    writeln!(
        s,
        "// ap_rst_n is a synchronous active-low reset; interrupt is level-high."
    )
    .unwrap();
    writeln!(s, "// Stream slots: s_axis_tdata lane i = [{IN_LANE_BITS}*i +: {IN_LANE_BITS}], m_axis_tdata lane i = [{OUT_LANE_BITS}*i +: {OUT_LANE_BITS}] (docs/stream.md).").unwrap();
    writeln!(s, "module {TOP} (").unwrap();
    for (i, (p, _)) in conns.iter().enumerate() {
        let dir = match p.direction {
            Direction::Input => "input ",
            Direction::Output => "output",
        };
        let range = if p.width > 1 {
            format!("[{}:0] ", p.width - 1)
        } else {
            String::new()
        };
        let comma = if i + 1 < conns.len() { "," } else { "" };
        writeln!(s, "    {dir} wire {range}{}{comma}", p.name).unwrap();
    }
    writeln!(s, ");\n    {CORE} core (").unwrap();
    let mut pins = Vec::new();
    for (p, body) in &conns {
        match body {
            Body::Port(name) => pins.push(format!(".{name}({})", p.name)),
            Body::Lanes { prefix, slice } => {
                for lane in 0..p.width / slice {
                    pins.push(format!(
                        ".{prefix}${lane}({}[{}:{}])",
                        p.name,
                        (lane + 1) * slice - 1,
                        lane * slice
                    ));
                }
            }
        }
    }
    writeln!(s, "        {}", pins.join(",\n        ")).unwrap();
    writeln!(s, "    );\nendmodule // {TOP}").unwrap();
    s
}

/// The complete `rtfpga_top.v`: wrapper, then the renamed body.
pub fn top_verilog(body: &str, lanes: usize) -> String {
    format!("{}\n{}", wrapper_verilog(lanes), rename_body(body))
}
