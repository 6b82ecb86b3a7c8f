//! Dual precision against its fallback: filter + fallback answers every query as the
//! fallback alone (random queries aimed at the tests' edges, whole renders of the thesis'
//! scenes), a margin below the derived bound is caught wrongly rejecting hits, and bad
//! pairs are clear errors.

use hw_model::dual::{DualError, DualIntersector, Filter, FilterKind, FormatChoice, FormatPair};
use hw_model::precision::SpawnChoice;
use hw_model::{lookup, mt_model, FormatError, ModelIntersector, MtQuery, MtResult};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use sw_renderer::intersect::Intersector;
use sw_renderer::rays::RayEngine;
use sw_renderer::render::{render, RenderOptions};
use sw_renderer::scene::Scene;
use sw_renderer::thesis_scenes;

type P = [f32; 3];

fn add(a: P, b: P) -> P {
    std::array::from_fn(|k| a[k] + b[k])
}
fn sub(a: P, b: P) -> P {
    std::array::from_fn(|k| a[k] - b[k])
}
fn scale(a: P, s: f32) -> P {
    a.map(|x| x * s)
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: P) -> f32 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// `x` moved by up to `ulps` fp32 ulps either way.
fn nudge(r: &mut StdRng, x: f32, ulps: i32) -> f32 {
    let k = r.gen_range(-ulps..=ulps);
    if x == 0.0 {
        k as f32 * f32::EPSILON * 0.5
    } else {
        f32::from_bits((x.to_bits() as i32 + k) as u32)
    }
}

/// A barycentric pair (a, b) on or within a few ulps of an edge of the triangle (a = 0,
/// b = 0, a = 1, a + b = 1), or anywhere near it.
fn near_edge(r: &mut StdRng) -> (f32, f32) {
    let x: f32 = r.gen_range(-0.2..1.2);
    match r.gen_range(0..5) {
        0 => (nudge(r, 0.0, 4), x),
        1 => (x, nudge(r, 0.0, 4)),
        2 => (nudge(r, 1.0, 4), nudge(r, 0.0, 4)),
        3 => (x, nudge(r, 1.0 - x, 4)),
        _ => (x, r.gen_range(-0.2..1.2)),
    }
}

fn point(r: &mut StdRng, size: f32) -> P {
    std::array::from_fn(|_| r.gen_range(-size..size))
}

/// One query of a mix: rays at barycentric edges, near-parallel rays (det near the
/// fallback's 1e-8 threshold), grazing rays, origins on the plane (t near 0), random rays;
/// scenes from 2^-12 to 2^12 units; thin and large triangles; t_min 0, random or near t.
fn query(r: &mut StdRng) -> MtQuery {
    // Mostly scene-like sizes, some far outside a narrow format's range.
    let size = 2f32.powi(if r.gen_bool(0.7) {
        r.gen_range(-3..=3)
    } else {
        r.gen_range(-12..=12)
    });
    let v0 = point(r, size);
    let spread = size * 2f32.powi(-r.gen_range(0..8));
    let (v1, v2) = (add(v0, point(r, spread)), add(v0, point(r, spread)));
    let (e1, e2) = (sub(v1, v0), sub(v2, v0));
    let n = cross(e1, e2);
    let n_len = norm(n).max(f32::MIN_POSITIVE);
    let (a, b) = near_edge(r);
    let target = add(v0, add(scale(e1, a), scale(e2, b)));
    let kind = r.gen_range(0..5);
    let orig = match kind {
        // On the plane (a few ulps off): t near 0 for any direction.
        3 => target.map(|x| nudge(r, x, 2)),
        _ => add(target, point(r, size * 4.0)),
    };
    let dir = match kind {
        // In the plane plus a component making det ≈ ±(0.25..4)·1e-8.
        1 | 2 => {
            let w = if r.gen_bool(0.5) { e1 } else { e2 };
            let det = if kind == 1 {
                r.gen_range(0.25..4.0) * 1e-8
            } else {
                r.gen_range(1e-4..1e-2) * norm(w) * n_len
            };
            let sign = if r.gen_bool(0.5) { 1.0 } else { -1.0 };
            add(w, scale(n, sign * det / (n_len * n_len)))
        }
        3 => point(r, 1.0),
        _ => sub(target, orig),
    };
    // A hit needs t > t_min: mostly the reference's 0, some spawn-like t_min, some near the
    // hit's t (1 for the aimed rays).
    let t_min = match r.gen_range(0..8) {
        0 => r.gen_range(0.0..2.0),
        1 => nudge(r, 1.0, 4),
        _ => 0.0,
    };
    MtQuery {
        orig,
        dir,
        v0,
        v1,
        v2,
        t_min,
    }
}

