//! Brings an exact two's-complement result into a W-bit format: Wrap keeps the low W bits,
//! Sat clamps to [min, max] (the overflow modes of the SPEC in `hw_model::format`).

use rust_hdl::prelude::*;

/// `v`: a K-bit two's-complement value (K ≥ W); `y`: it in W bits; SAT: clamp instead of wrap.
#[derive(LogicBlock)]
pub struct Fit<const K: usize, const W: usize, const SAT: bool> {
    pub v: Signal<In, Bits<K>>,
    pub y: Signal<Out, Bits<W>>,
    /// Bits W-1 … K-1 of `v`: all equal exactly when `v` fits in W bits.
    top: Signal<Local, Bits<K>>,
    saturate: Constant<Bit>,
    range_shift: Constant<Bits<8>>,
    top_ones: Constant<Bits<K>>,
    sign_shift: Constant<Bits<8>>,
    max: Constant<Bits<W>>,
    min: Constant<Bits<W>>,
}

impl<const K: usize, const W: usize, const SAT: bool> Default for Fit<K, W, SAT> {
    fn default() -> Self {
        assert!(
            K >= W && K < 256,
            "Fit<{K}, {W}>: the value must be at least as wide as the format"
        );
        Self {
            v: Default::default(),
            y: Default::default(),
            top: Default::default(),
            saturate: Constant::new(SAT),
            range_shift: Constant::new((W - 1).to_bits()),
            top_ones: Constant::new(Bits::<K>::mask() >> (W - 1) as u64),
            sign_shift: Constant::new((K - 1).to_bits()),
            max: Constant::new(Bits::<W>::mask() >> 1),
            min: Constant::new(Bits::<W>::from(1) << (W - 1) as u64),
        }
    }
}

impl<const K: usize, const W: usize, const SAT: bool> Logic for Fit<K, W, SAT> {
    #[hdl_gen]
    fn update(&mut self) {
        self.top.next = self.v.val() >> self.range_shift.val();
        self.y.next = bit_cast::<W, K>(self.v.val());
        if self.saturate.val() & self.top.val().any() & (self.top.val() != self.top_ones.val()) {
            if (self.v.val() >> self.sign_shift.val()).any() {
                self.y.next = self.min.val();
            } else {
                self.y.next = self.max.val();
            }
        }
    }
}
