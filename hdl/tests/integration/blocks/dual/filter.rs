//! `hdl::dual::filter`: the whole bfp filter lane, streamed one query per cycle, bit for
//! bit the model's `Filter::certain_miss(q, 1.0)` for bfp18/fp32 (`values`, then `decide`).

use hdl::dual::filter::{BfpFilter, LATENCY};
use hdl::dual::WIDTH;
use hw_model::dual::bfp::{
    margin_units, split, to_block, translate, values, widths, Fx, Vector, DET, EXP_MAX, EXP_MIN,
    N_T, N_U, N_V, SUM_MIN,
};
use hw_model::dual::{Filter, FilterKind, FormatPair};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::MtQuery;

use super::common::{lint_clean, named, near_parallel};

/// Why the model's `values` refuses a query (the filter forwards it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cause {
    NonFinite,
    Zero,
    Huge,
    Tiny,
    SumMin,
}

/// The first refusal of `values` that `q` meets, from the model's own steps (for counting
/// which causes the test reaches; the expected answer is `certain_miss`).
fn refusal(q: &MtQuery) -> Option<Cause> {
    let all = [q.v0, q.v1, q.v2, q.orig, q.dir];
    if all.iter().flatten().any(|x| !x.is_finite()) {
        return Some(Cause::NonFinite);
    }
    let moved = |p: [f32; 3]| -> [Fx; 3] {
        std::array::from_fn(|k| translate(p[k], q.v0[k]).expect("finite"))
    };
    let w = widths(WIDTH);
    let dir = q.dir.map(|c| split(c).expect("finite"));
    let blocks = [
        to_block(dir, w[Vector::Dir as usize]),
        to_block(moved(q.v1), w[Vector::E1 as usize]),
        to_block(moved(q.v2), w[Vector::E2 as usize]),
        to_block(moved(q.orig), w[Vector::S as usize]),
    ];
    if blocks.iter().any(Option::is_none) {
        return Some(Cause::Zero);
    }
    let e = blocks.map(|b| b.expect("not zero").e);
    if e.iter().any(|&e| e > EXP_MAX) {
        return Some(Cause::Huge);
    }
    if e.iter().any(|&e| e < EXP_MIN) {
        return Some(Cause::Tiny);
    }
    // The blocks are in the order of `Vector` (dir, e1, e2, s).
    let sum = |value: [Vector; 4]| value[..3].iter().map(|&v| e[v as usize]).sum::<i32>();
    if [DET, N_U, N_V, N_T].iter().any(|&v| sum(v) < SUM_MIN) {
        return Some(Cause::SumMin);
    }
    None
}

/// What the stream saw: misses, forwarded queries the filter decided on, and each refusal.
#[derive(Default, Debug)]
struct Seen {
    miss: usize,
    forward: usize,
    causes: Vec<Cause>,
}

impl Seen {
    fn assert_all(&self, n: usize) {
        assert!(self.miss >= n && self.forward >= n, "{self:?}");
        for cause in [
            Cause::NonFinite,
            Cause::Zero,
            Cause::Huge,
            Cause::Tiny,
            Cause::SumMin,
        ] {
            let count = self.causes.iter().filter(|&&c| c == cause).count();
            assert!(count >= n, "{cause:?} seen {count} times: {self:?}");
        }
    }
}

fn bits(x: f32) -> Bits<32> {
    u64::from(x.to_bits()).to_bits()
}

/// Streams `qs` through the lane one per cycle (then LATENCY idle cycles) and compares
/// every answer with the model.
fn stream(qs: &[MtQuery], seen: &mut Seen) {
    let filter = Filter::new(
        FormatPair::parse(&format!("bfp{WIDTH}/fp32")).unwrap(),
        FilterKind::Bfp,
    );
    let mut uut = BfpFilter::default();
    uut.connect_all();
    for cycle in 0..qs.len() + LATENCY {
        let q = qs.get(cycle);
        uut.valid.next = q.is_some();
        let q = q.copied().unwrap_or_default();
        for k in 0..3 {
            uut.v0[k].next = bits(q.v0[k]);
            uut.v1[k].next = bits(q.v1[k]);
            uut.v2[k].next = bits(q.v2[k]);
            uut.orig[k].next = bits(q.orig[k]);
            uut.dir[k].next = bits(q.dir[k]);
        }
        uut.t_min.next = bits(q.t_min);
        uut.clock.next = Clock { clk: false };
        assert!(simulate(&mut uut, 10_000));
        uut.clock.next = Clock { clk: true };
        assert!(simulate(&mut uut, 10_000));
        // After this edge the lane answers the query of LATENCY − 1 cycles before.
        let Some(i) = (cycle + 1).checked_sub(LATENCY) else {
            assert!(!uut.valid_out.val(), "valid out before any query");
            continue;
        };
        assert_eq!(
            uut.valid_out.val(),
            i < qs.len(),
            "valid out at cycle {cycle}"
        );
        let Some(q) = qs.get(i) else { continue };
        let want = filter.certain_miss(q, 1.0);
        let (miss, forward) = (uut.miss.val(), uut.forward.val());
        assert_eq!((miss, forward), (want, !want), "query {i}: {q:?}");
        let cause = refusal(q);
        // The test's reading of the refusals is the model's.
        assert_eq!(cause.is_some(), values(q, WIDTH, 1.0).is_none(), "{q:?}");
        match cause {
            Some(c) => seen.causes.push(c),
            None if want => seen.miss += 1,
            None => seen.forward += 1,
        }
    }
}