fn queries(seed: u64, n: usize) -> Vec<MtQuery> {
    let mut r = StdRng::seed_from_u64(seed);
    (0..n).map(|_| query(&mut r)).collect()
}

fn pair(s: &str) -> FormatPair {
    FormatPair::parse(s).unwrap()
}

/// The queries where the fallback hits: what a filter must never reject.
fn fallback_hits(pair: &FormatPair, qs: &[MtQuery]) -> Vec<(MtQuery, MtResult)> {
    per_chunk(qs, |chunk| {
        chunk
            .iter()
            .map(|q| (*q, mt_model(&pair.fallback, q)))
            .filter(|(_, r)| r.hit)
            .collect::<Vec<_>>()
    })
    .concat()
}

/// A filter under test and its pairs: `main` takes the long random run, `extra` 10^5 of its
/// queries, `margin` the margin and render tests, `largest` the ignored report; `rejects_at`
/// a margin scale shown to reject fallback hits (the largest such scale is 0.14–0.32 for
/// every filter and pair: the ignored report).
struct Case {
    kind: FilterKind,
    main: &'static str,
    extra: &'static [&'static str],
    margin: &'static [&'static str],
    largest: &'static [&'static str],
    rejects_at: f64,
}

/// The filters hardware builds: block floating point, and block floating point in Plücker
/// form with sign decisions.
const CASES: [Case; 2] = [
    Case {
        kind: FilterKind::Bfp,
        main: "bfp18/fp32",
        extra: &["bfp14/fp32", "bfp8/fp32", "bfp24/fp32"],
        margin: &["bfp18/fp32", "bfp14/fp32"],
        largest: &["bfp14/fp32", "bfp16/fp32", "bfp18/fp32", "bfp20/fp32"],
        rejects_at: 0.2,
    },
    Case {
        kind: FilterKind::Plucker,
        main: "bfp18/fp32",
        extra: &["bfp14/fp32", "bfp8/fp32", "bfp24/fp32"],
        margin: &["bfp18/fp32", "bfp14/fp32"],
        largest: &["bfp14/fp32", "bfp18/fp32", "bfp24/fp32"],
        rejects_at: 0.2,
    },
];

fn filter(p: &str, kind: FilterKind) -> Filter {
    Filter::new(pair(p), kind)
}

/// `f` over `items` in one contiguous chunk per core, results in chunk order. The checks
/// are per query on queries made beforehand from one seed, so a failure names the same
/// query whatever the split; a chunk's panic is re-raised as it was.
fn per_chunk<T: Sync, R: Send>(items: &[T], f: impl Fn(&[T]) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let size = items.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        let chunks: Vec<_> = items.chunks(size).map(|c| s.spawn(|| f(c))).collect();
        chunks
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}

