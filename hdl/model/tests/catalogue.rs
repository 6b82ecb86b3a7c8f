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

#[test]
fn hardware_formats_are_the_catalogue_entries_by_index() {
    use hw_model::HwFormat;
    assert_eq!(HwFormat::all().len(), catalogue().len());
    for (h, entry) in HwFormat::all().zip(catalogue()) {
        assert_eq!(h.entry(), entry);
        assert_eq!(HwFormat::from_code(h.code()), Some(h));
        assert_eq!(entry.name.parse::<HwFormat>(), Ok(h));
        // any spelling of the entry's arithmetic names the same hardware format
        assert_eq!(entry.format.to_string().parse::<HwFormat>(), Ok(h));
        assert_eq!(HwFormat::try_from(entry.format), Ok(h));
        assert_eq!(h.to_string(), entry.name);
        let json = serde_json::to_string(&h).unwrap();
        assert_eq!(json, format!("\"{}\"", entry.name));
        assert_eq!(serde_json::from_str::<HwFormat>(&json).unwrap(), h);
    }
    assert_eq!(HwFormat::from_code(catalogue().len() as u8), None);
    assert_eq!(HwFormat::FP32.name(), "fp32");
    assert_eq!("E5M10".parse::<HwFormat>().unwrap().name(), "fp16");
    assert_eq!("fx<16,10>".parse::<HwFormat>().unwrap().name(), "fx16_10");
}

#[test]
fn a_format_without_hardware_is_one_clear_error() {
    use hw_model::HwFormat;
    // a valid model format that has no operators: names it and the hardware formats
    let e = "e8m14".parse::<HwFormat>().unwrap_err();
    assert!(matches!(e, FormatError::NoHardware { .. }), "{e:?}");
    let text = e.to_string();
    assert!(
        text.contains("e8m14") && text.contains("fp32, fp24"),
        "{text}"
    );
    assert!(HwFormat::try_from(lookup("e8m14").unwrap()).is_err());
    // an unknown name is the same error type as for the model
    assert_eq!(
        "fp99".parse::<HwFormat>(),
        Err(FormatError::Unknown("fp99".into()))
    );
    let text = lookup("fp99").unwrap_err().to_string();
    assert!(
        text.contains("fp99") && text.contains("fx32_20_rnd_sat") && text.contains("e8m14"),
        "{text}"
    );
    assert!(serde_json::from_str::<HwFormat>("\"fp99\"").is_err());
    assert_eq!(
        "fp99".parse::<Format>(),
        Err(FormatError::Unknown("fp99".into()))
    );
}
