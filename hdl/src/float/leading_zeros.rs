//! Leading zeros of a 32-bit vector as a 4-ary tree: each nibble's count (one LUT per bit),
//! then each 16-bit half's (the first non-zero nibble's count, offset by its place), then
//! the word's. About four LUT levels, where a priority chain or a smear of ORs maps onto
//! LUT/MUXF7/MUXF8 chains of ten. Narrower vectors are passed left-aligned. An all-zero word
//! counts 31, a count the adder never uses: it knows a zero result beforehand, and it sets a
//! zero operand's trailing-zero count to 31 itself (a nonzero significand has its hidden bit).

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct LeadingZeros {
    pub x: Signal<In, Bits<32>>,
    /// Zeros above the leading one (0..=31; 31 also for an all-zero word).
    pub count: Signal<Out, Bits<8>>,
    nibble: [Signal<Local, Bits<4>>; 8],
    nibble_any: [Signal<Local, Bit>; 8],
    nibble_count: [Signal<Local, Bits<8>>; 8],
    half_any: [Signal<Local, Bit>; 2],
    half_count: [Signal<Local, Bits<8>>; 2],
    /// Leading zeros contributed by the non-zero nibbles above, by place in a half.
    place: [Constant<Bits<8>>; 4],
    lower_half: Constant<Bits<8>>,
}

impl Default for LeadingZeros {
    fn default() -> Self {
        Self {
            x: Default::default(),
            count: Default::default(),
            nibble: Default::default(),
            nibble_any: Default::default(),
            nibble_count: Default::default(),
            half_any: Default::default(),
            half_count: Default::default(),
            place: std::array::from_fn(|k| Constant::new(((3 - k as u64) * 4).into())),
            lower_half: Constant::new(16.into()),
        }
    }
}

impl Logic for LeadingZeros {
    #[hdl_gen]
    fn update(&mut self) {
        for g in 0..8 {
            self.nibble[g].next = self.x.val().get_bits::<4>(4 * g);
            self.nibble_any[g].next = self.nibble[g].val().any();
            self.nibble_count[g].next = 3.into();
            if self.nibble[g].val().get_bit(1) {
                self.nibble_count[g].next = 2.into();
            }
            if self.nibble[g].val().get_bit(2) {
                self.nibble_count[g].next = 1.into();
            }
            if self.nibble[g].val().get_bit(3) {
                self.nibble_count[g].next = 0.into();
            }
        }
        // Half h holds nibbles 4h..4h+3, the highest first.
        for h in 0..2 {
            self.half_any[h].next = self.nibble_any[4 * h].val()
                | self.nibble_any[4 * h + 1].val()
                | self.nibble_any[4 * h + 2].val()
                | self.nibble_any[4 * h + 3].val();
            self.half_count[h].next = self.nibble_count[4 * h].val() | self.place[0].val();
            if self.nibble_any[4 * h + 1].val() {
                self.half_count[h].next = self.nibble_count[4 * h + 1].val() | self.place[1].val();
            }
            if self.nibble_any[4 * h + 2].val() {
                self.half_count[h].next = self.nibble_count[4 * h + 2].val() | self.place[2].val();
            }
            if self.nibble_any[4 * h + 3].val() {
                self.half_count[h].next = self.nibble_count[4 * h + 3].val() | self.place[3].val();
            }
        }
        self.count.next = self.half_count[0].val() | self.lower_half.val();
        if self.half_any[1].val() {
            self.count.next = self.half_count[1].val();
        }
    }
}
