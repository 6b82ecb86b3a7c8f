//! `hdl::formats`.

use proptest::prelude::*;

/// The modules were built from the same list as the catalogue, in its order.
#[test]
fn every_hardware_format_has_its_module() {
    assert_eq!(hdl::formats::TABLE.len(), hw_model::HwFormat::all().len());
    for (ops, h) in hdl::formats::TABLE.iter().zip(hw_model::HwFormat::all()) {
        assert_eq!(ops.name, h.name());
    }
    assert_eq!(hdl::formats::fp16::FORMAT, hdl::formats::fp16::HW.format());
    assert_eq!(
        hdl::formats::fx21_12_rnd_sat::FORMAT,
        hdl::formats::fx21_12_rnd_sat::HW.format()
    );
}

/// Specials and edges of fp32, mixed into the random operands.
const EDGES: [u32; 10] = [
    0,
    0x8000_0000,
    1,
    0x007f_ffff,
    0x0080_0000,
    0x3f80_0000,
    0x7f7f_ffff,
    0x7f80_0000,
    0xff80_0000,
    0xffc0_0001,
];

fn operand() -> impl Strategy<Value = u32> {
    prop_oneof![any::<u32>(), proptest::sample::select(&EDGES[..])]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]
    /// `RAW_FP32` rests on this: every result of fp32's operators is its own fp32 word
    /// (no subnormal, a NaN only as the canonical one), so to_f32 would change nothing.
    #[test]
    fn fp32_operator_results_are_their_own_fp32_words(a in operand(), b in operand()) {
        let f = hdl::formats::fp32::FORMAT;
        let (a, b) = (u64::from(a), u64::from(b));
        for r in [f.add(a, b), f.sub(a, b), f.mul(a, b), f.recip(a)] {
            prop_assert_eq!(u64::from(f.to_f32(r).to_bits()), r, "{:#x} {:#x}", a, b);
        }
    }
}
