//! Streaming test vectors through a pipelined operator: one vector per cycle (II = 1).

use super::model::VerilatedModel;
use crate::SimError;

/// Cycles handed to the model per FFI call: large enough to amortise the call, small enough
/// to keep the buffers in cache.
const CHUNK: usize = 4096;

/// Feeds `inputs[i]` (one value per input port, in port order) in cycle `i` and returns, for
/// each, the outputs sampled `latency` cycles later — the result of an operator with `latency`
/// register stages (0 for a combinational one). Cycles after the last vector feed zeros.
pub fn run_pipelined<const N: usize, const M: usize>(
    model: &mut VerilatedModel,
    inputs: &[[u64; N]],
    latency: usize,
) -> Result<Vec<[u64; M]>, SimError> {
    let iface = model.interface().clone();
    let total = inputs.len() + latency;
    let zeros = [0u64; N];
    let mut results = Vec::with_capacity(inputs.len());
    let mut in_words = Vec::with_capacity(CHUNK * iface.in_words());
    let mut out_words = Vec::new();
    for start in (0..total).step_by(CHUNK) {
        let end = (start + CHUNK).min(total);
        in_words.clear();
        for cycle in start..end {
            iface.pack_inputs(inputs.get(cycle).unwrap_or(&zeros), &mut in_words)?;
        }
        out_words.resize((end - start) * iface.out_words(), 0);
        model.run(&in_words, &mut out_words)?;
        for cycle in start.max(latency)..end {
            let mut values = [0u64; M];
            let offset = (cycle - start) * iface.out_words();
            iface.unpack_outputs(&out_words[offset..offset + iface.out_words()], &mut values)?;
            results.push(values);
        }
    }
    Ok(results)
}
