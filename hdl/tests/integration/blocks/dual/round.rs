//! `hdl::dual::round`, `hdl::dual::short_lt`, `hdl::dual::pow2_lt` and
//! `hdl::dual::add_down`: step 5's normaliser, comparators and short adder, bit for bit the
//! model's `round`, `Fx::lt` and `add_down`.

use hdl::dual::add_down::{self, AddDown};
use hdl::dual::decide::{DET_SUM_BITS, NUM_SUM_BITS, PRODUCT_BITS};
use hdl::dual::pow2_lt::Pow2Lt;
use hdl::dual::round::{self, Round, SHORT_EXP_BITS, SHORT_M_BITS};
use hdl::dual::short_lt::Lt;
use hw_model::dual::bfp::{add_down, round, Fx, QUOTIENT_MAX, RECIPROCAL_MIN, SHORT_BITS};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use super::common::{lint_clean, named};

/// Sign-extends the low `width` bits of `raw`.
pub fn signed(raw: u64, width: usize) -> i128 {
    let shift = 64 - width;
    i128::from(((raw << shift) as i64) >> shift)
}

/// The low `width` bits of a two's-complement value.
pub fn raw(x: i128, width: usize) -> u64 {
    (x as u64) & (u64::MAX >> (64 - width))
}

/// The largest exponent magnitude the tests feed: a result still fits SHORT_EXP_BITS.
pub const EXP_LIMIT: i32 = (1 << (SHORT_EXP_BITS - 1)) - 70;

/// An IW-bit signed integer of a random bit count (zeros, ±1 and the extremes included).
fn integer(rng: &mut StdRng, width: usize) -> i128 {
    let bits = rng.gen_range(0..=width);
    match bits {
        0 => [0, -1][rng.gen_range(0..2)],
        _ => rng.gen_range(-(1i128 << (bits - 1))..1i128 << (bits - 1)),
    }
}

/// A block with a clock input.
pub trait Clocked: Block {
    fn clock(&mut self) -> &mut Signal<In, Clock>;
}

impl<const IW: usize, const UP: bool> Clocked for Round<IW, UP> {
    fn clock(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }
}

impl Clocked for AddDown {
    fn clock(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }
}

/// One clock cycle: the inputs set before it are registered at its rising edge.
pub fn tick<B: Clocked>(uut: &mut B) {
    uut.clock().next = Clock { clk: false };
    assert!(simulate(uut, 1000));
    uut.clock().next = Clock { clk: true };
    assert!(simulate(uut, 1000));
}

/// `cases` streamed through `uut` one a cycle (`set` drives a case's inputs; `fill` follows
/// the last), each checked (`check`) exactly `latency` clock edges after its inputs, so that
/// a wrong latency compares a neighbour's result.
pub fn stream<B: Clocked, C: Copy>(
    uut: &mut B,
    cases: &[C],
    latency: usize,
    fill: C,
    mut set: impl FnMut(&mut B, C),
    mut check: impl FnMut(&mut B, C),
) {
    assert!(latency > 0);
    for i in 0..cases.len() + latency - 1 {
        set(uut, cases.get(i).copied().unwrap_or(fill));
        tick(uut);
        if let Some(j) = (i + 1).checked_sub(latency) {
            check(uut, cases[j]);
        }
    }
}

/// The normaliser's answer as the model's value.
fn rounded<const IW: usize, const UP: bool>(uut: &Round<IW, UP>) -> Fx {
    Fx {
        m: signed(uut.m.val().to_u64(), SHORT_M_BITS),
        e: signed(uut.f.val().to_u64(), SHORT_EXP_BITS) as i32,
    }
}