/// Dual == fallback on every query: `hit` always, t, u, v bits on every fallback hit.
/// Returns the share the filter decided alone.
fn check_equal(filter: Filter, qs: &[MtQuery]) -> f64 {
    let pair = filter.pair;
    let dual = DualIntersector::with_filter(filter);
    let hits: usize = per_chunk(qs, |chunk| {
        let mut got = vec![MtResult::default(); chunk.len()];
        dual.intersect_batch(chunk, &mut got).unwrap();
        let mut hits = 0;
        for (q, g) in chunk.iter().zip(&got) {
            let want = mt_model(&pair.fallback, q);
            assert_eq!(g.hit, want.hit, "{filter:?}: {q:?}");
            if want.hit {
                hits += 1;
                assert!(g.same_bits(&want), "{pair}: {q:?}: {g:?} vs {want:?}");
            }
        }
        hits
    })
    .into_iter()
    .sum();
    let stats = dual.stats();
    assert_eq!(stats.tests, qs.len() as u64);
    assert!(hits > qs.len() / 10, "{pair}: only {hits} hits");
    1.0 - stats.forwarded_share()
}

#[test]
fn filter_and_fallback_equal_the_fallback_on_a_million_queries() {
    let qs = queries(17, 1_000_000);
    for case in &CASES {
        let kind = case.kind;
        let decided = check_equal(filter(case.main, kind), &qs);
        // Not vacuous: the filter decides a share alone (most queries are built to be close
        // calls).
        assert!(
            decided > 0.02,
            "{} {kind:?} decided only {decided:.3}",
            case.main
        );
        println!("{} {kind:?}: {decided:.3} decided by the filter", case.main);
        let some = &qs[..100_000];
        for &p in case.extra {
            let decided = check_equal(filter(p, kind), some);
            assert!(decided > 0.02, "{p} {kind:?} decided only {decided:.3}");
            println!("{p} {kind:?}: {decided:.3} decided by the filter");
        }
    }
}

/// The margin is the bound, not a bound with room to spare: with a fifth of it the same kind
/// of queries hold hits the filter would reject.
#[test]
fn a_fraction_of_the_margin_rejects_hits() {
    let qs = queries(17, 300_000);
    for case in &CASES {
        for &p in case.margin {
            let filter = filter(p, case.kind);
            let hits = fallback_hits(&filter.pair, &qs);
            let wrong = hits
                .iter()
                .filter(|(q, _)| filter.certain_miss(q, case.rejects_at))
                .count();
            assert!(
                wrong > 0,
                "{p} {:?}: no hit rejected with {} of the margin",
                case.kind,
                case.rejects_at
            );
            assert!(hits.iter().all(|(q, _)| !filter.certain_miss(q, 1.0)));
        }
    }
}

/// Queries where the exact u (or v) is negative but so small that the fallback's quotient
/// flushes to −0, so fp32 hits: v0 = (λ, 0, 0), e1 = (2s, 0, 0), e2 = (0, 2s, 0), the ray
/// along z through x = 0, a hair outside the u = 0 edge: det = −4s², N_u = 2sλ, u = −λ/(2s),
/// v = 0, t = s; with v and u swapped, and mirrored.
fn flushed_quotients() -> Vec<MtQuery> {
    let tiny = f32::MIN_POSITIVE;
    let mut qs = Vec::new();
    for k in [0, 3, 6, 9] {
        let s = 2f32.powi(k);
        let base = MtQuery {
            orig: [0.0, 0.0, -s],
            dir: [0.0, 0.0, 1.0],
            v0: [tiny, 0.0, 0.0],
            v1: [2.0 * s, 0.0, 0.0],
            v2: [tiny, 2.0 * s, 0.0],
            t_min: 0.0,
        };
        let swapped = MtQuery {
            v1: base.v2,
            v2: base.v1,
            ..base
        };
        let mirrored = |q: MtQuery| MtQuery {
            orig: [-q.orig[0], q.orig[1], q.orig[2]],
            v0: [-q.v0[0], q.v0[1], q.v0[2]],
            v1: [-q.v1[0], q.v1[1], q.v1[2]],
            v2: [-q.v2[0], q.v2[1], q.v2[2]],
            ..q
        };
        qs.extend([base, swapped, mirrored(base), mirrored(swapped)]);
    }
    qs
}

