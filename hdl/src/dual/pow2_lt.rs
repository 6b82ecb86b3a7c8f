//! Step 5 of the bfp filter, its comparator against a power of two: x < 2^k for a short
//! float x and a wired k, bit for bit `hw_model::dual::bfp::Fx::lt(x, Fx::new(1, k))`. A
//! negative or zero x is below any power of two; a positive x = m·2^e lies in
//! [2^(t−1), 2^t) with t = e + bit count of m, so x < 2^k exactly when t ≤ k: one bit count
//! and one exponent comparison, no negation and no normalising shift as in [`ShortLt`]
//! (`super::short_lt`). Combinational: `Decide` holds the registers.

use rust_hdl::prelude::*;

use super::round::{SHORT_EXP_BITS, SHORT_M_BITS};

/// `lt` = x < 2^k for x = `xm`·2^`xe` (a short float) and the k of [`Pow2Lt::new`].
#[derive(LogicBlock)]
pub struct Pow2Lt {
    pub xm: Signal<In, Bits<SHORT_M_BITS>>,
    pub xe: Signal<In, Bits<SHORT_EXP_BITS>>,
    pub lt: Signal<Out, Bit>,
    /// k, offset binary (the sign bit flipped: signed order is unsigned order).
    k: Constant<Bits<SHORT_EXP_BITS>>,
    sign: Constant<Bits<SHORT_M_BITS>>,
    one_e: Constant<Bits<SHORT_EXP_BITS>>,
    exp_sign: Constant<Bits<SHORT_EXP_BITS>>,
    /// The bit count of m (only a positive m's matters) and t = e + it, offset binary (not
    /// `top`: the name of the module when this block is synthesised alone).
    len: Signal<Local, Bits<SHORT_EXP_BITS>>,
    lead: Signal<Local, Bits<SHORT_EXP_BITS>>,
}

impl Pow2Lt {
    /// The comparator against 2^`k`.
    pub fn new(k: i32) -> Self {
        let exp = |v: i64| Constant::new(((v as u64) & ((1 << SHORT_EXP_BITS) - 1)).to_bits());
        assert!(
            (k as i64).unsigned_abs() < 1 << (SHORT_EXP_BITS - 1),
            "2^{k}: k fits the short exponents"
        );
        Self {
            xm: Default::default(),
            xe: Default::default(),
            lt: Default::default(),
            k: exp(i64::from(k) ^ (1 << (SHORT_EXP_BITS - 1))),
            sign: Constant::new((1u64 << (SHORT_M_BITS - 1)).to_bits()),
            one_e: exp(1),
            exp_sign: exp(1 << (SHORT_EXP_BITS - 1)),
            len: Default::default(),
            lead: Default::default(),
        }
    }
}

impl Logic for Pow2Lt {
    #[hdl_gen]
    fn update(&mut self) {
        self.len.next = 0.into();
        for i in 0..SHORT_M_BITS {
            if self.xm.val().get_bit(i) {
                self.len.next = i.to_bits() + self.one_e.val();
            }
        }
        self.lead.next = (self.xe.val() + self.len.val()) ^ self.exp_sign.val();
        // Negative or zero: below. (A negative m's bit count is never read.)
        self.lt.next = (self.xm.val() & self.sign.val()).any()
            || !self.xm.val().any()
            || self.lead.val() <= self.k.val();
    }
}
