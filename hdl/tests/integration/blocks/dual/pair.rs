//! `hdl::dual::pair`: two filter lanes (bfp, or Plücker fed the queries' stored vectors)
//! sharing an fp32 lane, streamed with random gaps, every answer bit for bit the model's
//! `DualIntersector` (bfp18/fp32 with that filter) and every query answered exactly once,
//! also when the fp32 lane is the bottleneck and `ready` falls.

use hdl::dual::pair::{forward_latency, miss_latency, DualPair, SlotFilter, QUEUE_DEPTH};
use hdl::dual::plucker_operands::{operand_words, OPERAND_BITS};
use hdl::dual::WIDTH;
use hdl::formats::fp32;
use hdl::mt::{query_words, Lane};
use hw_model::dual::plucker::datapath;
use hw_model::dual::{DualIntersector, Filter, FormatPair};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::intersect::{Intersector, MtQuery, MtResult};

use super::common::{lint_clean, named};
use super::filter::{random, refused, shaped};

/// The slots of the pair under test.
const N: usize = 2;
/// A short fp32 lane keeps the simulation quick; the queue logic does not depend on it.
const DEPTH: usize = 1;

/// One query's fate: the cycle it was taken, the cycle and port of its answer.
#[derive(Clone, Copy, Debug)]
struct Fate {
    taken: usize,
    answered: usize,
    forwarded: bool,
    result: MtResult,
}

/// What a run saw.
struct Run {
    /// Per slot, per query.
    fates: Vec<Vec<Fate>>,
    /// Cycles in which some slot offered a query and `ready` was low.
    stalls: usize,
    /// Cycles until the last answer.
    cycles: usize,
}

fn query_bits(q: &MtQuery) -> Bits<512> {
    let mut bits = Bits::<512>::default();
    for (k, &w) in query_words(q).iter().enumerate() {
        bits.set_bits::<32>(32 * k, u64::from(w).to_bits());
    }
    bits
}

/// The Plücker operands of `q` as the pair's port takes them.
fn operand_bits(q: &MtQuery) -> Bits<OPERAND_BITS> {
    let ops = datapath(q, WIDTH).map(|(ops, _)| ops);
    let mut bits = Bits::<OPERAND_BITS>::default();
    for (k, &w) in operand_words(ops.as_ref()).iter().enumerate() {
        bits.set_bits::<32>(32 * k, u64::from(w).to_bits());
    }
    bits
}

fn f32_of(bits: Bits<32>) -> f32 {
    f32::from_bits(bits.to_u64() as u32)
}

/// Tags say slot and index: index · N + slot.
fn tag(slot: usize, index: usize) -> usize {
    index * N + slot
}

/// Streams `queries[s]` into slot `s` in order, slot `s` offering its next query in a cycle
/// when `offer(cycle, s)`; each offer is held until `ready` takes it. Panics if an answer is
/// doubled, comes for a query not taken, or some query is never answered.
fn run(
    kind: SlotFilter,
    queries: &[Vec<MtQuery>; N],
    mut offer: impl FnMut(usize, usize) -> bool + Send + 'static,
) -> Run {
    let queries = queries.clone();
    hdl::top::with_build_stack(move || {
        let mut uut = DualPair::<N>::new(DEPTH, kind);
        uut.connect_all();
        let total: usize = queries.iter().map(Vec::len).sum();
        let mut next = [0; N];
        let mut taken: Vec<Vec<Option<usize>>> =
            queries.iter().map(|qs| vec![None; qs.len()]).collect();
        let mut fates: Vec<Vec<Option<Fate>>> =
            queries.iter().map(|qs| vec![None; qs.len()]).collect();
        let (mut answered, mut stalls, mut cycle) = (0, 0, 0);
        let limit = 40 * total + 1000;
        while answered < total {
            assert!(
                cycle < limit,
                "{answered} of {total} answered after {cycle} cycles"
            );
            let mut offered = [false; N];
            for s in 0..N {
                offered[s] = next[s] < queries[s].len() && offer(cycle, s);
                let q = queries[s].get(next[s]).copied().unwrap_or_default();
                uut.valid[s].next = offered[s];
                uut.query[s].next = query_bits(&q);
                uut.tag[s].next = (tag(s, next[s]) as u64).to_bits();
                if kind == SlotFilter::Plucker {
                    uut.operands[s].next = operand_bits(&q);
                }
            }
            uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut uut, 10_000), "logic did not settle");
            // What the outputs show in this cycle, before its edge.
            let mut answer = |t: usize, forwarded: bool, result: MtResult| {
                let (s, i) = (t % N, t / N);
                assert!(
                    i < queries[s].len() && taken[s][i].is_some(),
                    "cycle {cycle}: answer for tag {t}, never taken"
                );
                assert!(
                    fates[s][i].is_none(),
                    "cycle {cycle}: tag {t} answered twice"
                );
                fates[s][i] = Some(Fate {
                    taken: taken[s][i].unwrap(),
                    answered: cycle,
                    forwarded,
                    result,
                });
                answered += 1;
            };
            for s in 0..N {
                if uut.miss_valid[s].val() {
                    answer(
                        uut.miss_tag[s].val().to_u64() as usize,
                        false,
                        MtResult::default(),
                    );
                }
            }
            if uut.fp_valid.val() {
                let result = MtResult {
                    hit: uut.fp_hit.val(),
                    t: f32_of(uut.fp_t.val()),
                    u: f32_of(uut.fp_u.val()),
                    v: f32_of(uut.fp_v.val()),
                };
                answer(uut.fp_tag.val().to_u64() as usize, true, result);
            }
            let ready = uut.ready.val();
            if offered.iter().any(|&o| o) && !ready {
                stalls += 1;
            }
            for s in 0..N {
                if offered[s] && ready {
                    taken[s][next[s]] = Some(cycle);
                    next[s] += 1;
                }
            }
            uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut uut, 10_000), "logic did not settle");
            cycle += 1;
        }
        Run {
            fates: fates
                .into_iter()
                .map(|f| f.into_iter().map(Option::unwrap).collect())
                .collect(),
            stalls,
            cycles: cycle,
        }
    })
}

