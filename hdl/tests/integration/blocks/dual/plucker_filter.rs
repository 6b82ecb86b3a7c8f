//! `hdl::dual::s_bound`, `hdl::dual::plucker_margin` and `hdl::dual::plucker_filter`: the
//! Plücker filter's |s| bound and margins against the model's, and the whole lane streamed
//! one test per cycle, bit for bit `Filter::certain_miss(q, 1.0)` for bfp18/fp32 with the
//! Plücker filter (`plucker::sign_inputs`, then `signs::decide`).

use hdl::dual::decide::{DET_MARGIN_BITS, NUM_MARGIN_BITS};
use hdl::dual::plucker::W;
use hdl::dual::plucker_filter::{PluckerFilter, LATENCY};
use hdl::dual::plucker_margin::{self, PluckerMargin, Y_BIAS};
use hdl::dual::s_bound::{self, SBound};
use hdl::dual::WIDTH;
use hw_model::dual::bfp::Term;
use hw_model::dual::plucker::{
    datapath, decide_inputs, fallback_term, margin_constants, s_exponent, MarginConstants,
};
use hw_model::dual::{Filter, FilterKind, FormatPair};
use hw_model::precision::SpawnChoice;
use hw_model::{lookup, ModelIntersector, MtResult};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::{Intersector, MtQuery};
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;

use super::common::{lint_clean, named};
use super::cross_block::{field, tick, Clocked};
use super::filter::{random, refused, shaped};
use super::plucker::{drive, exp_field, exp_of, set_operands};

impl Clocked for SBound {
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

impl<const MB: usize> Clocked for PluckerMargin<MB> {
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

/// Random and filter-shaped queries, a third made to be refused.
fn queries(seed: u64, n: usize) -> Vec<MtQuery> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|i| match i % 6 {
            0 => random(&mut rng),
            1 | 2 => refused(&mut rng),
            _ => shaped(&mut rng),
        })
        .collect()
}

#[test]
fn the_s_bound_is_the_models() {
    let cases: Vec<_> = queries(31, 3000)
        .iter()
        .filter_map(|q| datapath(q, WIDTH))
        .map(|(o, _)| o)
        .collect();
    assert!(cases.len() > 2000, "{}", cases.len());
    let mut uut = SBound::default();
    uut.connect_all();
    for i in 0..cases.len() + s_bound::LATENCY {
        if let Some(o) = cases.get(i) {
            drive(&mut uut.orig, &mut uut.orig_e, &o.orig);
            drive(&mut uut.cut, &mut uut.cut_e, &o.v0_cut);
        }
        tick(&mut uut);
        let Some(j) = (i + 1).checked_sub(s_bound::LATENCY) else {
            continue;
        };
        if let Some(o) = cases.get(j) {
            let want = s_exponent(&o.orig, &o.v0_cut, WIDTH);
            assert_eq!(exp_of(uut.e.val()), want, "{o:?}");
        }
    }
}

/// The margin's specification from the model's terms: the fixed part, the finer dot's
/// bound C·2^-below rounded up, the fallback's m_F·2^y rounded up if `charged`; `None`
/// (over) once that reaches 2^(MB − 1).
fn margin_spec(mb: usize, c: MarginConstants, below: u32, y: i32, charged: bool) -> Option<i128> {
    let f = fallback_term();
    if charged && y + (128 - f.m.leading_zeros()) as i32 >= mb as i32 {
        return None;
    }
    let fine = Term {
        m: c.fine,
        shift: 0,
    }
    .units(below as i32)
    .unwrap();
    let fallback = if charged {
        Term { m: f.m, shift: 0 }.units(-y).unwrap()
    } else {
        0
    };
    Some(c.fixed + fine + fallback)
}

