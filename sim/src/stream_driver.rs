//! Batches of queries through the accelerator's AXI4-Stream front end, cycle by cycle.
//!
//! Each input beat carries one query per lane (docs/stream.md: words 0–15 the query with its
//! t_min, word 16 `valid | tag << 8`); a beat is presented until `s_axis_tready` takes it and the next one
//! follows in the next cycle, so every lane gets a query each cycle the front end is ready.
//! Output beat k answers input beat k: its slots are matched to the queries by position and
//! checked against the tags, the valid flags and `tlast`.

use crate::accel_model::{Accel, In, Out};
use crate::cosim_error::CosimError;
use hdl::mt::query_words;
use hdl::top::stream::{
    CTRL_VALID, CTRL_WORD, FIFO_DEPTH, FLAG_HIT, FLAG_VALID, TAG_BITS, TAG_SHIFT,
};
use hw_model::{MtQuery, MtResult};

/// What one batch cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StreamStats {
    /// Queries tested.
    pub tests: u64,
    /// Clock cycles from presenting the first beat to taking the last result.
    pub cycles: u64,
    /// Input beats (and output beats): `ceil(tests / lanes)`.
    pub beats: u64,
    /// Cycles in which a presented beat was refused (`s_axis_tvalid` high, `tready` low).
    pub input_stalls: u64,
}

impl std::ops::AddAssign for StreamStats {
    fn add_assign(&mut self, o: Self) {
        self.tests += o.tests;
        self.cycles += o.cycles;
        self.beats += o.beats;
        self.input_stalls += o.input_stalls;
    }
}

const TAG_MASK: u32 = (1 << TAG_BITS) - 1;

/// Puts beat `beat` (queries `beat·lanes ..`) into the input slots; lanes past the end get
/// an invalid slot.
fn load_beat(accel: &mut Accel, queries: &[MtQuery], beat: usize) {
    let lanes = accel.lanes();
    for lane in 0..lanes {
        let index = beat * lanes + lane;
        let slot = accel.in_slot(lane);
        match queries.get(index) {
            Some(q) => {
                slot[..CTRL_WORD].copy_from_slice(&query_words(q));
                slot[CTRL_WORD] = CTRL_VALID | (index as u32 & TAG_MASK) << TAG_SHIFT;
            }
            None => slot.fill(0),
        }
    }
}

/// Checks output beat `beat` as sampled now and stores its results.
fn take_beat(
    accel: &Accel,
    beat: usize,
    beats: usize,
    results: &mut [MtResult],
) -> Result<(), CosimError> {
    let lanes = accel.lanes();
    let protocol = |message: String| CosimError::Protocol {
        bus: "AXI4-Stream",
        cycle: accel.cycles(),
        message,
    };
    let last = accel.get(Out::MTLast) == 1;
    if last != (beat + 1 == beats) {
        return Err(protocol(format!(
            "m_axis_tlast = {last} on output beat {beat} of {beats}"
        )));
    }
    for lane in 0..lanes {
        let index = beat * lanes + lane;
        let slot = accel.out_slot(lane);
        let valid = slot[0] & FLAG_VALID != 0;
        match results.get_mut(index) {
            Some(r) => {
                let tag = slot[0] >> TAG_SHIFT;
                if !valid || tag != index as u32 & TAG_MASK {
                    return Err(protocol(format!(
                        "output beat {beat} lane {lane}: expected the result of query {index} (tag {:#x}), found valid = {valid}, tag {tag:#x}",
                        index as u32 & TAG_MASK
                    )));
                }
                *r = MtResult {
                    hit: slot[0] & FLAG_HIT != 0,
                    t: f32::from_bits(slot[1]),
                    u: f32::from_bits(slot[2]),
                    v: f32::from_bits(slot[3]),
                };
            }
            None if valid => {
                return Err(protocol(format!(
                    "output beat {beat} lane {lane} is valid but its input slot was empty"
                )))
            }
            None => {}
        }
    }
    Ok(())
}

/// Streams `queries` through `accel` and writes one result per query into `results`.
/// `sink_ready` gives `m_axis_tready` for each cycle (always `true` for full speed; a pattern
/// exercises back-pressure).
pub fn stream_batch(
    accel: &mut Accel,
    queries: &[MtQuery],
    results: &mut [MtResult],
    sink_ready: &mut dyn FnMut() -> bool,
) -> Result<StreamStats, CosimError> {
    assert_eq!(queries.len(), results.len(), "one result slot per query");
    let beats = queries.len().div_ceil(accel.lanes());
    // A refused beat waits for the FIFO to drain; no progress for this long means a hang.
    let budget = 4 * (accel.lane_latency() + FIFO_DEPTH) as u64 + 1000;
    let start = accel.cycles();
    let (mut sent, mut received, mut stalls) = (0, 0, 0);
    let mut last_progress = start;
    if beats > 0 {
        load_beat(accel, queries, 0);
    }
    while received < beats {
        let sink = sink_ready();
        accel.set(In::MTReady, u32::from(sink));
        accel.set(In::STValid, u32::from(sent < beats));
        accel.set(In::STLast, u32::from(sent + 1 == beats));
        accel.cycle()?;
        if sent < beats {
            if accel.get(Out::STReady) == 1 {
                sent += 1;
                last_progress = accel.cycles();
                if sent < beats {
                    load_beat(accel, queries, sent);
                }
            } else {
                stalls += 1;
            }
        }
        if sink && accel.get(Out::MTValid) == 1 {
            if received >= sent {
                return Err(CosimError::Protocol {
                    bus: "AXI4-Stream",
                    cycle: accel.cycles(),
                    message: format!("output beat {received} before its input beat was taken"),
                });
            }
            take_beat(accel, received, beats, results)?;
            received += 1;
            last_progress = accel.cycles();
        }
        if accel.cycles() - last_progress > budget {
            return Err(CosimError::Timeout {
                what: format!(
                    "stream batch of {} queries: {sent} of {beats} beats sent, {received} results",
                    queries.len()
                ),
                cycles: budget,
            });
        }
    }
    accel.set(In::STValid, 0);
    accel.set(In::STLast, 0);
    Ok(StreamStats {
        tests: queries.len() as u64,
        cycles: accel.cycles() - start,
        beats: beats as u64,
        input_stalls: stalls,
    })
}
