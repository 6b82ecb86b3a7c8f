//! The widths of every operator of a format, by name: the one place that says what each
//! operator's width parameters are and computes them.
//!
//! Why the operators take a list of single-letter const parameters rather than this struct:
//! rust-hdl 0.46 needs each width as a const generic (`Bits<W>`), and stable Rust cannot
//! compute one from another generic ("generic parameters may not be used in const
//! operations"), so neither `FloatAdd<F: FloatFormat>` with `Bits<{F::WORD}>` nor a
//! `FloatAdd<const F: FloatWidths>` compiles. Each derived width is therefore its own
//! parameter of the operator, and the format modules (`crate::formats`, `crate::fixed`) fill
//! the parameter lists from [`FloatWidths::of`] and [`FixedWidths::of`], whose fields name
//! them: those aliases are the one place the parameters are filled.

use crate::float::{recip, sqrt};

/// A float format's operator widths (exp = E, man = M bits). The letter is the parameter
/// the operators take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FloatWidths {
    /// `W` = 1 + E + M: a word (sign, exponent, fraction).
    pub word: usize,
    /// `S` = M + 1: a significand with its hidden bit.
    pub significand: usize,
    /// `X` = E + 2: a signed exponent with room for a result's overflow and underflow.
    pub exponent: usize,
    /// `A` = S + 3, `A1` = A + 1: the adder's aligned significand (guard, round and sticky
    /// bits) and its sum.
    pub aligned: usize,
    pub sum: usize,
    /// `S2` = 2·S: the multiplier's product of two significands.
    pub product: usize,
    /// The reciprocal's table and product widths.
    pub recip: RecipWidths,
    /// The square root's widths.
    pub sqrt: SqrtWidths,
}

/// The widths of `float::sqrt::FloatSqrt` (its docs derive them) for M fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SqrtWidths {
    /// `Q`: the root (significand, round bit and two more).
    pub root: usize,
    /// `R`: the partial remainder.
    pub remainder: usize,
    /// `RW`: the radicand's bits the rows bring down.
    pub radicand: usize,
}

/// The widths of `float::recip::FloatRecip` (its docs derive them) for M fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RecipWidths {
    /// `K`: the table index, the fraction's top bits.
    pub index: usize,
    /// `D`: d, the fraction below the index.
    pub d: usize,
    /// `YW`: the approximation Y without its top bit.
    pub y: usize,
    /// `BW`, `CW`: the linear and quadratic coefficients.
    pub b: usize,
    pub c: usize,
    /// `D2` = 2·D: d²; `D2H`: the bits of d² kept (at most a DSP input).
    pub d_squared: usize,
    pub d_squared_kept: usize,
    /// `P1` = BW + D, `P2` = CW + D2H: the products B·d and C·d².
    pub b_product: usize,
    pub c_product: usize,
    /// `PC` = 2·S: the rounding test's product sig·(2·frac + 1).
    pub rounding_product: usize,
}

impl FloatWidths {
    pub const fn of(exp: usize, man: usize) -> FloatWidths {
        let significand = man + 1;
        let aligned = significand + 3;
        FloatWidths {
            word: 1 + exp + man,
            significand,
            exponent: exp + 2,
            aligned,
            sum: aligned + 1,
            product: 2 * significand,
            recip: RecipWidths::of(man),
            sqrt: SqrtWidths {
                root: sqrt::root_bits(man),
                remainder: sqrt::remainder_bits(man),
                radicand: sqrt::radicand_bits(man),
            },
        }
    }
}

impl RecipWidths {
    pub const fn of(man: usize) -> RecipWidths {
        let d = recip::d_bits(man);
        let (b, c, kept) = (
            recip::b_bits(man),
            recip::c_bits(man),
            recip::square_bits(man),
        );
        RecipWidths {
            index: recip::index_bits(man),
            d,
            y: recip::y_bits(man),
            b,
            c,
            d_squared: 2 * d,
            d_squared_kept: kept,
            b_product: b + d,
            c_product: c + kept,
            rounding_product: 2 * (man + 1),
        }
    }
}

/// A fixed-point format's operator widths (W bits, F of them fraction).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FixedWidths {
    /// `W`: a word; `F`: its fraction bits.
    pub word: usize,
    pub frac: usize,
    /// `W1` = W + 1: the adder's sum before it is fitted.
    pub sum: usize,
    /// `P` = 2·W: the multiplier's full product.
    pub product: usize,
    /// `Q` = 2·F + 1: the reciprocal's quotient bits; `K` = max(2·F + 2, W): its signed
    /// quotient (±2^(2F) and every W-bit value fit).
    pub quotient: usize,
    pub signed_quotient: usize,
    /// `L` = W + 49, `K` = W + 3: fp32 → fixed's aligned significand and signed magnitude.
    pub from_f32_aligned: usize,
    pub from_f32_magnitude: usize,
    /// `G` = W + 25: fixed → fp32's normalized magnitude (fp32's significand and round bit).
    pub to_f32_normalized: usize,
}

impl FixedWidths {
    pub const fn of(width: usize, int: usize) -> FixedWidths {
        let frac = width - int;
        FixedWidths {
            word: width,
            frac,
            sum: width + 1,
            product: 2 * width,
            quotient: 2 * frac + 1,
            signed_quotient: if 2 * frac + 2 > width {
                2 * frac + 2
            } else {
                width
            },
            from_f32_aligned: width + 49,
            from_f32_magnitude: width + 3,
            to_f32_normalized: width + 25,
        }
    }
}
