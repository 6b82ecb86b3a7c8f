//! The node's far end in codes, `⌈(t_hi − τ)/2^U⌉` clamped to `−1..=CODE_LIMIT` (−1 enters
//! nothing: a NaN far end), and whether the node's children are all entered instead (no
//! bound fixes its grid, `t0` is NaN, or `τ` reaches `OFFSET_SAT`): the model's `t_hi_code`
//! with its limit, and its `unknown`.
//!
//! In units of `2^(U−8)`: `v = ⌈t_hi·2^(8−U)⌉ − τ + 255`, the code is `v >> 8`.
//!
//! Cut points ([`FarCode::CUTS`]), one carry chain each: 0. after `⌈t_hi⌉ + 255`; 1. after
//! `v`; 2. the results, clamped. (The far end waits for the planes anyway: its third register
//! costs no latency.)

use rust_hdl::prelude::*;

use super::{ExitCode, Magnitude, Offset};
use crate::pipe::{placement, Pipe};
use hw_model::traversal::wide::box_test::{CODE_LIMIT, FRAC_BITS, OFFSET_SAT};

// The clamp tests the bits of CODE_LIMIT = 2^14 + 1 in units of 2^FRAC_BITS = 2^8.
const _: () = assert!(CODE_LIMIT == (1 << 14) + 1 && FRAC_BITS == 8);

#[derive(LogicBlock)]
pub struct FarCode {
    pub clock: Signal<In, Clock>,
    pub t_hi_floor: Signal<In, Magnitude>,
    pub t_hi_ceil: Signal<In, Magnitude>,
    pub t_hi_negative: Signal<In, Bit>,
    pub t_hi_nan: Signal<In, Bit>,
    pub tau: Signal<In, Magnitude>,
    pub t0_nan: Signal<In, Bit>,
    /// The grid is fixed by some bound ([`super::grid::NodeGrid`]).
    pub bounded: Signal<In, Bit>,
    pub far_end: Signal<Out, ExitCode>,
    pub unknown: Signal<Out, Bit>,
    /// Cut 0.
    rounded_up: Pipe<Offset>,
    tau_0: Pipe<Offset>,
    nan_0: Pipe<Bit>,
    unknown_0: Pipe<Bit>,
    /// Cut 1.
    from_tau: Pipe<Offset>,
    nan_1: Pipe<Bit>,
    unknown_1: Pipe<Bit>,
    /// Cut 2.
    far_out: Pipe<ExitCode>,
    unknown_out: Pipe<Bit>,
    exit_round: Constant<Offset>,
    sat: Constant<Offset>,
    limit: Constant<ExitCode>,
    none: Constant<ExitCode>,
}

impl FarCode {
    pub const CUTS: usize = 3;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            t_hi_floor: Default::default(),
            t_hi_ceil: Default::default(),
            t_hi_negative: Default::default(),
            t_hi_nan: Default::default(),
            tau: Default::default(),
            t0_nan: Default::default(),
            bounded: Default::default(),
            far_end: Default::default(),
            unknown: Default::default(),
            rounded_up: Pipe::new(cut[0]),
            tau_0: Pipe::new(cut[0]),
            nan_0: Pipe::new(cut[0]),
            unknown_0: Pipe::new(cut[0]),
            from_tau: Pipe::new(cut[1]),
            nan_1: Pipe::new(cut[1]),
            unknown_1: Pipe::new(cut[1]),
            far_out: Pipe::new(cut[2]),
            unknown_out: Pipe::new(cut[2]),
            exit_round: Constant::new(((1u64 << FRAC_BITS) - 1).into()),
            sat: Constant::new((OFFSET_SAT as u64).into()),
            limit: Constant::new((CODE_LIMIT as u64).into()),
            none: Constant::new(0xFFFF.into()),
        }
    }
}

impl Logic for FarCode {
    #[hdl_gen]
    fn update(&mut self) {
        self.rounded_up.clock.next = self.clock.val();
        self.tau_0.clock.next = self.clock.val();
        self.nan_0.clock.next = self.clock.val();
        self.unknown_0.clock.next = self.clock.val();
        self.from_tau.clock.next = self.clock.val();
        self.nan_1.clock.next = self.clock.val();
        self.unknown_1.clock.next = self.clock.val();
        self.far_out.clock.next = self.clock.val();
        self.unknown_out.clock.next = self.clock.val();
        // ⌈t_hi⌉ of a negative t_hi is −⌊|t_hi|⌋.
        if self.t_hi_negative.val() {
            self.rounded_up.d.next =
                self.exit_round.val() - bit_cast::<48, 47>(self.t_hi_floor.val());
        } else {
            self.rounded_up.d.next =
                bit_cast::<48, 47>(self.t_hi_ceil.val()) + self.exit_round.val();
        }
        self.tau_0.d.next = bit_cast::<48, 47>(self.tau.val());
        self.nan_0.d.next = self.t_hi_nan.val();
        self.unknown_0.d.next = !self.bounded.val()
            | self.t0_nan.val()
            | (bit_cast::<48, 47>(self.tau.val()) >= self.sat.val());
        self.from_tau.d.next = self.rounded_up.q.val() - self.tau_0.q.val();
        self.nan_1.d.next = self.nan_0.q.val();
        self.unknown_1.d.next = self.unknown_0.q.val();
        // v >> 8 clamped to −1..=CODE_LIMIT = 2^14 + 1: v ≥ 2^22 + 2^8 is the limit.
        self.far_out.d.next = bit_cast::<16, 48>(self.from_tau.q.val() >> 8);
        if self.from_tau.q.val().get_bits::<24>(23).any()
            | (self.from_tau.q.val().get_bit(22) & self.from_tau.q.val().get_bits::<14>(8).any())
        {
            self.far_out.d.next = self.limit.val();
        }
        if self.from_tau.q.val().get_bit(47) | self.nan_1.q.val() {
            self.far_out.d.next = self.none.val();
        }
        self.unknown_out.d.next = self.unknown_1.q.val();
        self.far_end.next = self.far_out.q.val();
        self.unknown.next = self.unknown_out.q.val();
    }
}
