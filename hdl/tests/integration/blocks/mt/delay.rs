//! `hdl::mt::delay`.

use hdl::mt::delay::*;
use rust_hdl::prelude::*;

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
    let placed = |d: WordDelay<Bits<8>>| d.placement();
    assert_eq!(placed(WordDelay::new(3)), (0, 3));
    assert_eq!(placed(WordDelay::new(4)), (1, 0));
    assert_eq!(placed(WordDelay::new(66)), (1, 0));
    assert_eq!(placed(WordDelay::new(67)), (0, 67));
    let narrow = WordDelay::<Bits<4>>::new(40);
    assert_eq!(narrow.placement(), (0, 40));
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
    let options = hdl::synth::SynthOptions::default();
    let r = hdl::synth::synthesize(&generate_verilog(&uut), "top", &options).unwrap();
    assert_eq!(r.cells.get("RAMB18E1"), Some(&1), "{:?}", r.cells);
    assert_eq!((r.srl, r.lutram), (0, 0), "{:?}", r.cells);
    assert!(r.lut <= 6, "{:?}", r.cells);
}
