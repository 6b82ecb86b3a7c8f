//! The division-free filter (docs/precision.md, "The division-free filter"): the filter
//! computes det and the numerators of u, v, t, but no reciprocal and no quotient, and
//! decides the fallback's tests by comparing the numerators with det. Its bound can be
//! evaluated in a coarse float ([`BoundArith::Coarse`]) from the fp32 subtractors' rounding
//! bound, so every step is something a small hardware bound network can compute.

use sw_renderer::intersect::{MtQuery, MtResult};

use super::{
    coords, filter_input, holds_fp32, product_bounds, BoundArith, Bounded, Ctx, Fed, Filter,
    Rounding, BV, F64_SLACK,
};
use crate::mt::mt_traced;

/// `a < b` even after f64's roundings of the products and sums that formed them.
pub(super) fn certainly_below(a: f64, b: f64) -> bool {
    a < b - (a.abs() + b.abs()) * 1e-12
}

/// The filter's inputs to the products: dir, e1 = v1', e2 = v2', s = orig' of the fed
/// (translated, scaled) query, converted into the filter's format (v0' = 0, so its
/// subtractions are exact).
fn filter_inputs(fed: &[[Fed; 3]; 5], c: &Ctx, exact: bool) -> [BV; 4] {
    let load = |i: usize| fed[i].map(|x| Bounded::input(x, c, exact));
    [load(1), load(3), load(4), load(0)]
}

/// The fallback's inputs to the products: dir as given, and e1, e2, s as it subtracts them
/// from the query as given (`given`), within the translated values `fed` (scene units).
/// Converting a coordinate into a fallback that does not hold fp32 costs a rounding of
/// its untranslated magnitude.
fn fallback_inputs(given: &[[f64; 3]; 5], fed: &[[Fed; 3]; 5], c: &Ctx, holds: bool) -> [BV; 4] {
    let conv = |x: f64| if holds { 0.0 } else { c.error(x.abs()) };
    let dir = std::array::from_fn(|k| {
        let x = given[1][k];
        c.bounded(x.abs(), conv(x))
    });
    let edge = |i: usize| -> BV {
        std::array::from_fn(|k| {
            let carried = conv(given[i][k]) + conv(given[2][k]);
            let mag = c.up(fed[i][k].value.abs() + fed[i][k].off);
            c.bounded(mag, carried + c.error(mag + carried))
        })
    };
    [dir, edge(3), edge(4), edge(0)]
}

