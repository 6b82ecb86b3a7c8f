//! An fp32 word on the node's fixed-point grid: `⌊x·2^s⌋` and `⌈x·2^s⌉` of its magnitude,
//! saturated at [`SATURATED`] (every consumer saturates below it), as the model's `scaled`.
//!
//! Subnormals are zero (the operators flush them); an infinity bounds its value by `2^127` on
//! the near side (the floor is that of `2^127·2^s`) and is unbounded on the other (the ceiling
//! saturates); a NaN is flagged. `s` is the grid's shift plus an offset (a node's grid
//! exponent, for the reciprocal's step; 0 elsewhere).
//!
//! Cut points (registers spread by `pipe::placement`, [`Scaled::CUTS`]):
//!   0. after the shift amount `j = k + 24` (`k` the exponent of the significand's last bit on
//!      the grid: one 12-bit three-operand sum and its range tests)
//!   1. after the barrel shift (the 24-bit significand placed in 70 bits) and the sticky bit
//!   2. the results, after the ceiling's increment and the saturation

use rust_hdl::prelude::*;

use super::{Magnitude, Shift, Word};
use crate::pipe::{placement, Pipe};

/// Where a magnitude saturates: `2^46`, above every bound the stage keeps (`OFFSET_SAT` is
/// `2^45`, `STEP_MAX` below `2^24`).
pub const SATURATED: u64 = 1 << 46;

/// The position, in bits, of the significand's lowest bit after the shift, offset so that a
/// value below 1 (`k ≤ −25`) is at most 0 and a value of at least `2^46` (`k ≥ 23`) at least
/// 47: `j = k + 24 = biased exponent − 126 + s`.
const POSITION_BITS: usize = 12;
// The kernel reads the sign bit as bit 11 (a literal: rust-hdl emits constant names as such).
const _: () = assert!(POSITION_BITS == 12);
type Position = Bits<POSITION_BITS>;

#[derive(LogicBlock)]
pub struct Scaled {
    pub clock: Signal<In, Clock>,
    pub x: Signal<In, Word>,
    /// The grid's shift `s` (two's complement).
    pub shift: Signal<In, Shift>,
    /// Added to the shift: an i8 (two's complement).
    pub offset: Signal<In, Bits<8>>,
    /// `⌊|x|·2^s⌋` and `⌈|x|·2^s⌉`, each at most [`SATURATED`].
    pub floor: Signal<Out, Magnitude>,
    pub ceil: Signal<Out, Magnitude>,
    pub negative: Signal<Out, Bit>,
    pub nan: Signal<Out, Bit>,
    exp_field: Signal<Local, Bits<8>>,
    special: Signal<Local, Bit>,
    inf: Signal<Local, Bit>,
    sig: Signal<Local, Bits<24>>,
    shift_wide: Signal<Local, Position>,
    offset_wide: Signal<Local, Position>,
    position: Signal<Local, Position>,
    /// Cut 0.
    placed_sig: Pipe<Bits<24>>,
    placed_amount: Pipe<Bits<6>>,
    placed_big: Pipe<Bit>,
    placed_inf: Pipe<Bit>,
    placed_negative: Pipe<Bit>,
    placed_nan: Pipe<Bit>,
    wide: Signal<Local, Bits<70>>,
    /// Cut 1.
    shifted_whole: Pipe<Magnitude>,
    shifted_sticky: Pipe<Bit>,
    shifted_big: Pipe<Bit>,
    shifted_inf: Pipe<Bit>,
    shifted_negative: Pipe<Bit>,
    shifted_nan: Pipe<Bit>,
    /// Cut 2.
    floor_out: Pipe<Magnitude>,
    ceil_out: Pipe<Magnitude>,
    negative_out: Pipe<Bit>,
    nan_out: Pipe<Bit>,
    frac_mask: Constant<Bits<24>>,
    hidden: Constant<Bits<24>>,
    inf_sig: Constant<Bits<24>>,
    inf_exp: Constant<Bits<8>>,
    shift_sign: Constant<Position>,
    offset_sign: Constant<Position>,
    position_bias: Constant<Position>,
    position_big: Constant<Position>,
    last_position: Constant<Bits<6>>,
    sig_ones: Constant<Bits<24>>,
    saturated: Constant<Magnitude>,
}

impl Scaled {
    pub const CUTS: usize = 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            x: Default::default(),
            shift: Default::default(),
            offset: Default::default(),
            floor: Default::default(),
            ceil: Default::default(),
            negative: Default::default(),
            nan: Default::default(),
            exp_field: Default::default(),
            special: Default::default(),
            inf: Default::default(),
            sig: Default::default(),
            shift_wide: Default::default(),
            offset_wide: Default::default(),
            position: Default::default(),
            placed_sig: Pipe::new(cut[0]),
            placed_amount: Pipe::new(cut[0]),
            placed_big: Pipe::new(cut[0]),
            placed_inf: Pipe::new(cut[0]),
            placed_negative: Pipe::new(cut[0]),
            placed_nan: Pipe::new(cut[0]),
            wide: Default::default(),
            shifted_whole: Pipe::new(cut[1]),
            shifted_sticky: Pipe::new(cut[1]),
            shifted_big: Pipe::new(cut[1]),
            shifted_inf: Pipe::new(cut[1]),
            shifted_negative: Pipe::new(cut[1]),
            shifted_nan: Pipe::new(cut[1]),
            floor_out: Pipe::new(cut[2]),
            ceil_out: Pipe::new(cut[2]),
            negative_out: Pipe::new(cut[2]),
            nan_out: Pipe::new(cut[2]),
            frac_mask: Constant::new(0x7F_FFFF.into()),
            hidden: Constant::new(0x80_0000.into()),
            // An infinity floors as 2^127: significand 2^23, biased exponent 254.
            inf_sig: Constant::new(0x80_0000.into()),
            inf_exp: Constant::new(254.into()),
            shift_sign: Constant::new(
                (((1u64 << POSITION_BITS) - 1) & !((1u64 << Shift::BITS) - 1)).into(),
            ),
            offset_sign: Constant::new((((1u64 << POSITION_BITS) - 1) & !0xFF).into()),
            // j = biased − 126 + s, modulo 2^12.
            position_bias: Constant::new(((1u64 << POSITION_BITS) - 126).into()),
            position_big: Constant::new(47.into()),
            last_position: Constant::new(46.into()),
            sig_ones: Constant::new(0xFF_FFFF.into()),
            saturated: Constant::new(SATURATED.into()),
        }
    }
}

