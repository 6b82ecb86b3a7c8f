//! `hdl::dual::dot`.

use hdl::dual::dot::*;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::{dot, widths, Vector};
use rand::rngs::StdRng;
use rand::SeedableRng;
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};
use super::cross_block::{extremes, field, filter_blocks, mantissa, signed, tick, Clocked};

impl<const AW: usize, const BW: usize, const PW: usize, const OW: usize> Clocked
    for Dot<AW, BW, PW, OW>
{
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

/// `cases` streamed through the dot one a cycle, each against the model's exact `dot`.
fn stream<const AW: usize, const BW: usize, const PW: usize, const OW: usize>(
    uut: &mut Dot<AW, BW, PW, OW>,
    cases: &[([i128; 3], [i128; 3])],
) {
    for i in 0..cases.len() + LATENCY - 1 {
        // After the last case, zeros push it out.
        let (a, b) = cases.get(i).copied().unwrap_or(([0; 3], [0; 3]));
        for k in 0..3 {
            uut.a[k].next = field(a[k]);
            uut.b[k].next = field(b[k]);
        }
        tick(uut);
        let Some(j) = (i + 1).checked_sub(LATENCY) else {
            continue;
        };
        let (a, b) = cases[j];
        let got = signed(uut.v.val().to_u128(), OW);
        assert_eq!(got, dot(&a, &b), "{a:?} · {b:?}");
    }
}

/// Every combination of the extremes in the six mantissas, then random mantissas.
fn random_and_special<const AW: usize, const BW: usize, const PW: usize, const OW: usize>(
    uut: &mut Dot<AW, BW, PW, OW>,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut cases = Vec::new();
    let (xs, ys) = (extremes(AW), extremes(BW));
    for i in 0..4usize.pow(6) {
        let digit = |d: u32| i / 4usize.pow(d) % 4;
        let a = [xs[digit(0)], xs[digit(1)], xs[digit(2)]];
        let b = [ys[digit(3)], ys[digit(4)], ys[digit(5)]];
        cases.push((a, b));
    }
    for _ in 0..3000 {
        let a = std::array::from_fn(|_| mantissa(&mut rng, AW));
        let b = std::array::from_fn(|_| mantissa(&mut rng, BW));
        cases.push((a, b));
    }
    stream(uut, &cases);
}

/// The filter's dots of random triangle/ray queries (`filter_blocks`): `a`·`b` of two of
/// the blocks, in the order of `Vector`.
fn filter_shaped<const AW: usize, const BW: usize, const PW: usize, const OW: usize>(
    uut: &mut Dot<AW, BW, PW, OW>,
    a: Vector,
    b: Vector,
    seed: u64,
) {
    let cases: Vec<_> = filter_blocks(seed, 2000)
        .iter()
        .map(|blocks| (blocks[a as usize].m, blocks[b as usize].m))
        .collect();
    stream(uut, &cases);
}

#[test]
fn det_equals_the_model_bit_for_bit() {
    let mut uut = DetDot::default();
    uut.connect_all();
    random_and_special(&mut uut, 1);
    filter_shaped(&mut uut, Vector::E1, Vector::P, 10);
}

#[test]
fn numerators_equal_the_model_bit_for_bit() {
    let mut nu = NuDot::default();
    nu.connect_all();
    random_and_special(&mut nu, 2);
    filter_shaped(&mut nu, Vector::S, Vector::P, 20);
    let mut nv = NvDot::default();
    nv.connect_all();
    random_and_special(&mut nv, 3);
    filter_shaped(&mut nv, Vector::Dir, Vector::Q, 30);
    let mut nt = NtDot::default();
    nt.connect_all();
    filter_shaped(&mut nt, Vector::E2, Vector::Q, 40);
}

/// `dot_bits` is the smallest width that holds every dot: the largest (three products of
/// the most negative operands) needs all of it, and the most negative fits.
#[test]
fn dot_widths_are_the_smallest_that_hold_every_value() {
    let fits = |v: i128, bits: usize| -(1i128 << (bits - 1)) <= v && v < 1i128 << (bits - 1);
    let w = widths(WIDTH).map(|w| w as usize);
    let shapes = [
        (Vector::E1, Vector::P),
        (Vector::S, Vector::P),
        (Vector::Dir, Vector::Q),
        (Vector::E2, Vector::Q),
    ];
    for (a, b) in shapes {
        let (aw, bw) = (w[a as usize], w[b as usize]);
        let bits = dot_bits(aw, bw);
        let (amin, amax) = (-(1i128 << (aw - 1)), (1i128 << (aw - 1)) - 1);
        let (bmin, bmax) = (-(1i128 << (bw - 1)), (1i128 << (bw - 1)) - 1);
        let largest = dot(&[amin; 3], &[bmin; 3]);
        let most_negative = dot(&[amin; 3], &[bmax; 3]).min(dot(&[amax; 3], &[bmin; 3]));
        assert!(
            fits(largest, bits) && !fits(largest, bits - 1),
            "{a:?}·{b:?}"
        );
        assert!(fits(most_negative, bits), "{a:?}·{b:?}");
    }
    // At W = 18: 37 bits for det, 44 for the numerators.
    assert_eq!(dot_bits(w[Vector::E1 as usize], w[Vector::P as usize]), 37);
    assert_eq!(dot_bits(w[Vector::S as usize], w[Vector::P as usize]), 44);
}

/// Its Verilog, at both shapes, is what Vivado would read: Verilator lints it clean.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the dots:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture dot_resources`
#[test]
#[ignore]
fn dot_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}

/// Each dot's label (with its widths) and Verilog; N_v and N_t are the same block.
fn verilogs() -> Vec<(String, String)> {
    fn shape<const AW: usize, const BW: usize, const PW: usize, const OW: usize>(
        _: &Dot<AW, BW, PW, OW>,
    ) -> String {
        format!("{AW} · {BW} → {OW} bits")
    }
    vec![
        named(DetDot::default(), "det = e1·p (DetDot)", shape),
        named(NuDot::default(), "N_u = s·p (NuDot)", shape),
        named(
            NvDot::default(),
            "N_v = dir·q, N_t = e2·q (NvDot, NtDot)",
            shape,
        ),
    ]
}
