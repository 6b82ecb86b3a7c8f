//! The design-space sweep: a tiny configuration end to end (model engine, two formats under
//! both spawn policies and both origin advances, a float and a block-floating-point
//! dual-precision pair, tiny images, projection), a job run on its own reproducing the local
//! run's result, and bad configurations refused with the file, line and key before any work.
//!
//! Synthesis and co-simulation of the smallest accelerator take over a minute, so that test
//! is ignored by default: `cargo test --release -p sim --test integration sweep:: -- --ignored`.

use std::path::{Path, PathBuf};

use hw_model::dual::{DualIntersector, FormatPair};
use hw_model::precision::SpawnChoice;
use hw_model::{Advance, HwFormat};
use sim::sweep::config::Variant;
use sim::sweep::dual::DualResult;
use sim::sweep::hardware::PointResult;
use sim::sweep::layout::read_json;
use sim::sweep::quality::QualityResult;
use sim::sweep::{self, ConfigError, Job, Layout, LocalRun, Results};

/// The thesis scenes (the projection stage calibrates on them), or None after a
/// `SKIPPED sweep::<test>` line.
fn thesis_scenes(test: &str) -> Option<PathBuf> {
    sw_renderer::thesis_scenes::for_test(&format!("sweep::{test}"))
}

/// Writes `text` as `name` in `dir`, returns its path.
fn config_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn local(threads: usize) -> LocalRun {
    LocalRun {
        threads,
        progress: false,
        program: "rtfpga".into(),
    }
}

const TINY: &str = r#"
formats = ["fp32", "fx16_10"]
depths = [1]
lanes = [1, 2]
scenes = ["simple_plane", "utah_teapot"]
width = 48
height = 27
stages = ["quality", "projection"]
"#;

