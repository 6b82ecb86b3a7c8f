//! `hdl::traversal::slot_banks`, `hdl::traversal::live_table` and `hdl::traversal::lut_ram`:
//! a slot word in LUT-RAM banks with its live-value table, as `SlotState` wires them.

use hdl::harness::{built_verilog, simulate_cycles, Stepped};
use hdl::traversal::live_table::LiveTable;
use hdl::traversal::lut_ram::LutRam;
use hdl::traversal::slot_banks::SlotBanks;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

/// A word of `S` slots as the slot state keeps one: the banks and their table, each writer
/// and reader giving its slot both ways (the banks' index, the table's one-hot select).
#[derive(LogicBlock)]
struct Words<const S: usize, const SB: usize, const W: usize> {
    pub clock: Signal<In, Clock>,
    pub write_enable: Vec<Signal<In, Bit>>,
    pub write_slot: Vec<Signal<In, Bits<SB>>>,
    pub write_select: Vec<Signal<In, Bits<S>>>,
    pub write_data: Vec<Signal<In, Bits<W>>>,
    pub read_slot: Vec<Signal<In, Bits<SB>>>,
    pub read_select: Vec<Signal<In, Bits<S>>>,
    pub read_data: Vec<Signal<Out, Bits<W>>>,
    table: LiveTable<S>,
    banks: SlotBanks<SB, W>,
}

impl<const S: usize, const SB: usize, const W: usize> Words<S, SB, W> {
    fn new(writers: usize, readers: usize) -> Self {
        Self {
            clock: Default::default(),
            write_enable: (0..writers).map(|_| Default::default()).collect(),
            write_slot: (0..writers).map(|_| Default::default()).collect(),
            write_select: (0..writers).map(|_| Default::default()).collect(),
            write_data: (0..writers).map(|_| Default::default()).collect(),
            read_slot: (0..readers).map(|_| Default::default()).collect(),
            read_select: (0..readers).map(|_| Default::default()).collect(),
            read_data: (0..readers).map(|_| Default::default()).collect(),
            table: LiveTable::new(writers, readers),
            banks: SlotBanks::new(writers, readers),
        }
    }
}

impl<const S: usize, const SB: usize, const W: usize> Logic for Words<S, SB, W> {
    #[hdl_gen]
    fn update(&mut self) {
        self.table.clock.next = self.clock.val();
        self.banks.clock.next = self.clock.val();
        for w in 0..self.write_enable.len() {
            self.table.write_enable[w].next = self.write_enable[w].val();
            self.table.write_select[w].next = self.write_select[w].val();
            self.banks.write_enable[w].next = self.write_enable[w].val();
            self.banks.write_slot[w].next = self.write_slot[w].val();
            self.banks.write_data[w].next = self.write_data[w].val();
        }
        for r in 0..self.read_slot.len() {
            self.table.read_select[r].next = self.read_select[r].val();
            self.banks.read_slot[r].next = self.read_slot[r].val();
            self.banks.live[r].next = self.table.live[r].val();
            self.read_data[r].next = self.banks.read_data[r].val();
        }
    }
}

/// A cycle: each writer's write (slot, word) if any, each reader's slot.
#[derive(Clone)]
struct Access {
    writes: Vec<Option<(usize, u64)>>,
    reads: Vec<usize>,
}

impl<const S: usize, const SB: usize, const W: usize> Stepped for Words<S, SB, W> {
    type Input = Access;
    type Output = Vec<u64>;

    fn idle() -> Access {
        Access {
            writes: Vec::new(),
            reads: Vec::new(),
        }
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &Access) {
        for w in 0..self.write_enable.len() {
            let write = input.writes.get(w).copied().flatten();
            let (slot, data) = write.unwrap_or((0, 0));
            self.write_enable[w].next = write.is_some();
            self.write_slot[w].next = (slot as u64).into();
            self.write_select[w].next = (1u64 << slot).into();
            self.write_data[w].next = data.into();
        }
        for r in 0..self.read_slot.len() {
            let slot = input.reads.get(r).copied().unwrap_or(0);
            self.read_slot[r].next = (slot as u64).into();
            self.read_select[r].next = (1u64 << slot).into();
        }
    }

    fn observe(&self) -> Vec<u64> {
        self.read_data.iter().map(|d| d.val().to_u64()).collect()
    }
}