impl Filter {
    /// [`Filter::decide`] for [`super::FilterKind::Linear`]. With D, N the exact det and
    /// numerators, the filter's D_A, N_A and the error bounds e_D, e_N of filter plus
    /// fallback (so |D_B − D_A| ≤ e_D, |N_B − N_A| ≤ e_N), σ = sign(D_A), L = |D_A| − e_D > 0,
    /// H = |D_A| + e_D, and the fallback's quotient x_B = fl(N_B·fl(1/D_B)) within
    /// 3u·|N_B/D_B| + λ of N_B/D_B (no overflow, reciprocal not flushed):
    /// - u_B < 0 if σN_uA + e_u < 0 and |σN_uA + e_u|(1 − u) ≥ 2λH (not flushed to −0);
    /// - u_B > 1 if σN_uA − e_u > H(1 + 3u) (fl(x) > 1 needs x > 1 + u);
    /// - v likewise;
    /// - u_B + v_B > 1 + u if σ(N_uA + N_vA) − e_u − e_v − 3u(|N_uA| + |N_vA| + e_u + e_v)
    ///   > H(1 + u + 4λ);
    /// - t_B ≤ t_min if σN_tA + e_t + 3u(|N_tA| + e_t) ≤ τ·(L if τ ≥ 0 else H),
    ///   τ = t_min − λ.
    pub(super) fn decide_linear(
        &self,
        q: &MtQuery,
        margin_scale: f64,
        arith: BoundArith,
    ) -> Option<MtResult> {
        let given = coords(q);
        if given.iter().flatten().any(|x| !x.is_finite()) {
            return None;
        }
        // An exact bound may use the subtractions' exact errors; a hardware one knows their
        // rounding bound only.
        let known_offsets = arith == BoundArith::Exact;
        let (fed_query, fed) = filter_input(q, self.scale_exp, known_offsets)?;
        let c = 2f64.powi(self.scale_exp);
        let fed_b = fed.map(|v| {
            v.map(|f| Fed {
                value: f.value / c,
                off: f.off / c,
            })
        });
        let (filter, a) = self.float_filter();
        let ca = Ctx { r: a, arith };
        let cb = Ctx { r: self.b, arith };
        let (det_a, num_a) =
            product_bounds(filter_inputs(&fed, &ca, holds_fp32(&filter)), &[], &ca)?;
        let (det_b, num_b) = product_bounds(
            fallback_inputs(&given, &fed_b, &cb, holds_fp32(&self.pair.fallback)),
            &[],
            &cb,
        )?;
        let (_, x) = mt_traced(&filter, &fed_query);
        // det and the numerators are of degree 3 in lengths: back to scene units.
        let unscale = c.powi(-3);
        let margin = |a: Bounded, b: Bounded| (a.err * unscale + b.err) * margin_scale * F64_SLACK;
        let d = x.det * unscale;
        let e_d = margin(det_a, det_b);
        let n = x.num.map(|v| v * unscale);
        let e: [f64; 3] = std::array::from_fn(|k| margin(num_a[k], num_b[k]));
        self.decide_numerators(q, d, e_d, n, e)
    }

    /// The fallback's tests decided from a filter's det `d` and numerators `n` of u, v, t
    /// (scene units), each within `e_d`, `e` of the fallback's (the table of
    /// [`Filter::decide_linear`]); a certain miss answers zeros (the filter computes no t,
    /// u, v).
    pub(super) fn decide_numerators(
        &self,
        q: &MtQuery,
        d: f64,
        e_d: f64,
        n: [f64; 3],
        e: [f64; 3],
    ) -> Option<MtResult> {
        let miss = Some(MtResult::default());
        if certainly_below(d.abs() + e_d, self.eps_b) {
            return miss;
        }
        if !n.iter().all(|v| v.is_finite()) || !certainly_below(e_d, d.abs()) {
            return None;
        }
        let Rounding { unit: u, tiny, max } = self.b;
        let (low, high) = (d.abs() - e_d, d.abs() + e_d);
        // No reciprocal overflows or flushes, no quotient overflows.
        let in_range = certainly_below(1.0, low * max / 2.0)
            && certainly_below(2.0 * tiny * high, 1.0)
            && (0..3).all(|k| certainly_below(n[k].abs() + e[k], low * max / 4.0));
        if !in_range {
            return None;
        }
        let sigma = d.signum();
        let [nu, nv, nt] = n.map(|v| sigma * v);
        // Strictly below is what f64 can certify, and it implies "at most".
        let below_zero = |n: f64, e: f64| {
            certainly_below(n + e, 0.0) && certainly_below(2.0 * tiny * high, -(n + e) * (1.0 - u))
        };
        let above_one = |n: f64, e: f64| certainly_below(high * (1.0 + 3.0 * u), n - e);
        let uv_low = nu + nv - e[0] - e[1] - 3.0 * u * (nu.abs() + nv.abs() + e[0] + e[1]);
        let t_min = self.fallback_t_min(q);
        let tau = t_min - tiny;
        let t_high = nt + e[2] + 3.0 * u * (nt.abs() + e[2]);
        let certain = below_zero(nu, e[0])
            || above_one(nu, e[0])
            || below_zero(nv, e[1])
            || certainly_below(high * (1.0 + u + 4.0 * tiny), uv_low)
            || (t_min.is_finite()
                && certainly_below(t_high, tau * if tau >= 0.0 { low } else { high }));
        if certain {
            miss
        } else {
            None
        }
    }
}
