//! One child's slab on one axis: its entry and exit planes (the lower and the upper plane
//! for a positive direction, swapped for a negative one) and their codes: the plane shifted
//! down by `FRAC_BITS`, the entry floored into `0..=ENTRY_MAX` (−∞ is 0), the exit into
//! `−1..=ENTRY_MAX` (+∞ is `ENTRY_MAX`).
//!
//! The model clamps both to `CODE_MAX`; the far end is at most `CODE_LIMIT`, below
//! `ENTRY_MAX`, so an entry or exit beyond it gives the same answers.
//!
//! Cut points: the planes' ([`Plane::CUTS`]), then [`AxisSlab::CODE_CUTS`]: 0. the codes.

use rust_hdl::prelude::*;

use super::plane::Plane;
use super::{Code, EntryCode, ExitCode, Offset, Step, ENTRY_MAX};
use crate::pipe::{placement, Pipe};
use hw_model::traversal::wide::box_test::FRAC_BITS;

// The kernel takes a code's bits from the plane as bits 8..23 (literals: rust-hdl emits
// constant names as such): the code's unit is the plane's bit FRAC_BITS.
const _: () = assert!(FRAC_BITS == 8);

#[derive(LogicBlock)]
pub struct AxisSlab {
    pub clock: Signal<In, Clock>,
    pub lo: Signal<In, Code>,
    pub hi: Signal<In, Code>,
    pub offset_lo: Signal<In, Offset>,
    pub offset_hi: Signal<In, Offset>,
    pub step_lo: Signal<In, Step>,
    pub step_hi: Signal<In, Step>,
    pub lo_inf: Signal<In, Bit>,
    pub hi_inf: Signal<In, Bit>,
    pub step_lo_inf: Signal<In, Bit>,
    pub step_hi_inf: Signal<In, Bit>,
    pub positive: Signal<In, Bit>,
    pub entry: Signal<Out, EntryCode>,
    pub exit: Signal<Out, ExitCode>,
    entry_plane: Plane,
    exit_plane: Plane,
    entry_out: Pipe<EntryCode>,
    exit_out: Pipe<ExitCode>,
    entry_max: Constant<EntryCode>,
    exit_max: Constant<ExitCode>,
    exit_none: Constant<ExitCode>,
}

impl AxisSlab {
    pub const CODE_CUTS: usize = 1;

    pub fn new(plane_stages: usize, code_stages: usize) -> Self {
        let cut = placement(code_stages, Self::CODE_CUTS);
        Self {
            clock: Default::default(),
            lo: Default::default(),
            hi: Default::default(),
            offset_lo: Default::default(),
            offset_hi: Default::default(),
            step_lo: Default::default(),
            step_hi: Default::default(),
            lo_inf: Default::default(),
            hi_inf: Default::default(),
            step_lo_inf: Default::default(),
            step_hi_inf: Default::default(),
            positive: Default::default(),
            entry: Default::default(),
            exit: Default::default(),
            entry_plane: Plane::new(plane_stages),
            exit_plane: Plane::new(plane_stages),
            entry_out: Pipe::new(cut[0]),
            exit_out: Pipe::new(cut[0]),
            entry_max: Constant::new(ENTRY_MAX.into()),
            exit_max: Constant::new(ENTRY_MAX.into()),
            exit_none: Constant::new(0xFFFF.into()),
        }
    }
}

impl Logic for AxisSlab {
    #[hdl_gen]
    fn update(&mut self) {
        self.entry_plane.clock.next = self.clock.val();
        self.exit_plane.clock.next = self.clock.val();
        self.entry_out.clock.next = self.clock.val();
        self.exit_out.clock.next = self.clock.val();
        self.entry_plane.offset.next = self.offset_lo.val();
        self.entry_plane.step.next = self.step_lo.val();
        self.entry_plane.offset_inf.next = self.lo_inf.val();
        self.entry_plane.step_inf.next = self.step_lo_inf.val();
        self.exit_plane.offset.next = self.offset_hi.val();
        self.exit_plane.step.next = self.step_hi.val();
        self.exit_plane.offset_inf.next = self.hi_inf.val();
        self.exit_plane.step_inf.next = self.step_hi_inf.val();
        if self.positive.val() {
            self.entry_plane.code.next = self.lo.val();
            self.exit_plane.code.next = self.hi.val();
        } else {
            self.entry_plane.code.next = self.hi.val();
            self.exit_plane.code.next = self.lo.val();
        }
        // plane >> FRAC_BITS: negative (bit 47), beyond ENTRY_MAX (a bit above the code's
        // 15 bits), or the code's bits.
        self.entry_out.d.next = self.entry_plane.plane.val().get_bits::<15>(8);
        if self.entry_plane.plane.val().get_bits::<25>(23).any() {
            self.entry_out.d.next = self.entry_max.val();
        }
        if self.entry_plane.plane.val().get_bit(47) | self.entry_plane.inf.val() {
            self.entry_out.d.next = 0.into();
        }
        self.exit_out.d.next = bit_cast::<16, 15>(self.exit_plane.plane.val().get_bits::<15>(8));
        if self.exit_plane.plane.val().get_bits::<25>(23).any() {
            self.exit_out.d.next = self.exit_max.val();
        }
        if self.exit_plane.plane.val().get_bit(47) {
            self.exit_out.d.next = self.exit_none.val();
        }
        if self.exit_plane.inf.val() {
            self.exit_out.d.next = self.exit_max.val();
        }
        self.entry.next = self.entry_out.q.val();
        self.exit.next = self.exit_out.q.val();
    }
}
