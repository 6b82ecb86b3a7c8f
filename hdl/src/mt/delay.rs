//! A delay line of a length chosen when the pipeline is built: pads the shorter branches of
//! the MT dataflow so that every operator sees operands of the same query.
//!
//! Short or narrow lines are flip-flop chains (synthesis packs them into SRL LUTs). Word-wide
//! lines of [`RAM_MIN_CYCLES`] or more go into a block RAM ring instead ([`RamDelay`]): a
//! 32-bit line costs 32 SRL LUTs but one RAMB18E1 and a few counter LUTs, and an fp32 lane
//! spends about 800 LUTs on such lines while its block RAMs sit idle.

use std::collections::VecDeque;

use rust_hdl::prelude::*;

/// The shortest line that goes into block RAM: a ring of at least two words, the RAM's read
/// register and an output register.
pub const RAM_MIN_CYCLES: usize = 4;
/// The narrowest line that goes into block RAM (flags stay in SRLs).
pub const RAM_MIN_BITS: usize = 8;

/// `q` is `d` delayed by `new(cycles)` clocks; `cycles = 0` is a wire.
#[derive(LogicBlock)]
pub struct Delay<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    /// The whole line in block RAM, or empty.
    ram: Vec<RamDelay<T>>,
    /// The whole line in flip-flops, or empty.
    regs: Vec<DFF<T>>,
    /// The value at the current tap while walking the chain.
    tap: Signal<Local, T>,
}

impl<T: Synth> Delay<T> {
    pub fn new(cycles: usize) -> Self {
        let in_ram = T::BITS >= RAM_MIN_BITS && cycles >= RAM_MIN_CYCLES;
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            ram: if in_ram {
                vec![RamDelay::new(cycles)]
            } else {
                vec![]
            },
            regs: if in_ram {
                vec![]
            } else {
                (0..cycles).map(|_| Default::default()).collect()
            },
            tap: Default::default(),
        }
    }
}

impl<T: Synth> Logic for Delay<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.tap.next = self.d.val();
        for i in 0..self.ram.len() {
            self.ram[i].clock.next = self.clock.val();
            self.ram[i].d.next = self.tap.val();
            self.tap.next = self.ram[i].q.val();
        }
        for i in 0..self.regs.len() {
            self.regs[i].clock.next = self.clock.val();
            self.regs[i].d.next = self.tap.val();
            self.tap.next = self.regs[i].q.val();
        }
        self.q.next = self.tap.val();
    }
}

/// A delay line of `cycles >= RAM_MIN_CYCLES` in block RAM: a ring of `cycles − 2` words,
/// each read one cycle before it is overwritten (read-first, one address for both ports),
/// then the RAM's read register and a fabric output register (the RAM's clock-to-out is
/// slow). Everything starts at zero, like the flip-flops of a chain.
#[derive(LogicBlock)]
pub struct RamDelay<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub q: Signal<Out, T>,
    /// Simulation only: the last `cycles` inputs, oldest first.
    _line: VecDeque<T>,
}

impl<T: Synth> RamDelay<T> {
    pub fn new(cycles: usize) -> Self {
        assert!(
            cycles >= RAM_MIN_CYCLES,
            "a block RAM delay needs at least {RAM_MIN_CYCLES} cycles, not {cycles}"
        );
        Self {
            clock: Default::default(),
            d: Default::default(),
            q: Default::default(),
            _line: std::iter::repeat(T::default()).take(cycles).collect(),
        }
    }
}