fn stream_margin<const MB: usize>(c: MarginConstants, seed: u64, charged: bool) {
    let mut rng = StdRng::seed_from_u64(seed);
    let cases: Vec<(u32, i32)> = (0..4000)
        .map(|_| {
            let below = match rng.gen_range(0..4) {
                0 => 0,
                1 => rng.gen_range(0..64),
                2 => rng.gen_range(64..1 << plucker_margin::BELOW_BITS),
                _ => rng.gen_range(20..40),
            };
            (below, rng.gen_range(-200..MB as i32 + 8))
        })
        .collect();
    let mut uut = if charged {
        PluckerMargin::<MB>::new(c)
    } else {
        PluckerMargin::<MB>::dots_only(c)
    };
    uut.connect_all();
    for i in 0..cases.len() + plucker_margin::LATENCY {
        if let Some(&(below, y)) = cases.get(i) {
            uut.below.next = (below as u64).to_bits();
            uut.y.next = ((y as i64 + Y_BIAS) as u64).to_bits();
        }
        tick(&mut uut);
        let Some(j) = (i + 1).checked_sub(plucker_margin::LATENCY) else {
            continue;
        };
        if let Some(&(below, y)) = cases.get(j) {
            let want = margin_spec(MB, c, below, y, charged);
            assert_eq!(uut.over.val(), want.is_none(), "{below} {y}");
            if let Some(want) = want {
                assert_eq!(uut.margin.val().to_u128() as i128, want, "{below} {y}");
            }
        }
    }
}

/// Each of the lane's five margins (the model's `margin_constants`; N_w's has the edges'
/// constants and no fallback term).
#[test]
fn the_margins_are_their_specification() {
    let [det, u, v, t] = margin_constants(WIDTH);
    stream_margin::<DET_MARGIN_BITS>(det, 41, true);
    for (c, seed) in [(u, 42), (v, 43), (t, 44)] {
        stream_margin::<NUM_MARGIN_BITS>(c, seed, true);
    }
    stream_margin::<NUM_MARGIN_BITS>(u, 45, false);
}

/// What the stream saw: misses, decided forwards, tests with no stored vectors, and tests
/// the model refuses after storing them (exponents out of range, a fallback term too big).
#[derive(Default, Debug)]
struct Seen {
    miss: usize,
    forward: usize,
    unstored: usize,
    refused: usize,
}

fn bits(x: f32) -> Bits<32> {
    u64::from(x.to_bits()).to_bits()
}

/// Streams `qs` through the lane one per cycle (then LATENCY idle cycles) and compares
/// every answer with the model's.
fn stream(qs: &[MtQuery]) -> Seen {
    let filter = Filter::new(
        FormatPair::parse(&format!("bfp{WIDTH}/fp32")).unwrap(),
        FilterKind::Plucker,
    );
    let mut seen = Seen::default();
    let mut uut = PluckerFilter::default();
    uut.connect_all();
    for cycle in 0..qs.len() + LATENCY {
        let q = qs.get(cycle);
        uut.valid.next = q.is_some();
        let operands = q.and_then(|q| datapath(q, WIDTH)).map(|(o, _)| o);
        uut.stored.next = operands.is_some();
        if let Some(o) = &operands {
            set_operands!(&mut uut, o);
            drive(&mut uut.cut, &mut uut.cut_e, &o.v0_cut);
        }
        uut.t_min.next = bits(q.map_or(0.0, |q| q.t_min));
        tick(&mut uut);
        let Some(i) = (cycle + 1).checked_sub(LATENCY) else {
            assert!(!uut.valid_out.val(), "valid out before any query");
            continue;
        };
        assert_eq!(uut.valid_out.val(), i < qs.len(), "cycle {cycle}");
        let Some(q) = qs.get(i) else { continue };
        let want = filter.certain_miss(q, 1.0);
        assert_eq!(
            (uut.miss.val(), uut.forward.val()),
            (want, !want),
            "query {i}: {q:?}"
        );
        if datapath(q, WIDTH).is_none() {
            seen.unstored += 1;
        } else if decide_inputs(q, WIDTH, 1.0).is_none() {
            seen.refused += 1;
        } else if want {
            seen.miss += 1;
        } else {
            seen.forward += 1;
        }
    }
    seen
}

