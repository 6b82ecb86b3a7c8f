//! `formats`, `verilog` and the configurations `verilog`, `synth` and `cosim` refuse before
//! building anything.

use std::path::Path;

use crate::common::*;

#[test]
fn formats_lists_every_catalogue_format_as_a_table_and_as_json() {
    let out = rtfpga(&["formats"]).ok();
    let rows: Vec<&str> = out
        .lines()
        .filter_map(|l| l.strip_prefix("| "))
        .filter_map(|l| l.split(" |").next())
        .filter(|name| *name != "name" && !name.starts_with('-'))
        .collect();
    let names: Vec<&str> = hw_model::catalogue().iter().map(|f| f.name).collect();
    assert!(names.len() >= 4, "fp32, fp24, bf16, fp16 at least");
    assert_eq!(rows, names, "table rows vs hw_model::catalogue()\n{out}");
    let json: serde_json::Value =
        serde_json::from_str(&rtfpga(&["formats", "--json"]).ok()).unwrap();
    let json_names: Vec<&str> = json
        .as_array()
        .expect("a JSON array")
        .iter()
        .map(|f| f["name"].as_str().expect("a name"))
        .collect();
    assert_eq!(json_names, names, "rtfpga formats --json");
}

#[test]
fn verilog_fp32_d5_l1_equals_the_committed_copy() {
    let dir = tmp();
    let out_dir = at(&dir, "v");
    rtfpga(&[
        "verilog", "--format", "fp32", "--depth", "5", "--lanes", "1",
    ])
    .out(&out_dir)
    .ok();
    let committed = Path::new(REPO).join("generated-verilog/fp32_d5_l1");
    let listing = |d: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let names = listing(&out_dir);
    for needed in ["rtfpga_top.v", "xrtfpga.h"] {
        assert!(
            names.iter().any(|n| n == needed),
            "no {needed} in {names:?}"
        );
    }
    assert_eq!(names, listing(&committed), "files written vs committed");
    for name in &names {
        assert!(
            std::fs::read(out_dir.join(name)).unwrap()
                == std::fs::read(committed.join(name)).unwrap(),
            "{name} differs from generated-verilog/fp32_d5_l1/{name} (stale: `make verilog`)"
        );
    }
}

/// `verilog --unit traversal` writes the unit's AXI4-Lite top, its C files and a config.json
/// whose ports are the Verilog's, the streams as wide as the packets.
#[test]
fn verilog_of_the_traversal_unit_writes_its_verilog_and_config() {
    let dir = tmp();
    let out_dir = at(&dir, "unit");
    let out = rtfpga(&["verilog", "--unit", "traversal", "--depth", "2"])
        .out(&out_dir)
        .ok();
    assert!(out.contains("4096 nodes and 8192 triangles"), "{out}");
    let verilog = std::fs::read_to_string(out_dir.join("traversal_unit.v")).unwrap();
    assert!(verilog.contains("module top"));
    let config: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("config.json")).unwrap())
            .unwrap();
    assert_eq!(config["format"], "fp32");
    assert_eq!(config["depth"], 2);
    assert_eq!(config["memory"]["triangles"], 8192);
    let width = |name: &str| {
        config["ports"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("no port {name} in {config}"))["width"]
            .as_u64()
            .unwrap()
    };
    use hw_model::traversal::packet::{HIT_WORDS, RAY_WORDS};
    assert_eq!(width("ray$tdata"), 32 * RAY_WORDS as u64);
    assert_eq!(width("hit$tdata"), 32 * HIT_WORDS as u64);
    assert_eq!(width("axi$awaddr"), hdl::regmap::ADDR_BITS as u64);
    for name in [
        hdl::cgen::UNIT_HEADER_FILE,
        hdl::cgen::UNIT_DRIVER_HEADER_FILE,
        hdl::cgen::UNIT_DRIVER_SOURCE_FILE,
    ] {
        assert!(out_dir.join(name).is_file(), "no {name}");
    }
}

