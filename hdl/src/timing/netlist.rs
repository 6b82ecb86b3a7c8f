//! The parts of yosys' `write_json` netlist that the timing analysis reads: one flattened
//! module's cells (type, parameters, port directions, connections) and its net names.

use serde::Deserialize;
use std::collections::HashMap;

use super::TimingError;

/// One bit of a connection: a net, or a constant (`"0"`, `"1"`, `"x"`, `"z"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Bit {
    Net(u32),
    Const,
}

impl<'de> Deserialize<'de> for Bit {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Net(u32),
            Const(serde::de::IgnoredAny),
        }
        Ok(match Raw::deserialize(d)? {
            Raw::Net(n) => Bit::Net(n),
            Raw::Const(_) => Bit::Const,
        })
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Direction {
    Input,
    Output,
    Inout,
}

#[derive(Debug, Deserialize)]
pub(crate) struct Cell {
    #[serde(rename = "type")]
    pub kind: String,
    #[serde(default)]
    pub hide_name: u8,
    #[serde(default)]
    pub parameters: HashMap<String, String>,
    #[serde(default)]
    pub port_directions: HashMap<String, Direction>,
    pub connections: HashMap<String, Vec<Bit>>,
}

#[derive(Debug, Deserialize)]
pub(crate) struct NetName {
    #[serde(default)]
    pub hide_name: u8,
    pub bits: Vec<Bit>,
}

#[derive(Debug, Deserialize)]
pub(crate) struct Port {
    pub direction: Direction,
    pub bits: Vec<Bit>,
}

#[derive(Debug, Deserialize)]
pub(crate) struct Module {
    #[serde(default)]
    pub ports: HashMap<String, Port>,
    #[serde(default)]
    pub cells: HashMap<String, Cell>,
    #[serde(default)]
    pub netnames: HashMap<String, NetName>,
}

#[derive(Debug, Deserialize)]
struct Design {
    modules: HashMap<String, Module>,
}

/// Module `top` of a `write_json` netlist.
pub(crate) fn parse(json: &str, top: &str) -> Result<Module, TimingError> {
    let mut design: Design = serde_json::from_str(json).map_err(|e| TimingError::Netlist {
        detail: e.to_string(),
    })?;
    design
        .modules
        .remove(top)
        .ok_or_else(|| TimingError::Netlist {
            detail: format!("no module `{top}` in the netlist"),
        })
}

impl Cell {
    /// A parameter as yosys writes it: a binary string for numbers, the text for strings.
    pub fn parameter(&self, name: &str) -> Option<&str> {
        self.parameters.get(name).map(|s| s.trim_end())
    }

    /// An integer parameter (yosys writes them as binary strings), `default` when absent.
    pub fn int_parameter(&self, name: &str, default: u64) -> u64 {
        match self.parameter(name) {
            Some(s) if !s.is_empty() && s.bytes().all(|b| b == b'0' || b == b'1') => {
                // Wider than 64 bits: the low 64 decide (register enables are 0 or 1).
                let low = &s[s.len().saturating_sub(64)..];
                u64::from_str_radix(low, 2).unwrap_or(default)
            }
            _ => default,
        }
    }
}
