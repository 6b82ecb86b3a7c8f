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
