//! `hdl::intmul`.

use hdl::intmul::{IntMul, SignedMul};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
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

/// The low `width` bits of `raw` as a signed integer.
fn signed(raw: u128, width: usize) -> i128 {
    let shift = 128 - width as u32;
    ((raw << shift) as i128) >> shift
}

/// `SignedMul<A, B, P>` on the extremes of both operands (every pair of −2^(A−1),
/// −2^(A−1) + 1, −1, 0, 1, 2^(A−1) − 1, …) and on random operands of random bit counts,
/// against i128; returns the pairs it checked, for the Verilog's check.
fn signed_products<const A: usize, const B: usize, const P: usize>(seed: u64) -> Vec<(i128, i128)> {
    let mut m = SignedMul::<A, B, P>::default();
    m.connect_all();
    let special = |w: usize| {
        let (min, max) = (-(1i128 << (w - 1)), (1i128 << (w - 1)) - 1);
        vec![min, min + 1, -1, 0, 1, max - 1, max]
    };
    let mut pairs = Vec::new();
    for &a in &special(A) {
        for &b in &special(B) {
            pairs.push((a, b));
        }
    }
    let mut rng = StdRng::seed_from_u64(seed);
    let mut operand = |w: usize| {
        let bits = rng.gen_range(1..=w);
        rng.gen_range(-(1i128 << (bits - 1))..1i128 << (bits - 1))
    };
    for _ in 0..2000 {
        pairs.push((operand(A), operand(B)));
    }
    let field = |x: i128, w: usize| -> u128 { x as u128 & (u128::MAX >> (128 - w)) };
    for &(a, b) in &pairs {
        m.a.next = field(a, A).to_bits();
        m.b.next = field(b, B).to_bits();
        assert!(simulate(&mut m, 10));
        assert_eq!(signed(m.p.val().to_u128(), P), a * b, "{a} × {b}");
    }
    pairs
}

#[test]
fn signed_products_match_i128() {
    // The filter's two shapes, a narrow one, and a wide one (the high half beyond 64 bits).
    signed_products::<18, 18, 36>(1);
    signed_products::<25, 18, 43>(2);
    signed_products::<8, 8, 16>(3);
    signed_products::<40, 50, 90>(4);
}

/// The custom Verilog is a second description of the product: Icarus runs it on the same
/// operands and compares with i128's products.
#[test]
fn signed_verilog_matches_i128_in_icarus() {
    fn bench<const A: usize, const B: usize, const P: usize>(seed: u64) {
        let pairs = signed_products::<A, B, P>(seed);
        let mut uut = SignedMul::<A, B, P>::default();
        uut.connect_all();
        let hex = |x: i128, w: usize| format!("{w}'h{:x}", x as u128 & (u128::MAX >> (128 - w)));
        let checks: String = pairs
            .iter()
            .map(|&(a, b)| {
                format!(
                    "      a = {}; b = {}; #1 if (p !== {}) errors = errors + 1;\n",
                    hex(a, A),
                    hex(b, B),
                    hex(a * b, P)
                )
            })
            .collect();
        let verilog = format!(
            "{}
module bench;
   reg [{}:0] a;
   reg [{}:0] b;
   wire [{}:0] p;
   integer errors = 0;
   top uut(.a(a), .b(b), .p(p));
   initial begin
{checks}      $display(\"errors %0d of {}\", errors);
      $finish;
   end
endmodule
",
            generate_verilog(&uut),
            A - 1,
            B - 1,
            P - 1,
            pairs.len()
        );
        let dir = tempfile::tempdir().unwrap();
        let (src, out) = (dir.path().join("mul.v"), dir.path().join("mul.vvp"));
        std::fs::write(&src, verilog).unwrap();
        let compiled = std::process::Command::new("iverilog")
            .args(["-g2012", "-s", "bench", "-o"])
            .args([&out, &src])
            .output()
            .expect("iverilog (make setup installs it)");
        assert!(compiled.status.success(), "{compiled:?}");
        let ran = std::process::Command::new("vvp")
            .arg(&out)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&ran.stdout);
        assert!(text.contains("errors 0 of"), "{A} × {B}: {text}");
    }
    bench::<18, 18, 36>(5);
    bench::<25, 18, 43>(6);
    bench::<40, 50, 90>(7);
}

/// The bfp filter's two product shapes, 18 × 18 and 25 × 18 signed, are one DSP48E1 each in
/// yosys (the ports are 25 × 18 signed), with no logic around it.
#[test]
fn signed_filter_products_are_one_dsp48e1() {
    fn report<const A: usize, const B: usize, const P: usize>() -> hdl::synth::SynthReport {
        let mut uut = SignedMul::<A, B, P>::default();
        uut.connect_all();
        let options = hdl::synth::SynthOptions::default();
        hdl::synth::synthesize(&generate_verilog(&uut), "top", &options).unwrap()
    }
    for r in [report::<18, 18, 36>(), report::<25, 18, 43>()] {
        assert_eq!((r.dsp48e1, r.lut), (1, 0), "{:?}", r.cells);
    }
}
