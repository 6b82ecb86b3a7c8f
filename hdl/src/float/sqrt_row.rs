//! One row of a restoring square root (the float square root's): brings down the radicand's
//! next two bits and subtracts the trial 4·root + 1 if it fits, shifting the root bit in.

use rust_hdl::prelude::*;

/// R: the partial remainder's bits; Q: the root's; RW: the radicand's, whose top two bits
/// this row brings down (the radicand leaves shifted by two, zeros coming in).
#[derive(LogicBlock)]
pub struct SqrtRow<const R: usize, const Q: usize, const RW: usize> {
    pub remainder_in: Signal<In, Bits<R>>,
    pub root_in: Signal<In, Bits<Q>>,
    pub radicand_in: Signal<In, Bits<RW>>,
    pub remainder_out: Signal<Out, Bits<R>>,
    pub root_out: Signal<Out, Bits<Q>>,
    pub radicand_out: Signal<Out, Bits<RW>>,
    brought_down: Signal<Local, Bits<R>>,
    trial: Signal<Local, Bits<R>>,
    fits: Signal<Local, Bit>,
    pair_shift: Constant<Bits<8>>,
    two: Constant<Bits<8>>,
    one_r: Constant<Bits<R>>,
    one_q: Constant<Bits<Q>>,
}

impl<const R: usize, const Q: usize, const RW: usize> Default for SqrtRow<R, Q, RW> {
    fn default() -> Self {
        assert!(Q < R && RW >= 2, "SqrtRow: inconsistent widths");
        Self {
            remainder_in: Default::default(),
            root_in: Default::default(),
            radicand_in: Default::default(),
            remainder_out: Default::default(),
            root_out: Default::default(),
            radicand_out: Default::default(),
            brought_down: Default::default(),
            trial: Default::default(),
            fits: Default::default(),
            pair_shift: Constant::new((RW - 2).to_bits()),
            two: Constant::new(2usize.to_bits()),
            one_r: Constant::new(1.into()),
            one_q: Constant::new(1.into()),
        }
    }
}

impl<const R: usize, const Q: usize, const RW: usize> Logic for SqrtRow<R, Q, RW> {
    #[hdl_gen]
    fn update(&mut self) {
        // remainder ≤ 2·root, so 4·remainder + 3 fits R bits (the operator's widths say why).
        self.brought_down.next = (self.remainder_in.val() << self.two.val())
            | bit_cast::<R, RW>(self.radicand_in.val() >> self.pair_shift.val());
        self.trial.next =
            (bit_cast::<R, Q>(self.root_in.val()) << self.two.val()) | self.one_r.val();
        self.fits.next = self.brought_down.val() >= self.trial.val();
        if self.fits.val() {
            self.remainder_out.next = self.brought_down.val() - self.trial.val();
            self.root_out.next = (self.root_in.val() << 1) | self.one_q.val();
        } else {
            self.remainder_out.next = self.brought_down.val();
            self.root_out.next = self.root_in.val() << 1;
        }
        self.radicand_out.next = self.radicand_in.val() << self.two.val();
    }
}
