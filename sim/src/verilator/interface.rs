//! How a model's ports map onto the packed word buffers that cross the FFI.
//!
//! Inputs (without the clock) and outputs are packed in port order, each port taking
//! `ceil(width / 32)` little-endian 32-bit words.

use super::ports::{Direction, Port};
use crate::SimError;

/// The clock and the data ports of a top module.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Interface {
    pub clock: Option<String>,
    pub inputs: Vec<Port>,
    pub outputs: Vec<Port>,
}

impl Interface {
    /// Splits `ports` into the clock (a 1-bit input named `clock`, if given) and the data ports.
    pub fn new(ports: &[Port], clock: Option<&str>) -> Result<Self, SimError> {
        if let Some(name) = clock {
            match ports.iter().find(|p| p.name == name) {
                Some(p) if p.direction == Direction::Input && p.width == 1 => {}
                Some(p) => {
                    return Err(SimError::Interface(format!(
                        "clock `{name}` must be a 1-bit input, found {:?} of width {}",
                        p.direction, p.width
                    )))
                }
                None => {
                    let names: Vec<&str> = ports.iter().map(|p| p.name.as_str()).collect();
                    return Err(SimError::Interface(format!(
                        "no clock port `{name}` among the ports [{}] (use no clock for a combinational design)",
                        names.join(", ")
                    )));
                }
            }
        }
        let data = |dir| -> Vec<Port> {
            ports
                .iter()
                .filter(|p| p.direction == dir && Some(p.name.as_str()) != clock)
                .cloned()
                .collect()
        };
        Ok(Interface {
            clock: clock.map(str::to_string),
            inputs: data(Direction::Input),
            outputs: data(Direction::Output),
        })
    }

    pub fn in_words(&self) -> usize {
        self.inputs.iter().map(Port::words).sum()
    }

    pub fn out_words(&self) -> usize {
        self.outputs.iter().map(Port::words).sum()
    }

    /// Word offset of port `name` in the packed inputs or outputs, checking its width
    /// (`None`: at most 32 bits, one word).
    pub fn word_offset(
        &self,
        direction: Direction,
        name: &str,
        width: Option<u32>,
    ) -> Result<usize, SimError> {
        let ports = match direction {
            Direction::Input => &self.inputs,
            Direction::Output => &self.outputs,
        };
        let mut at = 0;
        for p in ports {
            if p.name == name {
                return match width {
                    Some(w) if w != p.width => Err(SimError::Interface(format!(
                        "port `{name}` is {} bits wide, expected {w}",
                        p.width
                    ))),
                    None if p.width > 32 => Err(SimError::Interface(format!(
                        "port `{name}` is {} bits wide, expected at most 32",
                        p.width
                    ))),
                    _ => Ok(at),
                };
            }
            at += p.words();
        }
        Err(SimError::Interface(format!(
            "the model has no {direction:?} port `{name}`"
        )))
    }

    /// Appends one cycle's input words for `values` (one per input port, each ≤ 64 bits wide).
    pub fn pack_inputs(&self, values: &[u64], words: &mut Vec<u32>) -> Result<(), SimError> {
        check_narrow(&self.inputs, values.len(), "input")?;
        for (p, v) in self.inputs.iter().zip(values) {
            words.push(*v as u32);
            if p.words() == 2 {
                words.push((v >> 32) as u32);
            }
        }
        Ok(())
    }

    /// One cycle's output values (one per output port, each ≤ 64 bits wide) from its words.
    pub fn unpack_outputs(&self, words: &[u32], values: &mut [u64]) -> Result<(), SimError> {
        check_narrow(&self.outputs, values.len(), "output")?;
        let mut w = 0;
        for (p, v) in self.outputs.iter().zip(values) {
            *v = u64::from(words[w]);
            if p.words() == 2 {
                *v |= u64::from(words[w + 1]) << 32;
            }
            w += p.words();
        }
        Ok(())
    }
}

/// Value-per-port packing needs as many values as ports and ports of at most 64 bits.
fn check_narrow(ports: &[Port], values: usize, what: &str) -> Result<(), SimError> {
    if ports.len() != values {
        return Err(SimError::Interface(format!(
            "{values} {what} values given, the model has {} {what} ports",
            ports.len()
        )));
    }
    match ports.iter().find(|p| p.width > 64) {
        Some(p) => Err(SimError::Interface(format!(
            "{what} port `{}` is {} bits wide; use the packed word interface for ports over 64 bits",
            p.name, p.width
        ))),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ports() -> Vec<Port> {
        vec![
            Port::new("clock", Direction::Input, 1),
            Port::new("a", Direction::Input, 40),
            Port::new("b", Direction::Input, 3),
            Port::new("y", Direction::Output, 100),
        ]
    }

    #[test]
    fn clock_is_not_a_data_input() {
        let i = Interface::new(&ports(), Some("clock")).unwrap();
        assert_eq!(i.inputs.len(), 2);
        assert_eq!((i.in_words(), i.out_words()), (3, 4));
        let comb = Interface::new(&ports(), None).unwrap();
        assert_eq!(comb.in_words(), 4);
    }

    #[test]
    fn values_round_trip_through_words() {
        let narrow = vec![
            Port::new("a", Direction::Input, 40),
            Port::new("b", Direction::Input, 3),
            Port::new("x", Direction::Output, 40),
            Port::new("y", Direction::Output, 3),
        ];
        let i = Interface::new(&narrow, None).unwrap();
        let mut words = Vec::new();
        i.pack_inputs(&[0xAB_1234_5678, 5], &mut words).unwrap();
        assert_eq!(words, vec![0x1234_5678, 0xAB, 5]);
        let mut values = [0; 2];
        i.unpack_outputs(&words, &mut values).unwrap();
        assert_eq!(values, [0xAB_1234_5678, 5]);
        assert!(i.pack_inputs(&[1], &mut words).is_err());
        assert_eq!(i.word_offset(Direction::Input, "b", Some(3)).unwrap(), 2);
        assert_eq!(i.word_offset(Direction::Output, "y", None).unwrap(), 2);
        for (dir, name, width, needle) in [
            (
                Direction::Input,
                "a",
                None,
                "`a` is 40 bits wide, expected at most 32",
            ),
            (
                Direction::Input,
                "b",
                Some(4),
                "`b` is 3 bits wide, expected 4",
            ),
            (Direction::Output, "a", None, "no Output port `a`"),
        ] {
            let e = i.word_offset(dir, name, width).unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
        let wide = Interface::new(&ports(), Some("clock")).unwrap();
        let e = wide
            .unpack_outputs(&[0; 4], &mut [0])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`y` is 100 bits"), "{e}");
    }

    #[test]
    fn bad_clock_is_an_error() {
        let e = Interface::new(&ports(), Some("ap_clk"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no clock port `ap_clk`") && e.contains("clock, a, b, y"),
            "{e}"
        );
        assert!(Interface::new(&ports(), Some("a")).is_err());
    }
}