/// A flushed quotient makes the fallback hit where exact arithmetic misses; every filter
/// must leave such a query to the fallback. (Here the margins already cover N_u, so this
/// does not show the flush guards of the u < 0 and v < 0 tests necessary: removing the
/// Plücker filter's guard still passes. With 1/1000 of its margin the bfp filter does
/// reject these hits.)
#[test]
fn flushed_quotients_are_left_to_the_fallback() {
    let qs = flushed_quotients();
    let fp32 = lookup("fp32").unwrap();
    assert!(
        qs.iter().all(|q| mt_model(&fp32, q).hit),
        "the fallback should hit every flushed-quotient query"
    );
    for case in &CASES {
        let pairs = std::iter::once(&case.main)
            .chain(case.extra)
            .chain(case.margin)
            .chain(case.largest);
        for &p in pairs {
            let filter = filter(p, case.kind);
            for q in &qs {
                assert!(!filter.certain_miss(q, 1.0), "{p} {:?}: {q:?}", case.kind);
            }
        }
    }
    // Not vacuous: the hits are close enough calls that a too-small margin rejects them.
    let bfp = filter("bfp18/fp32", FilterKind::Bfp);
    assert!(qs.iter().any(|q| bfp.certain_miss(q, 1e-3)));
}

/// How much of the bound the worst of these queries needs: the largest margin scale (on a
/// grid of 1/100, then 1/1000 below 0.01) at which some fallback hit is rejected.
/// `--ignored`: it prints the numbers docs/precision.md reports.
#[test]
#[ignore]
fn largest_margin_scale_that_rejects_a_hit() {
    let qs = queries(17, 100_000);
    for case in &CASES {
        for &p in case.largest {
            let filter = filter(p, case.kind);
            let hits = fallback_hits(&filter.pair, &qs);
            let rejects = |scale: f64| hits.iter().any(|(q, _)| filter.certain_miss(q, scale));
            assert!(!rejects(1.0), "{p} {:?} rejects a hit", case.kind);
            let grid = (1..100)
                .rev()
                .map(|k| k as f64 / 100.0)
                .chain((1..10).rev().map(|k| k as f64 / 1000.0));
            let largest = grid.into_iter().find(|&s| rejects(s));
            println!(
                "{p} {:?}: largest rejecting margin scale {largest:?}",
                case.kind
            );
        }
    }
}

fn render_small(scene: &Scene, engine: &dyn RayEngine) -> image::RgbImage {
    let opts = RenderOptions {
        width: Some(64),
        height: Some(36),
        progress: false,
        ..Default::default()
    };
    render(scene, engine, &opts).unwrap().image
}

#[test]
fn dual_renders_of_the_thesis_scenes_equal_the_fallbacks() {
    let Some(root) =
        thesis_scenes::for_test("dual::dual_renders_of_the_thesis_scenes_equal_the_fallbacks")
    else {
        return;
    };
    let fp32 = ModelIntersector::new(lookup("fp32").unwrap());
    for name in thesis_scenes::SCENE_DIRS {
        let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
        let want = render_small(&scene, &fp32);
        for case in &CASES {
            for &p in case.margin {
                let kind = case.kind;
                let dual = DualIntersector::with_filter(filter(p, kind));
                let got = render_small(&scene, &dual);
                assert!(
                    got.as_raw() == want.as_raw(),
                    "{name} {p} {kind:?}: images differ"
                );
                let s = dual.stats();
                assert!(s.certain_misses > 0, "{name} {p} {kind:?}: {s:?}");
            }
        }
    }
}

