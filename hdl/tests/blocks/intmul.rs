//! `hdl::intmul`.

use hdl::intmul::IntMul;
use rust_hdl::prelude::*;

#[test]
fn product_matches_u128() {
    let mut m = IntMul::<24, 24, 48>::default();
    m.connect_all();
    for (a, b) in [
        (0u64, 0u64),
        (1, 0xff_ffff),
        (0xff_ffff, 0xff_ffff),
        (0x80_0001, 0x7f_fff3),
    ] {
        m.a.next = a.into();
        m.b.next = b.into();
        assert!(simulate(&mut m, 10));
        assert_eq!(m.p.val().to_u64(), a * b);
    }
}

#[test]
fn wide_product_keeps_the_high_half() {
    let mut m = IntMul::<40, 40, 80>::default();
    m.connect_all();
    let (a, b) = ((1u64 << 40) - 1, (1u64 << 40) - 3);
    m.a.next = a.into();
    m.b.next = b.into();
    assert!(simulate(&mut m, 10));
    let p = (a as u128) * (b as u128);
    assert_eq!(m.p.val().get_bits::<16>(64).to_u64() as u128, p >> 64);
    assert_eq!(
        m.p.val().get_bits::<64>(0).to_u64() as u128,
        p & u64::MAX as u128
    );
}
