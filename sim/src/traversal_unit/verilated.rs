//! The Verilated traversal unit: `hdl::traversal::unit`'s Verilog built once per
//! configuration and process (the builder's disk cache spans processes), its ports found by
//! name in the packed cycle buffers.

use std::sync::Arc;

use hdl::traversal::config::{unit_verilog, UnitConfig};
use hw_model::traversal::packet::{HIT_WORDS, RAY_WORDS};

use super::{In, Out, UnitError, UnitPorts, HIT_TDATA, IN_NAMES, OUT_NAMES, RAY_TDATA};
use crate::verilator::{BuiltModel, BuiltModels, Direction};
use crate::{SimError, VerilatedModel};

/// A built model of the unit and what it was built from.
pub type UnitModel = BuiltModel<UnitConfig>;

/// The unit of `config`, built (or taken from the builder's cache) once per process.
pub fn unit_model(config: &UnitConfig) -> Result<Arc<UnitModel>, UnitError> {
    static BUILT: BuiltModels<UnitConfig> = BuiltModels::new();
    BUILT.get(config, |c| Ok(unit_verilog(c)?))
}

/// One simulated unit: the inputs held for the next cycle and the outputs of the last.
pub struct VerilatedUnit {
    sim: VerilatedModel,
    inputs: [usize; IN_NAMES.len()],
    outputs: [usize; OUT_NAMES.len()],
    ray: usize,
    hit: usize,
    input: Vec<u32>,
    output: Vec<u32>,
}

impl VerilatedUnit {
    /// A fresh instance of `model` (not yet reset: the driver resets it).
    pub fn new(model: &UnitModel) -> Result<VerilatedUnit, SimError> {
        let sim = model.model.instantiate();
        let iface = sim.interface().clone();
        let mut inputs = [0; IN_NAMES.len()];
        for (i, (port, name)) in IN_NAMES.iter().enumerate() {
            debug_assert_eq!(*port as usize, i);
            inputs[i] = iface.word_offset(Direction::Input, name, None)?;
        }
        let mut outputs = [0; OUT_NAMES.len()];
        for (i, (port, name)) in OUT_NAMES.iter().enumerate() {
            debug_assert_eq!(*port as usize, i);
            outputs[i] = iface.word_offset(Direction::Output, name, None)?;
        }
        let bits = |words: usize| Some(32 * words as u32);
        Ok(VerilatedUnit {
            ray: iface.word_offset(Direction::Input, RAY_TDATA, bits(RAY_WORDS))?,
            hit: iface.word_offset(Direction::Output, HIT_TDATA, bits(HIT_WORDS))?,
            input: vec![0; iface.in_words()],
            output: vec![0; iface.out_words()],
            sim,
            inputs,
            outputs,
        })
    }
}

impl UnitPorts for VerilatedUnit {
    #[inline]
    fn set(&mut self, port: In, value: u32) {
        self.input[self.inputs[port as usize]] = value;
    }

    #[inline]
    fn ray_data(&mut self) -> &mut [u32; RAY_WORDS] {
        (&mut self.input[self.ray..self.ray + RAY_WORDS])
            .try_into()
            .expect("the port's width was checked")
    }

    #[inline]
    fn get(&self, port: Out) -> u32 {
        self.output[self.outputs[port as usize]]
    }

    #[inline]
    fn hit_data(&self) -> [u32; HIT_WORDS] {
        (self.output[self.hit..self.hit + HIT_WORDS])
            .try_into()
            .expect("the port's width was checked")
    }

    #[inline]
    fn cycle(&mut self) -> Result<(), SimError> {
        self.sim.step(&self.input, &mut self.output)
    }

    fn cycles(&self) -> u64 {
        self.sim.cycles()
    }
}
