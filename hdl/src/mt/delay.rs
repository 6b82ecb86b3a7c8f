//! A delay line of a length chosen when the pipeline is built: pads the shorter branches of
//! the MT dataflow so that every operator sees operands of the same query.
//!
//! [`Delay`] is a flip-flop chain (synthesis packs it into SRL LUTs). A word-wide line of
//! [`RAM_MIN_CYCLES`] or more, a [`WordDelay`], goes into a block RAM ring instead
//! ([`RamDelay`]): a 32-bit line costs 32 SRL LUTs but one RAMB18E1, and an fp32 lane spends
//! about 800 LUTs on such lines while its block RAMs sit idle. The ring position comes from a
//! [`Ring`] counter that every line of the same length shares.

use rust_hdl::prelude::*;

/// The shortest line that goes into block RAM: a ring of at least two words, the RAM's read
/// register and an output register.
pub const RAM_MIN_CYCLES: usize = 4;
/// The narrowest word line that goes into block RAM (narrower ones stay in SRLs).
pub const RAM_MIN_BITS: usize = 8;
/// Width of a ring position: a block RAM line holds at most 2^RING_BITS words.
pub const RING_BITS: usize = 6;
pub type RingPosition = Bits<RING_BITS>;

/// The words of the block RAM ring of a line of `cycles`, if it is long enough for one and
/// not too long (the ring, then the RAM's read register and the output register).
fn ring_words(cycles: usize) -> Option<usize> {
    (RAM_MIN_CYCLES..=(1 << RING_BITS) + 2)
        .contains(&cycles)
        .then(|| cycles - 2)
}

/// Bits of a counter over `words` positions.
fn count_bits(words: usize) -> usize {
    (usize::BITS - (words - 1).leading_zeros()).max(1) as usize
}

/// `q` is `d` delayed by `new(cycles)` clocks in flip-flops; `cycles = 0` is a wire.
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

/// `q` is the word `d` delayed by `new(cycles)` clocks: in block RAM on the position `at` of
/// a [`Ring`] of the same `cycles` when the line is long and wide enough, else in flip-flops
/// (and `at` is not used).
#[derive(LogicBlock)]
pub struct WordDelay<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub at: Signal<In, RingPosition>,
    pub q: Signal<Out, T>,
    /// The whole line in block RAM, or empty.
    ram: Vec<RamDelay<T>>,
    /// The whole line in flip-flops, or a wire after the RAM.
    regs: Delay<T>,
}

impl<T: Synth> WordDelay<T> {
    pub fn new(cycles: usize) -> Self {
        let ram: Vec<_> = ring_words(cycles)
            .filter(|_| T::BITS >= RAM_MIN_BITS)
            .map(RamDelay::new)
            .into_iter()
            .collect();
        let regs = if ram.is_empty() { cycles } else { 0 };
        Self {
            clock: Default::default(),
            d: Default::default(),
            at: Default::default(),
            q: Default::default(),
            ram,
            regs: Delay::new(regs),
        }
    }
}

impl<T: Synth> Logic for WordDelay<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.regs.clock.next = self.clock.val();
        self.regs.d.next = self.d.val();
        for i in 0..self.ram.len() {
            self.ram[i].clock.next = self.clock.val();
            self.ram[i].at.next = self.at.val();
            self.ram[i].d.next = self.d.val();
            self.regs.d.next = self.ram[i].q.val();
        }
        self.q.next = self.regs.q.val();
    }
}

/// The ring position of every block RAM line of `new(cycles)`: counts 0, 1, …, words − 1, 0, …
/// from power-on (always 0 for a line too short or too long for a ring).
#[derive(LogicBlock)]
pub struct Ring {
    pub clock: Signal<In, Clock>,
    pub at: Signal<Out, RingPosition>,
    /// The ring's words (1: idle).
    _words: usize,
}

