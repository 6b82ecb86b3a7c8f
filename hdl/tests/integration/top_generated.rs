//! The committed generated-verilog/ folders equal what the generator makes now (regenerate
//! with `make verilog`), and the file set of a configuration is complete and consistent.

use hdl::generate::{
    default_configs, default_unit_config, generate, unit_dir_name, unit_files, CONFIG_FILE,
    VERILOG_FILE,
};
use hdl::top::TopConfig;
use hw_model::HwFormat;
use std::path::Path;

fn committed_root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../generated-verilog"))
}

#[test]
fn committed_configurations_are_current() {
    let root = committed_root();
    let unit = default_unit_config();
    let mut expected: Vec<String> = default_configs().iter().map(TopConfig::dir_name).collect();
    expected.push(unit_dir_name(&unit));
    let mut present: Vec<String> = std::fs::read_dir(root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    expected.sort();
    present.sort();
    assert_eq!(
        present, expected,
        "generated-verilog/ folders differ from the defaults: run `make verilog`"
    );
    let mut sets: Vec<(String, Vec<(String, String)>)> = default_configs()
        .iter()
        .map(|c| (c.dir_name(), generate(c).unwrap().files))
        .collect();
    // The unit's C files and config.json (its Verilog is not committed).
    sets.push((unit_dir_name(&unit), unit_files(&unit, false).unwrap()));
    for (dir, files) in sets {
        let dir = root.join(dir);
        for (name, text) in &files {
            let path = dir.join(name);
            let committed = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(
                committed == *text,
                "{} is stale: run `make verilog`",
                path.display()
            );
        }
    }
}

#[test]
fn config_json_describes_the_verilog() {
    let config = TopConfig::new(HwFormat::named("fp16"), 1, 3);
    let g = generate(&config).unwrap();
    let json: serde_json::Value = serde_json::from_str(g.file(CONFIG_FILE).unwrap()).unwrap();
    assert_eq!(json["format"], "fp16");
    assert_eq!(json["lanes"], 3);
    assert_eq!(
        json["lane_latency"].as_u64().unwrap() as usize,
        hdl::mt::latency(HwFormat::named("fp16"), 1)
    );
    assert_eq!(
        json["config_word"].as_u64().unwrap() as u32,
        config.config_word().unwrap().pack()
    );
    let verilog = g.file(VERILOG_FILE).unwrap();
    for port in json["ports"].as_array().unwrap() {
        let (name, width) = (
            port["name"].as_str().unwrap(),
            port["width"].as_u64().unwrap(),
        );
        let decl = if width > 1 {
            format!("wire [{}:0] {name}", width - 1)
        } else {
            format!("wire {name}")
        };
        assert!(verilog.contains(&decl), "rtfpga_top lacks `{decl}`");
    }
    assert!(verilog.contains("module rtfpga_top ("));
    assert!(
        !verilog.contains("module top"),
        "the body's modules are renamed"
    );
    for name in [
        hdl::cgen::HEADER_FILE,
        hdl::cgen::DRIVER_HEADER_FILE,
        hdl::cgen::DRIVER_SOURCE_FILE,
    ] {
        assert!(g.file(name).is_some_and(|t| !t.is_empty()), "{name}");
    }
}

#[test]
fn impossible_configurations_fail_before_generation() {
    // A format without hardware cannot even be named as one.
    let e = "e9m9".parse::<HwFormat>().unwrap_err().to_string();
    assert!(e.contains("e9m9") && e.contains("no hardware"), "{e}");
    for (config, needle) in [
        (TopConfig::new(HwFormat::named("fp32"), 1, 0), "lanes = 0"),
        (
            TopConfig::new(HwFormat::named("fp16"), 1000, 1),
            "depth = 1000",
        ),
    ] {
        let e = generate(&config).unwrap_err().to_string();
        assert!(e.contains(needle), "{e}");
    }
}
