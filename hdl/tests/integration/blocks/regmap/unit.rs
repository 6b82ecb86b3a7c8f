//! `hdl::regmap::unit`.

use super::check_map;
use hdl::regmap::unit::*;
use hdl::regmap::{Access, Field};
use hdl::traversal::scene_memory::ERROR_CODE_BITS;

#[test]
fn the_unit_map_is_well_formed() {
    check_map(&MAP);
    for &c in &COUNTERS {
        assert_eq!(MAP.register(c).access, Access::Ro);
    }
    // The counters are contiguous words in port order.
    for pair in COUNTERS.windows(2) {
        assert_eq!(pair[0] + 4, pair[1]);
    }
    assert_eq!(ID_VALUE, 0x5255_0100);
    assert_ne!(UNIT_ID, hdl::regmap::ACCEL_ID, "the two slaves tell apart");
}

#[test]
fn bit_constants_are_the_table_fields() {
    let masks = |offset| -> Vec<u32> {
        MAP.register(offset)
            .fields
            .iter()
            .map(Field::mask)
            .collect()
    };
    assert_eq!(masks(CONTROL), vec![LOAD_START, RESET]);
    let code_mask = ((1 << ERROR_CODE_BITS) - 1) << ERROR_CODE_LSB;
    assert_eq!(
        masks(STATUS),
        vec![
            IDLE,
            SCENE_LOADED,
            SCENE_ERROR,
            OVERFLOW,
            RESETTING,
            code_mask
        ]
    );
}

#[test]
fn memory_word_round_trips() {
    let m = MemoryWord {
        node_bits: 12,
        triangle_bits: 13,
        stack_depth: 32,
        slots: 32,
    };
    assert_eq!(m.pack(), 0x2020_0d0c);
    assert_eq!(MemoryWord::unpack(m.pack()), m);
}
