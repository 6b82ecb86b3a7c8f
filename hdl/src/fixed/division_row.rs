//! One row of a restoring divider (the fixed-point reciprocal's): doubles the partial
//! remainder and subtracts the divisor if it fits, shifting the quotient bit in.

use rust_hdl::prelude::*;

/// One row of the restoring divider: doubles the partial remainder and subtracts the
/// divisor if it fits, shifting the quotient bit into `q`.
#[derive(LogicBlock)]
pub struct DivisionRow<const R: usize, const Q: usize> {
    pub remainder_in: Signal<In, Bits<R>>,
    pub quotient_in: Signal<In, Bits<Q>>,
    pub divisor: Signal<In, Bits<R>>,
    pub remainder_out: Signal<Out, Bits<R>>,
    pub quotient_out: Signal<Out, Bits<Q>>,
    doubled: Signal<Local, Bits<R>>,
    low_doubled: Signal<Local, Bits<R>>,
    low_divisor: Signal<Local, Bits<R>>,
    high_doubled: Signal<Local, Bits<R>>,
    high_divisor: Signal<Local, Bits<R>>,
    low_difference: Signal<Local, Bits<R>>,
    high_difference: Signal<Local, Bits<R>>,
    fits: Signal<Local, Bit>,
    one: Constant<Bits<Q>>,
    half: Constant<Bits<8>>,
    low_mask: Constant<Bits<R>>,
    borrow: Constant<Bits<R>>,
}

impl<const R: usize, const Q: usize> Default for DivisionRow<R, Q> {
    fn default() -> Self {
        Self {
            remainder_in: Default::default(),
            quotient_in: Default::default(),
            divisor: Default::default(),
            remainder_out: Default::default(),
            quotient_out: Default::default(),
            doubled: Default::default(),
            low_doubled: Default::default(),
            low_divisor: Default::default(),
            high_doubled: Default::default(),
            high_divisor: Default::default(),
            low_difference: Default::default(),
            high_difference: Default::default(),
            fits: Default::default(),
            one: Constant::new(1.into()),
            half: Constant::new((R / 2).to_bits()),
            low_mask: Constant::new((Bits::<R>::from(1) << (R / 2) as u64) - 1),
            borrow: Constant::new(1.into()),
        }
    }
}

impl<const R: usize, const Q: usize> Logic for DivisionRow<R, Q> {
    #[hdl_gen]
    fn update(&mut self) {
        // The remainder is below the divisor (< 2^(R-1)), so doubling it never overflows.
        self.doubled.next = self.remainder_in.val() << 1;
        // Compare and subtract in two halves side by side (carry select): the high half's
        // difference is taken with and without the low half's borrow.
        self.low_doubled.next = self.doubled.val() & self.low_mask.val();
        self.low_divisor.next = self.divisor.val() & self.low_mask.val();
        self.high_doubled.next = self.doubled.val() >> self.half.val();
        self.high_divisor.next = self.divisor.val() >> self.half.val();
        // doubled ≥ divisor: by the high halves, ≥ or > as the low half borrows or not.
        if self.low_doubled.val() >= self.low_divisor.val() {
            self.fits.next = self.high_doubled.val() >= self.high_divisor.val();
        } else {
            self.fits.next = self.high_doubled.val() > self.high_divisor.val();
        }
        self.low_difference.next =
            (self.low_doubled.val() - self.low_divisor.val()) & self.low_mask.val();
        if self.low_doubled.val() >= self.low_divisor.val() {
            self.high_difference.next = self.high_doubled.val() - self.high_divisor.val();
        } else {
            self.high_difference.next =
                self.high_doubled.val() - self.high_divisor.val() - self.borrow.val();
        }
        if self.fits.val() {
            self.remainder_out.next =
                (self.high_difference.val() << self.half.val()) | self.low_difference.val();
            self.quotient_out.next = (self.quotient_in.val() << 1) | self.one.val();
        } else {
            self.remainder_out.next = self.doubled.val();
            self.quotient_out.next = self.quotient_in.val() << 1;
        }
    }
}
