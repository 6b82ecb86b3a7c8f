//! Step 2 of the bfp filter: three signed integers, each at its own exponent, to one block,
//! bit for bit `hw_model::dual::bfp::to_block`. The block exponent is the largest of each
//! component's leading bit (of the component XOR its sign) plus its exponent; each
//! component is shifted to the block's last bit (left, exactly, or right arithmetically:
//! truncation towards −∞); the dropped parts' bound is the leading one of each component's
//! dropped bits, a 3-way max, clamped to `DROP_WINDOW` below the block. One register stage.
//!
//! Exponents are the inputs' biased fields, and so is the block exponent: a component `x`
//! at field `f` is worth x·2^(f − bias) for a bias common to the three (150 for an fp32
//! significand, 150 + `GUARD_BITS` for `Translate`'s difference), so the block never needs
//! it. The block's last bit is implicit: 2^(e − bias − W + 1).

use hw_model::dual::bfp::{widths, Vector, DROP_WINDOW, FAR_BELOW};
use rust_hdl::prelude::*;

use super::translate::{DIFF_BITS, FIELD_BITS, SIGNIFICAND_BITS};
use super::WIDTH;
use crate::macros::clock;

/// Width of block exponents and of the distances inside the block: a field plus a
/// component's bit count or the mantissa width, each below 2^FIELD_BITS.
pub const EXP_BITS: usize = FIELD_BITS + 1;

/// Width of [`ToBlock::below`]: the distance from the block exponent to the dropped parts'
/// bound, at most `DROP_WINDOW`.
pub const BELOW_BITS: usize = (u32::BITS - DROP_WINDOW.leading_zeros()) as usize;

/// Cycles from the inputs to the block.
pub const LATENCY: usize = 1;

/// dir: fp32 significands with their sign, to W bits.
pub type DirToBlock =
    ToBlock<{ SIGNIFICAND_BITS + 1 }, { widths(WIDTH)[Vector::Dir as usize] as usize }>;
/// e1 or e2: `Translate`'s differences, to W bits.
pub type EdgeToBlock = ToBlock<DIFF_BITS, { widths(WIDTH)[Vector::E1 as usize] as usize }>;
/// s: `Translate`'s differences, to W + `S_EXTRA_BITS` bits.
pub type SToBlock = ToBlock<DIFF_BITS, { widths(WIDTH)[Vector::S as usize] as usize }>;

