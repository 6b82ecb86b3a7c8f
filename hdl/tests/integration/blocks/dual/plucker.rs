//! `hdl::dual::align_add`, `hdl::dual::edge_value` and `hdl::dual::plucker`: the Plücker
//! filter's datapath streamed one query per cycle, bit for bit the model's
//! `plucker::datapath` at W = 18.

use hdl::dual::align_add::{self, AlignAdd, EXP_BIAS};
use hdl::dual::edge_value::EdgeValue;
use hdl::dual::plucker::*;
use hdl::dual::WIDTH;
use hw_model::dual::bfp::Fx;
use hw_model::dual::plucker::{align_add, datapath, BlockBits, Operands};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::MtQuery;

use super::common::{lint_clean, named};
use super::cross_block::{extremes, field, mantissa, signed, tick, Clocked};
use super::filter::{random, shaped};

impl<const N: usize, const O: usize> Clocked for AlignAdd<N, O> {
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

impl Clocked for PluckerDatapath {
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

/// A grid exponent as its biased field.
pub(super) fn exp_field(e: i32) -> Bits<10> {
    field::<10>(e as i128 + EXP_BIAS as i128)
}

/// A field read back as a grid exponent.
pub(super) fn exp_of(raw: Bits<10>) -> i32 {
    raw.to_u128() as i32 - EXP_BIAS as i32
}

/// An N-bit operand: an extreme or a mantissa of random bit count.
fn operand(rng: &mut StdRng, n: usize) -> i128 {
    if rng.gen_range(0..4) == 0 {
        extremes(n)[rng.gen_range(0..4)]
    } else {
        mantissa(rng, n)
    }
}

/// `cases` (a, ea, b, eb) through an `AlignAdd<N, O>` one a cycle, each against the model.
fn stream_align<const N: usize, const O: usize>(cases: &[(i128, i32, i128, i32)]) {
    let mut uut = AlignAdd::<N, O>::default();
    uut.connect_all();
    for i in 0..cases.len() + align_add::LATENCY - 1 {
        let (a, ea, b, eb) = cases.get(i).copied().unwrap_or((0, 0, 0, 0));
        uut.a.next = field(a);
        uut.ea.next = exp_field(ea);
        uut.b.next = field(b);
        uut.eb.next = exp_field(eb);
        tick(&mut uut);
        let Some(j) = (i + 1).checked_sub(align_add::LATENCY) else {
            continue;
        };
        let (a, ea, b, eb) = cases[j];
        let (want, bits) = align_add((Fx::new(a, ea), N as u32), (Fx::new(b, eb), N as u32));
        assert_eq!(bits as usize, O);
        let got = Fx::new(signed(uut.s.val().to_u128(), O), exp_of(uut.e.val()));
        assert_eq!(got, want, "{a}·2^{ea} + {b}·2^{eb}");
    }
}

fn align_cases(n: usize, seed: u64) -> Vec<(i128, i32, i128, i32)> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..3000)
        .map(|_| {
            let ea = rng.gen_range(-300..250);
            // Equal grids, shifts around N − 1, and anything up to far apart.
            let eb = match rng.gen_range(0..4) {
                0 => ea,
                1 => ea + rng.gen_range(-(n as i32) - 2..=n as i32 + 2),
                _ => rng.gen_range(-300..250),
            };
            (operand(&mut rng, n), ea, operand(&mut rng, n), eb)
        })
        .collect()
}

#[test]
fn align_add_floors_onto_the_coarser_grid_as_the_model() {
    stream_align::<EDGE_DOT_BITS, EDGE_VALUE_BITS>(&align_cases(EDGE_DOT_BITS, 1));
    stream_align::<NT_DOT_BITS, NT_BITS>(&align_cases(NT_DOT_BITS, 2));
}

/// Drives one block's mantissas and exponent field.
pub(super) fn drive<const N: usize, const M: usize>(
    ports: &mut [Signal<In, Bits<M>>; 3],
    e: &mut Signal<In, Bits<10>>,
    block: &BlockBits<N>,
) {
    for (port, m) in ports.iter_mut().zip(block.m) {
        port.next = field(m as i128);
    }
    e.next = exp_field(block.lsb);
}