impl Ring {
    pub fn new(cycles: usize) -> Self {
        Self {
            clock: Default::default(),
            at: Default::default(),
            _words: ring_words(cycles).unwrap_or(1),
        }
    }
}

impl Logic for Ring {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            let next = (self.at.val().to_u64() + 1) % self._words as u64;
            self.at.next = next.into();
        }
    }

    fn connect(&mut self) {
        self.at.connect();
    }

    fn hdl(&self) -> Verilog {
        let bits = count_bits(self._words);
        let last = self._words - 1;
        let at = if bits < RING_BITS {
            format!("{{{}'d0, count}}", RING_BITS - bits)
        } else {
            "count".to_string()
        };
        Verilog::Custom(format!(
            "\
reg [{top}:0] count;
initial count = {bits}'d0;
always @(posedge clock) count <= (count == {bits}'d{last}) ? {bits}'d0 : count + {bits}'d1;
always @(*) at = {at};
",
            top = bits - 1,
        ))
    }
}

/// A delay line of `words + 2` cycles in block RAM at the ring position `at` (from a [`Ring`]
/// of the same length): each word is read one cycle before it is overwritten (read-first, one
/// address for both ports), then passes the RAM's read register and a fabric output register
/// (the RAM's clock-to-out is slow). Everything starts at zero, like the flip-flops of a chain.
#[derive(LogicBlock)]
pub struct RamDelay<T: Synth> {
    pub clock: Signal<In, Clock>,
    pub d: Signal<In, T>,
    pub at: Signal<In, RingPosition>,
    pub q: Signal<Out, T>,
    /// Simulation only: the ring and the read register.
    _ring: Vec<T>,
    _read: T,
}

impl<T: Synth> RamDelay<T> {
    fn new(words: usize) -> Self {
        Self {
            clock: Default::default(),
            d: Default::default(),
            at: Default::default(),
            q: Default::default(),
            _ring: vec![T::default(); words],
            _read: T::default(),
        }
    }
}

impl<T: Synth> Logic for RamDelay<T> {
    fn update(&mut self) {
        if self.clock.pos_edge() {
            let at = self.at.val().to_u64() as usize;
            assert!(
                at < self._ring.len(),
                "ring position {at} beyond a {}-word ring: the line is on another length's Ring",
                self._ring.len()
            );
            self.q.next = self._read;
            self._read = self._ring[at];
            self._ring[at] = self.d.val();
        }
    }

    fn connect(&mut self) {
        self.q.connect();
    }