/// `x[k]`·2^`f[k]` (IW-bit two's complement, biased fields) to `m[k]`·2^(`e` − W + 1).
/// `below` is e minus the exponent of the largest dropped part (in W − 1..=`DROP_WINDOW`),
/// 0 when nothing was dropped; `zero` marks the zero vector, which has no block.
#[derive(LogicBlock)]
pub struct ToBlock<const IW: usize, const W: usize> {
    pub clock: Signal<In, Clock>,
    pub x: [Signal<In, Bits<IW>>; 3],
    pub f: [Signal<In, Bits<FIELD_BITS>>; 3],
    pub m: [Signal<Out, Bits<W>>; 3],
    pub e: Signal<Out, Bits<EXP_BITS>>,
    pub below: Signal<Out, Bits<BELOW_BITS>>,
    pub zero: Signal<Out, Bit>,
    m_reg: [DFF<Bits<W>>; 3],
    e_reg: DFF<Bits<EXP_BITS>>,
    below_reg: DFF<Bits<BELOW_BITS>>,
    zero_reg: DFF<Bit>,
    /// The components' sign bit (a Rust constant as a bit index would reach the Verilog
    /// as an undefined name).
    sign: Constant<Bits<IW>>,
    ones: Constant<Bits<IW>>,
    one: Constant<Bits<EXP_BITS>>,
    /// W − 1: the block exponent less its last bit's.
    last: Constant<Bits<EXP_BITS>>,
    /// IW: from this distance below the last bit a component is dropped whole.
    whole: Constant<Bits<EXP_BITS>>,
    /// IW − 1: the largest right shift that still matters.
    max_shift: Constant<Bits<EXP_BITS>>,
    far: Constant<Bits<EXP_BITS>>,
    window: Constant<Bits<EXP_BITS>>,
    field: [Signal<Local, Bits<EXP_BITS>>; 3],
    negative: [Signal<Local, Bit>; 3],
    /// The component XOR its sign, and its bit count (its leading one's position plus one).
    magnitude: [Signal<Local, Bits<IW>>; 3],
    length: [Signal<Local, Bits<EXP_BITS>>; 3],
    /// Each component's bound f + length (0 for a zero component) and their max.
    top: [Signal<Local, Bits<EXP_BITS>>; 3],
    block: Signal<Local, Bits<EXP_BITS>>,
    /// A component at or above the block's last bit moves up by `up`, else right by `down`.
    above: [Signal<Local, Bit>; 3],
    up: [Signal<Local, Bits<EXP_BITS>>; 3],
    down: [Signal<Local, Bits<EXP_BITS>>; 3],
    shift: [Signal<Local, Bits<EXP_BITS>>; 3],
    shifted: [Signal<Local, Bits<IW>>; 3],
    /// The mantissa before its cut to W bits.
    placed: [Signal<Local, Bits<IW>>; 3],
    /// The bits shifted out (a partly dropped component) and their bit count.
    rest: [Signal<Local, Bits<IW>>; 3],
    rest_length: [Signal<Local, Bits<EXP_BITS>>; 3],
    dropped: [Signal<Local, Bit>; 3],
    distance: [Signal<Local, Bits<EXP_BITS>>; 3],
    nearest: Signal<Local, Bits<EXP_BITS>>,
}

impl<const IW: usize, const W: usize> Default for ToBlock<IW, W> {
    fn default() -> Self {
        let exp = |v: usize| Constant::new((v as u64).to_bits());
        Self {
            clock: Default::default(),
            x: Default::default(),
            f: Default::default(),
            m: Default::default(),
            e: Default::default(),
            below: Default::default(),
            zero: Default::default(),
            m_reg: Default::default(),
            e_reg: Default::default(),
            below_reg: Default::default(),
            zero_reg: Default::default(),
            sign: Constant::new(Bits::<IW>::from(1) << (IW as u64 - 1)),
            ones: Constant::new(!Bits::<IW>::default()),
            one: exp(1),
            last: exp(W - 1),
            whole: exp(IW),
            max_shift: exp(IW - 1),
            far: exp(FAR_BELOW as usize),
            window: exp(DROP_WINDOW as usize),
            field: Default::default(),
            negative: Default::default(),
            magnitude: Default::default(),
            length: Default::default(),
            top: Default::default(),
            block: Default::default(),
            above: Default::default(),
            up: Default::default(),
            down: Default::default(),
            shift: Default::default(),
            shifted: Default::default(),
            placed: Default::default(),
            rest: Default::default(),
            rest_length: Default::default(),
            dropped: Default::default(),
            distance: Default::default(),
            nearest: Default::default(),
        }
    }
}

