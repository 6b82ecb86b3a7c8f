//! `hdl::synth`.

use hdl::synth::*;
use std::collections::BTreeMap;

#[test]
fn categories_sum_the_right_cells() {
    let cells: BTreeMap<String, u64> = [
        ("LUT2", 3),
        ("LUT6", 4),
        ("LUT6_2", 100),
        ("FDRE", 5),
        ("FDSE", 1),
        ("DSP48E1", 2),
        ("CARRY4", 7),
        ("RAMB18E1", 1),
        ("RAMB36E1", 2),
        ("MUXF7", 8),
        ("MUXF8", 9),
        ("SRLC32E", 10),
        ("RAM64M", 11),
    ]
    .into_iter()
    .map(|(c, n)| (c.to_string(), n))
    .collect();
    let r = SynthReport::from_cells(cells, 6);
    assert_eq!((r.lut, r.ff, r.dsp48e1, r.carry4, r.bram), (7, 6, 2, 7, 3));
    assert_eq!(
        (r.muxf7, r.muxf8, r.srl, r.lutram, r.logic_depth),
        (8, 9, 10, 11, 6)
    );
    assert_eq!(
        r.markdown_row("x"),
        "| x | 7 | 6 | 2 | 7 | 3 | 8 | 9 | 10 | 11 | 6 |"
    );
    let columns = |s: &str| s.matches('|').count();
    let header = SynthReport::markdown_header();
    assert!(header
        .lines()
        .all(|l| columns(l) == columns(&r.markdown_row("x"))));
}

#[test]
fn parses_stat_json_and_ltp() {
    let json =
        r#"{"modules": {"\\top": {"num_cells": 3, "num_cells_by_type": {"FDRE": 2, "LUT3": 1}}}}"#;
    let cells = parse_stat_json(json, "top").unwrap();
    assert_eq!(cells.get("FDRE"), Some(&2));
    assert!(parse_stat_json(json, "other").is_err());
    assert!(parse_stat_json("not json", "top").is_err());
    let empty = r#"{"modules": {"\\top": {"num_cells": 0}}}"#;
    assert!(parse_stat_json(empty, "top").unwrap().is_empty());

    assert_eq!(
        parse_ltp("\nLongest topological path in top (length=12):\n  0: \\a\n").unwrap(),
        12
    );
    assert!(parse_ltp("nothing here").is_err());
}
