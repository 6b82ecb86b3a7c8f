//! The bit length of an unsigned integer: the position of its leading one plus one, 0 for
//! 0 (`hw_model::dual::signs::length` of a non-negative value; a signed value's caller
//! passes it XOR its sign). x lies in [2^(len − 1), 2^len). Combinational: the sign
//! decisions hold the registers.

use rust_hdl::prelude::*;

/// Bits of a length: any input of up to 127 bits.
pub const LENGTH_BITS: usize = 7;

#[derive(LogicBlock)]
pub struct BitLength<const N: usize> {
    pub x: Signal<In, Bits<N>>,
    pub len: Signal<Out, Bits<LENGTH_BITS>>,
    one: Constant<Bits<LENGTH_BITS>>,
}

impl<const N: usize> Default for BitLength<N> {
    fn default() -> Self {
        assert!(
            N < 1 << LENGTH_BITS,
            "{N} bits: a length fits {LENGTH_BITS} bits"
        );
        Self {
            x: Default::default(),
            len: Default::default(),
            one: Constant::new(1u64.to_bits()),
        }
    }
}

impl<const N: usize> Logic for BitLength<N> {
    #[hdl_gen]
    fn update(&mut self) {
        self.len.next = 0.into();
        for i in 0..N {
            if self.x.val().get_bit(i) {
                self.len.next = i.to_bits() + self.one.val();
            }
        }
    }
}
