//! The wide unit's ray setup answer: the fp32 ray setup's ([`super::ray_entry::RayEntry`]'s
//! [`SetUp`]) with the ray's padding in t ([`PadInT`], `pad_t = pad·|inv_dir|`) beside it,
//! [`PadInT::latency`] cycles later, so that a slot is granted its first box test only once
//! every word the wide box stage reads is written. Its answer's box words are the wide
//! stage's (`WideRay::from_setup`): inv_dir x y z in bits 0–95, pad_t x y z in bits 96–191
//! (the origin is the ray's own, kept from its entry); pad and far end pass as they come.

use rust_hdl::prelude::*;

use super::slot_ports::{SetUp, SetUpSource, BOX_WORDS_BITS};
use super::wide::pad_in_t::PadInT;
use crate::macros::clock;
use crate::mt::delay::Delay;

/// Bits of the wide box words a slot keeps: inv_dir and pad_t.
pub const WIDE_RAY_BITS: usize = 6 * 32;

/// `SB` slot bits.
#[derive(LogicBlock)]
pub struct WideSetUp<const SB: usize> {
    pub clock: Signal<In, Clock>,
    /// The fp32 setup's answer (box words: orig_lo, orig_hi, inv_dir).
    pub fp32: SetUp<SB>,
    /// The wide answer.
    pub set_up: SetUpSource<SB>,
    pad_t: PadInT,
    valid: Delay<Bit>,
    slot: Delay<Bits<SB>>,
    pad: Delay<Bits<32>>,
    t_hi: Delay<Bits<32>>,
    inv_dir: [Delay<Bits<32>>; 3],
}

impl<const SB: usize> WideSetUp<SB> {
    /// The block at `depth` (its multiplies' registers).
    pub fn new(depth: usize) -> Self {
        let latency = PadInT::latency(depth);
        Self {
            clock: Default::default(),
            fp32: Default::default(),
            set_up: Default::default(),
            pad_t: PadInT::new(depth),
            valid: Delay::new(latency),
            slot: Delay::new(latency),
            pad: Delay::new(latency),
            t_hi: Delay::new(latency),
            inv_dir: Delay::lines(latency),
        }
    }
}

impl<const SB: usize> Logic for WideSetUp<SB> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, pad_t, valid, slot, pad, t_hi);
        self.pad_t.valid_in.next = self.fp32.valid.val();
        self.pad_t.pad.next = self.fp32.pad.val();
        self.valid.d.next = self.fp32.valid.val();
        self.slot.d.next = self.fp32.slot.val();
        self.pad.d.next = self.fp32.pad.val();
        self.t_hi.d.next = self.fp32.t_hi.val();
        for a in 0..3 {
            clock!(self, clock, inv_dir[a]);
            self.pad_t.inv_dir[a].next = self.fp32.box_words.val().get_bits::<32>(192 + 32 * a);
            self.inv_dir[a].d.next = self.fp32.box_words.val().get_bits::<32>(192 + 32 * a);
        }
        self.set_up.valid.next = self.valid.q.val();
        self.set_up.slot.next = self.slot.q.val();
        self.set_up.pad.next = self.pad.q.val();
        self.set_up.t_hi.next = self.t_hi.q.val();
        self.set_up.box_words.next = bit_cast::<BOX_WORDS_BITS, 32>(self.inv_dir[0].q.val())
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.inv_dir[1].q.val()) << 32)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.inv_dir[2].q.val()) << 64)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.pad_t.pad_t[0].val()) << 96)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.pad_t.pad_t[1].val()) << 128)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.pad_t.pad_t[2].val()) << 160);
    }
}
