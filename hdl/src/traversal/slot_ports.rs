//! What the ray slots ([`super::slots::SlotState`]) and the unit's ports say to each other,
//! one bundle each way, so that a port is a block behind a narrow seam:
//!
//! - a **grant**, from the slots to a port: the slot a scheduler granted this cycle (`valid`
//!   and its index) and the slot's words the port reads in the grant's cycle;
//! - a **step**, from a port back to the slots: "slot s is done with this step, and goes on
//!   so", for a link step (box test or pop) the next link, a pop, or out; for a leaf step the
//!   answer's effect on the slot's nearest hit, and at the leaf's end a pop or out.
//!
//! The bundles a port holds carry the plain name ([`BoxGrant`], [`LinkStep`], …); the slots'
//! side is the mirror (`…Source` for a grant, `…Sink` for a step). Rays entering and their
//! setup reach every block that keeps a slot word: [`Entered`], [`SetUp`].
//!
//! rust-hdl cannot derive widths: `SB` slot index bits, `LF`, `LC` a link's first and count
//! (`scene_memory::link_first_bits`, `link_count_bits`), `W` a stack entry (`LF + LC + 32`).

use rust_hdl::prelude::*;

use super::config::MAX_LANES;
use super::scene_memory::INDEX_BITS;

/// A slot's box-test words: orig_lo x y z, orig_hi x y z, inv_dir x y z.
pub const BOX_WORDS_BITS: usize = 9 * 32;
/// A slot's lane words: the ray packet's first eight words as they come (orig x y z, dir x y
/// z, t_max, t_min).
pub const LANE_WORDS_BITS: usize = 8 * 32;
/// A slot's leaf-port words: the lane words, then the excluded triangle.
pub const LEAF_WORDS_BITS: usize = LANE_WORDS_BITS + INDEX_BITS;

/// The box scheduler's grant: the slot, its far end, the node of its current link and
/// whether the test is the root's box (a new ray's first test).
#[derive(LogicInterface, Default)]
#[join = "BoxGrantSource"]
pub struct BoxGrant<const SB: usize, const LF: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub t_hi: Signal<In, Bits<32>>,
    pub node: Signal<In, Bits<LF>>,
    pub root: Signal<In, Bit>,
}

#[derive(LogicInterface, Default)]
#[join = "BoxGrant"]
pub struct BoxGrantSource<const SB: usize, const LF: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub t_hi: Signal<Out, Bits<32>>,
    pub node: Signal<Out, Bits<LF>>,
    pub root: Signal<Out, Bit>,
}

/// The stack scheduler's grant: the slot to pop and its far end.
#[derive(LogicInterface, Default)]
#[join = "PopGrantSource"]
pub struct PopGrant<const SB: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub t_hi: Signal<In, Bits<32>>,
}

#[derive(LogicInterface, Default)]
#[join = "PopGrant"]
pub struct PopGrantSource<const SB: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub t_hi: Signal<Out, Bits<32>>,
}

/// A leaf scheduler's grant: the slot, the triangle it issues (its link's first), whether
/// that is the leaf's last, and the ray's flags.
#[derive(LogicInterface, Default)]
#[join = "LeafGrantSource"]
pub struct LeafGrant<const SB: usize, const LF: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub triangle: Signal<In, Bits<LF>>,
    pub last: Signal<In, Bit>,
    pub any_hit: Signal<In, Bit>,
    pub has_exclude: Signal<In, Bit>,
}

#[derive(LogicInterface, Default)]
#[join = "LeafGrant"]
pub struct LeafGrantSource<const SB: usize, const LF: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub triangle: Signal<Out, Bits<LF>>,
    pub last: Signal<Out, Bit>,
    pub any_hit: Signal<Out, Bit>,
    pub has_exclude: Signal<Out, Bit>,
}

/// The hit output's grant: `ready` (the output can take an answer: the scheduler grants only
/// then), the slot, whether it has a hit, and its lane (one-hot: which lane's copy of the
/// nearest hit holds it).
#[derive(LogicInterface, Default)]
#[join = "OutGrantSource"]
pub struct OutGrant<const SB: usize> {
    pub ready: Signal<Out, Bit>,
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub hit: Signal<In, Bit>,
    pub lane: Signal<In, Bits<MAX_LANES>>,
}

#[derive(LogicInterface, Default)]
#[join = "OutGrant"]
pub struct OutGrantSource<const SB: usize> {
    pub ready: Signal<In, Bit>,
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub hit: Signal<Out, Bit>,
    pub lane: Signal<Out, Bits<MAX_LANES>>,
}

/// A link step's answer (a box test's, a pop's): with `enter` the slot takes the link
/// `first`, `count` (a leaf when `count` > 0, else a node) entered at distance `entry`; else
/// it pops (`pop`) or its walk is over.
#[derive(LogicInterface, Default)]
#[join = "LinkStepSink"]
pub struct LinkStep<const SB: usize, const LF: usize, const LC: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub enter: Signal<Out, Bit>,
    pub pop: Signal<Out, Bit>,
    pub first: Signal<Out, Bits<LF>>,
    pub count: Signal<Out, Bits<LC>>,
    pub entry: Signal<Out, Bits<32>>,
}

