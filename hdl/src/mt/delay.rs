//! A delay line of a length chosen when the pipeline is built: pads the shorter branches of
//! the MT dataflow so that every operator sees operands of the same query.
//!
//! [`Delay`] is a flip-flop chain (synthesis packs it into SRL LUTs). A word-wide line of
//! [`RAM_MIN_CYCLES`] or more, a [`WordDelay`], goes into a block RAM ring instead
//! ([`RamDelay`]): a 32-bit line costs 32 SRL LUTs but one RAMB18E1, and an fp32 lane spends
//! about 800 LUTs on such lines while its block RAMs sit idle. The ring position comes from a
//! [`Ring`] counter that every line of the same length shares.

use crate::macros::clock;
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

    /// `N` lines of `cycles` clocks each (one per component of a vector, say).
    pub fn lines<const N: usize>(cycles: usize) -> [Self; N] {
        std::array::from_fn(|_| Self::new(cycles))
    }
}

impl<T: Synth> Logic for Delay<T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.tap.next = self.d.val();
        for i in 0..self.regs.len() {
            clock!(self, clock, regs[i]);
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

    /// Where the line went: (block RAM lines, 0 or 1; flip-flop stages).
    pub fn placement(&self) -> (usize, usize) {
        (self.ram.len(), self.regs.regs.len())
    }
}

impl<T: Synth> Logic for WordDelay<T> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, regs);
        self.regs.d.next = self.d.val();
        for i in 0..self.ram.len() {
            clock!(self, clock, ram[i]);
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