/// Random, special and extreme integers at random exponents; the count of checks.
fn check_round<const IW: usize, const UP: bool>(seed: u64) -> usize {
    let mut uut = Round::<IW, UP>::default();
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(seed);
    let (min, max) = (-(1i128 << (IW - 1)), (1i128 << (IW - 1)) - 1);
    let short = 1i128 << (SHORT_BITS - 1);
    let mut xs: Vec<i128> = (0..3000).map(|_| integer(&mut rng, IW)).collect();
    // The edges: fits or not, a carry into the next power of two, ±powers of two, ±extremes.
    for s in [0, 1, 2, 7, IW - SHORT_BITS as usize - 1] {
        for x in [short - 1, short, -short, -short - 1, 1, -1, 0] {
            xs.push((x << s).clamp(min, max));
            xs.push(((x << s) - 1).clamp(min, max));
            xs.push(((x << s) + 1).clamp(min, max));
        }
    }
    xs.extend([min, max, min + 1, max - 1, 0, (1 << 40) - 1]);
    let cases: Vec<(i128, i32)> = xs
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let e = match i % 3 {
                0 => 0,
                1 => [-EXP_LIMIT, EXP_LIMIT][i % 2],
                _ => rng.gen_range(-EXP_LIMIT..=EXP_LIMIT),
            };
            (x.clamp(min, max), e)
        })
        .collect();
    stream(
        &mut uut,
        &cases,
        round::LATENCY,
        (0, 0),
        |uut, (x, e)| {
            uut.x.next = raw(x, IW).to_bits();
            uut.e.next = raw(i128::from(e), SHORT_EXP_BITS).to_bits();
        },
        |uut, (x, e)| {
            let want = round(Fx { m: x, e }, UP);
            assert_eq!(rounded(uut), want, "round({x}·2^{e}, up = {UP})");
        },
    );
    xs.len()
}

#[test]
fn round_equals_the_model_bit_for_bit() {
    // The widths Decide rounds: value ± margin and τ'·bound, both directions.
    let n = check_round::<DET_SUM_BITS, true>(1)
        + check_round::<DET_SUM_BITS, false>(2)
        + check_round::<NUM_SUM_BITS, true>(3)
        + check_round::<NUM_SUM_BITS, false>(4)
        + check_round::<PRODUCT_BITS, false>(5);
    assert!(n > 15_000);
}

/// A short float as the normalisers produce them: a rounded integer, at times a power of
/// two or a value that kept its own exponent.
fn short(rng: &mut StdRng, near: i32) -> Fx {
    let e = (near + rng.gen_range(-14..=14)).clamp(-EXP_LIMIT, EXP_LIMIT);
    let x = Fx {
        m: integer(rng, 40),
        e,
    };
    match rng.gen_range(0..8) {
        0 => Fx { m: 0, e },
        1 => Fx {
            m: [1, -1, 1 << (SHORT_BITS - 1), -(1 << (SHORT_BITS - 1))][rng.gen_range(0..4)],
            e,
        },
        _ => round(x, rng.gen_bool(0.5)),
    }
}

fn set(m: &mut Signal<In, Bits<SHORT_M_BITS>>, e: &mut Signal<In, Bits<SHORT_EXP_BITS>>, x: Fx) {
    m.next = raw(x.m, SHORT_M_BITS).to_bits();
    e.next = raw(i128::from(x.e), SHORT_EXP_BITS).to_bits();
}

/// Pairs at near and far exponents, equal leading bits, equal values, and opposite signs.
fn pairs(seed: u64) -> Vec<(Fx, Fx)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut out = Vec::new();
    for _ in 0..4000 {
        let base = rng.gen_range(-EXP_LIMIT + 20..EXP_LIMIT - 20);
        let x = short(&mut rng, base);
        let y = match rng.gen_range(0..6) {
            0 => x,
            1 => Fx { m: -x.m, e: x.e },
            // The same value at another exponent, where the mantissa has room.
            2 if x.m.abs() < 1 << (SHORT_BITS - 1) => Fx {
                m: x.m * 2,
                e: x.e - 1,
            },
            3 => {
                let far = rng.gen_range(-EXP_LIMIT + 20..EXP_LIMIT - 20);
                short(&mut rng, far)
            }
            _ => short(&mut rng, base),
        };
        out.push((x, y));
    }
    out
}