impl Logic for Scaled {
    #[hdl_gen]
    fn update(&mut self) {
        self.placed_sig.clock.next = self.clock.val();
        self.placed_amount.clock.next = self.clock.val();
        self.placed_big.clock.next = self.clock.val();
        self.placed_inf.clock.next = self.clock.val();
        self.placed_negative.clock.next = self.clock.val();
        self.placed_nan.clock.next = self.clock.val();
        self.shifted_whole.clock.next = self.clock.val();
        self.shifted_sticky.clock.next = self.clock.val();
        self.shifted_big.clock.next = self.clock.val();
        self.shifted_inf.clock.next = self.clock.val();
        self.shifted_negative.clock.next = self.clock.val();
        self.shifted_nan.clock.next = self.clock.val();
        self.floor_out.clock.next = self.clock.val();
        self.ceil_out.clock.next = self.clock.val();
        self.negative_out.clock.next = self.clock.val();
        self.nan_out.clock.next = self.clock.val();
        // The significand and its exponent; zero and subnormals have none.
        self.exp_field.next = self.x.val().get_bits::<8>(23);
        self.special.next = self.exp_field.val().all();
        self.inf.next = self.special.val() & !self.x.val().get_bits::<23>(0).any();
        self.sig.next =
            (bit_cast::<24, 32>(self.x.val()) & self.frac_mask.val()) | self.hidden.val();
        if self.inf.val() {
            self.sig.next = self.inf_sig.val();
            self.exp_field.next = self.inf_exp.val();
        }
        if !self.exp_field.val().any() {
            self.sig.next = 0.into();
        }
        self.shift_wide.next = bit_cast::<POSITION_BITS, 11>(self.shift.val());
        if self.shift.val().get_bit(10) {
            self.shift_wide.next = self.shift_wide.val() | self.shift_sign.val();
        }
        self.offset_wide.next = bit_cast::<POSITION_BITS, 8>(self.offset.val());
        if self.offset.val().get_bit(7) {
            self.offset_wide.next = self.offset_wide.val() | self.offset_sign.val();
        }
        self.position.next = bit_cast::<POSITION_BITS, 8>(self.exp_field.val())
            + self.shift_wide.val()
            + self.offset_wide.val()
            + self.position_bias.val();
        // Below 1 (j < 0): the significand stays where it is and only its sticky bit counts;
        // at least 2^46 (j ≥ 47): saturated.
        self.placed_amount.d.next = bit_cast::<6, POSITION_BITS>(self.position.val());
        self.placed_big.d.next = false;
        if self.position.val().get_bit(11) {
            self.placed_amount.d.next = 0.into();
        } else if self.position.val() >= self.position_big.val() {
            self.placed_amount.d.next = self.last_position.val();
            self.placed_big.d.next = self.sig.val().any();
        }
        self.placed_sig.d.next = self.sig.val();
        self.placed_inf.d.next = self.inf.val();
        self.placed_negative.d.next = self.x.val().get_bit(31);
        self.placed_nan.d.next = self.special.val() & !self.inf.val();
        // m·2^k = (m << j) / 2^24: the whole part and whether a fraction remains.
        self.wide.next = bit_cast::<70, 24>(self.placed_sig.q.val()) << self.placed_amount.q.val();
        self.shifted_whole.d.next = bit_cast::<47, 70>(self.wide.val() >> 24);
        self.shifted_sticky.d.next =
            (self.placed_sig.q.val() & (self.sig_ones.val() >> self.placed_amount.q.val())).any();
        self.shifted_big.d.next = self.placed_big.q.val();
        self.shifted_inf.d.next = self.placed_inf.q.val();
        self.shifted_negative.d.next = self.placed_negative.q.val();
        self.shifted_nan.d.next = self.placed_nan.q.val();
        self.floor_out.d.next = self.shifted_whole.q.val();
        self.ceil_out.d.next = self.shifted_whole.q.val();
        if self.shifted_sticky.q.val() {
            self.ceil_out.d.next = self.shifted_whole.q.val() + 1;
        }
        if self.shifted_big.q.val() {
            self.floor_out.d.next = self.saturated.val();
        }
        if self.shifted_big.q.val() | self.shifted_inf.q.val() {
            self.ceil_out.d.next = self.saturated.val();
        }
        self.negative_out.d.next = self.shifted_negative.q.val();
        self.nan_out.d.next = self.shifted_nan.q.val();
        self.floor.next = self.floor_out.q.val();
        self.ceil.next = self.ceil_out.q.val();
        self.negative.next = self.negative_out.q.val();
        self.nan.next = self.nan_out.q.val();
    }
}
