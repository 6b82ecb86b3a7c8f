//! The number of ones among 8 bits, as full adders written out in logic (a carry-save count):
//! a couple of LUT levels, where adding each bit in turn (`count + 1`) maps onto one carry
//! chain per bit, in series. Combinational.

use rust_hdl::prelude::*;

use super::{Count, SlotBits, MAX_WIDTH};

// The adder tree below is written out for 8 bits.
const _: () = assert!(MAX_WIDTH == 8);

#[derive(LogicBlock, Default)]
pub struct Ones {
    pub x: Signal<In, SlotBits>,
    pub count: Signal<Out, Count>,
    /// Weight 1: the sums of bits 0–2, 3–5 and 6–7; weight 2: their carries.
    sum: [Signal<Local, Bit>; 3],
    carry: [Signal<Local, Bit>; 3],
    /// The weight-2 carry of adding the three sums.
    sum_carry: Signal<Local, Bit>,
    /// The three carries added: their sum (weight 2) and carry (weight 4).
    carries_sum: Signal<Local, Bit>,
    carries_carry: Signal<Local, Bit>,
    /// Weight 4 from adding the weight-2 bits.
    twos_carry: Signal<Local, Bit>,
    total: Signal<Local, Count>,
}

impl Logic for Ones {
    #[hdl_gen]
    fn update(&mut self) {
        self.sum[0].next =
            self.x.val().get_bit(0) ^ self.x.val().get_bit(1) ^ self.x.val().get_bit(2);
        self.carry[0].next = (self.x.val().get_bit(0) & self.x.val().get_bit(1))
            | (self.x.val().get_bit(2) & (self.x.val().get_bit(0) ^ self.x.val().get_bit(1)));
        self.sum[1].next =
            self.x.val().get_bit(3) ^ self.x.val().get_bit(4) ^ self.x.val().get_bit(5);
        self.carry[1].next = (self.x.val().get_bit(3) & self.x.val().get_bit(4))
            | (self.x.val().get_bit(5) & (self.x.val().get_bit(3) ^ self.x.val().get_bit(4)));
        self.sum[2].next = self.x.val().get_bit(6) ^ self.x.val().get_bit(7);
        self.carry[2].next = self.x.val().get_bit(6) & self.x.val().get_bit(7);
        self.sum_carry.next = (self.sum[0].val() & self.sum[1].val())
            | (self.sum[2].val() & (self.sum[0].val() ^ self.sum[1].val()));
        self.carries_sum.next = self.carry[0].val() ^ self.carry[1].val() ^ self.carry[2].val();
        self.carries_carry.next = (self.carry[0].val() & self.carry[1].val())
            | (self.carry[2].val() & (self.carry[0].val() ^ self.carry[1].val()));
        self.twos_carry.next = self.carries_sum.val() & self.sum_carry.val();
        self.total.next = 0.into();
        self.total.next = self
            .total
            .val()
            .replace_bit(0, self.sum[0].val() ^ self.sum[1].val() ^ self.sum[2].val());
        self.total.next = self
            .total
            .val()
            .replace_bit(1, self.carries_sum.val() ^ self.sum_carry.val());
        self.total.next = self
            .total
            .val()
            .replace_bit(2, self.carries_carry.val() ^ self.twos_carry.val());
        self.total.next = self
            .total
            .val()
            .replace_bit(3, self.carries_carry.val() & self.twos_carry.val());
        self.count.next = self.total.val();
    }
}
