//! A pixel coordinate (an unsigned integer of [`COORD_BITS`]) → its fp32 value, exactly
//! (`hw_model::fp32::Fp32::of_int`): every integer below 2^24 is an fp32, so there is nothing
//! to round. The leading one goes to the hidden bit: shift left by the leading zeros, exponent
//! 127 + 31 − zeros; 0 gives +0.
//!
//! Cut point (max_stages() = 1): the result.

use rust_hdl::prelude::*;

use hw_model::frame::FrameLimits;

use crate::float::leading_zeros::LeadingZeros;
use crate::pipe::{placement, Pipe};

/// Bits of a pixel coordinate i or j: the widest the frame unit renders, less one.
pub const COORD_BITS: usize = 11;
const _: () =
    assert!(FrameLimits::HW.width <= 1 << COORD_BITS && FrameLimits::HW.height <= 1 << COORD_BITS);
// The kernel spells the width as a literal (rust-hdl leaks named consts into Verilog).
const _: () = assert!(COORD_BITS == 11);

/// Exponent field of 2^31: a word whose leading one is `zeros` below bit 31 is 2^(31 − zeros).
const EXPONENT_OF_BIT_31: u64 = 127 + 31;

#[derive(LogicBlock)]
pub struct CoordToFp32 {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<COORD_BITS>>,
    pub y: Signal<Out, Bits<32>>,
    zeros: LeadingZeros,
    /// The leading one at bit 31.
    aligned: Signal<Local, Bits<32>>,
    exponent: Signal<Local, Bits<32>>,
    result: Pipe<Bits<32>>,
    exponent_of_bit_31: Constant<Bits<32>>,
    fraction: Constant<Bits<32>>,
}

impl CoordToFp32 {
    pub const CUTS: usize = 1;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            a: Default::default(),
            y: Default::default(),
            zeros: Default::default(),
            aligned: Default::default(),
            exponent: Default::default(),
            result: Pipe::new(cut[0]),
            exponent_of_bit_31: Constant::new(EXPONENT_OF_BIT_31.into()),
            fraction: Constant::new(0x7F_FFFFu64.into()),
        }
    }
}

impl Logic for CoordToFp32 {
    #[hdl_gen]
    fn update(&mut self) {
        // The kernel reads `a` (not a local copy of it) beside the count: Verilator then sees
        // no loop through the leading-zeros block.
        self.zeros.x.next = bit_cast::<32, 11>(self.a.val());
        self.aligned.next = bit_cast::<32, 11>(self.a.val()) << self.zeros.count.val();
        self.exponent.next =
            self.exponent_of_bit_31.val() - bit_cast::<32, 8>(self.zeros.count.val());
        clock!(self, clock, result);
        // Exponent above bit 23, the 23 bits below the leading one as the fraction.
        self.result.d.next =
            (self.exponent.val() << 23) | ((self.aligned.val() >> 8) & self.fraction.val());
        if !self.a.val().any() {
            self.result.d.next = 0.into();
        }
        self.y.next = self.result.q.val();
    }
}

crate::impl_operator!(unary CoordToFp32, [], COORD_BITS, 32, out = bits);