#[test]
fn a_tiny_sweep_runs_end_to_end_with_consistent_numbers() {
    let Some(scenes) = thesis_scenes("a_tiny_sweep_runs_end_to_end_with_consistent_numbers") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // Both policies and both advances by default; two pairs.
    let text = format!(
        "{TINY}pairs = [\"bfp14/fp32\", \"bfp16/fp32\"]\n\n[projection]\nthesis_scenes = {:?}\n",
        scenes.display().to_string()
    );
    let path = config_file(dir.path(), "tiny.toml", &text);
    let config = sweep::load(&path).unwrap();
    assert_eq!(config.points.len(), 4);
    assert_eq!(config.policies, SpawnChoice::ALL);
    assert_eq!(config.advances, Advance::ALL);
    // The advance under format-aware only (its default lane in `rtfpga render`).
    let (thesis, fa) = (SpawnChoice::Thesis, SpawnChoice::FormatAware);
    let variant = |policy, advance| Variant { policy, advance };
    let (plain, fa_plain, fa_advanced) = (
        variant(thesis, Advance::None),
        variant(fa, Advance::None),
        variant(fa, Advance::TriangleBox),
    );
    assert_eq!(config.variants(), [plain, fa_plain, fa_advanced]);
    let out = dir.path().join("out");
    let results = sweep::run_local(&config, &out, &local(2)).unwrap();
    let layout = Layout::new(&out);

    for file in [
        "manifest.json",
        "jobs.txt",
        "sweep.json",
        "results.csv",
        "quality.csv",
        "results.json",
        "results.md",
    ] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    for v in config.variants() {
        for ext in ["png", "svg"] {
            assert!(layout
                .plot(&format!("psnr_vs_bits_{}", v.name()), ext)
                .is_file());
        }
        for format in ["fp32", "fx16_10"] {
            let grid = image::open(layout.grid(format, v)).unwrap();
            // Two scenes stacked, render and heat-map side by side (4-pixel gaps).
            assert_eq!(
                (grid.width(), grid.height()),
                (2 * 48 + 3 * 4, 2 * 27 + 3 * 4)
            );
        }
    }

    // The manifest: prepare, one quality job per format, one per pair, one per point, merge.
    let jobs = std::fs::read_to_string(layout.jobs_txt()).unwrap();
    assert_eq!(jobs.lines().count(), 2 + 2 + 4);
    assert!(jobs.contains(" --job dual/bfp14/fp32") && jobs.contains(" --job dual/bfp16/fp32"));
    assert!(jobs
        .lines()
        .all(|l| l.starts_with("rtfpga sweep-job --config ") && l.contains(" --job ")));

    // fp32 with the thesis' spawning and no advance is the reference's arithmetic:
    // identical; the 16-bit fixed format is not, under either policy.
    assert_eq!(results.quality.len(), 2 * 3);
    let q = |f: &str, v: Variant| {
        results
            .quality
            .iter()
            .find(|q| q.format == f && q.variant() == v)
            .unwrap()
    };
    assert_eq!(q("fp32", plain).min_psnr_db(), f64::INFINITY);
    assert!(q("fp32", plain)
        .scenes
        .iter()
        .all(|s| s.differing_pixels == 0));
    for v in [plain, fa_plain] {
        let coarse = q("fx16_10", v).min_psnr_db();
        assert!(
            coarse.is_finite() && coarse < 40.0,
            "fx16_10 {v} min PSNR {coarse}"
        );
        assert!(q("fx16_10", v).max_differing_share() > 0.0);
    }
    // The advance really changes the narrow format's renders (and its saved images).
    let scenes_of = |v| {
        q("fx16_10", v)
            .scenes
            .iter()
            .map(|s| (s.psnr_db, s.differing_pixels))
            .collect::<Vec<_>>()
    };
    assert_ne!(scenes_of(fa_plain), scenes_of(fa_advanced));
    let teapot = |v| image::open(layout.quality_dir("fx16_10", v).join("utah_teapot.png")).unwrap();
    assert_ne!(teapot(fa_plain), teapot(fa_advanced));

    // The pairs: one result per policy, every image equal to the fp32 model's (so identical
    // to the reference under the thesis' spawning), a share of its tests forwarded, and the
    // counts those of the pair's own intersector (the engines' filter for it) rendering the
    // scene.
    assert_eq!(results.dual.len(), 2 * 2);
    for d in &results.dual {
        let pair = FormatPair::parse(&d.pair).unwrap();
        assert_eq!(d.filter_bits, pair.filter_width);
        assert!(d.exact(), "{d:?}");
        for s in &d.scenes {
            assert!(
                s.tests > 0 && s.forwarded > 0 && s.forwarded < s.tests,
                "{s:?}"
            );
            // Read back from JSON: serde_json may round the last bit.
            let share = s.forwarded as f64 / s.tests as f64;
            assert!((s.forwarded_share - share).abs() <= 1e-15 * share, "{s:?}");
        }
        if d.policy == thesis {
            assert_eq!(d.min_psnr_db(), f64::INFINITY);
        }
        let scene = &config.scenes[0];
        let direct = DualIntersector::new(pair);
        sw_renderer::render::render(
            &scene.load().unwrap(),
            &direct,
            &sw_renderer::render::RenderOptions {
                width: Some(48),
                height: Some(27),
                spawn: d.policy.policy(&pair.fallback, 0),
                ..Default::default()
            },
        )
        .unwrap();
        let stats = direct.stats();
        assert_eq!(
            (stats.tests, stats.forwarded()),
            (d.scenes[0].tests, d.scenes[0].forwarded)
        );
    }
    assert_eq!(
        results
            .dual
            .iter()
            .map(|d| d.pair.as_str())
            .collect::<Vec<_>>(),
        ["bfp14/fp32", "bfp14/fp32", "bfp16/fp32", "bfp16/fp32"]
    );
    let on_disk: DualResult = read_json(&layout.dual_result("bfp16/fp32", fa)).unwrap();
    assert_eq!(Some(&on_disk), results.dual.last());

    // Rows: one per point and policy, with the hardware's lane (no advance); quality comes
    // from the format and policy, cycles per test from the lanes, and the frame time from the
    // projection (same workload, so every row's ARM-only time agrees).
    assert_eq!(results.rows.len(), 4 * 2);
    let arm = results.arm_only_s.unwrap();
    for r in &results.rows {
        let v = variant(r.policy.unwrap(), r.advance.unwrap());
        assert!(v.in_hardware(), "{v}");
        assert_eq!(r.min_psnr_db.unwrap().0, q(&r.format, v).min_psnr_db());
        assert_eq!(r.cycles_per_test, 1.0 / r.lanes as f64);
        assert_eq!(
            r.latency,
            hdl::mt::latency(r.format.parse().unwrap(), r.depth)
        );
        let frame = r.projected_frame_s.unwrap();
        assert!(
            frame > 0.0 && frame < arm,
            "{}: frame {frame} s, ARM {arm} s",
            r.id
        );
        assert!((r.speedup_vs_arm.unwrap() - arm / frame).abs() < 1e-9);
        assert!(
            r.lut.is_none() && r.resources.is_none(),
            "synthesis was not configured"
        );
    }

    // The files say the same as the returned results.
    let json: Results = read_json(&layout.results("json")).unwrap();
    assert_eq!(json.rows.len(), results.rows.len());
    for (a, b) in json.rows.iter().zip(&results.rows) {
        // serde_json may round the last bit of a float.
        let close =
            |x: Option<f64>, y: Option<f64>| (x.unwrap() - y.unwrap()).abs() <= 1e-12 * y.unwrap();
        assert!(
            a.id == b.id
                && a.policy == b.policy
                && a.min_psnr_db == b.min_psnr_db
                && a.lanes == b.lanes
        );
        assert!(
            close(a.projected_frame_s, b.projected_frame_s)
                && close(a.speedup_vs_arm, b.speedup_vs_arm)
        );
    }
    let csv = std::fs::read_to_string(layout.results("csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 4 * 2);
    assert!(csv
        .lines()
        .any(|l| l.starts_with("fp32_d1_l1,fp32,32,1,1,thesis,none,") && l.contains(",inf,")));
    // quality.csv: 2 formats × 3 variants and 2 pairs × 2 policies, each × 2 scenes.
    let quality_csv = std::fs::read_to_string(layout.quality_csv()).unwrap();
    assert_eq!(quality_csv.lines().count(), 1 + (2 * 3 + 2 * 2) * 2);
    for start in [
        "bfp14/fp32,pair,14,format-aware,none,simple_plane,",
        "bfp16/fp32,pair,16,thesis,none,utah_teapot,",
    ] {
        assert!(
            quality_csv
                .lines()
                .any(|l| l.starts_with(start) && l.ends_with(",true")),
            "{start}"
        );
    }
    assert!(quality_csv
        .lines()
        .any(|l| l.starts_with("fx16_10,hardware,16,format-aware,triangle-box,utah_teapot,")));
    let md = std::fs::read_to_string(layout.results("md")).unwrap();
    for r in &results.rows {
        assert!(
            md.contains(&format!("| {} |", r.id)),
            "{} not in results.md",
            r.id
        );
    }
    assert!(md.contains(
        "Smallest hardware format with PSNR ≥ 40 dB on every scene (thesis policy, advance none): **fp32**"
    ));
    assert!(md.contains("| fx16_10 | format-aware | triangle-box | 16 |"));
    assert!(md.contains("| bfp16/fp32 | format-aware |"));

    // A job run on its own (as a manifest line does) writes the same result.
    let before: QualityResult = read_json(&layout.quality_result("fx16_10", fa_advanced)).unwrap();
    let job = Job::parse("quality/fx16_10", &config).unwrap();
    sweep::run_job(&config, &layout, &job).unwrap();
    let again: QualityResult = read_json(&layout.quality_result("fx16_10", fa_advanced)).unwrap();
    assert_eq!(
        before
            .scenes
            .iter()
            .map(|s| (s.psnr_db, s.differing_pixels))
            .collect::<Vec<_>>(),
        again
            .scenes
            .iter()
            .map(|s| (s.psnr_db, s.differing_pixels))
            .collect::<Vec<_>>()
    );
    assert!(
        Job::parse("quality/fp16", &config).is_err(),
        "fp16 is not in this sweep"
    );
    assert!(Job::parse("point/fp32_d9_l1", &config).is_err());
    assert_eq!(
        Job::parse("dual/bfp14/fp32", &config).unwrap(),
        Job::Dual("bfp14/fp32".into())
    );
    assert!(
        Job::parse("dual/bfp18/fp32", &config).is_err(),
        "bfp18/fp32 is not in this sweep"
    );

    // The merge refuses to run with a result missing, naming it.
    std::fs::remove_file(layout.point_result("fx16_10_d1_l2")).unwrap();
    let e = sweep::merge(&layout).unwrap_err().to_string();
    assert!(e.contains("fx16_10_d1_l2") && e.contains("missing"), "{e}");
}

/// Where the bad configs pretend to live: the repository's sweeps/. Their thesis_scenes is
/// the default (`sw_renderer::thesis_scenes`).
fn bad_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../sweeps/bad.toml")
}

#[test]
fn synthesis_selection_is_the_product_of_its_subsets_plus_the_listed_points() {
    let text =
        format!("{TINY}stages = [\"synth\"]\n[synth]\nlanes = [1]\npoints = [\"fp32_d1_l2\"]\n")
            .replace("stages = [\"quality\", \"projection\"]\n", "");
    let config = sweep::parse(&text, &bad_path()).unwrap();
    let chosen: Vec<String> = config
        .points
        .iter()
        .filter(|p| config.synthesises(p))
        .map(|p| p.id())
        .collect();
    assert_eq!(chosen, ["fp32_d1_l1", "fp32_d1_l2", "fx16_10_d1_l1"]);
}

#[test]
fn the_pair_built_in_hardware_is_queued_first_when_it_is_synthesised() {
    let ids = |stages: &str| {
        let text =
            format!("{TINY}pairs = [\"bfp16/fp32\", \"bfp18/fp32\"]\n[synth]\nlanes = [1]\n")
                .replace("[\"quality\", \"projection\"]", stages);
        let config = sweep::parse(&text, &bad_path()).unwrap();
        sweep::manifest::jobs(&config)
            .iter()
            .map(Job::id)
            .collect::<Vec<_>>()
    };
    // Its job synthesises two designs: the longest, so ahead of the points' syntheses.
    let synth = ids("[\"synth\", \"quality\"]");
    assert_eq!(
        synth[..4],
        [
            "dual/bfp18/fp32",
            "point/fp32_d1_l1",
            "point/fx16_10_d1_l1",
            "dual/bfp16/fp32"
        ]
    );
    // Without synth or cosim it only renders: a pair job like the others, in file order.
    let model = ids("[\"quality\"]");
    assert_eq!(model[..2], ["dual/bfp16/fp32", "dual/bfp18/fp32"]);
}

/// The error of `text` (a tiny config with one change).
fn rejection(text: &str) -> ConfigError {
    sweep::parse(text, &bad_path()).expect_err(text)
}

fn with(key_line: &str) -> String {
    let key = key_line.split('=').next().unwrap().trim();
    TINY.lines()
        .map(|l| {
            if l.split('=').next().unwrap().trim() == key {
                key_line
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn bad_configurations_are_rejected_with_file_line_and_key() {
    // TINY's projection stage needs the thesis scenes (found by the default thesis_scenes).
    if thesis_scenes("bad_configurations_are_rejected_with_file_line_and_key").is_none() {
        return;
    }
    // The tiny config itself is fine.
    sweep::parse(TINY, &bad_path()).unwrap();

    let e = rejection(&with(r#"formats = ["fp32", "fp33"]"#));
    assert_eq!(
        (e.file.as_str(), e.line, e.key.as_str()),
        (bad_path().to_str().unwrap(), 2, "formats")
    );
    assert!(
        e.message.contains("unknown format `fp33`") && e.message.contains("fp16"),
        "{e}"
    );
    assert!(
        e.to_string()
            .ends_with(&format!("bad.toml:2: `formats`: {}", e.message)),
        "{e}"
    );

    let e = rejection(&with(r#"formats = ["fp32", "bfp18/fp32"]"#));
    assert_eq!((e.line, e.key.as_str()), (2, "formats"));
    assert!(
        e.message.contains("dual-precision pair") && e.message.contains("list it under `pairs`"),
        "{e}"
    );
    let e = rejection(&with(r#"formats = ["fp16/fp32"]"#));
    assert!(e.message.contains("not block floating point"), "{e}");

    // Spawn policies and dual-precision pairs (appended after TINY's 9 lines: line 10).
    let after = |line: &str| rejection(&format!("{TINY}\n{line}\n"));
    for (line, expected) in [
        (
            r#"policies = ["thesis", "fast"]"#,
            "unknown spawn policy `fast`: expected thesis or format-aware",
        ),
        (
            r#"policies = ["format-aware", "format-aware"]"#,
            "listed twice",
        ),
        ("policies = []", "empty list"),
        (
            r#"advances = ["none", "sideways"]"#,
            "unknown origin advance `sideways`: expected none or triangle-box",
        ),
        (r#"advances = ["none", "none"]"#, "listed twice"),
        ("advances = []", "empty list"),
        (
            r#"advances = ["triangle-box"]"#,
            "the thesis policy would have no render",
        ),
        (r#"pairs = ["fp16/fp32"]"#, "not block floating point"),
        (r#"pairs = ["bfp16/fp33"]"#, "fallback half"),
        (r#"pairs = ["bfp16/fx16_10"]"#, "holds fp32"),
        (r#"pairs = ["bfp16"]"#, "expected FILTER/FALLBACK"),
        (r#"pairs = ["bfp16/fp32", " BFP16/fp32"]"#, "listed twice"),
        ("pairs = []", "empty list"),
    ] {
        let e = after(line);
        let key = line.split(' ').next().unwrap();
        assert_eq!(
            (e.file.as_str(), e.line, e.key.as_str()),
            (bad_path().to_str().unwrap(), 10, key),
            "{line}: {e}"
        );
        assert!(e.message.contains(expected), "{line}: {e}");
    }
    let chosen = sweep::parse(
        &format!("{TINY}policies = [\"format-aware\"]\npairs = [\"bfp20/fp32\"]\n"),
        &bad_path(),
    )
    .unwrap();
    assert_eq!(chosen.policies, [SpawnChoice::FormatAware]);
    assert_eq!(chosen.pairs, ["bfp20/fp32"]);
    let advanced_only = sweep::parse(
        &format!("{TINY}policies = [\"format-aware\"]\nadvances = [\"triangle-box\"]\n"),
        &bad_path(),
    )
    .unwrap();
    assert_eq!(
        advanced_only.variants(),
        [Variant {
            policy: SpawnChoice::FormatAware,
            advance: Advance::TriangleBox
        }]
    );

    let e = rejection(&with("lanes = [1, 0]"));
    assert_eq!((e.line, e.key.as_str()), (4, "lanes"));
    assert!(e.message.contains("0 lanes"), "{e}");

    let e = rejection(&with("lanes = [9]"));
    assert!(e.key == "lanes" && e.message.contains("at most 8"), "{e}");

    // A format's operators have registers for depth 0..=max only: a depth beyond both formats'
    // maxima is refused for the first of them, fp32.
    let max =
        hdl::mt::max_depth(HwFormat::FP32).max(hdl::mt::max_depth(HwFormat::named("fx16_10")));
    let e = rejection(&with(&format!("depths = [1, {}]", max + 1)));
    assert_eq!((e.line, e.key.as_str()), (3, "depths"));
    assert!(
        e.message.contains("impossible depth") && e.message.contains("format fp32"),
        "{e}"
    );
    let e = rejection(&with(r#"depths = ["deep"]"#));
    assert!(e.message.contains("\"max\""), "{e}");

    let e = rejection(&with(r#"scenes = ["simple_plane", "no_such_scene"]"#));
    assert_eq!((e.line, e.key.as_str()), (5, "scenes"));
    assert!(
        e.message.contains("no_such_scene") && e.message.contains("glass_pen"),
        "{e}"
    );

    for empty in ["formats = []", "depths = []", "lanes = []", "scenes = []"] {
        let e = rejection(&with(empty));
        assert!(e.message.contains("empty list"), "{empty}: {e}");
        assert_eq!(e.key, empty.split(' ').next().unwrap());
    }

    let e = rejection(&with("width = 0"));
    assert_eq!(e.key, "width");
    let e = rejection(&with(r#"stages = ["quality", "render"]"#));
    assert!(
        e.key == "stages" && e.message.contains("unknown stage `render`"),
        "{e}"
    );
    let e = rejection(&format!("{TINY}\n[cosim]\npoints = [\"fp16_d1_l1\"]\n"));
    assert_eq!((e.line, e.key.as_str()), (11, "cosim.points"));
    assert!(
        e.message.contains("fp32_d1_l1"),
        "lists the sweep's points: {e}"
    );
    let e = rejection(&format!("{TINY}\n[synth]\nformats = [\"fp64\"]\n"));
    assert_eq!(e.key, "synth.formats");
    let e = rejection(&format!(
        "{TINY}\n[synth]\npoints = [\"fp32_d1_l1\", \"fp16_d1_l2\"]\n"
    ));
    assert_eq!((e.line, e.key.as_str()), (11, "synth.points"));
    assert!(
        e.message.contains("`fp16_d1_l2`") && e.message.contains("fx16_10_d1_l2"),
        "{e}"
    );
    let e = rejection(&format!("{TINY}\nmodel_formats = [\"e0m0x\"]\n"));
    assert_eq!(e.key, "model_formats");

    let e = rejection(&format!(
        "{TINY}\n[projection]\nthesis_scenes = \"nowhere\"\n"
    ));
    assert_eq!((e.line, e.key.as_str()), (10, "projection.thesis_scenes"));
    assert!(e.message.contains("nowhere"), "{e}");
    let e = rejection(&format!("{TINY}\n[projection]\nhp_ports = 7\n"));
    assert!(
        e.key == "projection" && e.message.contains("HP ports"),
        "{e}"
    );

    // Unknown keys and type errors are syntax errors with their line.
    let e = rejection(&format!("{TINY}\ncolour = true\n"));
    assert_eq!((e.line, e.key.as_str()), (10, "(syntax)"));
    assert!(e.message.contains("colour"), "{e}");
    let e = rejection(&with("width = \"wide\""));
    assert_eq!(e.line, 6);

    // Loading checks before anything touches the output: the error names the file.
    let dir = tempfile::tempdir().unwrap();
    let path = config_file(dir.path(), "bad.toml", &with("lanes = [0]"));
    let e = sweep::load(&path).unwrap_err();
    assert!(e.to_string().contains("bad.toml:4: `lanes`"), "{e}");
}

/// Synthesis (yosys) and co-simulation (Verilator) of the smallest accelerator, fx16_13 at
/// depth 0 with one lane (about 1.5 min): the report's numbers reach the results, the
/// hardware's images equal the model's, and a re-run takes the synthesis from the cache.
/// `cargo test --release -p sim --test integration sweep:: -- --ignored`
#[test]
#[ignore]
fn synthesis_and_cosimulation_of_the_smallest_point() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"
formats = ["fx16_13"]
depths = [0]
lanes = [1]
scenes = ["simple_plane"]
width = 32
height = 18
stages = ["verilog", "synth", "cosim"]
keep_verilog = true
[cosim]
points = ["fx16_13_d0_l1"]
"#;
    let config = sweep::load(&config_file(dir.path(), "synth.toml", text)).unwrap();
    let out = dir.path().join("out");
    let layout = Layout::new(&out);
    let results = sweep::run_local(&config, &out, &local(1)).unwrap();
    let point: PointResult = read_json(&layout.point_result("fx16_13_d0_l1")).unwrap();
    let synth = point.synth.clone().expect("synthesised");
    assert!(!point.synth_cached);
    assert!(
        synth.lut > 1000 && synth.ff > 100 && synth.dsp48e1 > 0 && synth.logic_depth > 0,
        "{synth:?}"
    );
    assert!(layout
        .point_dir("fx16_13_d0_l1")
        .join("verilog/rtfpga_top.v")
        .is_file());
    // One co-simulation per spawn policy, each equal to the model.
    assert_eq!(point.cosim.len(), SpawnChoice::ALL.len());
    assert_eq!(point.cosim_identical(), Some(true));
    for c in &point.cosim {
        assert!(c.tests > 0 && c.cycles >= c.tests, "{c:?}");
    }

    let row = &results.rows[0];
    assert_eq!(
        (row.lut, row.dsp48e1, row.logic_depth),
        (
            Some(synth.lut),
            Some(synth.dsp48e1),
            Some(synth.logic_depth)
        )
    );
    assert!(row.cycles_measured && row.cycles_per_test == point.cycles_per_test());
    assert_eq!(row.lanes_fit, None, "a fit needs the 2-lane design too");
    // The timing estimate (the accelerator has registers, so a path) reaches the row.
    let fmax = synth
        .fmax_mhz_estimate()
        .expect("a register-to-register path");
    assert_eq!(row.fmax_mhz_estimate, Some(fmax));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert!(
        csv.lines().next().unwrap().contains("fmax_mhz_estimate"),
        "{csv}"
    );

    // Same Verilog: the synthesis comes from the cache.
    sweep::run_local(&config, &out, &local(1)).unwrap();
    let again: PointResult = read_json(&layout.point_result("fx16_13_d0_l1")).unwrap();
    assert!(again.synth_cached);
    assert_eq!(again.synth, Some(synth));
}

/// The pair built in hardware, bfp18/fp32, is co-simulated at every built slot count, its
/// images the fallback's; `cargo test --release -p sim --test integration sweep:: -- --ignored` (four
/// Verilator builds of the pair, about a minute each; its synthesis, ~30 min, is not run).
#[test]
#[ignore]
fn the_hardware_pair_is_cosimulated_at_every_slot_count() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"
formats = ["fp32"]
depths = [1]
lanes = [1]
pairs = ["bfp18/fp32"]
policies = ["thesis"]
scenes = ["simple_plane"]
width = 32
height = 18
stages = ["quality", "cosim"]
"#;
    let config = sweep::load(&config_file(dir.path(), "pair.toml", text)).unwrap();
    let out = dir.path().join("out");
    let layout = Layout::new(&out);
    let results = sweep::run_local(&config, &out, &local(1)).unwrap();
    let dual: DualResult =
        read_json(&layout.dual_result("bfp18/fp32", SpawnChoice::Thesis)).unwrap();
    let hw = dual.hardware.expect("bfp18/fp32 is built in hardware");
    assert!(hw.synth.is_empty() && hw.fit().is_none());
    let slots: Vec<usize> = hw.cosim.iter().map(|c| c.slots).collect();
    assert_eq!(slots, [1, 2, 3, 4]);
    for c in &hw.cosim {
        assert_eq!(c.differing_from_fallback, 0, "{c:?}");
        assert_eq!(c.tests, dual.scenes[0].tests, "{c:?}");
        assert_eq!(c.forwarded, dual.scenes[0].forwarded, "{c:?}");
        // At most one query per slot and cycle (this image's batches are too small to
        // fill the pipeline: no lower bound).
        let rate = hw.tests_per_cycle(c.slots).unwrap();
        assert!(rate > 0.0 && rate <= c.slots as f64, "{c:?}");
    }
    let md = sweep::table::markdown(&results).unwrap();
    assert!(md.contains("### bfp18/fp32 in hardware"), "{md}");
    assert!(md.contains("Not synthesised"), "{md}");
    // A format and the hardware-less pair have no hardware record.
    let float: DualResult = {
        let text = text
            .replace("bfp18/fp32", "bfp16/fp32")
            .replace("\"cosim\"", "");
        let text = text.replace("[\"quality\", ]", "[\"quality\"]");
        let config = sweep::load(&config_file(dir.path(), "model.toml", &text)).unwrap();
        let out = dir.path().join("out2");
        sweep::run_local(&config, &out, &local(1)).unwrap();
        read_json(&Layout::new(&out).dual_result("bfp16/fp32", SpawnChoice::Thesis)).unwrap()
    };
    assert_eq!(float.hardware, None);
}