impl<const IW: usize, const W: usize> Logic for ToBlock<IW, W> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..3 {
            clock!(self, clock, m_reg[k]);
        }
        clock!(self, clock, e_reg, below_reg, zero_reg);
        // The block exponent: every component in [−2^(e − bias), 2^(e − bias)).
        // (bit_cast in a loop loses the loop variable: one per component.)
        self.field[0].next = bit_cast::<EXP_BITS, FIELD_BITS>(self.f[0].val());
        self.field[1].next = bit_cast::<EXP_BITS, FIELD_BITS>(self.f[1].val());
        self.field[2].next = bit_cast::<EXP_BITS, FIELD_BITS>(self.f[2].val());
        self.block.next = 0.into();
        for k in 0..3 {
            self.negative[k].next = (self.x[k].val() & self.sign.val()).any();
            self.magnitude[k].next = self.x[k].val();
            if self.negative[k].val() {
                self.magnitude[k].next = !self.x[k].val();
            }
            self.length[k].next = 0.into();
            for i in 0..IW {
                if self.magnitude[k].val().get_bit(i) {
                    self.length[k].next = i.to_bits() + self.one.val();
                }
            }
            // A zero component bounds nothing (a nonzero one's bound is at least 0).
            self.top[k].next = 0.into();
            if self.x[k].val().any() {
                self.top[k].next = self.field[k].val() + self.length[k].val();
            }
            if self.top[k].val() > self.block.val() {
                self.block.next = self.top[k].val();
            }
        }
        // Each component at the block's last bit; distances kept unsigned by comparing first.
        self.nearest.next = 0.into();
        for k in 0..3 {
            self.above[k].next = self.field[k].val() + self.last.val() >= self.block.val();
            self.up[k].next = self.field[k].val() + self.last.val() - self.block.val();
            self.down[k].next = self.block.val() - self.last.val() - self.field[k].val();
            self.shift[k].next = self.down[k].val();
            if self.down[k].val() > self.max_shift.val() {
                self.shift[k].next = self.max_shift.val();
            }
            // Arithmetic shift right: a negative value's complement shifts in zeros.
            self.shifted[k].next = self.x[k].val() >> self.shift[k].val();
            if self.negative[k].val() {
                self.shifted[k].next = !(!self.x[k].val() >> self.shift[k].val());
            }
            self.rest[k].next = self.x[k].val() & !(self.ones.val() << self.shift[k].val());
            self.rest_length[k].next = 0.into();
            for i in 0..IW {
                if self.rest[k].val().get_bit(i) {
                    self.rest_length[k].next = i.to_bits() + self.one.val();
                }
            }
            if self.above[k].val() {
                self.placed[k].next = self.x[k].val() << self.up[k].val();
                self.dropped[k].next = false;
                self.distance[k].next = 0.into();
            } else {
                self.placed[k].next = self.shifted[k].val();
                // The dropped part's leading bit, as a distance below the block exponent.
                self.dropped[k].next = self.rest[k].val().any();
                self.distance[k].next =
                    self.down[k].val() + self.last.val() - self.rest_length[k].val();
                if self.down[k].val() >= self.whole.val() {
                    // Dropped whole: a positive part's own leading bit, a negative one's
                    // complement to 2^lsb (and anything far below) charged at the last bit.
                    self.dropped[k].next = self.x[k].val().any();
                    self.distance[k].next =
                        self.down[k].val() + self.last.val() - self.length[k].val();
                    if self.negative[k].val() || self.down[k].val() >= self.far.val() {
                        self.distance[k].next = self.last.val();
                    }
                }
            }
            if self.distance[k].val() > self.window.val() {
                self.distance[k].next = self.window.val();
            }
            if self.dropped[k].val()
                && (!self.nearest.val().any() || self.distance[k].val() < self.nearest.val())
            {
                self.nearest.next = self.distance[k].val();
            }
        }
        // The mantissas fit W bits, so their low W bits are all of them.
        self.m_reg[0].d.next = bit_cast::<W, IW>(self.placed[0].val());
        self.m_reg[1].d.next = bit_cast::<W, IW>(self.placed[1].val());
        self.m_reg[2].d.next = bit_cast::<W, IW>(self.placed[2].val());
        self.e_reg.d.next = self.block.val();
        self.below_reg.d.next = bit_cast::<BELOW_BITS, EXP_BITS>(self.nearest.val());
        self.zero_reg.d.next =
            !(self.x[0].val().any() || self.x[1].val().any() || self.x[2].val().any());
        for k in 0..3 {
            self.m[k].next = self.m_reg[k].q.val();
        }
        self.e.next = self.e_reg.q.val();
        self.below.next = self.below_reg.q.val();
        self.zero.next = self.zero_reg.q.val();
    }
}
