//! The integer multiplier leaf: `p = a * b`, full width, unsigned ([`IntMul`]) or two's
//! complement ([`SignedMul`]).
//!
//! rust-hdl's `*` only exists for 16×16 bits, so this one block is written by hand: the
//! simulation computes the product in Rust, the Verilog is a plain `always @(*) p = a * b;`
//! that synthesis maps onto DSP slices (24×24 unsigned → 2 DSP48E1, 18×18 or 25×18 signed
//! → 1, in yosys `synth_xilinx`). It is the only custom-Verilog block of the operators.

use rust_hdl::prelude::*;

/// `P`-bit product of an `A`-bit and a `B`-bit operand (`P = A + B`, at most 128: the
/// product of the two largest operands needs all of them, unsigned or signed), both
/// unsigned or, with `SIGNED`, both two's complement. Use it by its two names.
#[derive(LogicBlock)]
pub struct Mul<const A: usize, const B: usize, const P: usize, const SIGNED: bool> {
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    pub p: Signal<Out, Bits<P>>,
}

/// The unsigned product (the float and fixed operators' significands, the filter's τ'·bound
/// on magnitudes).
pub type IntMul<const A: usize, const B: usize, const P: usize> = Mul<A, B, P, false>;

/// The two's-complement product. The bfp filter's cross products and dots (`crate::dual`)
/// multiply signed mantissas; as a signed product an 18×18 or 25×18 one is a single DSP48E1
/// (yosys `synth_xilinx`), where an unsigned one of the magnitudes would need sign logic
/// around it and a 19×19 or 26×19 port.
pub type SignedMul<const A: usize, const B: usize, const P: usize> = Mul<A, B, P, true>;

impl<const A: usize, const B: usize, const P: usize, const SIGNED: bool> Default
    for Mul<A, B, P, SIGNED>
{
    fn default() -> Self {
        let name = if SIGNED { "SignedMul" } else { "IntMul" };
        assert_eq!(
            P,
            A + B,
            "{name}<{A}, {B}, {P}>: the product needs A + B bits"
        );
        assert!(P <= 128, "{name} products are at most 128 bits");
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

impl<const A: usize, const B: usize, const P: usize, const SIGNED: bool> Logic
    for Mul<A, B, P, SIGNED>
{
    fn update(&mut self) {
        let (a, b) = (self.a.val().to_u128(), self.b.val().to_u128());
        let product = if SIGNED {
            // Exact in i128 (|a·b| ≤ 2^(P−2) ≤ 2^126); its low P bits are the two's complement.
            (sign_extended(a, A) * sign_extended(b, B)) as u128 & (u128::MAX >> (128 - P))
        } else {
            a * b
        };
        let lo: Bits<P> = bits((product as u64) as LiteralType);
        let hi: Bits<P> = bits(((product >> 64) as u64) as LiteralType);
        // `<< 64` of a `P <= 64`-bit vector would overflow the shift: only wide products have a high half.
        self.p.next = if P > 64 { (hi << 64) | lo } else { lo };
    }

    fn connect(&mut self) {
        self.p.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(if SIGNED {
            // Both operands signed: the expression takes p's width and sign-extends them to it.
            "always @(*) p = $signed(a) * $signed(b);".into()
        } else {
            // Zero-extend both operands to the product width so the multiply is width-clean.
            format!("always @(*) p = {{{}'d0, a}} * {{{}'d0, b}};", P - A, P - B)
        })
    }
}

/// The DSP48E1's multiply-add: `p = c + a·b` with `a` a `A`-bit two's complement value, `b` a
/// `B`-bit unsigned one and `c` and `p` 48-bit two's complement (the post-adder's width; the
/// caller keeps the sum within it). With `A ≤ 25` and `B ≤ 17` the product fits the DSP's
/// 25×18 signed multiplier and yosys `synth_xilinx` maps the whole expression onto one
/// DSP48E1, its C port feeding the post-adder, and registers around it into the DSP's
/// input (B) and output (P) registers.
#[derive(LogicBlock)]
pub struct MulAdd<const A: usize, const B: usize> {
    pub a: Signal<In, Bits<A>>,
    pub b: Signal<In, Bits<B>>,
    pub c: Signal<In, Bits<48>>,
    pub p: Signal<Out, Bits<48>>,
}

impl<const A: usize, const B: usize> Default for MulAdd<A, B> {
    fn default() -> Self {
        assert!(
            A <= 25 && B <= 17,
            "MulAdd<{A}, {B}>: one DSP48E1 multiplies 25-bit signed by 17-bit unsigned values"
        );
        Self {
            a: Default::default(),
            b: Default::default(),
            c: Default::default(),
            p: Default::default(),
        }
    }
}

impl<const A: usize, const B: usize> Logic for MulAdd<A, B> {
    fn update(&mut self) {
        let a = sign_extended(self.a.val().to_u128(), A);
        let b = self.b.val().to_u128() as i128;
        let c = sign_extended(self.c.val().to_u128(), 48);
        let p = (c + a * b) as u128 & ((1 << 48) - 1);
        self.p.next = (p as u64).into();
    }

    fn connect(&mut self) {
        self.p.connect();
    }

    fn hdl(&self) -> Verilog {
        // `b` zero-extended by one bit is a signed operand; the sum takes p's 48 bits and
        // sign-extends the other operands to it.
        Verilog::Custom("always @(*) p = $signed(c) + $signed(a) * $signed({1'b0, b});".into())
    }
}