#[test]
fn bad_pairs_are_clear_errors() {
    let err = |s: &str| FormatPair::parse(s).unwrap_err();
    for bad in ["fp16/", "/fp32", "a/b/c", "bfp18//fp32", "/"] {
        assert!(matches!(err(bad), DualError::Malformed(_)), "{bad}");
    }
    // A float filter is no filter of a pair.
    for bad in ["fp16/fp32", "e6m13/fp32", "fp32/fp16", "fx32_16/fp32"] {
        let e = err(bad);
        assert!(matches!(e, DualError::NotBfp { .. }), "{bad}: {e:?}");
        assert!(
            e.to_string().contains("is not block floating point") && e.to_string().contains(bad),
            "{e}"
        );
    }
    for bad in [
        "bfp7/fp32",
        "bfp25/fp32",
        "bfp/fp32",
        "bfpx/fp32",
        "bfp-18/fp32",
    ] {
        let e = err(bad);
        assert!(matches!(e, DualError::BfpWidth { .. }), "{bad}: {e:?}");
        assert!(e.to_string().contains("8 to 24 bits"), "{e}");
    }
    for bad in ["bfp18/fp16", "bfp18/fp24", "bfp18/fx32_16"] {
        let e = err(bad);
        assert!(matches!(e, DualError::BfpFallback { .. }), "{bad}: {e:?}");
        assert!(e.to_string().contains("holds fp32"), "{e}");
    }
    match err("bfp18/xyz") {
        DualError::Half { half, source, .. } => {
            assert_eq!(half, "fallback");
            assert!(matches!(source, FormatError::Unknown(_)));
        }
        e => panic!("{e:?}"),
    }
    assert!(err("bfp18/xyz").to_string().contains("xyz"));
    // Spelled as a format: a `/` makes it a pair; the engines pick the bfp filter for it.
    let choice: FormatChoice = " BFP18 / fp32 ".parse().unwrap();
    assert_eq!(choice, FormatChoice::Pair(pair("bfp18/fp32")));
    assert_eq!(choice.to_string(), "bfp18/fp32");
    assert_eq!(
        "fp16".parse::<FormatChoice>().unwrap(),
        FormatChoice::Single(lookup("fp16").unwrap())
    );
    let p = pair("bfp18/fp32");
    assert_eq!(p.filter_width, 18);
    assert_eq!(
        Intersector::name(&DualIntersector::new(p)),
        "model bfp18/fp32"
    );
    assert_eq!(DualIntersector::new(p).filter.kind, FilterKind::Bfp);
    assert_eq!(pair("bfp14/e8m30").to_string(), "bfp14/e8m30");
    // The filters by their CLI names.
    for kind in FilterKind::ALL {
        assert_eq!(kind.to_string().parse::<FilterKind>(), Ok(kind));
    }
    assert_eq!(FilterKind::Plucker.to_string(), "plucker-signs");
    let e = "linear".parse::<FilterKind>().unwrap_err();
    assert!(e.contains("bfp or plucker-signs"), "{e}");
}

/// What any filter must forward on a query, for the floors below: the fp32 answer is a hit,
/// or the ray passes inside the triangle's edges in exact arithmetic (estimated in f64 from
/// the fp32 coordinates) and only t (t ≤ t_min) makes it a miss.
#[derive(Default)]
struct Floors {
    tests: std::sync::atomic::AtomicU64,
    forwarded: std::sync::atomic::AtomicU64,
    hits: std::sync::atomic::AtomicU64,
    inside: std::sync::atomic::AtomicU64,
    /// The Plücker filter's ([`FloorCounter::plucker`]): tests it would forward, fp32 hits it
    /// would have rejected.
    plucker: [std::sync::atomic::AtomicU64; 2],
}

/// bfp18/fp32 with [`Floors`] counted beside it, and what the Plücker filter would forward.
struct FloorCounter {
    dual: DualIntersector,
    plucker: Filter,
    floors: Floors,
}

/// Exact-arithmetic Möller-Trumbore edge test (u ≥ 0, v ≥ 0, u + v ≤ 1, det ≠ 0), in f64.
fn inside_edges(q: &MtQuery) -> bool {
    let f = |a: P| a.map(f64::from);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (v0, d) = (f(q.v0), f(q.dir));
    let (e1, e2, s) = (sub(f(q.v1), v0), sub(f(q.v2), v0), sub(f(q.orig), v0));
    let p = cross(d, e2);
    let det = dot(e1, p);
    let sigma = det.signum();
    let (nu, nv) = (sigma * dot(s, p), sigma * dot(d, cross(s, e1)));
    det != 0.0 && nu >= 0.0 && nv >= 0.0 && nu + nv <= det.abs()
}