/// The model of a pair with `kind`'s filter.
fn model(kind: SlotFilter) -> DualIntersector {
    let pair = FormatPair::parse(&format!("bfp{WIDTH}/fp32")).unwrap();
    DualIntersector::with_filter(Filter::new(pair, kind.model_kind()))
}

const KINDS: [SlotFilter; 2] = [SlotFilter::Bfp, SlotFilter::Plucker];

/// Every answer is the model's bit for bit, on the port the model says (a certain miss on
/// the slot's miss port, the rest from the fp32 lane). Returns the forwarded count.
fn assert_model(kind: SlotFilter, queries: &[Vec<MtQuery>; N], run: &Run) -> usize {
    let model = model(kind);
    let mut forwarded = 0;
    for (s, (slot, fates)) in queries.iter().zip(&run.fates).enumerate() {
        let mut want = vec![MtResult::default(); slot.len()];
        model.intersect_batch(slot, &mut want).unwrap();
        for (i, (q, fate)) in slot.iter().zip(fates).enumerate() {
            let miss = model.filter.certain_miss(q, 1.0);
            assert_eq!(fate.forwarded, !miss, "slot {s} query {i}: {q:?}");
            assert!(
                fate.result.same_bits(&want[i]),
                "slot {s} query {i}: {:?} != model {:?} for {q:?}",
                fate.result,
                want[i]
            );
            forwarded += usize::from(fate.forwarded);
        }
    }
    forwarded
}

/// A ray aimed at the inside of a triangle: a hit, which the filter forwards.
fn hit(rng: &mut StdRng) -> MtQuery {
    let p = |rng: &mut StdRng| -> [f32; 3] { std::array::from_fn(|_| rng.gen_range(-4.0..4.0)) };
    let (a, b) = (rng.gen_range(0.1..0.4), rng.gen_range(0.1..0.4));
    MtQuery::aimed(p(rng), [p(rng), p(rng), p(rng)], (a, b), 0.0)
}

/// Queries of every kind, hits among them, into both slots with random gaps, for either
/// filter.
#[test]
fn streamed_queries_equal_the_model_and_each_is_answered_once() {
    for kind in KINDS {
        streamed(kind);
    }
}

fn streamed(kind: SlotFilter) {
    let mut rng = StdRng::seed_from_u64(91);
    let queries: [Vec<MtQuery>; N] = std::array::from_fn(|_| {
        (0..600)
            .map(|_| match rng.gen_range(0..8) {
                0 => random(&mut rng),
                1 => refused(&mut rng),
                2 | 3 => hit(&mut rng),
                _ => shaped(&mut rng),
            })
            .collect()
    });
    let mut gaps = StdRng::seed_from_u64(92);
    let run = run(kind, &queries, move |_, _| gaps.gen_range(0..4) != 0);
    let forwarded = assert_model(kind, &queries, &run);
    println!(
        "{kind:?}: {} queries, {forwarded} forwarded, {} cycles, {} stall cycles",
        2 * 600,
        run.cycles,
        run.stalls
    );
    assert!(forwarded > 300 && forwarded < 1000, "{forwarded} forwarded");
}

