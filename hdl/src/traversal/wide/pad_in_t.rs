//! The wide ray's padding in t: `pad_t = pad·|inv_dir|` per axis (three fp32 multiplies),
//! what the wide box stage takes beside the fp32 ray setup's words, bit for bit
//! `hw_model::traversal::wide::box_test::WideRay::from_setup`. It follows the ray setup
//! (`ray_setup::RaySetupUnit`, whose `pad` and `inv_dir` it reads) in the wide unit, one ray a
//! cycle; [`PadInT::latency`] cycles (one fp32 `Mul`'s) from `valid_in` to `valid_out`.

use rust_hdl::prelude::*;

use super::Word;
use crate::formats::fp32::{self, Mul};
use crate::harness::{simulate_cycles, Stepped};
use crate::macros::clock;
use crate::mt::delay::Delay;
use crate::mt::schedule::OpLatencies;

#[derive(LogicBlock)]
pub struct PadInT {
    pub clock: Signal<In, Clock>,
    pub valid_in: Signal<In, Bit>,
    pub pad: Signal<In, Word>,
    pub inv_dir: [Signal<In, Word>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub pad_t: [Signal<Out, Word>; 3],
    scale: [Mul; 3],
    valid: Delay<Bit>,
    /// Clears an fp32 word's sign: `|x|`.
    magnitude: Constant<Word>,
}

impl PadInT {
    /// The block at `depth` (its multiplies' registers: `min(depth, Mul`'s stages)).
    pub fn new(depth: usize) -> Self {
        let mul = Self::latency(depth);
        Self {
            clock: Default::default(),
            valid_in: Default::default(),
            pad: Default::default(),
            inv_dir: Default::default(),
            valid_out: Default::default(),
            pad_t: Default::default(),
            scale: std::array::from_fn(|_| Mul::new(mul)),
            valid: Delay::new(mul),
            magnitude: Constant::new(0x7FFF_FFFF_u64.into()),
        }
    }

    /// Cycles from `valid_in` to `valid_out` at `depth`.
    pub fn latency(depth: usize) -> usize {
        OpLatencies::for_depth(depth, fp32::max_stages).mul
    }
}

impl Logic for PadInT {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, valid);
        self.valid.d.next = self.valid_in.val();
        self.valid_out.next = self.valid.q.val();
        for a in 0..3 {
            self.scale[a].clock.next = self.clock.val();
            self.scale[a].a.next = self.pad.val();
            self.scale[a].b.next = self.inv_dir[a].val() & self.magnitude.val();
            self.pad_t[a].next = self.scale[a].y.val();
        }
    }
}

/// One cycle's inputs: valid, pad, inv_dir x y z (fp32 words).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PadInput {
    pub valid: bool,
    pub pad: u32,
    pub inv_dir: [u32; 3],
}

/// What the outputs show in one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PadOutput {
    pub valid: bool,
    pub pad_t: [u32; 3],
}

impl Stepped for PadInT {
    type Input = PadInput;
    type Output = PadOutput;

    fn idle() -> PadInput {
        PadInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, x: &PadInput) {
        self.valid_in.next = x.valid;
        self.pad.next = u64::from(x.pad).into();
        for a in 0..3 {
            self.inv_dir[a].next = u64::from(x.inv_dir[a]).into();
        }
    }

    fn observe(&self) -> PadOutput {
        PadOutput {
            valid: self.valid_out.val(),
            pad_t: std::array::from_fn(|a| self.pad_t[a].val().to_u64() as u32),
        }
    }
}

/// The block at `depth` in rust-hdl's simulator: `inputs` then `flush` idle cycles, the
/// outputs of every cycle.
pub fn simulate_pad_in_t(depth: usize, inputs: &[PadInput], flush: usize) -> Vec<PadOutput> {
    simulate_cycles(move || PadInT::new(depth), inputs, flush)
}
