//! The closest-hit update: whether a Möller-Trumbore result counts for its ray, and whether it
//! replaces the ray's nearest hit so far — `sw_renderer::hit`'s `Window::counts` and
//! `nearer`, in hardware.
//!
//! A result counts when `hit && t_min < t && t < bound && t < FLT_MAX`; it is nearer when no
//! hit is kept yet, or `t < best_t`, or `t == best_t` with a lower global triangle index. The
//! comparisons are IEEE fp32 order on the words (NaN compares false, −0 equals +0, subnormals
//! are ordered), the renderer's `f32` comparisons: t is never subnormal (the lanes flush), but
//! a ray's `t_min` and bound are the renderer's. The excluded triangle and, for an any-hit
//! ray, the triangles that cast no shadow are never tested (the unit skips them when it
//! issues a leaf, as `hw_model::traversal` does), so they are not this block's concern.
//!
//! Combinational: the unit registers around it.

use rust_hdl::prelude::*;

/// IEEE fp32 `a < b` and `a == b` on the words.
#[derive(LogicBlock)]
pub struct F32Order {
    pub a: Signal<In, Bits<32>>,
    pub b: Signal<In, Bits<32>>,
    pub lt: Signal<Out, Bit>,
    pub eq: Signal<Out, Bit>,
    abs_a: Signal<Local, Bits<32>>,
    abs_b: Signal<Local, Bits<32>>,
    /// Neither is NaN.
    ordered: Signal<Local, Bit>,
    both_zero: Signal<Local, Bit>,
    abs_mask: Constant<Bits<32>>,
    inf: Constant<Bits<32>>,
    zero: Constant<Bits<32>>,
}

impl Default for F32Order {
    fn default() -> Self {
        Self {
            a: Default::default(),
            b: Default::default(),
            lt: Default::default(),
            eq: Default::default(),
            abs_a: Default::default(),
            abs_b: Default::default(),
            ordered: Default::default(),
            both_zero: Default::default(),
            abs_mask: Constant::new(0x7FFF_FFFFu64.into()),
            inf: Constant::new(u64::from(f32::INFINITY.to_bits()).into()),
            zero: Constant::new(0.into()),
        }
    }
}

impl Logic for F32Order {
    #[hdl_gen]
    fn update(&mut self) {
        self.abs_a.next = self.a.val() & self.abs_mask.val();
        self.abs_b.next = self.b.val() & self.abs_mask.val();
        self.ordered.next =
            (self.abs_a.val() <= self.inf.val()) & (self.abs_b.val() <= self.inf.val());
        self.both_zero.next = (self.abs_a.val() | self.abs_b.val()) == self.zero.val();
        // Sign-magnitude: a negative a is below a positive b unless both are zeros; two
        // positives order like their magnitudes, two negatives the other way round.
        self.lt.next = self.ordered.val()
            & !self.both_zero.val()
            & ((self.a.val().get_bit(31) & !self.b.val().get_bit(31))
                | (!self.a.val().get_bit(31)
                    & !self.b.val().get_bit(31)
                    & (self.abs_a.val() < self.abs_b.val()))
                | (self.a.val().get_bit(31)
                    & self.b.val().get_bit(31)
                    & (self.abs_b.val() < self.abs_a.val())));
        self.eq.next = self.ordered.val() & ((self.a.val() == self.b.val()) | self.both_zero.val());
    }
}

#[derive(LogicBlock)]
pub struct HitUpdate {
    /// The lane's result for one triangle: hit flag and t (fp32 word).
    pub hit: Signal<In, Bit>,
    pub t: Signal<In, Bits<32>>,
    pub triangle: Signal<In, Bits<32>>,
    /// The ray's window: hits need `t_min < t < bound`.
    pub t_min: Signal<In, Bits<32>>,
    pub bound: Signal<In, Bits<32>>,
    /// The ray's nearest hit so far (`best_valid` low: none yet).
    pub best_valid: Signal<In, Bit>,
    pub best_t: Signal<In, Bits<32>>,
    pub best_triangle: Signal<In, Bits<32>>,
    /// The result is a hit of the ray.
    pub counts: Signal<Out, Bit>,
    /// It counts and is nearer than the kept hit: it becomes the ray's nearest hit.
    pub closer: Signal<Out, Bit>,
    above_t_min: F32Order,
    below_bound: F32Order,
    below_max: F32Order,
    against_best: F32Order,
    flt_max: Constant<Bits<32>>,
}

impl Default for HitUpdate {
    fn default() -> Self {
        Self {
            hit: Default::default(),
            t: Default::default(),
            triangle: Default::default(),
            t_min: Default::default(),
            bound: Default::default(),
            best_valid: Default::default(),
            best_t: Default::default(),
            best_triangle: Default::default(),
            counts: Default::default(),
            closer: Default::default(),
            above_t_min: Default::default(),
            below_bound: Default::default(),
            below_max: Default::default(),
            against_best: Default::default(),
            flt_max: Constant::new(u64::from(f32::MAX.to_bits()).into()),
        }
    }
}

impl Logic for HitUpdate {
    #[hdl_gen]
    fn update(&mut self) {
        self.above_t_min.a.next = self.t_min.val();
        self.above_t_min.b.next = self.t.val();
        self.below_bound.a.next = self.t.val();
        self.below_bound.b.next = self.bound.val();
        // FLT_MAX: the reference's kInfinity, which a hit must stay below.
        self.below_max.a.next = self.t.val();
        self.below_max.b.next = self.flt_max.val();
        self.against_best.a.next = self.t.val();
        self.against_best.b.next = self.best_t.val();
        self.counts.next = self.hit.val()
            & self.above_t_min.lt.val()
            & self.below_bound.lt.val()
            & self.below_max.lt.val();
        self.closer.next = self.counts.val()
            & (!self.best_valid.val()
                | self.against_best.lt.val()
                | (self.against_best.eq.val() & (self.triangle.val() < self.best_triangle.val())));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};
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
}
