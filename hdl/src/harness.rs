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
    let mut inputs = (inputs.iter().cloned())
        .chain(std::iter::repeat_with(B::idle).take(flush))
        .collect::<Vec<_>>()
        .into_iter();
    simulate_driven(build, move |_| inputs.next())
        .into_iter()
        .map(|(_, out)| out)
        .collect()
}

/// Runs the block `build` makes in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from what the outputs showed in the cycle before (`None` in the first cycle), until
/// it returns `None`: a test bench that reacts, as a stream's sender and receiver do to
/// `ready` and `valid`. Returns every cycle's inputs and what the outputs showed, read once
/// the inputs have settled, before the clock rises.
pub fn simulate_driven<B: Stepped>(
    build: impl FnOnce() -> B + Send + 'static,
    mut drive: impl FnMut(Option<&B::Output>) -> Option<B::Input> + Send + 'static,
) -> Vec<(B::Input, B::Output)> {
    crate::top::with_build_stack(move || {
        let mut uut = build();
        uut.connect_all();
        let mut cycles: Vec<(B::Input, B::Output)> = Vec::new();
        while let Some(input) = drive(cycles.last().map(|(_, out)| out)) {
            uut.apply(&input);
            settle(&mut uut, false);
            let out = uut.observe();
            settle(&mut uut, true);
            cycles.push((input, out));
        }
        cycles
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
