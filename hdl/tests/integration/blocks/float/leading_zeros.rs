//! `hdl::float::leading_zeros`.

use hdl::float::leading_zeros::LeadingZeros;
use rust_hdl::prelude::*;

fn count(x: u32) -> u64 {
    let mut uut = LeadingZeros::default();
    uut.connect_all();
    uut.x.next = (x as u64).into();
    assert!(simulate(&mut uut, 100));
    uut.count.val().to_u64()
}

#[test]
fn counts_every_leading_one_place_with_any_bits_below() {
    for place in 0..32 {
        for below in [0u32, 1, 0x5555_5555, u32::MAX] {
            let x = (1u32 << place) | (below & ((1u64 << place) - 1) as u32);
            assert_eq!(count(x), u64::from(x.leading_zeros()), "x = {x:#x}");
        }
    }
    assert_eq!(count(0), 31);
}