/// An fp32 number of either sign, exponent in [lo, hi), or 0.
fn float(rng: &mut StdRng, lo: i32, hi: i32) -> f32 {
    if rng.gen_range(0..16) == 0 {
        return 0.0;
    }
    let e = rng.gen_range(lo..hi);
    let x = f32::from_bits(((e + 127) as u32) << 23 | rng.gen_range(0..1u32 << 23));
    if rng.gen() {
        -x
    } else {
        x
    }
}

/// Coordinates at random, in one scale or in wildly mixed ones.
pub(super) fn random(rng: &mut StdRng) -> MtQuery {
    let (lo, hi) = if rng.gen() {
        let e = rng.gen_range(-20..20);
        (e - 3, e + 3)
    } else {
        (-30, 30)
    };
    let mut p = || -> [f32; 3] { std::array::from_fn(|_| float(rng, lo, hi)) };
    MtQuery {
        v0: p(),
        v1: p(),
        v2: p(),
        orig: p(),
        dir: p(),
        t_min: 0.0,
    }
}

fn point(rng: &mut StdRng, size: f32) -> [f32; 3] {
    std::array::from_fn(|_| rng.gen_range(-size..size))
}

fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|k| a[k] + b[k])
}

/// A t_min: mostly 0, else positive, negative, tiny, near the aimed hit's t = 1, or not
/// finite (which decides nothing but is no refusal).
fn t_min(rng: &mut StdRng) -> f32 {
    match rng.gen_range(0..12) {
        0..=5 => 0.0,
        6 | 7 => rng.gen_range(0.0..2.0),
        8 => rng.gen_range(-2.0..0.0),
        9 => f32::from_bits(rng.gen_range(0..0x0d00_0000)),
        10 => [f32::NAN, f32::INFINITY][rng.gen_range(0..2)],
        _ => 1.0 + rng.gen_range(-1e-6f32..1e-6),
    }
}

/// A query shaped like the filter's work: rays aimed near the triangle's edges (hits and
/// misses), near-parallel rays, origins just off the plane, rays behind their origin;
/// scenes from 2^-12 to 2^12 units, thin and large triangles.
pub(super) fn shaped(rng: &mut StdRng) -> MtQuery {
    let size = 2f32.powi(rng.gen_range(-12..=12));
    let v0 = point(rng, size);
    let spread = size * 2f32.powi(-rng.gen_range(0..8));
    let (v1, v2) = (add(v0, point(rng, spread)), add(v0, point(rng, spread)));
    let edge = |rng: &mut StdRng| match rng.gen_range(0..4) {
        0 => rng.gen_range(-1e-4..1e-4),
        1 => 1.0 + rng.gen_range(-1e-4..1e-4),
        _ => rng.gen_range(-0.2..1.2),
    };
    let (a, b) = (edge(rng), edge(rng));
    let orig = add(v0, point(rng, size * 4.0));
    let mut q = MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min(rng));
    match rng.gen_range(0..6) {
        // Near-parallel: along e1 plus a little of the normal.
        0 => {
            q.dir = near_parallel(rng, [v0, v1, v2]);
        }
        // The origin a hair off the plane: t near 0.
        1 => {
            q.orig = add(orig, q.dir.map(|d| d * (1.0 + 1e-7)));
            q.dir = point(rng, 1.0);
        }
        // Behind the origin.
        2 => q.dir = q.dir.map(|d| -d),
        _ => {}
    }
    q
}

/// `q` with every coordinate (not dir) times 2^k.
fn scaled(q: MtQuery, k: i32) -> MtQuery {
    let s = |p: [f32; 3]| p.map(|x| x * 2f32.powi(k));
    MtQuery {
        v0: s(q.v0),
        v1: s(q.v1),
        v2: s(q.v2),
        orig: s(q.orig),
        ..q
    }
}

