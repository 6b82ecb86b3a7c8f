//! The Plücker filter's sign decisions (docs/precision.md, "The Plücker filter"): the rows
//! of the bfp filter's step 5 ([`bfp::decide`]) made stronger, so that no value is
//! normalised, no two values are aligned and nothing is multiplied. Every row is a sign, or
//! a comparison of bit lengths plus grid exponents: with len(x) the bit length of x XOR
//! its sign ([`length`]), |x| lies in [2^(len − 1), 2^len] for x ≠ 0 and x < 2^len for
//! x ≥ 0, so a comparison of lengths proves the comparison of the values it stands for.
//! u + v > 1 is the third edge's sign: n_w = σ·N_w below −M_w (M_w from the other
//! margins' lengths, [`uv_margin`]). u > 1 is left to v and w (v + w = 1 − u). Each row
//! implies bfp's row on the same values and margins, so every certain miss here is one
//! there; the converse fails only by the factors of two the lengths give away.

use super::bfp::{det_epsilon, margin_bits, top, Fx, Rows, N_U};
use super::bfp::{FLUSH_SHIFT, QUOTIENT_MAX, RECIPROCAL_MIN};

/// The bit length of x XOR its sign (0 for 0 and −1).
pub fn length(x: i128) -> i32 {
    (128 - (x ^ (x >> 127)).leading_zeros()) as i32
}

/// 2^EPS_EXP ≤ the fallback's eps: H < 2^EPS_EXP decides the parallel row.
pub fn eps_exp() -> i32 {
    top(det_epsilon()) - 1
}

/// The smallest t_min exponent whose τ' = t_min − 1 ulp ([`bfp::t_min_below`]): below,
/// τ' = t_min − 2^-126, which may be 0 or negative.
pub const T_NORMAL_MIN: i32 = RECIPROCAL_MIN + 23;

/// What the t row knows of τ' ≤ t_min − λ (the bfp filter's [`bfp::t_min_below`]) from
/// t_min's fp32 fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tau {
    /// NaN, ±Inf or a negative normal t_min: the row decides nothing.
    Unknown,
    /// 0 ≤ t_min < 2^[`T_NORMAL_MIN`] (zeros and subnormals read as 0): τ' ≥ −2^-126.
    Small,
    /// t_min ≥ 2^[`T_NORMAL_MIN`]: τ' ≥ 2^p, p its exponent, one less for a power of two.
    AtLeast(i32),
}

impl Tau {
    pub fn of(t_min: f32) -> Tau {
        let bits = t_min.to_bits();
        let field = ((bits >> 23) & 0xff) as i32;
        let exp = field - 127;
        if field == 0xff || field != 0 && bits >> 31 != 0 {
            Tau::Unknown
        } else if field == 0 || exp < T_NORMAL_MIN {
            Tau::Small
        } else {
            Tau::AtLeast(exp - i32::from(bits & 0x7f_ffff == 0))
        }
    }
}

/// M_w in units of N_w's last bit 2^`lw`: N_w's own margin `own` (its dots, its alignment)
/// plus, for det, N_u and N_v (margins e at grids L), 2^(len(e) + 1 + L − lw) rounded up
/// to a unit: each ≥ 2e·2^(L − lw), the margin of a value and its filter's error again
/// (which the margin includes). `None` if a shift exceeds [`uv_shift_max`], where M_w
/// would leave [`margin_bits`] of N_u (the row then decides nothing).
pub fn uv_margin(own: i128, lw: i32, others: [(i128, i32); 3], width: u32) -> Option<i128> {
    others.iter().try_fold(own, |sum, &(e, l)| {
        let s = length(e) + 1 + l - lw;
        (s <= uv_shift_max(width)).then(|| sum + if s >= 0 { 1 << s } else { 1 })
    })
}

/// The largest shift of M_w's terms: three of 2^(MB − 3) and N_w's own margin (its dots'
/// part, below 2^(MB − 2)) stay below 2^MB.
pub const fn uv_shift_max(width: u32) -> i32 {
    margin_bits(width, N_U) as i32 - 3
}