impl Intersector for FloorCounter {
    fn name(&self) -> String {
        Intersector::name(&self.dual)
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), sw_renderer::rays::EngineError> {
        use std::sync::atomic::Ordering::Relaxed;
        self.dual.intersect_batch(queries, results)?;
        // Counted here, not from the shared counters, which other threads' batches move too.
        let forwarded = queries
            .iter()
            .filter(|q| !self.dual.filter.certain_miss(q, 1.0))
            .count() as u64;
        let hits = results.iter().filter(|r| r.hit).count() as u64;
        let inside = queries
            .iter()
            .zip(results.iter())
            .filter(|(q, r)| r.hit || inside_edges(q))
            .count() as u64;
        let f = &self.floors;
        let [plucker_forwarded, plucker_rejected] = &f.plucker;
        for (q, r) in queries.iter().zip(results.iter()) {
            let miss = self.plucker.certain_miss(q, 1.0);
            plucker_forwarded.fetch_add(u64::from(!miss), Relaxed);
            plucker_rejected.fetch_add(u64::from(miss && r.hit), Relaxed);
        }
        f.tests.fetch_add(queries.len() as u64, Relaxed);
        f.forwarded.fetch_add(forwarded, Relaxed);
        f.hits.fetch_add(hits, Relaxed);
        f.inside.fetch_add(inside, Relaxed);
        Ok(())
    }
}

/// The forwarded share's floors on the thesis scenes at 320×180 under both spawn policies
/// (as the fp32 renders spawn): any filter forwards the fp32 hits; a filter that decides only
/// the edge tests (no t test) also forwards the misses inside the edges. Beside them, what
/// bfp18/fp32 and its Plücker filter forward. `--ignored`: it prints the table
/// docs/precision.md reports.
#[test]
#[ignore]
fn forwarding_floors_on_the_thesis_scenes() {
    use std::sync::atomic::Ordering::Relaxed;
    let Some(root) = thesis_scenes::for_test("dual::forwarding_floors_on_the_thesis_scenes") else {
        return;
    };
    println!(
        "| policy | scene | tests | fp32 hits | hits or inside the edges | bfp18/fp32 forwards | Plücker (`plucker-signs`) forwards |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|");
    for choice in [SpawnChoice::Thesis, SpawnChoice::FormatAware] {
        let opts = RenderOptions {
            width: Some(320),
            height: Some(180),
            spawn: choice.policy(&lookup("fp32").unwrap(), 0),
            ..Default::default()
        };
        let mut total = [0u64; 5];
        let row = |scene: &str, n: [u64; 5]| {
            let share = |k: usize| n[k] as f64 / n[0].max(1) as f64;
            println!(
                "| {choice} | {scene} | {} | {:.4} | {:.4} | {:.4} | {:.4} |",
                n[0],
                share(1),
                share(2),
                share(3),
                share(4)
            );
        };
        for name in thesis_scenes::SCENE_DIRS {
            let scene = Scene::load(root.join(name).to_str().unwrap()).unwrap();
            let counter = FloorCounter {
                dual: DualIntersector::new(pair("bfp18/fp32")),
                plucker: filter("bfp18/fp32", FilterKind::Plucker),
                floors: Floors::default(),
            };
            render(&scene, &counter, &opts).unwrap();
            let f = &counter.floors;
            let n = [&f.tests, &f.hits, &f.inside, &f.forwarded, &f.plucker[0]]
                .map(|c| c.load(Relaxed));
            // The floors are floors: a filter that forwarded less would have dropped a hit.
            assert!(
                n[3..].iter().all(|&k| n[1] <= k) && n[1] <= n[2],
                "{name}: {n:?}"
            );
            assert_eq!(
                f.plucker[1].load(Relaxed),
                0,
                "{name}: an fp32 hit rejected"
            );
            row(name, n);
            for k in 0..5 {
                total[k] += n[k];
            }
        }
        row("all", total);
    }
}
