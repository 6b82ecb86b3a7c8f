//! `hdl::dual::cross_block`.

use std::collections::BTreeSet;

use hdl::dual::cross_block::*;
use hdl::dual::to_block::EXP_BITS;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::Block as ModelBlock;
use hw_model::dual::bfp::{blocks, cross_block, Vector};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};
use sw_renderer::intersect::MtQuery;

/// The low `width` bits of `raw` as a signed integer.
pub(super) fn signed(raw: u128, width: usize) -> i128 {
    let shift = 128 - width as u32;
    ((raw << shift) as i128) >> shift
}

/// The low `width` bits of `x`, as a port's value.
pub(super) fn field<const N: usize>(x: i128) -> Bits<N> {
    (x as u128 & (u128::MAX >> (128 - N))).to_bits()
}

/// One clock edge after the inputs settle.
pub(super) fn tick<T: Clocked>(uut: &mut T) {
    uut.set_clock(false);
    assert!(simulate(uut, 100));
    uut.set_clock(true);
    assert!(simulate(uut, 100));
}

/// The blocks with a clock input (both of step 3's).
pub(super) trait Clocked: rust_hdl::prelude::Block {
    fn set_clock(&mut self, clk: bool);
}

impl<const XW: usize, const YW: usize, const PW: usize, const W: usize> Clocked
    for CrossBlock<XW, YW, PW, W>
{
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

/// A block of mantissas `m` whose exponent has the biased field `f`.
fn block(m: [i128; 3], f: usize, bias: usize, width: usize) -> ModelBlock {
    let e = f as i32 - bias as i32;
    ModelBlock {
        m,
        e,
        lsb: e - (width as i32 - 1),
        dropped: None,
    }
}

/// The cut blocks of `cases` (x, its field, y, its field) streamed through the block one a
/// cycle, each against the model's `cross_block`; returns the `below`s seen.
fn stream<const XW: usize, const YW: usize, const PW: usize, const W: usize>(
    uut: &mut CrossBlock<XW, YW, PW, W>,
    cases: &[([i128; 3], usize, [i128; 3], usize)],
    (xbias, ybias): (usize, usize),
) -> BTreeSet<u64> {
    let mut seen = BTreeSet::new();
    for i in 0..cases.len() + LATENCY - 1 {
        // After the last case, zeros push it out.
        let (x, fx, y, fy) = cases.get(i).copied().unwrap_or(([0; 3], 0, [0; 3], 0));
        for k in 0..3 {
            uut.x[k].next = field(x[k]);
            uut.y[k].next = field(y[k]);
        }
        uut.ex.next = (fx as u64).to_bits();
        uut.ey.next = (fy as u64).to_bits();
        tick(uut);
        let Some(j) = (i + 1).checked_sub(LATENCY) else {
            continue;
        };
        let (x, fx, y, fy) = cases[j];
        let want = cross_block(&block(x, fx, xbias, XW), &block(y, fy, ybias, YW), W as u32);
        let e = uut.e.val().to_u64() as i32 - (xbias + ybias) as i32;
        let below = uut.below.val().to_u64();
        seen.insert(below);
        let got = ModelBlock {
            m: std::array::from_fn(|k| signed(uut.m[k].val().to_u128(), W)),
            e,
            // The last bit is implicit: the model's lsb must be where the block says.
            lsb: e - (W as i32 - 1),
            dropped: (below != 0).then_some(e - below as i32),
        };
        assert_eq!(got, want, "{x:?} at {fx} × {y:?} at {fy}");
    }
    seen
}

/// A `width`-bit signed integer of a random bit count, sometimes with trailing zeros (so
/// that the products' dropped bits end anywhere).
pub(super) fn mantissa(rng: &mut StdRng, width: usize) -> i128 {
    let bits = rng.gen_range(0..=width);
    let x = match bits {
        0 => [0, -1][rng.gen_range(0..2)],
        _ => rng.gen_range(-(1i128 << (bits - 1))..1i128 << (bits - 1)),
    };
    if rng.gen_range(0..4) == 0 {
        signed((x << rng.gen_range(0..width)) as u128, width)
    } else {
        x
    }
}

/// The extremes of a `width`-bit mantissa: −2^(W−1), 2^(W−1) − 1, 0 and −1.
pub(super) fn extremes(width: usize) -> [i128; 4] {
    [-(1i128 << (width - 1)), (1i128 << (width - 1)) - 1, 0, -1]
}

/// Every combination of the extremes in the six mantissas, then random mantissas, at random
/// exponent fields (both ends included).
fn random_and_special<const XW: usize, const YW: usize, const PW: usize, const W: usize>(
    uut: &mut CrossBlock<XW, YW, PW, W>,
    bias: (usize, usize),
    seed: u64,
) -> BTreeSet<u64> {
    let mut rng = StdRng::seed_from_u64(seed);
    let fmax = (1usize << EXP_BITS) - 1;
    let f = |rng: &mut StdRng| match rng.gen_range(0..6) {
        0 => 0,
        1 => fmax,
        _ => rng.gen_range(0..=fmax),
    };
    let mut cases = Vec::new();
    let (xs, ys) = (extremes(XW), extremes(YW));
    for i in 0..4usize.pow(6) {
        let digit = |d: u32| i / 4usize.pow(d) % 4;
        let x = [xs[digit(0)], xs[digit(1)], xs[digit(2)]];
        let y = [ys[digit(3)], ys[digit(4)], ys[digit(5)]];
        cases.push((x, f(&mut rng), y, f(&mut rng)));
    }
    for _ in 0..3000 {
        let x = std::array::from_fn(|_| mantissa(&mut rng, XW));
        let y = std::array::from_fn(|_| mantissa(&mut rng, YW));
        cases.push((x, f(&mut rng), y, f(&mut rng)));
    }
    stream(uut, &cases, bias)
}

/// The six blocks (in the order of `Vector`: dir, e1, e2, s, p, q) of `n` random
/// triangle/ray queries as the model's `blocks` (steps 1 to 3) gives them at W = `WIDTH`;
/// queries it forwards (a zero vector, an exponent out of range) are skipped.
pub(super) fn filter_blocks(seed: u64, n: usize) -> Vec<[ModelBlock; 6]> {
    // A point within ±s, some coordinates 0 (axis-aligned rays and edges).
    fn point(rng: &mut StdRng, s: f32) -> [f32; 3] {
        std::array::from_fn(|_| match rng.gen_range(0..8) {
            0 => 0.0,
            _ => rng.gen_range(-1.0f32..1.0) * s,
        })
    }
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = Vec::new();
    while out.len() < n {
        let scale = 2f32.powi(rng.gen_range(-16..16));
        let v0 = point(&mut rng, scale);
        // Triangles from the scene's size down to a tiny one far from the origin.
        let size = scale * 2f32.powi(-rng.gen_range(0..20));
        let (d1, d2) = (point(&mut rng, size), point(&mut rng, size));
        let v1 = std::array::from_fn(|k| v0[k] + d1[k]);
        let v2 = std::array::from_fn(|k| v0[k] + d2[k]);
        let orig = match rng.gen_range(0..3) {
            // Far, near, or on the triangle (a shadow ray leaving its plane).
            0 => point(&mut rng, scale * 4.0),
            1 => {
                let d = point(&mut rng, size * 2.0);
                std::array::from_fn(|k| v0[k] + d[k])
            }
            _ => {
                let (a, b) = (rng.gen_range(0.0f32..0.5), rng.gen_range(0.0f32..0.5));
                std::array::from_fn(|k| v0[k] + a * d1[k] + b * d2[k])
            }
        };
        let aim = (rng.gen_range(-0.5f32..1.5), rng.gen_range(-0.5f32..1.5));
        let mut q = MtQuery::aimed(orig, [v0, v1, v2], aim, 0.0);
        if rng.gen_range(0..4) == 0 {
            let length = 2f32.powi(rng.gen_range(-8..8));
            q.dir = point(&mut rng, length);
        }
        out.extend(blocks(&q, WIDTH));
    }
    out
}

/// A block's biased exponent field, as `ToBlock::e` gives it.
fn biased(b: &ModelBlock, bias: usize) -> usize {
    usize::try_from(b.e + bias as i32).unwrap()
}

/// `uut` is x × y cut, of the vectors `x` and `y` at their biases `bias`: on the extremes
/// and random blocks, whose `below`s must span nothing dropped, the nearest (W − 1) and the
/// farthest (only the exact product's last bit, XW + YW − 2 below), then on the blocks of
/// random queries.
fn cross_equals_the_model<const XW: usize, const YW: usize, const PW: usize, const W: usize>(
    mut uut: CrossBlock<XW, YW, PW, W>,
    [x, y]: [Vector; 2],
    bias: (usize, usize),
    seed: u64,
) {
    uut.connect_all();
    let seen = random_and_special(&mut uut, bias, seed);
    for b in [0, W - 1, XW + YW - 2] {
        assert!(seen.contains(&(b as u64)), "below {b} never seen: {seen:?}");
    }
    let cases: Vec<_> = filter_blocks(seed * 10, 2000)
        .iter()
        .map(|blocks| {
            let (x, y) = (&blocks[x as usize], &blocks[y as usize]);
            (x.m, biased(x, bias.0), y.m, biased(y, bias.1))
        })
        .collect();
    stream(&mut uut, &cases, bias);
}

#[test]
fn p_cross_equals_the_model_bit_for_bit() {
    let vectors = [Vector::Dir, Vector::E2];
    cross_equals_the_model(PCross::default(), vectors, (DIR_BIAS, EDGE_BIAS), 1);
}

#[test]
fn q_cross_equals_the_model_bit_for_bit() {
    let vectors = [Vector::S, Vector::E1];
    cross_equals_the_model(QCross::default(), vectors, (EDGE_BIAS, EDGE_BIAS), 2);
}

/// Its Verilog, at both shapes, is what Vivado would read: Verilator lints it clean.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the two cut cross products:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture cross_block_resources`
#[test]
#[ignore]
fn cross_block_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}

/// Each cross product's label (with its widths) and Verilog.
fn verilogs() -> Vec<(String, String)> {
    fn shape<const XW: usize, const YW: usize, const PW: usize, const W: usize>(
        _: &CrossBlock<XW, YW, PW, W>,
    ) -> String {
        format!("{XW} × {YW} → {W} bits")
    }
    vec![
        named(PCross::default(), "p = dir × e2 (PCross)", shape),
        named(QCross::default(), "q = s × e1 (QCross)", shape),
    ]
}