/// The rows for det and the numerators N_u, N_v, N_t (values at their last bits'
/// exponents, margins in units of those bits, as [`bfp::decide`] takes them), N_w with its
/// own margin, and the query's t_min. With D = |det|, σ = sign(det), n = σN, H = D + e_D,
/// L = D − e_D, hi = n + e, reach = |n| + e and grids written as exponents:
/// - parallel: len(H) + L_D ≤ [`eps_exp`];
/// - in range: L > 0, len(L) − 1 + L_D ≥ −126, len(H) + L_D ≤ 125 and, for u, v, t,
///   len(reach) + L_x ≤ len(L) − 1 + L_D + 125;
/// - u < 0: hi_u < 0 and len(H) + L_D − 124 ≤ len(hi_u) − 1 + L_u; v likewise;
/// - u + v > 1: n_w + M_w < 0 ([`uv_margin`]);
/// - t ≤ t_min ([`Tau`]): for τ' ≥ 2^p, hi_t ≤ 0 or len(hi_t) + L_t ≤ p + len(L) − 1 + L_D;
///   for τ' ≥ −2^-126, hi_t < 0 and len(H) + L_D − 126 ≤ len(hi_t) − 1 + L_t.
pub fn decide(
    det: (Fx, i128),
    nums: [(Fx, i128); 3],
    w: (Fx, i128),
    t_min: f32,
    width: u32,
) -> Rows {
    let ((det, e_d), l_d) = (det, det.0.e);
    let d = det.m.abs();
    let (high, low) = (d + e_d, d - e_d);
    let sigma = det.m.signum();
    let [u, v, t] = nums.map(|(n, e)| (sigma * n.m, e, n.e));
    let hi = |(n, e, _): (i128, i128, i32)| n + e;
    let (lh, ll) = (length(high) + l_d, length(low) - 1 + l_d);
    let in_range = low > 0
        && ll >= RECIPROCAL_MIN
        && lh <= QUOTIENT_MAX
        && [u, v, t]
            .iter()
            .all(|&(n, e, l)| length(n.abs() + e) + l <= ll + QUOTIENT_MAX);
    let below_zero = |x| hi(x) < 0 && lh + FLUSH_SHIFT <= length(hi(x)) - 1 + x.2;
    let uv_above = uv_margin(w.1, w.0.e, [(e_d, l_d), (u.1, u.2), (v.1, v.2)], width)
        .is_some_and(|m| sigma * w.0.m + m < 0);
    let t_below = match Tau::of(t_min) {
        Tau::Unknown => false,
        Tau::Small => hi(t) < 0 && lh + RECIPROCAL_MIN <= length(hi(t)) - 1 + t.2,
        Tau::AtLeast(p) => hi(t) <= 0 || length(hi(t)) + t.2 <= p + ll,
    };
    Rows {
        parallel: lh <= eps_exp(),
        in_range,
        u_below: below_zero(u),
        u_above: false,
        v_below: below_zero(v),
        uv_above,
        t_below,
    }
}

#[cfg(test)]
mod tests {
    use super::super::bfp;
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// |x| lies in [2^(len − 1), 2^len] for x ≠ 0, x < 2^len for x ≥ 0.
        #[test]
        fn lengths_bound_magnitudes(x in -(1i128 << 60)..(1i128 << 60)) {
            let l = length(x);
            prop_assume!(x != 0);
            prop_assert!(x.unsigned_abs() >= 1u128 << (l - 1).max(0) || l == 0);
            prop_assert!(x.unsigned_abs() <= 1u128 << l);
            if x > 0 {
                prop_assert!(x < 1i128 << l);
            }
        }