#[test]
fn short_lt_equals_the_model_bit_for_bit() {
    let mut uut = Lt::default();
    uut.connect_all();
    let mut seen = [0usize; 2];
    for (x, y) in pairs(6) {
        set(&mut uut.xm, &mut uut.xe, x);
        set(&mut uut.ym, &mut uut.ye, y);
        assert!(simulate(&mut uut, 100));
        assert_eq!(uut.lt.val(), x.lt(y), "{x:?} < {y:?}");
        seen[usize::from(x.lt(y))] += 1;
    }
    assert!(seen.iter().all(|&n| n > 1000), "{seen:?}");
}

#[test]
fn pow2_lt_equals_the_model_bit_for_bit() {
    let mut rng = StdRng::seed_from_u64(8);
    let mut seen = [0usize; 2];
    // Decide's two powers, 0 and the tests' exponent limits.
    let limit = EXP_LIMIT - 2 * SHORT_BITS as i32;
    for k in [RECIPROCAL_MIN, QUOTIENT_MAX, 0, -limit, limit] {
        let mut uut = Pow2Lt::new(k);
        uut.connect_all();
        let top = SHORT_BITS as i32 - 1;
        // Short floats whose leading bit is near 2^k, zeros, ±1 and the extremes, and the
        // boundary: 2^k itself at every mantissa length, just below and just above it.
        let mut xs: Vec<Fx> = (0..2000).map(|_| short(&mut rng, k - top)).collect();
        for s in 0..SHORT_BITS as i32 {
            for m in [1i128, -1, 2, 3, (1 << s) - 1, (1 << s) + 1] {
                for e in [k - s, k - s - 1, k - s + 1] {
                    xs.push(Fx { m: m << s, e });
                    xs.push(Fx { m, e });
                }
            }
        }
        xs.extend([
            Fx { m: 0, e: k },
            Fx {
                m: 1 << top,
                e: k - top,
            },
            Fx {
                m: -(1 << top),
                e: k - top,
            },
            Fx {
                m: (1 << top) - 1,
                e: k - top + 1,
            },
        ]);
        for x in xs {
            let x = Fx {
                m: x.m.clamp(-(1 << top) - 1, 1 << top),
                ..x
            };
            set(&mut uut.xm, &mut uut.xe, x);
            assert!(simulate(&mut uut, 100));
            let want = x.lt(Fx { m: 1, e: k });
            assert_eq!(uut.lt.val(), want, "{x:?} < 2^{k}");
            seen[usize::from(want)] += 1;
        }
    }
    assert!(seen.iter().all(|&n| n > 1000), "{seen:?}");
}

#[test]
fn add_down_equals_the_model_bit_for_bit() {
    let mut uut = AddDown::default();
    uut.connect_all();
    let cases = pairs(7);
    let zero = Fx { m: 0, e: 0 };
    stream(
        &mut uut,
        &cases,
        add_down::LATENCY,
        (zero, zero),
        |uut, (x, y)| {
            set(&mut uut.xm, &mut uut.xe, x);
            set(&mut uut.ym, &mut uut.ye, y);
        },
        |uut, (x, y)| {
            let got = Fx {
                m: signed(uut.sm.val().to_u64(), SHORT_M_BITS),
                e: signed(uut.se.val().to_u64(), SHORT_EXP_BITS) as i32,
            };
            assert_eq!(got, add_down(x, y), "{x:?} + {y:?}");
        },
    );
}

/// Their Verilog is what Vivado would read: Verilator lints it clean.
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the normalisers, the comparator and the adder:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture round_resources`
#[test]
#[ignore]
fn round_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}

fn verilogs() -> Vec<(String, String)> {
    vec![
        named(Round::<NUM_SUM_BITS, true>::default(), "Round up", |_| {
            format!("{NUM_SUM_BITS} → {SHORT_M_BITS} bits")
        }),
        named(
            Round::<NUM_SUM_BITS, false>::default(),
            "Round down",
            |_| format!("{NUM_SUM_BITS} → {SHORT_M_BITS} bits"),
        ),
        named(Lt::default(), "ShortLt", |_| format!("{SHORT_M_BITS} bits")),
        named(Pow2Lt::new(QUOTIENT_MAX), "Pow2Lt", |_| {
            format!("{SHORT_M_BITS} bits")
        }),
        named(AddDown::default(), "AddDown", |_| {
            format!("{SHORT_M_BITS}-bit sums")
        }),
    ]
}
