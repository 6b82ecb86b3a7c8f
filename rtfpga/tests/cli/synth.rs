//! `synth`'s timing estimate: `fmax_mhz_estimate` and the critical path, as `key=value` lines
//! and in `--json` (docs/timing.md). Needs yosys.

use crate::common::*;

/// The estimate in the text output and in `--json` agree, and the path's parts add up.
#[test]
fn synth_reports_the_fmax_estimate_and_its_critical_path() {
    let test = "synth_reports_the_fmax_estimate_and_its_critical_path";
    if !needs("yosys", test) {
        return;
    }
    // fp16 add with two pipeline stages: logic between its registers.
    let args = ["synth", "--format", "fp16", "--op", "add", "--stages", "2"];
    let json: serde_json::Value =
        serde_json::from_str(&rtfpga(&args).args(&["--json"]).synthesis().ok()).unwrap();
    let path = &json["critical_path"];
    let delay_ps = path["delay_ps"].as_u64().expect("critical_path.delay_ps");
    let fmax = json["fmax_mhz_estimate"]
        .as_f64()
        .expect("fmax_mhz_estimate");
    assert!((fmax - 1e6 / delay_ps as f64).abs() < 1e-6, "{json}");
    let (cell_ps, routing_ps) = (
        path["cell_ps"].as_u64().unwrap(),
        path["routing_ps"].as_u64().unwrap(),
    );
    assert_eq!(cell_ps + routing_ps, delay_ps, "{path}");
    let levels = path["levels"].as_u64().unwrap();
    let steps = path["steps"].as_array().unwrap();
    assert!(levels >= 1 && steps.len() as u64 >= levels + 2, "{path}");
    let step_ps: u64 = steps
        .iter()
        .map(|s| s["cell_ps"].as_u64().unwrap() + s["route_ps"].as_u64().unwrap())
        .sum();
    assert_eq!(step_ps, delay_ps, "{path}");

    // yosys maps the same Verilog the same way: the text run reports the same path.
    let text = rtfpga(&args).synthesis().ok();
    let num = |key: &str| -> f64 {
        value(&text, key)
            .unwrap_or_else(|| panic!("no {key}= in:\n{text}"))
            .parse()
            .unwrap()
    };
    assert_eq!(num("fmax_mhz_estimate"), fmax.round(), "{text}");
    assert_eq!(num("delay_ns"), (delay_ps as f64 / 10.0).round() / 100.0);
    assert_eq!(num("levels"), levels as f64);
    let (_, ends) = fields(labelled(&text, "critical_path")).unwrap();
    assert_eq!(
        ends,
        [
            (
                "from".to_string(),
                path["start"].as_str().unwrap().to_string()
            ),
            ("to".to_string(), path["end"].as_str().unwrap().to_string()),
        ],
        "{text}"
    );
    let table_rows = text.lines().filter(|l| l.starts_with("| ")).count();
    assert!(table_rows >= steps.len(), "a table row per step:\n{text}");
}

/// Without registers there is no register-to-register path, and no estimate.
#[test]
fn a_design_without_registers_has_no_estimate() {
    if !needs("yosys", "a_design_without_registers_has_no_estimate") {
        return;
    }
    let args = ["synth", "--format", "fp16", "--op", "lt", "--stages", "0"];
    let json: serde_json::Value =
        serde_json::from_str(&rtfpga(&args).args(&["--json"]).synthesis().ok()).unwrap();
    assert!(
        json["fmax_mhz_estimate"].is_null() && json["critical_path"].is_null(),
        "{json}"
    );
}