/// A shaped query made to meet one of `values`' refusals: a non-finite coordinate, a zero
/// vector, coordinates beyond the exponent range either way, or triples below SUM_MIN with
/// every vector in range.
pub(super) fn refused(rng: &mut StdRng) -> MtQuery {
    let mut q = shaped(rng);
    let k = rng.gen_range(0..3);
    match rng.gen_range(0..8) {
        0 => {
            let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.gen_range(0..3)];
            let slot = rng.gen_range(0..5);
            [&mut q.v0, &mut q.v1, &mut q.v2, &mut q.orig, &mut q.dir][slot][k] = bad;
        }
        1 => match rng.gen_range(0..4) {
            0 => q.v1 = q.v0,
            1 => q.v2 = q.v0,
            2 => q.orig = q.v0,
            _ => q.dir = [0.0, -0.0, f32::MIN_POSITIVE / 2.0],
        },
        // The query alone beyond 2^EXP_MAX, or its direction.
        2 => q = scaled(q, EXP_MAX + rng.gen_range(1..20)),
        3 => q.dir = q.dir.map(|d| d * 2f32.powi(EXP_MAX + rng.gen_range(1..20))),
        // Below 2^EXP_MIN (still normal numbers).
        4 => q = scaled(q, EXP_MIN - rng.gen_range(14..30)),
        5 => q.dir = q.dir.map(|d| d * 2f32.powi(EXP_MIN - rng.gen_range(1..20))),
        // Each block near 2^-30: in range, but three of them sum below SUM_MIN.
        _ => {
            let unit = |rng: &mut StdRng| {
                let size = 2f32.powi(-30 - rng.gen_range(0..6));
                point(rng, size)
            };
            let size = 2f32.powi(-28);
            q.v0 = point(rng, size);
            q.v1 = add(q.v0, unit(rng));
            q.v2 = add(q.v0, unit(rng));
            q.orig = add(q.v0, point(rng, size));
            q.dir = unit(rng);
        }
    }
    q
}

#[test]
fn random_queries_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(71);
    let qs: Vec<_> = (0..400).map(|_| random(&mut rng)).collect();
    let mut seen = Seen::default();
    stream(&qs, &mut seen);
    println!(
        "random: {} misses, {} decided forwards, {} refused",
        seen.miss,
        seen.forward,
        seen.causes.len()
    );
    assert!(seen.miss > 0 && seen.forward > 0, "{seen:?}");
}

#[test]
fn filter_shaped_and_refused_queries_equal_the_model() {
    let mut rng = StdRng::seed_from_u64(72);
    let mut qs: Vec<_> = (0..3000)
        .map(|i| {
            if i % 3 == 0 {
                refused(&mut rng)
            } else {
                shaped(&mut rng)
            }
        })
        .collect();
    // Extremes: the largest and smallest finite coordinates, signed zeros, subnormals.
    let q = shaped(&mut rng);
    for x in [f32::MAX, -f32::MAX, f32::MIN_POSITIVE, -0.0, 1e-45] {
        qs.push(MtQuery { v1: [x; 3], ..q });
        qs.push(MtQuery {
            dir: [x, 1.0, -1.0],
            ..q
        });
    }
    let mut seen = Seen::default();
    stream(&qs, &mut seen);
    println!(
        "shaped: {} misses, {} decided forwards, {} refused",
        seen.miss,
        seen.forward,
        seen.causes.len()
    );
    seen.assert_all(10);
}

/// `values`' last refusal, a margin term overflowing i128, cannot happen at this width:
/// the largest margin (every vector dropping right below its last bit) fits.
#[test]
fn no_margin_overflows_at_the_filter_width() {
    let w = widths(WIDTH);
    for value in [DET, N_U, N_V, N_T] {
        let below = value.map(|v| Some(w[v as usize] as i32 - 1));
        assert!(
            margin_units(WIDTH, value, below, 1.0).is_some(),
            "{value:?}"
        );
    }
}

/// Its Verilog is what Vivado would read: Verilator lints it clean but for UNOPTFLAT, the
/// traversal unit's waiver (one `always` block drives the blocks' inputs and reads their
/// outputs, which Verilator sees as a loop although every path crosses a register).
#[test]
fn verilog_passes_verilator_lint() {
    lint_clean(&[verilog()], hdl::verilog::UNIT_VERILATOR_WAIVERS);
}

/// yosys xc7 resources of the whole lane:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture bfp_filter_resources`
#[test]
#[ignore]
fn bfp_filter_resources() {
    println!("{}", hdl::synth::markdown_table(&[verilog()]).unwrap());
}

fn verilog() -> (String, String) {
    named(BfpFilter::default(), "BfpFilter", |_| {
        format!("bfp{WIDTH}/fp32, latency {LATENCY}")
    })
}
