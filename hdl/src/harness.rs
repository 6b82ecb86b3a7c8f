//! Driving a block in rust-hdl's simulator one clock cycle at a time, and generating its
//! Verilog, each on a thread with room for the block ([`crate::top::with_build_stack`]: the
//! blocks are large structs built by value and walked recursively).

use rust_hdl::prelude::*;

/// A block a test drives with plain values, one input a cycle.
pub trait Stepped: Block + Sized {
    /// One cycle's inputs.
    type Input: Clone + Send + 'static;
    /// What the outputs show in one cycle.
    type Output: Send + 'static;
    /// The inputs of a cycle without work: not valid, every word zero.
    fn idle() -> Self::Input;
    fn clock_input(&mut self) -> &mut Signal<In, Clock>;
    /// Drives the inputs (the simulator's side of the ports).
    fn apply(&mut self, input: &Self::Input);
    fn observe(&self) -> Self::Output;
}

/// Runs the block `build` makes in rust-hdl's simulator for `inputs.len() + flush` cycles,
/// feeding `inputs[c]` in cycle `c` (then [`Stepped::idle`]) and returning what the outputs
/// show in every cycle, read once the inputs have settled, before the clock rises.
pub fn simulate_cycles<B: Stepped>(
    build: impl FnOnce() -> B + Send + 'static,
    inputs: &[B::Input],
    flush: usize,
) -> Vec<B::Output> {
    let inputs = inputs.to_vec();
    crate::top::with_build_stack(move || {
        let mut uut = build();
        uut.connect_all();
        let idle = B::idle();
        (0..inputs.len() + flush)
            .map(|cycle| {
                uut.apply(inputs.get(cycle).unwrap_or(&idle));
                settle(&mut uut, false);
                let out = uut.observe();
                settle(&mut uut, true);
                out
            })
            .collect()
    })
}

/// Sets the clock to `clk` and lets the logic settle.
fn settle<B: Stepped>(uut: &mut B, clk: bool) {
    uut.clock_input().next = Clock { clk };
    assert!(
        simulate(uut, 10_000),
        "{} logic did not settle",
        std::any::type_name::<B>()
    );
}

/// The Verilog of the block `build` makes, top module `top`.
pub fn built_verilog<B: Block>(build: impl FnOnce() -> B + Send + 'static) -> String {
    crate::top::with_build_stack(move || {
        let mut uut = build();
        uut.connect_all();
        generate_verilog(&uut)
    })
}
