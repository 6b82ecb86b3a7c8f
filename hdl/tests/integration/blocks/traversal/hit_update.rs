//! `hdl::traversal::hit_update`.

use hdl::traversal::hit_update::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;
use sw_renderer::hit::{nearer, Hit, Window};
use sw_renderer::intersect::MtResult;

/// Words that exercise every branch of the order: zeros of both signs, subnormals,
/// FLT_MAX, infinities, NaNs of both signs, and neighbours of 1.
const SPECIAL: [u32; 14] = [
    0x0000_0000,
    0x8000_0000,
    0x0000_0001,
    0x8000_0001,
    0x007F_FFFF,
    0x3F80_0000,
    0x3F80_0001,
    0x3F7F_FFFF,
    0xBF80_0000,
    0x7F7F_FFFF,
    0x7F80_0000,
    0xFF80_0000,
    0x7FC0_0000,
    0xFFC0_0001,
];

fn word(rng: &mut StdRng) -> u32 {
    match rng.gen_range(0..4) {
        0 => SPECIAL[rng.gen_range(0..SPECIAL.len())],
        1 => rng.gen(),
        // Nearby positive values, so that equal and adjacent t's are common.
        _ => 0x3F80_0000 + rng.gen_range(0..4),
    }
}

fn settle<T: Block>(uut: &mut T) {
    assert!(simulate(uut, 100), "did not settle");
}

#[test]
fn order_is_ieee_order() {
    let mut uut = F32Order::default();
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(1);
    let pairs = SPECIAL
        .iter()
        .flat_map(|&a| SPECIAL.iter().map(move |&b| (a, b)))
        .chain((0..20_000).map(|_| (word(&mut rng), word(&mut rng))))
        .collect::<Vec<_>>();
    for (a, b) in pairs {
        uut.a.next = u64::from(a).into();
        uut.b.next = u64::from(b).into();
        settle(&mut uut);
        let (x, y) = (f32::from_bits(a), f32::from_bits(b));
        assert_eq!(uut.lt.val(), x < y, "{x:e} < {y:e} ({a:#x}, {b:#x})");
        assert_eq!(uut.eq.val(), x == y, "{x:e} == {y:e} ({a:#x}, {b:#x})");
    }
}

#[test]
fn update_is_the_renderers_reduction() {
    let mut uut = HitUpdate::default();
    uut.connect_all();
    let mut rng = StdRng::seed_from_u64(2);
    let (mut counted, mut closer) = (0, 0);
    for _ in 0..20_000 {
        let r = MtResult {
            hit: rng.gen_bool(0.8),
            t: f32::from_bits(word(&mut rng)),
            u: 0.25,
            v: 0.5,
        };
        let triangle = rng.gen_range(0..8u32);
        let window = Window {
            t_min: f32::from_bits(word(&mut rng)),
            bound: f32::from_bits(word(&mut rng)),
            exclude: None,
        };
        let best = rng.gen_bool(0.7).then(|| Hit {
            triangle: rng.gen_range(0..8),
            t: f32::from_bits(word(&mut rng)),
            u: 0.0,
            v: 0.0,
        });
        uut.hit.next = r.hit;
        uut.t.next = u64::from(r.t.to_bits()).into();
        uut.triangle.next = u64::from(triangle).into();
        uut.t_min.next = u64::from(window.t_min.to_bits()).into();
        uut.bound.next = u64::from(window.bound.to_bits()).into();
        uut.best_valid.next = best.is_some();
        uut.best_t.next = u64::from(best.map_or(0, |h| h.t.to_bits())).into();
        uut.best_triangle.next = u64::from(best.map_or(0, |h| h.triangle)).into();
        settle(&mut uut);

        let counts = window.counts(triangle, &r);
        let candidate = Hit {
            triangle,
            t: r.t,
            u: r.u,
            v: r.v,
        };
        // `nearer` keeps the old hit on a tie it wins; the candidate replaces it only
        // when the reduction's answer is the candidate and differs from the old one.
        let want_closer = counts
            && nearer(best, Some(candidate)).map(|h| (h.triangle, h.t.to_bits()))
                == Some((triangle, r.t.to_bits()))
            && best.map(|h| (h.triangle, h.t.to_bits())) != Some((triangle, r.t.to_bits()));
        assert_eq!(uut.counts.val(), counts, "{r:?} {window:?}");
        assert_eq!(
            uut.closer.val(),
            want_closer,
            "{r:?} {triangle} vs {best:?}"
        );
        counted += usize::from(counts);
        closer += usize::from(want_closer);
    }
    assert!(
        counted > 1_000 && closer > 500,
        "{counted} counted, {closer} closer"
    );
}
