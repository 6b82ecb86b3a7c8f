//! A delay line of a length chosen when the pipeline is built: pads the shorter branches of
//! the MT dataflow so that every operator sees operands of the same query.

use rust_hdl::prelude::*;

/// `q` is `d` delayed by `new(cycles)` clocks; `cycles = 0` is a wire.
#[derive(LogicBlock)]
pub struct Delay<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    regs: Vec<DFF<T>>,
    /// The value at the current tap while walking the chain.
    tap: Signal<Local, T>,
}

impl<T: Synth> Delay<T> {
    pub fn new(cycles: usize) -> Self {
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            regs: (0..cycles).map(|_| Default::default()).collect(),
            tap: Default::default(),
        }
    }
}

impl<T: Synth> Logic for Delay<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.tap.next = self.d.val();
        for i in 0..self.regs.len() {
            self.regs[i].clock.next = self.clock.val();
            self.regs[i].d.next = self.tap.val();
            self.tap.next = self.regs[i].q.val();
        }
        self.q.next = self.tap.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds 0, 1, 2, … and checks `q` lags `d` by exactly `cycles`.
    fn lag(cycles: usize) {
        let mut uut = Delay::<Bits<8>>::new(cycles);
        uut.connect_all();
        for cycle in 0..20u64 {
            uut.d.next = cycle.into();
            uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut uut, 100));
            let want = cycle.saturating_sub(cycles as u64);
            assert_eq!(uut.q.val().to_u64(), want, "delay {cycles}, cycle {cycle}");
            uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut uut, 100));
        }
    }

    #[test]
    fn delays_by_the_requested_cycles() {
        for cycles in [0, 1, 2, 5] {
            lag(cycles);
        }
    }

    #[test]
    fn generates_verilog() {
        for cycles in [0, 3] {
            let mut uut = Delay::<Bits<8>>::new(cycles);
            uut.connect_all();
            let v = generate_verilog(&uut);
            assert!(v.contains("module top"), "{v}");
        }
    }
}
