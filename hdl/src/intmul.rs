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

/// `P`-bit product of an `A`-bit and a `B`-bit two's-complement operand (`P = A + B`, at
/// most 128: the product of the two most negative operands, 2^(A+B−2), needs all of them).
/// The bfp filter's cross products and dots (`crate::dual`) multiply signed mantissas; as a
/// signed product an 18×18 or 25×18 one is a single DSP48E1 (yosys `synth_xilinx`), where an
/// unsigned one of the magnitudes would need sign logic around it and a 19×19 or 26×19 port.
#[derive(LogicBlock)]
pub struct SignedMul<const A: usize, const B: usize, const P: usize> {
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    pub p: Signal<Out, Bits<P>>,
}

impl<const A: usize, const B: usize, const P: usize> Default for SignedMul<A, B, P> {
    fn default() -> Self {
        assert_eq!(
            P,
            A + B,
            "SignedMul<{A}, {B}, {P}>: the product needs A + B bits"
        );
        assert!(P <= 128, "SignedMul products are at most 128 bits");
        Self {
            a: Default::default(),
            b: Default::default(),
            p: Default::default(),
        }
    }
}

/// The low `width` bits of `x` (at most 128) as a signed integer.
fn sign_extended(x: u128, width: usize) -> i128 {
    let shift = 128 - width as u32;
    ((x << shift) as i128) >> shift
}

impl<const A: usize, const B: usize, const P: usize> Logic for SignedMul<A, B, P> {
    fn update(&mut self) {
        let a = sign_extended(self.a.val().to_u128(), A);
        let b = sign_extended(self.b.val().to_u128(), B);
        // Exact in i128 (|a·b| ≤ 2^(P−2) ≤ 2^126); its low P bits are the two's complement.
        let product = (a * b) as u128 & (u128::MAX >> (128 - P));
        let lo: Bits<P> = bits((product as u64) as LiteralType);
        let hi: Bits<P> = bits(((product >> 64) as u64) as LiteralType);
        self.p.next = if P > 64 { (hi << 64) | lo } else { lo };
    }

    fn connect(&mut self) {
        self.p.connect();
    }

    fn hdl(&self) -> Verilog {
        // Both operands signed: the expression takes p's width and sign-extends them to it.
        Verilog::Custom("always @(*) p = $signed(a) * $signed(b);".into())
    }
}
