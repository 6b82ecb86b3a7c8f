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