        /// τ' (bfp's, exactly) is at least what the class claims.
        #[test]
        fn tau_classes_bound_tau(bits in any::<u32>()) {
            let t_min = f32::from_bits(bits);
            let tau = bfp::t_min_below(t_min);
            match Tau::of(t_min) {
                Tau::Unknown => {}
                Tau::Small => {
                    let tau = tau.unwrap();
                    prop_assert!(!tau.lt(Fx::new(-1, RECIPROCAL_MIN)));
                }
                Tau::AtLeast(p) => {
                    let tau = tau.unwrap();
                    prop_assert!(!tau.lt(Fx::new(1, p)), "{} {:?}", t_min, tau);
                }
            }
        }
    }

    /// The classes' edges: every power of two and its neighbours, of either sign.
    #[test]
    fn tau_classes_bound_tau_at_powers_of_two() {
        for e in -149..128 {
            let x = 2f32.powi(e);
            for t in [
                x,
                f32::from_bits(x.to_bits() + 1),
                f32::from_bits(x.to_bits() - 1),
            ] {
                for t in [t, -t].into_iter().filter(|t| t.is_finite()) {
                    let (tau, class) = (bfp::t_min_below(t).unwrap(), Tau::of(t));
                    match class {
                        Tau::Unknown => assert!(t < 0.0, "{t}"),
                        Tau::Small => assert!(!tau.lt(Fx::new(-1, RECIPROCAL_MIN)), "{t}"),
                        Tau::AtLeast(p) => assert!(!tau.lt(Fx::new(1, p)), "{t} {p}"),
                    }
                }
            }
        }
    }

    #[test]
    fn eps_exp_is_below_eps() {
        let eps = f64::from(crate::mt::DET_EPSILON);
        assert!(2f64.powi(eps_exp()) <= eps && 2f64.powi(eps_exp() + 1) > eps);
    }

    /// Every sign row implies the exact row it stands for (bfp's rows before their
    /// roundings outward, which only weaken them): H < eps; L > 0, L ≥ 2^-126,
    /// H < 2^125, |n| + e < L·2^125; hi < 0 and −hi ≥ H·2^-124; hi_t < τ'·(L if τ' ≥ 0
    /// else H). (u + v > 1 rests on its own argument, docs/precision.md.)
    #[test]
    fn rows_imply_the_exact_rows() {
        use proptest::test_runner::TestRunner;
        let value = (-(1i128 << 40)..(1i128 << 40), -160i32..100, 0i128..1 << 20);
        let strategy = (
            value.clone(),
            [value.clone(), value.clone(), value],
            prop_oneof![
                Just(0.0f32),
                Just(1e-3f32),
                Just(0.5f32),
                1e-6f32..10.0,
                any::<u32>().prop_map(f32::from_bits)
            ],
        );
        let decided = std::cell::Cell::new(0);
        TestRunner::default()
            .run(&strategy, |((dm, de, dmar), nums, t_min)| {
                let det = (Fx::new(dm, de), dmar);
                let nums = nums.map(|(m, e, mar)| (Fx::new(m, e), mar));
                // A w that never decides.
                let w = (Fx::new(0, 0), 1i128 << 50);
                let rows = decide(det, nums, w, t_min, 18);
                let at = |m: i128, e: i32| Fx::new(m, e);
                let d = dm.abs();
                let (high, low) = (at(d + dmar, de), at(d - dmar, de));
                let sigma = dm.signum();
                let scaled = |x: Fx, k: i32| Fx::new(x.m, x.e + k);
                prop_assert!(!rows.parallel || high.lt(det_epsilon()));
                if !rows.in_range {
                    return Ok(());
                }
                prop_assert!(low.m > 0 && !low.lt(Fx::new(1, RECIPROCAL_MIN)));
                prop_assert!(high.lt(Fx::new(1, QUOTIENT_MAX)));
                for (n, e) in nums {
                    let reach = at((sigma * n.m).abs() + e, n.e);
                    prop_assert!(reach.lt(scaled(low, QUOTIENT_MAX)));
                }
                for (row, (n, e)) in [(rows.u_below, nums[0]), (rows.v_below, nums[1])] {
                    let hi = sigma * n.m + e;
                    prop_assert!(!row || hi < 0 && !at(-hi, n.e).lt(scaled(high, FLUSH_SHIFT)));
                }
                if rows.t_below {
                    let (n, e) = nums[2];
                    let tau = bfp::t_min_below(t_min).unwrap();
                    let bound = if tau.m >= 0 { low } else { high };
                    let product = Fx::new(tau.m * bound.m, tau.e + bound.e);
                    prop_assert!(at(sigma * n.m + e, n.e).lt(product));
                    decided.set(decided.get() + 1);
                }
                Ok(())
            })
            .unwrap();
        assert!(decided.get() > 0, "no t row decided");
    }
}