impl<T: Synth> Logic for RamDelay<T> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            self._line.push_back(self.d.val());
            self._line.pop_front();
            self.q.next = self._line[0];
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        let words = self._line.len() - 2;
        let last = words - 1;
        let at_bits = (usize::BITS - last.leading_zeros()).max(1);
        let top = T::BITS - 1;
        Verilog::Custom(format!(
            "\
(* ram_style = \"block\" *) reg [{top}:0] ring [0:{last}];
reg [{a}:0] at;
reg [{top}:0] ring_out;
integer i;
initial begin
   at = {at_bits}'d0;
   ring_out = {w}'d0;
   q = {w}'d0;
   for (i = 0; i <= {last}; i = i + 1) ring[i] = {w}'d0;
end

always @(posedge clock) begin
   ring_out <= ring[at];
   ring[at] <= d;
   q <= ring_out;
   at <= (at == {at_bits}'d{last}) ? {at_bits}'d0 : at + {at_bits}'d1;
end
",
            a = at_bits - 1,
            w = T::BITS,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds 0, 1, 2, … and checks `q` lags `d` by exactly `cycles`.
    fn lag(cycles: usize) {
        let mut uut = Delay::<Bits<8>>::new(cycles);
        uut.connect_all();
        for cycle in 0..80u64 {
            uut.d.next = (cycle + 1).into();
            uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut uut, 100));
            let want = (cycle + 1).saturating_sub(cycles as u64);
            assert_eq!(uut.q.val().to_u64(), want, "delay {cycles}, cycle {cycle}");
            uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut uut, 100));
        }
    }

    #[test]
    fn delays_by_the_requested_cycles() {
        for cycles in [0, 1, 2, 3, 4, 5, 8, 33] {
            lag(cycles);
        }
    }

    #[test]
    fn long_word_lines_go_into_block_ram_and_the_rest_into_registers() {
        let lines = |d: &Delay<Bits<8>>| (d.ram.len(), d.regs.len());
        assert_eq!(
            lines(&Delay::new(RAM_MIN_CYCLES - 1)),
            (0, RAM_MIN_CYCLES - 1)
        );
        assert_eq!(lines(&Delay::new(RAM_MIN_CYCLES)), (1, 0));
        let flag = Delay::<Bit>::new(40);
        assert_eq!((flag.ram.len(), flag.regs.len()), (0, 40));
    }

    /// The generated Verilog in Icarus, the same stimulus as [`lag`]: the block RAM ring's
    /// read-first order, its wrap and its power-on zeros.
    #[test]
    fn verilog_delays_by_the_requested_cycles_in_icarus() {
        for cycles in [3, 4, 5, 8, 33] {
            let mut uut = Delay::<Bits<8>>::new(cycles);
            uut.connect_all();
            let bench = format!(
                "{}
module bench;
   reg clock = 0;
   reg [7:0] d = 0;
   wire [7:0] q;
   integer c, want, errors = 0;
   top uut(.clock(clock), .d(d), .q(q));
   initial begin
      for (c = 0; c < 80; c = c + 1) begin
         d = c + 1;
         #1 want = c + 1 < {cycles} ? 0 : c + 1 - {cycles};
         if (q !== want[7:0]) errors = errors + 1;
         clock = 1;
         #1 clock = 0;
      end
      $display(\"errors %0d\", errors);
      $finish;
   end
endmodule
",
                generate_verilog(&uut)
            );
            let dir = tempfile::tempdir().unwrap();
            let (src, out) = (dir.path().join("delay.v"), dir.path().join("delay.vvp"));
            std::fs::write(&src, bench).unwrap();
            let compiled = std::process::Command::new("iverilog")
                .args(["-g2012", "-s", "bench", "-o"])
                .args([&out, &src])
                .output()
                .expect("iverilog (make setup installs it)");
            assert!(compiled.status.success(), "{compiled:?}");
            let ran = std::process::Command::new("vvp")
                .arg(&out)
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&ran.stdout);
            assert!(text.contains("errors 0"), "delay {cycles}: {text}");
        }
    }

    /// A 32-bit line of 12 cycles through yosys: one RAMB18E1, no SRL, a few counter LUTs.
    #[test]
    fn word_line_maps_to_one_block_ram() {
        let mut uut = Delay::<Bits<32>>::new(12);
        uut.connect_all();
        let options = crate::synth::SynthOptions::default();
        let r = crate::synth::synthesize(&generate_verilog(&uut), "top", &options).unwrap();
        assert_eq!(r.cells.get("RAMB18E1"), Some(&1), "{:?}", r.cells);
        assert_eq!((r.srl, r.lutram), (0, 0), "{:?}", r.cells);
        assert!(r.lut <= 8, "{:?}", r.cells);
    }

    #[test]
    fn generates_verilog() {
        for (cycles, ram) in [(0, false), (3, false), (4, true), (12, true)] {
            let mut uut = Delay::<Bits<8>>::new(cycles);
            uut.connect_all();
            let v = generate_verilog(&uut);
            assert!(v.contains("module top"), "{v}");
            assert_eq!(v.contains("ram_style = \"block\""), ram, "{v}");
        }
    }
}
