//! Rays in: the ray stream takes a ray while a scene is loaded and a slot is free (the
//! slots' lowest free one), and the ray goes into its slot ([`Entered`]: the leaf ports'
//! lane words, the id, the flags) and into the ray setup ([`RaySetupUnit`]), whose answer
//! [`SetUp`] gives the slot its box-test words, pad and far end.

use hw_model::traversal::packet::{ray_word, ANY_HIT, HAS_EXCLUDE};
use rust_hdl::prelude::*;

use super::ports::{RayStream, RAY_BITS};
use super::ray_setup::RaySetupUnit;
use super::scene_memory::INDEX_BITS;
use super::slot_ports::{
    EnteredSource, SetUpSource, BOX_WORDS_BITS, LANE_WORDS_BITS, LEAF_WORDS_BITS,
};

// The kernel spells the packet's word offsets as numbers (hdl_gen leaks a named const into
// the Verilog); a slot's lane words are the packet's first eight words as they come.
const _: () = assert!(
    ray_word::ORIG == 0
        && ray_word::DIR == 3
        && ray_word::T_MAX == 6
        && ray_word::T_MIN == 7
        && ray_word::FLAGS == 8
        && ray_word::EXCLUDE == 9
        && ray_word::ID == 10
        && ANY_HIT == 1 << 0
        && HAS_EXCLUDE == 1 << 1
        && LANE_WORDS_BITS == 32 * 8
);

/// `SB` slot bits.
#[derive(LogicBlock)]
pub struct RayEntry<const SB: usize> {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub ray: RayStream,
    /// A scene is loaded.
    pub loaded: Signal<In, Bit>,
    /// A slot is free, and where the next ray enters (the slots').
    pub free: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub entered: EnteredSource<SB>,
    pub set_up: SetUpSource<SB>,
    setup: RaySetupUnit,
}

impl<const SB: usize> RayEntry<SB> {
    /// Rays set up by operators of `depth` pipeline registers each.
    pub fn new(depth: usize) -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            ray: Default::default(),
            loaded: Default::default(),
            free: Default::default(),
            slot: Default::default(),
            entered: Default::default(),
            set_up: Default::default(),
            setup: RaySetupUnit::new(depth),
        }
    }
}

impl<const SB: usize> Logic for RayEntry<SB> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, setup);
        self.ray.tready.next = self.loaded.val() & self.free.val() & self.reset_n.val();
        self.entered.valid.next = self.ray.tready.val() & self.ray.tvalid.val();
        self.entered.slot.next = self.slot.val();
        self.entered.leaf_words.next =
            bit_cast::<LEAF_WORDS_BITS, LANE_WORDS_BITS>(bit_cast::<LANE_WORDS_BITS, RAY_BITS>(
                self.ray.tdata.val(),
            )) | (bit_cast::<LEAF_WORDS_BITS, INDEX_BITS>(bit_cast::<INDEX_BITS, RAY_BITS>(
                self.ray.tdata.val() >> 288,
            )) << 256);
        self.entered.id.next = self.ray.tdata.val().get_bits::<32>(320);
        self.entered.any_hit.next = self.ray.tdata.val().get_bit(256);
        self.entered.has_exclude.next = self.ray.tdata.val().get_bit(257);

        self.setup.valid_in.next = self.entered.valid.val();
        self.setup.tag_in.next = bit_cast::<16, SB>(self.slot.val());
        for k in 0..3 {
            self.setup.orig[k].next = self.ray.tdata.val().get_bits::<32>(32 * k);
            self.setup.dir[k].next = self.ray.tdata.val().get_bits::<32>(32 * (3 + k));
        }
        self.setup.bound.next = self.ray.tdata.val().get_bits::<32>(192);
        // The setup's answer: the slot's box words (orig_lo, orig_hi, inv_dir; word 0
        // lowest), pad and far end.
        self.set_up.valid.next = self.setup.valid_out.val();
        self.set_up.slot.next = bit_cast::<SB, 16>(self.setup.tag_out.val());
        self.set_up.box_words.next = bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_lo[0].val())
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_lo[1].val()) << 32)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_lo[2].val()) << 64)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_hi[0].val()) << 96)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_hi[1].val()) << 128)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.orig_hi[2].val()) << 160)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.inv_dir[0].val()) << 192)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.inv_dir[1].val()) << 224)
            | (bit_cast::<BOX_WORDS_BITS, 32>(self.setup.inv_dir[2].val()) << 256);
        self.set_up.pad.next = self.setup.pad.val();
        self.set_up.t_hi.next = self.setup.t_hi.val();
    }
}
