//! One plane of one child on one axis: `offset + q·step` in a DSP48E1 (25-bit signed step,
//! 8-bit code, 48-bit offset and sum), and whether the plane is infinite instead: its offset
//! is, or its step is and the code is not 0 (`q·∞` with `q = 0` is 0, as in the model).
//!
//! Cut points ([`Plane::CUTS`]): 0. the DSP's input registers (the code's B register; the
//! offset and the step are shared by a node's children, so their registers stay in the
//! fabric); 1. its output register P.

use rust_hdl::prelude::*;

use super::{Code, Offset, Step, STEP_BITS};
use crate::intmul::MulAdd;
use crate::pipe::{placement, Pipe};

#[derive(LogicBlock)]
pub struct Plane {
    pub clock: Signal<In, Clock>,
    pub offset: Signal<In, Offset>,
    pub step: Signal<In, Step>,
    pub code: Signal<In, Code>,
    pub offset_inf: Signal<In, Bit>,
    pub step_inf: Signal<In, Bit>,
    pub plane: Signal<Out, Offset>,
    pub inf: Signal<Out, Bit>,
    offset_in: Pipe<Offset>,
    step_in: Pipe<Step>,
    code_in: Pipe<Code>,
    inf_in: Pipe<Bit>,
    multiply_add: MulAdd<STEP_BITS, 8>,
    plane_out: Pipe<Offset>,
    inf_out: Pipe<Bit>,
}

impl Plane {
    pub const CUTS: usize = 2;

    pub fn max_stages() -> usize {
        Self::CUTS
    }

    pub fn new(stages: usize) -> Self {
        let cut = placement(stages, Self::CUTS);
        Self {
            clock: Default::default(),
            offset: Default::default(),
            step: Default::default(),
            code: Default::default(),
            offset_inf: Default::default(),
            step_inf: Default::default(),
            plane: Default::default(),
            inf: Default::default(),
            offset_in: Pipe::new(cut[0]),
            step_in: Pipe::new(cut[0]),
            code_in: Pipe::new(cut[0]),
            inf_in: Pipe::new(cut[0]),
            multiply_add: Default::default(),
            plane_out: Pipe::new(cut[1]),
            inf_out: Pipe::new(cut[1]),
        }
    }
}

impl Logic for Plane {
    #[hdl_gen]
    fn update(&mut self) {
        self.offset_in.clock.next = self.clock.val();
        self.step_in.clock.next = self.clock.val();
        self.code_in.clock.next = self.clock.val();
        self.inf_in.clock.next = self.clock.val();
        self.plane_out.clock.next = self.clock.val();
        self.inf_out.clock.next = self.clock.val();
        self.offset_in.d.next = self.offset.val();
        self.step_in.d.next = self.step.val();
        self.code_in.d.next = self.code.val();
        self.inf_in.d.next = self.offset_inf.val() | (self.step_inf.val() & self.code.val().any());
        self.multiply_add.a.next = self.step_in.q.val();
        self.multiply_add.b.next = self.code_in.q.val();
        self.multiply_add.c.next = self.offset_in.q.val();
        self.plane_out.d.next = self.multiply_add.p.val();
        self.inf_out.d.next = self.inf_in.q.val();
        self.plane.next = self.plane_out.q.val();
        self.inf.next = self.inf_out.q.val();
    }
}
