//! Models built once per process and configuration: a driver asks for the model of a
//! configuration, and the first ask generates its Verilog and builds it (or loads it from the
//! builder's disk cache, which spans processes).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use super::{build, BuildOptions, Model, ModelSpec};
use crate::SimError;

/// A built model and what it was built from.
pub struct BuiltModel<C> {
    pub config: C,
    pub model: Model,
    /// Time spent generating the Verilog and building (or loading) the model.
    pub build_time: Duration,
}

/// The models of one kind of design, by configuration (for a `static`).
pub struct BuiltModels<C>(Mutex<Vec<Arc<BuiltModel<C>>>>);

impl<C: Clone + PartialEq> Default for BuiltModels<C> {
    fn default() -> Self {
        Self::new()
    }
}

impl<C: Clone + PartialEq> BuiltModels<C> {
    pub const fn new() -> Self {
        BuiltModels(Mutex::new(Vec::new()))
    }

    /// The model of `config`, its Verilog from `verilog` the first time. Builds are
    /// serialised: each one already uses every core.
    pub fn get<E: From<SimError>>(
        &self,
        config: &C,
        verilog: impl FnOnce(&C) -> Result<String, E>,
    ) -> Result<Arc<BuiltModel<C>>, E> {
        let mut built = self
            .0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(m) = built.iter().find(|m| m.config == *config) {
            return Ok(m.clone());
        }
        let start = Instant::now();
        let verilog = verilog(config)?;
        let model = build(&ModelSpec::rust_hdl(verilog), &BuildOptions::default())?;
        let m = Arc::new(BuiltModel {
            config: config.clone(),
            model,
            build_time: start.elapsed(),
        });
        built.push(m.clone());
        Ok(m)
    }
}
