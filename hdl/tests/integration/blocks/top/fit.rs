//! `hdl::top::fit`.

use hdl::synth::SynthReport;
use hdl::top::fit::*;

#[test]
fn a_design_fits_when_every_resource_does() {
    let full = Usage {
        lut: XC7Z020.lut,
        ff: XC7Z020.ff,
        dsp48e1: XC7Z020.dsp48e1,
        bram18: XC7Z020.bram18,
    };
    assert!(XC7Z020.holds(full));
    assert!(XC7Z020.holds(Usage::default()));
    assert!(!XC7Z020.holds(Usage {
        lut: full.lut + 1,
        ..full
    }));
    assert!(!XC7Z020.holds(Usage {
        ff: full.ff + 1,
        ..full
    }));
    assert!(!XC7Z020.holds(Usage {
        dsp48e1: full.dsp48e1 + 1,
        ..full
    }));
    assert!(!XC7Z020.holds(Usage {
        bram18: full.bram18 + 1,
        ..full
    }));
}

#[test]
fn lut_ram_counts_the_luts_it_occupies() {
    let cells = [("LUT6", 10), ("SRLC32E", 2), ("RAM32M", 3), ("RAM64X1D", 1)]
        .into_iter()
        .map(|(c, n)| (c.to_string(), n))
        .collect();
    let usage = Usage::of(&SynthReport::from_cells(cells, 1));
    assert_eq!(usage.lut, 10 + 2 + 3 * 4 + 2);
    assert_eq!((lut_ram_luts("RAMB36E1"), lut_ram_luts("FDRE")), (0, 0));
    assert_eq!(lut_ram_luts("RAM64M8"), 8);
}

#[test]
fn the_scarcest_resource_sets_the_lane_count() {
    let one = Usage {
        lut: 3000,
        ff: 4000,
        dsp48e1: 20,
        bram18: 6,
    };
    let two = Usage {
        lut: 5000,
        ff: 7000,
        dsp48e1: 38,
        bram18: 10,
    };
    let f = fit_from(one, two, &XC7Z020);
    assert_eq!(
        f.per_lane,
        Usage {
            lut: 2000,
            ff: 3000,
            dsp48e1: 18,
            bram18: 4
        }
    );
    assert_eq!(
        f.fixed,
        Usage {
            lut: 1000,
            ff: 1000,
            dsp48e1: 2,
            bram18: 2
        }
    );
    // DSP: (220 - 2) / 18 = 12; LUT: 52200 / 2000 = 26; FF: 35; BRAM: 278 / 4 = 69.
    assert_eq!((f.lanes, f.limit), (12, "DSP48E1"));
    let lut_bound = fit_from(one, Usage { lut: 33_000, ..two }, &XC7Z020);
    assert_eq!((lut_bound.lanes, lut_bound.limit), (1, "LUT"));
}

#[test]
fn a_fixed_part_from_elsewhere_leaves_the_rest_to_the_lane() {
    let one = Usage {
        lut: 9000,
        ff: 12_000,
        dsp48e1: 30,
        bram18: 6,
    };
    let fixed = Usage {
        lut: 1000,
        ff: 2000,
        dsp48e1: 2,
        bram18: 2,
    };
    let f = fit_with_fixed(one, fixed, &XC7Z020);
    assert_eq!(
        f.per_lane,
        Usage {
            lut: 8000,
            ff: 10_000,
            dsp48e1: 28,
            bram18: 4
        }
    );
    // LUT: 52200 / 8000 = 6; FF: 104400 / 10000 = 10; DSP: 218 / 28 = 7.
    assert_eq!((f.lanes, f.limit), (6, "LUT"));
    assert_eq!(Usage::with_lanes(f.fixed, f.per_lane, 1), one);
}
