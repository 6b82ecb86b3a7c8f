//! yosys reports on small designs whose resources and logic depth are known.

use hdl::synth::{synthesize, SynthError, SynthOptions};
use hdl::timing::ROUTING;

fn synth(verilog: &str) -> hdl::synth::SynthReport {
    synthesize(verilog, "top", &SynthOptions::default()).unwrap()
}

#[test]
fn multiplier_24x24_uses_two_dsp48e1() {
    let r = synth("module top(input [23:0] a, input [23:0] b, output [47:0] p);\n  assign p = a * b;\nendmodule\n");
    assert_eq!(r.dsp48e1, 2, "{r:?}");
    assert_eq!(r.lut, 0, "{r:?}");
    // Unregistered DSPs are logic levels: low partial product cascades into the high one.
    assert_eq!(r.logic_depth, 2, "{r:?}");
}

#[test]
fn registered_8bit_adder_has_8_ff_and_a_carry_chain() {
    let r = synth(
        "module top(input clk, input [7:0] a, input [7:0] b, output reg [7:0] s);\n\
         always @(posedge clk) s <= a + b;\nendmodule\n",
    );
    assert_eq!(r.ff, 8, "{r:?}");
    assert!(r.carry4 >= 2, "{r:?}");
    assert_eq!(r.dsp48e1, 0);
    // Inputs → LUT (propagate) → CARRY4 → CARRY4 → register.
    assert!((2..=4).contains(&r.logic_depth), "{r:?}");
}

/// `stages` LUT6 primitives in a row between two registers. Instantiated primitives are kept
/// as they are by the mapper (inferred logic would be restructured), so the depth is exactly
/// `stages`.
fn lut_chain(stages: usize) -> String {
    let width = 5 * stages + 1;
    let mut v = format!(
        "module top(input clk, input [{w}:0] a, output reg q);\n  reg [{w}:0] r;\n  wire [{stages}:0] y;\n  assign y[0] = r[0];\n",
        w = width - 1
    );
    for i in 0..stages {
        let b = 5 * i;
        v += &format!(
            "  LUT6 #(.INIT(64'h6996_9669_9669_6996)) l{i} (.O(y[{}]), .I0(y[{i}]), .I1(r[{}]), .I2(r[{}]), .I3(r[{}]), .I4(r[{}]), .I5(r[{}]));\n",
            i + 1, b + 1, b + 2, b + 3, b + 4, b + 5
        );
    }
    v += &format!("  always @(posedge clk) begin r <= a; q <= y[{stages}]; end\nendmodule\n");
    v
}

#[test]
fn logic_depth_counts_the_luts_between_registers() {
    for stages in [1, 3, 5] {
        let r = synth(&lut_chain(stages));
        assert_eq!(r.logic_depth, stages as u64, "{stages} stages: {r:?}");
        assert_eq!(r.lut, stages as u64, "{r:?}");
        assert_eq!(r.ff as usize, 5 * stages + 2, "{r:?}");
        // The timing estimate on the mapped netlist: every net has fanout 1, so the first
        // LUT's six inputs arrive together (one of them on the slowest pin, A1), and each
        // later LUT's chain input arrives last (the fastest pin, A6); the last LUT drives q's
        // D inside its slice (no routing). Delays: hdl/src/timing/xc7.rs.
        let path = r
            .critical_path
            .as_ref()
            .expect("a register-to-register path");
        let net = u64::from(ROUTING.net_ps(1));
        let (clock_to_q, a1, a6) = (303, 642, 127);
        let expected = clock_to_q + net + a1 + (stages as u64 - 1) * (net + a6);
        assert_eq!(path.delay_ps, expected, "{stages} stages: {path:?}");
        assert_eq!(path.levels, stages as u64, "{path:?}");
        assert!(path.end.starts_with("q ("), "{path:?}");
    }
}

#[test]
fn a_register_in_the_middle_halves_the_depth() {
    // The same 4-stage chain, with y[2] registered: two 2-LUT paths.
    let v = lut_chain(4)
        .replace("wire [4:0] y;", "wire [4:0] y; reg y2;")
        .replace(".I0(y[2])", ".I0(y2)")
        .replace("q <= y[4];", "q <= y[4]; y2 <= y[2];");
    let r = synth(&v);
    assert_eq!(r.logic_depth, 2, "{r:?}");
}

#[test]
fn missing_yosys_is_a_clear_error() {
    let options = SynthOptions {
        yosys: "yosys-not-installed-rtfpga".into(),
        ..SynthOptions::default()
    };
    let err = synthesize("module top; endmodule", "top", &options).unwrap_err();
    assert!(matches!(err, SynthError::YosysNotFound));
    assert_eq!(
        err.to_string(),
        "yosys not found on PATH: install it with `apt-get install yosys` (or run `make setup`)"
    );
}

#[test]
fn invalid_verilog_is_an_error_with_yosys_message() {
    let err = synthesize(
        "module top(input a, output b);\n  assign b = a +;\nendmodule\n",
        "top",
        &SynthOptions::default(),
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, SynthError::Failed { .. }), "{text}");
    assert!(
        text.contains("ERROR") && text.contains("design.v:2"),
        "{text}"
    );
}
