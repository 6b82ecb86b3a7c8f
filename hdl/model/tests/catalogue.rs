//! Catalogue contents, lookup spellings and format validation.

use hw_model::{catalogue, lookup, Format, FormatError, Overflow, Quant};

#[test]
fn catalogue_has_the_required_formats_and_all_are_valid() {
    let want = [
        ("fp32", Format::Float { exp: 8, man: 23 }),
        ("fp24", Format::Float { exp: 8, man: 15 }),
        ("bf16", Format::Float { exp: 8, man: 7 }),
        ("fp16", Format::Float { exp: 5, man: 10 }),
        (
            "fx16_10",
            Format::Fixed {
                int: 10,
                frac: 6,
                quant: Quant::Trn,
                overflow: Overflow::Wrap,
            },
        ),
        (
            "fx21_12_rnd_sat",
            Format::Fixed {
                int: 12,
                frac: 9,
                quant: Quant::Rnd,
                overflow: Overflow::Sat,
            },
        ),
    ];
    for (name, format) in want {
        assert_eq!(lookup(name), Ok(format), "{name}");
    }
    for (w, i) in [(16, 10), (16, 13), (21, 12), (25, 10), (32, 16), (32, 20)] {
        for suffix in ["", "_rnd_sat"] {
            let name = format!("fx{w}_{i}{suffix}");
            let f = lookup(&name).unwrap();
            assert_eq!(
                (f.width(), f.to_string()),
                (w, format!("fx<{w},{i}>{suffix}")),
                "{name}"
            );
        }
    }
    let mut names: Vec<&str> = catalogue().iter().map(|n| n.name).collect();
    for n in catalogue() {
        n.format.validate().unwrap();
        assert!(!n.description.is_empty());
        // the generic spelling of every entry finds the same format
        assert_eq!(lookup(&n.format.to_string()), Ok(n.format), "{}", n.name);
    }
    names.sort();
    names.dedup();
    assert_eq!(names.len(), catalogue().len(), "duplicate names");
}

#[test]
fn generic_spellings() {
    assert_eq!(lookup("e5m10"), Ok(Format::Float { exp: 5, man: 10 }));
    assert_eq!(lookup("E11M52").unwrap().width(), 64);
    let fx = |int, frac, quant, overflow| {
        Ok(Format::Fixed {
            int,
            frac,
            quant,
            overflow,
        })
    };
    assert_eq!(lookup("fx<16,10>"), fx(10, 6, Quant::Trn, Overflow::Wrap));
    assert_eq!(
        lookup("fx<24, 8>_sat"),
        fx(8, 16, Quant::Trn, Overflow::Sat)
    );
    assert_eq!(lookup("fx20_4_rnd"), fx(4, 16, Quant::Rnd, Overflow::Wrap));
    assert_eq!(
        lookup("fx20_4_sat_rnd"),
        fx(4, 16, Quant::Rnd, Overflow::Sat)
    );
    assert_eq!(lookup("fx<64,1>"), fx(1, 63, Quant::Trn, Overflow::Wrap));
}

#[test]
fn unknown_and_impossible_formats_are_errors() {
    for bad in [
        "",
        "fp33",
        "e5",
        "e5m",
        "m10",
        "fx<16>",
        "fx16_10_rnd_rnd",
        "fx16_10_foo",
        "fx<a,b>",
        "e-1m3",
    ] {
        assert!(
            matches!(lookup(bad), Err(FormatError::Unknown(_))),
            "{bad:?}: {:?}",
            lookup(bad)
        );
    }
    for bad in [
        "e1m10",
        "e12m3",
        "e5m0",
        "e8m53",
        "fx<65,10>",
        "fx<1,1>",
        "fx<16,0>",
        "fx<16,17>",
        "fx<0,0>",
    ] {
        let err = lookup(bad).unwrap_err();
        assert!(
            matches!(err, FormatError::Impossible { .. }),
            "{bad}: {err:?}"
        );
        assert!(err.to_string().contains("impossible format"), "{err}");
    }
    assert!(Format::Fixed {
        int: 0,
        frac: 8,
        quant: Quant::Trn,
        overflow: Overflow::Wrap
    }
    .validate()
    .is_err());
    assert!(Format::Float { exp: 11, man: 52 }.validate().is_ok());
}