/// `cycles` of random writes (each writer to a slot of its own, or none) and reads against a
/// plain array: every read answers the slot's last word written before the cycle.
fn random_accesses<const S: usize, const SB: usize, const W: usize>(
    writers: usize,
    readers: usize,
    cycles: usize,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    let inputs: Vec<Access> = (0..cycles)
        .map(|_| {
            let mut slots: Vec<usize> = (0..S).collect();
            let writes = (0..writers)
                .map(|_| {
                    let slot = slots.swap_remove(rng.gen_range(0..slots.len()));
                    let word = rng.gen_range(0..=u64::MAX >> (64 - W));
                    rng.gen_bool(0.7).then_some((slot, word))
                })
                .collect();
            let reads = (0..readers).map(|_| rng.gen_range(0..S)).collect();
            Access { writes, reads }
        })
        .collect();
    let outputs = simulate_cycles(move || Words::<S, SB, W>::new(writers, readers), &inputs, 0);
    let mut words = [0u64; S];
    let mut overwritten = 0;
    for (cycle, (input, output)) in inputs.iter().zip(&outputs).enumerate() {
        let want: Vec<u64> = input.reads.iter().map(|&s| words[s]).collect();
        assert_eq!(
            output, &want,
            "cycle {cycle}: {writers} writers, {readers} readers of slots {:?}",
            input.reads
        );
        for &(slot, word) in input.writes.iter().flatten() {
            overwritten += usize::from(words[slot] != 0);
            words[slot] = word;
        }
    }
    // The writers took turns at the same slots (so the table had to follow them).
    assert!(
        overwritten > cycles,
        "{overwritten} overwrites in {cycles} cycles"
    );
}

#[test]
fn banks_read_the_last_word_written_of_each_slot() {
    // The binary unit's far ends (set-up, one lane's far end; the box and pop readers) ...
    random_accesses::<32, 5, 32>(2, 2, 1_500, 1);
    // ... the 8-wide unit's links (box, pop, a lane's advance; box and lane readers) ...
    random_accesses::<64, 6, 20>(3, 2, 1_500, 2);
    // ... and three lanes' links: five writers, four readers.
    random_accesses::<8, 3, 9>(5, 4, 1_500, 3);
}

#[test]
fn a_lone_bank_reads_asynchronously_and_writes_at_the_edge() {
    let mut ram = LutRam::<8, 2>::default();
    ram.connect_all();
    let mut step = |write: Option<(u64, u64)>, read: u64, clk: bool| {
        let (address, data) = write.unwrap_or((0, 0));
        ram.write_enable.next = write.is_some();
        ram.write_address.next = address.into();
        ram.write_data.next = data.into();
        ram.read_address.next = read.into();
        ram.clock.next = Clock { clk };
        assert!(simulate(&mut ram, 100));
        ram.read_data.val().to_u64()
    };
    assert_eq!(step(Some((2, 0xA5)), 2, false), 0, "before the edge");
    assert_eq!(step(Some((2, 0xA5)), 2, true), 0xA5, "after it");
    assert_eq!(step(None, 3, false), 0, "another word, combinationally");
    assert_eq!(step(None, 2, false), 0xA5);
}

/// yosys xc7 resources of the banks: a lone LUT RAM (is it RAM32M / RAM64M?) and the slot
/// words of the units' far ends and links:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture slot_banks::slot_banks_resources`
#[test]
#[ignore]
fn slot_banks_resources() {
    let parts = [
        (
            "LUT RAM 32 × 32 bits".to_string(),
            built_verilog(LutRam::<32, 5>::default),
        ),
        (
            "LUT RAM 64 × 32 bits".to_string(),
            built_verilog(LutRam::<32, 6>::default),
        ),
        (
            "t_hi, 32 slots: 2 writers, 2 readers".to_string(),
            built_verilog(|| Words::<32, 5, 32>::new(2, 2)),
        ),
        (
            "t_hi, 64 slots: 2 writers, 2 readers".to_string(),
            built_verilog(|| Words::<64, 6, 32>::new(2, 2)),
        ),
        (
            "link first, 64 slots: 3 writers, 2 readers".to_string(),
            built_verilog(|| Words::<64, 6, 20>::new(3, 2)),
        ),
    ];
    println!("{}", hdl::synth::markdown_table(&parts).unwrap());
}
