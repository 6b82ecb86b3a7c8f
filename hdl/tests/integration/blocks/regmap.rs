//! `hdl::regmap`.

use hdl::regmap::*;

/// Both maps: offsets aligned, unique, sorted and within the bus' address; fields
/// within their register and not overlapping.
fn check_map(map: &RegisterMap) {
    for pair in map.registers.windows(2) {
        assert!(
            pair[0].offset < pair[1].offset,
            "{} / {}",
            pair[0].name,
            pair[1].name
        );
    }
    for r in map.registers {
        assert_eq!(r.offset % 4, 0, "{}", r.name);
        assert!(r.offset < 1 << ADDR_BITS, "{}", r.name);
        assert!(r.width >= 1 && r.width <= 32, "{}", r.name);
        let mut used = 0;
        for f in r.fields {
            assert!(f.lsb + f.width <= r.width, "{}.{}", r.name, f.name);
            assert_eq!(used & f.mask(), 0, "{}.{} overlaps", r.name, f.name);
            used |= f.mask();
        }
    }
    for &c in map.control {
        assert!(map.register_at(c).is_some(), "{}: 0x{c:02x}", map.title);
    }
}

#[test]
fn offsets_are_aligned_unique_sorted_and_fit_the_address() {
    check_map(&MAP);
}

#[test]
fn operands_are_contiguous_and_in_the_table_as_rw() {
    for (i, &off) in OPERANDS.iter().enumerate() {
        assert_eq!(off, ORIG_X + 4 * i);
        assert_eq!(register_at(off).unwrap().access, Access::Rw);
    }
    assert_eq!(OPERANDS[14], 0x48);
    assert_eq!(OPERANDS[15], T_MIN);
}

#[test]
fn map_matches_the_architecture_table() {
    let expect = [
        (CONTROL, 0x00),
        (GIE, 0x04),
        (IER, 0x08),
        (ISR, 0x0C),
        (T_MIN, 0x4C),
        (RESULT, 0x50),
        (T, 0x54),
        (U, 0x58),
        (V, 0x5C),
        (ID, 0x60),
        (CONFIG, 0x64),
    ];
    for (c, v) in expect {
        assert_eq!(c, v);
        assert!(register_at(c).is_some());
    }
    assert!(register_at(0x68).is_none());
    assert_eq!(REGISTERS.len(), 4 + 16 + 4 + 2);
}

#[test]
fn control_field_masks_match_the_bit_constants() {
    let ctrl = register_at(CONTROL).unwrap();
    let masks: Vec<u32> = ctrl.fields.iter().map(Field::mask).collect();
    assert_eq!(
        masks,
        vec![AP_START, AP_DONE, AP_IDLE, AP_READY, AUTO_RESTART]
    );
}

#[test]
fn config_word_round_trips() {
    let c = ConfigWord {
        format_code: 7,
        depth: 3,
        lanes: 4,
    };
    assert_eq!(c.pack(), 0x0004_0307);
    assert_eq!(ConfigWord::unpack(c.pack()), c);
    assert_eq!(ID_VALUE, 0x5246_0101);
}

mod unit;
