//! The integer multiplier leaf: `p = a * b`, unsigned, full width.
//!
//! rust-hdl's `*` only exists for 16×16 bits, so this one block is written by hand: the
//! simulation computes the product in Rust, the Verilog is a plain `always @(*) p = a * b;` that
//! synthesis maps onto DSP slices (24×24 → 2 DSP48E1 in yosys `synth_xilinx`). It is the
//! only custom-Verilog block of the operators.

use rust_hdl::prelude::*;

/// `P`-bit product of an `A`-bit and a `B`-bit unsigned operand (`P = A + B`, at most 128).
#[derive(LogicBlock)]
pub struct IntMul<const A: usize, const B: usize, const P: usize> {
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    pub p: Signal<Out, Bits<P>>,
}

impl<const A: usize, const B: usize, const P: usize> Default for IntMul<A, B, P> {
    fn default() -> Self {
        assert_eq!(
            P,
            A + B,
            "IntMul<{A}, {B}, {P}>: the product needs A + B bits"
        );
        assert!(P <= 128, "IntMul products are at most 128 bits");
        Self {
            a: Default::default(),
            b: Default::default(),
            p: Default::default(),
        }
    }
}

impl<const A: usize, const B: usize, const P: usize> Logic for IntMul<A, B, P> {
    fn update(&mut self) {
        let product = self.a.val().to_u128() * self.b.val().to_u128();
        let lo: Bits<P> = bits((product as u64) as LiteralType);
        let hi: Bits<P> = bits(((product >> 64) as u64) as LiteralType);
        // `<< 64` of a `P <= 64`-bit vector would overflow the shift: only wide products have a high half.
        self.p.next = if P > 64 { (hi << 64) | lo } else { lo };
    }

    fn connect(&mut self) {
        self.p.connect();
    }

    fn hdl(&self) -> Verilog {
        // Zero-extend both operands to the product width so the multiply is width-clean.
        Verilog::Custom(format!(
            "always @(*) p = {{{}'d0, a}} * {{{}'d0, b}};",
            P - A,
            P - B
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::IntMul;
    use rust_hdl::prelude::*;

    #[test]
    fn product_matches_u128() {
        let mut m = IntMul::<24, 24, 48>::default();
        m.connect_all();
        for (a, b) in [
            (0u64, 0u64),
            (1, 0xff_ffff),
            (0xff_ffff, 0xff_ffff),
            (0x80_0001, 0x7f_fff3),
        ] {
            m.a.next = a.into();
            m.b.next = b.into();
            assert!(simulate(&mut m, 10));
            assert_eq!(m.p.val().to_u64(), a * b);
        }
    }

    #[test]
    fn wide_product_keeps_the_high_half() {
        let mut m = IntMul::<40, 40, 80>::default();
        m.connect_all();
        let (a, b) = ((1u64 << 40) - 1, (1u64 << 40) - 3);
        m.a.next = a.into();
        m.b.next = b.into();
        assert!(simulate(&mut m, 10));
        let p = (a as u128) * (b as u128);
        assert_eq!(m.p.val().get_bits::<16>(64).to_u64() as u128, p >> 64);
        assert_eq!(
            m.p.val().get_bits::<64>(0).to_u64() as u128,
            p & u64::MAX as u128
        );
    }
}