#[derive(LogicInterface, Default)]
#[join = "LinkStep"]
pub struct LinkStepSink<const SB: usize, const LF: usize, const LC: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub enter: Signal<In, Bit>,
    pub pop: Signal<In, Bit>,
    pub first: Signal<In, Bits<LF>>,
    pub count: Signal<In, Bits<LC>>,
    pub entry: Signal<In, Bits<32>>,
}

/// A leaf port's answers: a lane answer for `slot` (`valid`), whose result becomes the
/// slot's nearest hit (`take`; `nearer` for a closest-hit ray, whose far end then needs
/// recomputing) and which may end the leaf (`last`: then `out`, or `pop`, or neither while
/// the far end is recomputed); the slot's flags the answer is judged by (`best_valid`: it
/// has a hit, `changed`: its hit got nearer during this leaf); and the far end of a slot
/// (`far_valid`, `far_slot`, `t_hi`), after which it pops.
#[derive(LogicInterface, Default)]
#[join = "LeafStepSink"]
pub struct LeafStep<const SB: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub take: Signal<Out, Bit>,
    pub nearer: Signal<Out, Bit>,
    pub last: Signal<Out, Bit>,
    pub out: Signal<Out, Bit>,
    pub pop: Signal<Out, Bit>,
    pub best_valid: Signal<In, Bit>,
    pub changed: Signal<In, Bit>,
    pub far_valid: Signal<Out, Bit>,
    pub far_slot: Signal<Out, Bits<SB>>,
    pub t_hi: Signal<Out, Bits<32>>,
}

#[derive(LogicInterface, Default)]
#[join = "LeafStep"]
pub struct LeafStepSink<const SB: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub take: Signal<In, Bit>,
    pub nearer: Signal<In, Bit>,
    pub last: Signal<In, Bit>,
    pub out: Signal<In, Bit>,
    pub pop: Signal<In, Bit>,
    pub best_valid: Signal<Out, Bit>,
    pub changed: Signal<Out, Bit>,
    pub far_valid: Signal<In, Bit>,
    pub far_slot: Signal<In, Bits<SB>>,
    pub t_hi: Signal<In, Bits<32>>,
}

/// A push onto a slot's stack: the farther child and its entry distance (a stack entry).
#[derive(LogicInterface, Default)]
#[join = "PushSink"]
pub struct Push<const SB: usize, const W: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub data: Signal<Out, Bits<W>>,
}

#[derive(LogicInterface, Default)]
#[join = "Push"]
pub struct PushSink<const SB: usize, const W: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub data: Signal<In, Bits<W>>,
}

/// A ray taken into `slot`: its leaf-port words, its id and flags.
#[derive(LogicInterface, Default)]
#[join = "EnteredSource"]
pub struct Entered<const SB: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub leaf_words: Signal<In, Bits<LEAF_WORDS_BITS>>,
    pub id: Signal<In, Bits<32>>,
    pub any_hit: Signal<In, Bit>,
    pub has_exclude: Signal<In, Bit>,
}

#[derive(LogicInterface, Default)]
#[join = "Entered"]
pub struct EnteredSource<const SB: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub leaf_words: Signal<Out, Bits<LEAF_WORDS_BITS>>,
    pub id: Signal<Out, Bits<32>>,
    pub any_hit: Signal<Out, Bit>,
    pub has_exclude: Signal<Out, Bit>,
}

/// A ray's setup done for `slot`: its box-test words, its pad and far end.
#[derive(LogicInterface, Default)]
#[join = "SetUpSource"]
pub struct SetUp<const SB: usize> {
    pub valid: Signal<In, Bit>,
    pub slot: Signal<In, Bits<SB>>,
    pub box_words: Signal<In, Bits<BOX_WORDS_BITS>>,
    pub pad: Signal<In, Bits<32>>,
    pub t_hi: Signal<In, Bits<32>>,
}

#[derive(LogicInterface, Default)]
#[join = "SetUp"]
pub struct SetUpSource<const SB: usize> {
    pub valid: Signal<Out, Bit>,
    pub slot: Signal<Out, Bits<SB>>,
    pub box_words: Signal<Out, Bits<BOX_WORDS_BITS>>,
    pub pad: Signal<Out, Bits<32>>,
    pub t_hi: Signal<Out, Bits<32>>,
}

/// A slot's nearest hit so far, as the slot RAMs hold it: t, u, v (fp32 words) and the global
/// triangle index (zero-extended).
#[derive(Clone, Copy, Debug, Default, PartialEq, LogicStruct)]
pub struct NearestHit {
    pub t: Bits<32>,
    pub u: Bits<32>,
    pub v: Bits<32>,
    pub triangle: Bits<32>,
}