/// All hits, offered every cycle in both slots: twice what the fp32 lane takes. The queues
/// fill, `ready` falls, the lane answers one query every cycle and nothing is lost.
#[test]
fn a_forwarded_flood_holds_the_inputs_back_and_loses_nothing() {
    let mut rng = StdRng::seed_from_u64(93);
    let queries: [Vec<MtQuery>; N] =
        std::array::from_fn(|_| (0..300).map(|_| hit(&mut rng)).collect());
    let run = run(SlotFilter::Bfp, &queries, |_, _| true);
    assert_eq!(assert_model(SlotFilter::Bfp, &queries, &run), 600);
    assert!(run.stalls > 200, "{} stall cycles", run.stalls);
    // One answer a cycle from the first to the last: the lane never idles.
    let answers: Vec<usize> = run.fates.iter().flatten().map(|f| f.answered).collect();
    let (first, last) = (answers.iter().min().unwrap(), answers.iter().max().unwrap());
    assert_eq!(last - first + 1, 600, "the fp32 lane idled");
    // The slots share the lane fairly: neither finishes long before the other.
    let last_answer = |s: usize| run.fates[s].iter().map(|f| f.answered).max().unwrap();
    assert!(last_answer(0).abs_diff(last_answer(1)) <= 2);
    // Each slot filled its credits: `QUEUE_DEPTH` queries in its filter and queue, plus
    // those in the fp32 lane, and never more.
    let lane = <fp32::MtLane as Lane>::latency(DEPTH);
    for s in 0..N {
        let in_flight = |cycle: usize| {
            let fates = run.fates[s].iter();
            fates
                .filter(|f| f.taken <= cycle && f.answered > cycle)
                .count()
        };
        let most = (0..run.cycles).map(in_flight).max().unwrap();
        assert!(
            (QUEUE_DEPTH..=QUEUE_DEPTH + lane + 1).contains(&most),
            "slot {s}: {most} queries in flight"
        );
    }
}

/// Alone in the pair, a certain miss is answered `miss_latency` cycles after it is taken,
/// a forwarded query `forward_latency(kind, depth)`, for either filter.
#[test]
fn isolated_queries_take_the_documented_latencies() {
    for kind in KINDS {
        isolated(kind);
    }
}

fn isolated(kind: SlotFilter) {
    let mut rng = StdRng::seed_from_u64(94);
    let model = model(kind);
    let mut miss = shaped(&mut rng);
    while !model.filter.certain_miss(&miss, 1.0) {
        miss = shaped(&mut rng);
    }
    let queries: [Vec<MtQuery>; N] = [vec![miss, hit(&mut rng)], vec![hit(&mut rng)]];
    // Slot 0 offers at cycle 0 and 100, slot 1 at cycle 200: nothing overlaps.
    let run = run(kind, &queries, |cycle, s| {
        cycle == [0, 200][s] || (s == 0 && cycle == 100)
    });
    assert_model(kind, &queries, &run);
    let latency = |f: &Fate| f.answered - f.taken;
    assert_eq!(latency(&run.fates[0][0]), miss_latency(kind));
    assert_eq!(latency(&run.fates[0][1]), forward_latency(kind, DEPTH));
    assert_eq!(latency(&run.fates[1][0]), forward_latency(kind, DEPTH));
}

/// Its Verilog is what Vivado would read (the traversal unit's waiver, as for the filter),
/// also with one slot, whose one-bit vectors take no bit select; with either filter.
#[test]
fn verilog_passes_verilator_lint() {
    let verilogs = KINDS.map(|kind| [verilog::<1>(DEPTH, kind), verilog::<N>(DEPTH, kind)]);
    lint_clean(
        verilogs.as_flattened(),
        hdl::verilog::UNIT_VERILATOR_WAIVERS,
    );
}

/// yosys xc7 resources of two filters sharing an fp32 lane at depth 5 (the depth of the
/// fp32 lanes' figures in docs/precision.md):
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture dual_pair_resources`
#[test]
#[ignore]
fn dual_pair_resources() {
    println!(
        "{}",
        hdl::synth::markdown_table(&[verilog::<N>(5, SlotFilter::Bfp)]).unwrap()
    );
}

fn verilog<const S: usize>(depth: usize, kind: SlotFilter) -> (String, String) {
    hdl::top::with_build_stack(move || {
        named(DualPair::<S>::new(depth, kind), "DualPair", |_| {
            format!("{S} {kind:?} bfp{WIDTH} filters, fp32 depth {depth}")
        })
    })
}