/// `--advance leaf-box` builds the traversal unit with the leaf advance around its lane
/// (`none`, the default, has none of it).
#[test]
fn verilog_of_the_traversal_unit_with_the_leaf_advance() {
    let dir = tmp();
    let unit = |advance: &str| {
        let out_dir = at(&dir, advance);
        rtfpga(&["verilog", "--unit", "traversal", "--scene-memory", "16,32"])
            .args(&["--advance", advance])
            .out(&out_dir)
            .ok();
        std::fs::read_to_string(out_dir.join("traversal_unit.v")).unwrap()
    };
    assert!(unit("leaf-box").contains("around$0$lane$query"));
    assert!(!unit("none").contains("around"));
}

/// The configurations the unit's RTL does not build are errors naming what is wrong, in the
/// units typed, before any model is built or file written.
#[test]
fn the_traversal_unit_refuses_what_its_rtl_does_not_build() {
    let dir = tmp();
    let png = at(&dir, "unit.png");
    let out_dir = at(&dir, "v");
    let unit = |command: &str| rtfpga(&[command, "--unit", "traversal"]);
    for (extra, needles) in [
        (
            &["--lanes", "4"][..],
            &["4 Möller-Trumbore lanes", "built with 1 to 3"][..],
        ),
        (&["--slots", "16"], &["32 ray slots, not 16"]),
        (
            &["--scene-memory", "100,100"],
            &[
                "--scene-memory 100,100",
                "16,32, 512,1024, 2048,4096 and 4096,8192",
            ],
        ),
        (&["--depth", "99"], &["depth = 99", "depth 0 to"]),
        (
            &["--advance", "triangle-box"],
            &["--advance triangle-box", "none or leaf-box"],
        ),
        (&["--format", "bfp18/fp32"], &["model-only"]),
    ] {
        unit("cosim")
            .args(&["--scene", "simple_plane"])
            .args(extra)
            .out(&png)
            .fails(1, needles);
        unit("verilog").args(extra).out(&out_dir).fails(1, needles);
        unit("synth").args(extra).fails(1, needles);
    }
    assert!(!png.exists());
    assert!(!out_dir.exists(), "no folder for a refused configuration");
    unit("cosim")
        .args(&["--scene", "simple_plane", "--mode", "register"])
        .out(&png)
        .fails(
            1,
            &["--mode does not act on --unit traversal: it applies to --unit mt"],
        );
    unit("synth")
        .args(&["--op", "add"])
        .fails(1, &["--op", "--unit traversal"]);
    unit("verilog")
        .args(&["--defaults"])
        .out(&out_dir)
        .fails(1, &["--defaults"]);
    rtfpga(&["cosim", "--unit", "bvh", "--scene", "simple_plane"])
        .out(&png)
        .fails(2, &["--unit"]);
}

#[test]
fn the_accelerator_refuses_depths_and_lane_counts_it_is_not_built_with() {
    let dir = tmp();
    let out_dir = at(&dir, "v");
    let png = at(&dir, "x.png");
    for (extra, needles) in [
        (
            &["--depth", "99"][..],
            &["depth = 99", "fp32", "depth 0 to"][..],
        ),
        (&["--lanes", "0"], &["lanes = 0", "at least one lane"]),
        (&["--lanes", "1000"], &["lanes = 1000", "at most"]),
    ] {
        rtfpga(&["verilog"])
            .args(extra)
            .out(&out_dir)
            .fails(1, needles);
        rtfpga(&["synth"]).args(extra).fails(1, needles);
        render("simple_plane", 8, 8, &png)
            .args(&["--engine", "hw"])
            .args(extra)
            .fails(1, needles);
        cosim("simple_plane", 8, 8, &png)
            .args(extra)
            .fails(1, needles);
    }
    assert!(!out_dir.exists(), "no Verilog for a refused configuration");
    assert!(!png.exists());
}