/// Drives the datapath's operands into `$uut` (the datapath, or the filter: the same
/// ports).
macro_rules! set_operands {
    ($uut:expr, $o:expr) => {{
        let (uut, o) = ($uut, $o);
        drive(&mut uut.dir, &mut uut.dir_e, &o.dir);
        drive(&mut uut.moment, &mut uut.moment_e, &o.moment);
        drive(&mut uut.orig, &mut uut.orig_e, &o.orig);
        drive(&mut uut.n, &mut uut.n_e, &o.n);
        drive(&mut uut.e1, &mut uut.e1_e, &o.edges[0]);
        drive(&mut uut.e2, &mut uut.e2_e, &o.edges[1]);
        drive(&mut uut.e3, &mut uut.e3_e, &o.edges[2]);
        drive(&mut uut.m1, &mut uut.m1_e, &o.moments[0]);
        drive(&mut uut.m2, &mut uut.m2_e, &o.moments[1]);
        drive(&mut uut.m3, &mut uut.m3_e, &o.moments[2]);
        uut.offset.next = field(o.offset.m[0] as i128);
        uut.offset_e.next = exp_field(o.offset.lsb);
    }};
}
pub(super) use set_operands;

/// The five values as the datapath gives them.
fn values(uut: &PluckerDatapath) -> [Fx; 5] {
    let v = |raw: u128, bits: usize, e: Bits<10>| Fx::new(signed(raw, bits), exp_of(e));
    [
        v(uut.det.val().to_u128(), DET_BITS, uut.det_e.val()),
        v(uut.nu.val().to_u128(), EDGE_VALUE_BITS, uut.nu_e.val()),
        v(uut.nv.val().to_u128(), EDGE_VALUE_BITS, uut.nv_e.val()),
        v(uut.nw.val().to_u128(), EDGE_VALUE_BITS, uut.nw_e.val()),
        v(uut.nt.val().to_u128(), NT_BITS, uut.nt_e.val()),
    ]
}

/// `queries` the model computes (it forwards the others before any arithmetic) through
/// the datapath one a cycle, every value against the model's `datapath` `LATENCY` cycles
/// later; returns how many were compared.
fn stream(queries: &[MtQuery]) -> usize {
    let cases: Vec<(Operands, [Fx; 5])> =
        queries.iter().filter_map(|q| datapath(q, WIDTH)).collect();
    let mut uut = PluckerDatapath::default();
    uut.connect_all();
    for i in 0..cases.len() + LATENCY {
        if let Some((operands, _)) = cases.get(i) {
            set_operands!(&mut uut, operands);
        }
        tick(&mut uut);
        let Some(j) = (i + 1).checked_sub(LATENCY) else {
            continue;
        };
        if let Some((operands, want)) = cases.get(j) {
            assert_eq!(values(&uut), *want, "{operands:?}");
        }
    }
    cases.len()
}

/// Random queries in one scale or mixed scales, and queries shaped like the filter's work
/// (aimed near edges, near-parallel, origins just off the plane, behind the origin).
#[test]
fn the_datapath_is_the_models_bit_for_bit() {
    let mut rng = StdRng::seed_from_u64(18);
    let mut queries: Vec<MtQuery> = (0..600).map(|_| random(&mut rng)).collect();
    queries.extend((0..1800).map(|_| shaped(&mut rng)));
    let compared = stream(&queries);
    assert!(
        compared > 2200,
        "only {compared} queries computed by the model"
    );
}

fn verilogs() -> Vec<(String, String)> {
    vec![
        named(
            AlignAdd::<EDGE_DOT_BITS, EDGE_VALUE_BITS>::default(),
            "AlignAdd",
            |_| format!("{EDGE_DOT_BITS} bits"),
        ),
        named(
            AlignAdd::<NT_DOT_BITS, NT_BITS>::default(),
            "AlignAdd",
            |_| format!("{NT_DOT_BITS} bits"),
        ),
        named(EdgeValue::default(), "EdgeValue", |_| format!("W = {W}")),
        named(PluckerDatapath::default(), "PluckerDatapath", |_| {
            format!("W = {W}, orig and n {WT} bits")
        }),
    ]
}

#[test]
fn the_datapath_lints_clean() {
    lint_clean(&verilogs(), &[]);
}

/// yosys xc7 resources of the datapath and its blocks:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture plucker_resources`
#[test]
#[ignore]
fn plucker_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}