    fn hdl(&self) -> Verilog {
        let last = self._ring.len() - 1;
        let a = count_bits(self._ring.len()) - 1;
        let top = T::BITS - 1;
        Verilog::Custom(format!(
            "\
(* ram_style = \"block\" *) reg [{top}:0] ring [0:{last}];
reg [{top}:0] ring_out;
integer i;
initial begin
   ring_out = {w}'d0;
   q = {w}'d0;
   for (i = 0; i <= {last}; i = i + 1) ring[i] = {w}'d0;
end

always @(posedge clock) begin
   ring_out <= ring[at[{a}:0]];
   ring[at[{a}:0]] <= d;
   q <= ring_out;
end
",
            w = T::BITS,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A word line on its ring, wired as the lane wires them (`ring_cycles` = `cycles`, except
    /// to show that a wrong ring is caught).
    #[derive(LogicBlock)]
    struct Line<T: Synth> {
        pub clock: Signal<In, Clock>,
        pub d: Signal<In, T>,
        pub q: Signal<Out, T>,
        ring: Ring,
        line: WordDelay<T>,
    }

    impl<T: Synth> Line<T> {
        fn new(cycles: usize, ring_cycles: usize) -> Self {
            Self {
                clock: Default::default(),
                d: Default::default(),
                q: Default::default(),
                ring: Ring::new(ring_cycles),
                line: WordDelay::new(cycles),
            }
        }
    }

    impl<T: Synth> Logic for Line<T> {
        #[hdl_gen]
        fn update(&mut self) {
            self.ring.clock.next = self.clock.val();
            self.line.clock.next = self.clock.val();
            self.line.at.next = self.ring.at.val();
            self.line.d.next = self.d.val();
            self.q.next = self.line.q.val();
        }
    }

    /// Feeds 1, 2, 3, … into a line of `cycles` on a ring of `ring_cycles` and checks that `q`
    /// lags `d` by exactly `cycles`.
    fn word_lag(cycles: usize, ring_cycles: usize) {
        let mut uut = Line::<Bits<8>>::new(cycles, ring_cycles);
        uut.connect_all();
        for cycle in 0..150u64 {
            uut.d.next = (cycle + 1).into();
            uut.clock.next = Clock { clk: false };
            assert!(simulate(&mut uut, 100));
            let want = (cycle + 1).saturating_sub(cycles as u64) % 256;
            assert_eq!(uut.q.val().to_u64(), want, "delay {cycles}, cycle {cycle}");
            uut.clock.next = Clock { clk: true };
            assert!(simulate(&mut uut, 100));
        }
    }

    #[test]
    fn word_lines_delay_by_the_requested_cycles() {
        for cycles in 0..=67 {
            word_lag(cycles, cycles);
        }
    }

    #[test]
    #[should_panic(expected = "another length's Ring")]
    fn a_line_on_a_longer_ring_is_caught_in_simulation() {
        word_lag(8, 12);
    }

    #[test]
    fn flag_lines_delay_by_the_requested_cycles() {
        for cycles in [0, 1, 5, 40] {
            let mut uut = Delay::<Bit>::new(cycles);
            uut.connect_all();
            for cycle in 0..60 {
                uut.d.next = cycle % 3 == 0;
                uut.clock.next = Clock { clk: false };
                assert!(simulate(&mut uut, 100));
                let want = cycle >= cycles && (cycle - cycles) % 3 == 0;
                assert_eq!(uut.q.val(), want, "delay {cycles}, cycle {cycle}");
                uut.clock.next = Clock { clk: true };
                assert!(simulate(&mut uut, 100));
            }
        }
    }

    #[test]
    fn long_word_lines_go_into_block_ram_and_the_rest_into_registers() {
        let placed = |d: WordDelay<Bits<8>>| (d.ram.len(), d.regs.regs.len());
        assert_eq!(placed(WordDelay::new(3)), (0, 3));
        assert_eq!(placed(WordDelay::new(4)), (1, 0));
        assert_eq!(placed(WordDelay::new(66)), (1, 0));
        assert_eq!(placed(WordDelay::new(67)), (0, 67));
        let narrow = WordDelay::<Bits<4>>::new(40);
        assert_eq!((narrow.ram.len(), narrow.regs.regs.len()), (0, 40));
    }

    /// The generated Verilog in Icarus, the same stimulus as [`word_lag`]: the block RAM
    /// ring's read-first order, the ring's wrap and their power-on zeros.
    #[test]
    fn verilog_delays_by_the_requested_cycles_in_icarus() {
        for cycles in [3, 4, 5, 8, 33, 66] {
            let mut uut = Line::<Bits<8>>::new(cycles, cycles);
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
      for (c = 0; c < 150; c = c + 1) begin
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

    /// A 32-bit line of 12 cycles on its ring through yosys: one RAMB18E1, no SRL, the ring
    /// counter's few LUTs.
    #[test]
    fn word_line_maps_to_one_block_ram() {
        let mut uut = Line::<Bits<32>>::new(12, 12);
        uut.connect_all();
        let options = crate::synth::SynthOptions::default();
        let r = crate::synth::synthesize(&generate_verilog(&uut), "top", &options).unwrap();
        assert_eq!(r.cells.get("RAMB18E1"), Some(&1), "{:?}", r.cells);
        assert_eq!((r.srl, r.lutram), (0, 0), "{:?}", r.cells);
        assert!(r.lut <= 6, "{:?}", r.cells);
    }
}
