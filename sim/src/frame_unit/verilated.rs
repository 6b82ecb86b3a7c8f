//! The Verilated frame engine: `hdl::frame::engine`'s Verilog built once per configuration
//! and process (the builder's disk cache spans processes), its ports found by name in the
//! packed cycle buffers.

use std::sync::Arc;

use hdl::frame::engine::{
    frame_engine_verilog, CAMERA_BITS, COUNTERS, LOAD_DATA_BITS, LOAD_DATA_WORDS,
};
use hdl::traversal::ports::{HIT_BITS, RAY_BITS};
use hw_model::traversal::packet::{HIT_WORDS, RAY_WORDS};

use super::{EngineConfig, FrameSimError};
use crate::verilator::{BuiltModel, BuiltModels, Direction, Interface};
use crate::{SimError, VerilatedModel};

/// A built model of the engine and what it was built from.
pub type EngineModel = BuiltModel<EngineConfig>;

/// The engine of `config`, built (or taken from the builder's cache) once per process.
pub fn engine_model(config: &EngineConfig) -> Result<Arc<EngineModel>, FrameSimError> {
    static BUILT: BuiltModels<EngineConfig> = BuiltModels::new();
    BUILT.get(config, |c| match c.triangle_bits {
        12 => Ok(frame_engine_verilog::<12>(c.depth)),
        14 => Ok(frame_engine_verilog::<14>(c.depth)),
        bits => Err(FrameSimError::Usage(format!(
            "a triangle memory of {bits} address bits: the co-simulation builds 12 or 14"
        ))),
    })
}

/// The engine's inputs the driver sets (each at most 32 bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
    LoadProgram,
    LoadConstant,
    LoadTriangle,
    LoadObject,
    LoadAddress,
    Width,
    Height,
    MissEntry,
    MissCasts,
    MaxDepth,
    Reservation,
    SpawnReserve,
    EscapeReserve,
    Start,
    RayTready,
    HitTvalid,
    PixelReady,
}

/// The ports the driver sets, in [`In`] order (rust-hdl's flattened names).
const IN_NAMES: [&str; 17] = [
    "load_program",
    "load_constant",
    "load_triangle",
    "load_object",
    "load_address",
    "width",
    "height",
    "miss_entry",
    "miss_casts",
    "max_depth",
    "reservation",
    "spawn_reserve",
    "escape_reserve",
    "start",
    "ray$tready",
    "hit$tvalid",
    "pixel_ready",
];

/// The engine's outputs the driver reads (each at most 32 bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Out {
    Idle,
    Done,
    RayTvalid,
    HitTready,
    PixelValid,
    PixelIndex,
    PixelRgb,
}

const OUT_NAMES: [&str; 7] = [
    "idle",
    "done",
    "ray$tvalid",
    "hit$tready",
    "pixel_valid",
    "pixel_index",
    "pixel_rgb",
];

/// One simulated engine: the inputs held for the next cycle and the outputs of the last.
pub struct VerilatedEngine {
    sim: VerilatedModel,
    inputs: [usize; IN_NAMES.len()],
    outputs: [usize; OUT_NAMES.len()],
    load_data: usize,
    camera: usize,
    ray: usize,
    hit: usize,
    counters: [usize; COUNTERS.len()],
    core_counters: [usize; 3],
    input: Vec<u32>,
    output: Vec<u32>,
}

fn offset(
    iface: &Interface,
    d: Direction,
    name: &str,
    bits: Option<usize>,
) -> Result<usize, SimError> {
    iface.word_offset(d, name, bits.map(|b| b as u32))
}

impl VerilatedEngine {
    /// A fresh instance of `model` (its flip-flops at their power-on zeros).
    pub fn new(model: &EngineModel) -> Result<VerilatedEngine, SimError> {
        let sim = model.model.instantiate();
        let iface = sim.interface().clone();
        let (i, o) = (Direction::Input, Direction::Output);
        let mut inputs = [0; IN_NAMES.len()];
        for (k, name) in IN_NAMES.iter().enumerate() {
            inputs[k] = offset(&iface, i, name, None)?;
        }
        let mut outputs = [0; OUT_NAMES.len()];
        for (k, name) in OUT_NAMES.iter().enumerate() {
            outputs[k] = offset(&iface, o, name, None)?;
        }
        let mut counters = [0; COUNTERS.len()];
        for (k, c) in counters.iter_mut().enumerate() {
            *c = offset(&iface, o, &format!("counters${k}"), None)?;
        }
        let mut core_counters = [0; 3];
        for (k, c) in core_counters.iter_mut().enumerate() {
            *c = offset(&iface, o, &format!("core_counters${k}"), None)?;
        }
        Ok(VerilatedEngine {
            load_data: offset(&iface, i, "load_data", Some(LOAD_DATA_BITS))?,
            camera: offset(&iface, i, "camera", Some(CAMERA_BITS))?,
            ray: offset(&iface, o, "ray$tdata", Some(RAY_BITS))?,
            hit: offset(&iface, i, "hit$tdata", Some(HIT_BITS))?,
            input: vec![0; iface.in_words()],
            output: vec![0; iface.out_words()],
            sim,
            inputs,
            outputs,
            counters,
            core_counters,
        })
    }

    pub fn set(&mut self, port: In, value: u32) {
        self.input[self.inputs[port as usize]] = value;
    }

    pub fn get(&self, port: Out) -> u32 {
        self.output[self.outputs[port as usize]]
    }

    pub fn load_data(&mut self) -> &mut [u32] {
        &mut self.input[self.load_data..self.load_data + LOAD_DATA_WORDS]
    }

    pub fn camera(&mut self) -> &mut [u32] {
        &mut self.input[self.camera..self.camera + CAMERA_BITS / 32]
    }

    pub fn hit_data(&mut self) -> &mut [u32] {
        &mut self.input[self.hit..self.hit + HIT_WORDS]
    }

    pub fn ray_data(&self) -> [u32; RAY_WORDS] {
        (self.output[self.ray..self.ray + RAY_WORDS])
            .try_into()
            .expect("the port's width was checked")
    }

    /// [`COUNTERS`]' values as sampled in the last cycle.
    pub fn counters(&self) -> [u32; COUNTERS.len()] {
        self.counters.map(|k| self.output[k])
    }

    /// The shader core's counters (`Counter::ALL`'s order, from power-on).
    pub fn core_counters(&self) -> [u32; 3] {
        self.core_counters.map(|k| self.output[k])
    }

    pub fn cycle(&mut self) -> Result<(), SimError> {
        self.sim.step(&self.input, &mut self.output)
    }

    pub fn cycles(&self) -> u64 {
        self.sim.cycles()
    }
}
