//! Splits a float bit pattern into its fields and classifies it (subnormals flushed to zero).

use rust_hdl::prelude::*;

/// `x` = sign | exponent (E bits) | fraction (M bits), W = 1 + E + M, S = M + 1.
#[derive(LogicBlock)]
pub struct Unpack<const E: usize, const M: usize, const W: usize, const S: usize> {
    pub x: Signal<In, Bits<W>>,
    pub sign: Signal<Out, Bit>,
    /// The biased exponent field.
    pub exp: Signal<Out, Bits<E>>,
    /// The fraction with its hidden bit (set when the exponent field is not 0). A subnormal's
    /// is not flushed here: every operator treats it as zero by `zero`, which costs less than
    /// a mask on every significand bit (most operators decide a zero operand by its class).
    pub sig: Signal<Out, Bits<S>>,
    /// Zero or subnormal (exponent field 0).
    pub zero: Signal<Out, Bit>,
    pub inf: Signal<Out, Bit>,
    pub nan: Signal<Out, Bit>,
    frac: Signal<Local, Bits<M>>,
    frac_width: Constant<Bits<8>>,
    sign_position: Constant<Bits<8>>,
    exp_ones: Constant<Bits<E>>,
    hidden_bit: Constant<Bits<S>>,
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> Default
    for Unpack<E, M, W, S>
{
    fn default() -> Self {
        assert!(
            W == 1 + E + M && S == M + 1,
            "Unpack<{E}, {M}, {W}, {S}>: inconsistent widths"
        );
        Self {
            x: Default::default(),
            sign: Default::default(),
            exp: Default::default(),
            sig: Default::default(),
            zero: Default::default(),
            inf: Default::default(),
            nan: Default::default(),
            frac: Default::default(),
            frac_width: Constant::new(M.to_bits()),
            sign_position: Constant::new((W - 1).to_bits()),
            exp_ones: Constant::new(Bits::<E>::mask()),
            hidden_bit: Constant::new(Bits::<S>::from(1) << M as u64),
        }
    }
}

impl<const E: usize, const M: usize, const W: usize, const S: usize> Logic for Unpack<E, M, W, S> {
    #[hdl_gen]
    fn update(&mut self) {
        self.frac.next = bit_cast::<M, W>(self.x.val());
        self.exp.next = bit_cast::<E, W>(self.x.val() >> self.frac_width.val());
        self.sign.next = (self.x.val() >> self.sign_position.val()).any();
        self.zero.next = !self.exp.val().any();
        self.inf.next = (self.exp.val() == self.exp_ones.val()) & !self.frac.val().any();
        self.nan.next = (self.exp.val() == self.exp_ones.val()) & self.frac.val().any();
        self.sig.next = bit_cast::<S, M>(self.frac.val());
        if !self.zero.val() {
            self.sig.next = bit_cast::<S, M>(self.frac.val()) | self.hidden_bit.val();
        }
    }
}
