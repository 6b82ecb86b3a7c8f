//! A memory written at the clock edge and read asynchronously: what Xilinx builds from LUTs
//! (RAM32M, RAM64M; yosys `synth_xilinx` maps it so).
//!
//! rust-hdl's own `RAM` registers its read (a block RAM's timing), so this one leaf is written
//! by hand, as `RAM` itself is: the simulation keeps the words in Rust, the Verilog is a plain
//! `reg` array with a clocked write and a combinational read. The slot words
//! ([`super::slot_banks`]) are built from it.

use rust_hdl::prelude::*;

/// `2^N` words of `W` bits, all zero at first: one write port (`write_data` into
/// `write_address` at the rising edge when `write_enable`) and one read port (`read_data` is
/// the word at `read_address` now, the write of this cycle's edge not yet in it).
#[derive(LogicBlock)]
pub struct LutRam<const W: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Signal<In, Bit>,
    pub write_address: Signal<In, Bits<N>>,
    pub write_data: Signal<In, Bits<W>>,
    pub read_address: Signal<In, Bits<N>>,
    pub read_data: Signal<Out, Bits<W>>,
    _words: Vec<Bits<W>>,
}

impl<const W: usize, const N: usize> Default for LutRam<W, N> {
    fn default() -> Self {
        assert!(
            (1..=8).contains(&N),
            "LutRam<{W}, {N}>: a LUT RAM has 2 to 256 words (1 to 8 address bits)"
        );
        Self {
            clock: Default::default(),
            write_enable: Default::default(),
            write_address: Default::default(),
            write_data: Default::default(),
            read_address: Default::default(),
            read_data: Default::default(),
            _words: vec![Bits::default(); 1 << N],
        }
    }
}

impl<const W: usize, const N: usize> Logic for LutRam<W, N> {
    fn update(&mut self) {
        if self.clock.pos_edge() && self.write_enable.val() {
            self._words[self.write_address.val().index()] = self.write_data.val();
        }
        self.read_data.next = self._words[self.read_address.val().index()];
    }

    fn connect(&mut self) {
        self.read_data.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "reg [{top}:0] mem [0:{last}];\n\
             integer i;\n\
             initial for (i = 0; i <= {last}; i = i + 1) mem[i] = {W}'d0;\n\
             always @(posedge clock) if (write_enable) mem[write_address] <= write_data;\n\
             always @(*) read_data = mem[read_address];",
            top = W - 1,
            last = (1 << N) - 1,
        ))
    }
}