impl Clocked for PluckerFilter {
    fn set_clock(&mut self, clk: bool) {
        self.clock.next = Clock { clk };
    }
}

#[test]
fn the_filter_is_the_models_bit_for_bit() {
    let seen = stream(&queries(51, 3000));
    println!("{seen:?}");
    assert!(
        seen.miss > 500 && seen.forward > 200 && seen.unstored > 50 && seen.refused > 50,
        "{seen:?}"
    );
}

/// An fp32 intersector that keeps every query whose bits hash to 0 modulo `every`: a sample
/// of a render's tests that does not depend on how the renderer's threads split the work.
struct Sampler {
    fp32: ModelIntersector,
    every: u32,
    kept: std::sync::Mutex<Vec<MtQuery>>,
}

impl Intersector for Sampler {
    fn name(&self) -> String {
        "sampled fp32".into()
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), sw_renderer::rays::EngineError> {
        self.fp32.intersect_batch(queries, results)?;
        let hash = |q: &MtQuery| {
            [q.orig, q.dir, q.v0, q.v1, q.v2]
                .iter()
                .flatten()
                .fold(0u32, |h, x| h.rotate_left(5) ^ x.to_bits())
                .wrapping_mul(0x9e37_79b9)
        };
        let sampled = queries.iter().filter(|q| hash(q) % self.every == 0);
        self.kept.lock().unwrap().extend(sampled);
        Ok(())
    }
}

/// The lane on real work: a sixteenth of the tests of the 7 thesis scenes at 64×36 under
/// both spawn policies (the format-aware one gives spawned rays t_min > 0), against the
/// model.
#[test]
fn the_filter_is_the_models_on_the_thesis_scenes() {
    let Some(root) = thesis_scenes::for_test(
        "dual::plucker_filter::the_filter_is_the_models_on_the_thesis_scenes",
    ) else {
        return;
    };
    let fp32 = lookup("fp32").unwrap();
    let mut qs = Vec::new();
    for choice in [SpawnChoice::Thesis, SpawnChoice::FormatAware] {
        let opts = RenderOptions {
            width: Some(64),
            height: Some(36),
            progress: false,
            spawn: choice.policy(&fp32, 0),
            ..Default::default()
        };
        for name in thesis_scenes::SCENE_DIRS {
            let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
            let sampler = Sampler {
                fp32: ModelIntersector::new(fp32),
                every: 16,
                kept: Default::default(),
            };
            render(&scene, &sampler, &opts).unwrap();
            qs.extend(sampler.kept.into_inner().unwrap());
        }
    }
    let spawned = qs.iter().filter(|q| q.t_min > 0.0).count();
    let seen = stream(&qs);
    println!("{} tests, {spawned} with t_min > 0: {seen:?}", qs.len());
    assert!(
        seen.miss > 1000 && seen.forward > 100 && spawned > 100,
        "{spawned} with t_min > 0: {seen:?}"
    );
}

fn verilogs() -> Vec<(String, String)> {
    let u = margin_constants(WIDTH)[1];
    vec![
        named(SBound::default(), "SBound", |_| format!("W = {W}")),
        named(
            PluckerMargin::<NUM_MARGIN_BITS>::new(u),
            "PluckerMargin",
            |_| "an edge value".to_string(),
        ),
        named(PluckerFilter::default(), "PluckerFilter", |_| {
            format!("bfp{WIDTH}/fp32, latency {LATENCY}")
        }),
    ]
}

/// Verilator lints it clean but for UNOPTFLAT, the traversal unit's waiver (as the bfp
/// filter's lane).
#[test]
fn the_filter_lints_clean() {
    lint_clean(&verilogs(), hdl::verilog::UNIT_VERILATOR_WAIVERS);
}

/// yosys xc7 resources of the whole lane and its new blocks:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture plucker_filter_resources`
#[test]
#[ignore]
fn plucker_filter_resources() {
    println!("{}", hdl::synth::markdown_table(&verilogs()).unwrap());
}
