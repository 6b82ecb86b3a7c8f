//! The AXI4-Lite slave in rust-hdl's simulator, driven by an AXI4-Lite master bus-functional
//! model, with a stand-in core attached; plus Verilator lint and yosys synthesis of its
//! generated Verilog.
//!
//! rust-hdl's simulator runs a few thousand cycles per second on this design, so the default
//! tests are short. The long random soak:
//! `cargo test --release -p hdl --test integration -- --ignored axil_slave::random_soak`
use std::process::Command;

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

use hdl::axil::AxiLiteSlave;
use hdl::regmap::{self, OPERANDS, OPERAND_COUNT};

const ID: u32 = regmap::ID_VALUE;
const CONFIG: u32 = 0x0004_0307;

/// Stands in for the MT core: `latency` cycles after `start` it pulses `done` with
/// hit = operand 2 bit 0, t = operand 0 + operand 1 (integers), u = operand 3, v = operand 14,
/// computed from the operands at `done` time. It records protocol faults of the slave: a
/// start while running, and operands that changed while it was running. Reset (shared with
/// the slave) stops a run.
#[derive(LogicBlock, Default)]
struct StandInCore {
    clock: Signal<In, Clock>,
    reset_n: Signal<In, Bit>,
    start: Signal<In, Bit>,
    operands: [Signal<In, Bits<32>>; OPERAND_COUNT],
    latency: Signal<In, Bits<8>>,
    done: Signal<Out, Bit>,
    hit: Signal<Out, Bit>,
    t: Signal<Out, Bits<32>>,
    u: Signal<Out, Bits<32>>,
    v: Signal<Out, Bits<32>>,
    running: DFF<Bit>,
    count: DFF<Bits<8>>,
    starts: DFF<Bits<16>>,
    signature: DFF<Bits<32>>,
    unstable: DFF<Bit>,
    overlap: DFF<Bit>,
    operand_xor: Signal<Local, Bits<32>>,
}

impl Logic for StandInCore {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, running, count, starts, signature, unstable, overlap);
        self.operand_xor.next = 0.into();
        for i in 0..OPERAND_COUNT {
            self.operand_xor.next = self.operand_xor.val() ^ self.operands[i].val();
        }
        self.done.next = self.running.q.val() & !self.count.q.val().any();
        self.hit.next = self.operands[2].val().get_bit(0);
        self.t.next = self.operands[0].val() + self.operands[1].val();
        self.u.next = self.operands[3].val();
        self.v.next = self.operands[14].val();
        if self.running.q.val() {
            if self.count.q.val().any() {
                self.count.d.next = self.count.q.val() - 1;
            } else {
                self.running.d.next = false;
            }
            if self.operand_xor.val() != self.signature.q.val() {
                self.unstable.d.next = true;
            }
        }
        if self.start.val() {
            if self.running.q.val() {
                self.overlap.d.next = true;
            }
            self.running.d.next = true;
            self.count.d.next = self.latency.val();
            self.starts.d.next = self.starts.q.val() + 1;
            self.signature.d.next = self.operand_xor.val();
        }
        if !self.reset_n.val() {
            self.running.d.next = false;
        }
    }
}

#[derive(LogicBlock, Default)]
struct Bench {
    clock: Signal<In, Clock>,
    slave: AxiLiteSlave,
    core: StandInCore,
}

impl Logic for Bench {
    #[hdl_gen]
    fn update(&mut self) {
        self.slave.clock.next = self.clock.val();
        self.core.clock.next = self.clock.val();
        self.core.reset_n.next = self.slave.reset_n.val();
        self.core.start.next = self.slave.start.val();
        for i in 0..OPERAND_COUNT {
            self.core.operands[i].next = self.slave.operands[i].val();
        }
        self.slave.done.next = self.core.done.val();
        self.slave.hit.next = self.core.hit.val();
        self.slave.t.next = self.core.t.val();
        self.slave.u.next = self.core.u.val();
        self.slave.v.next = self.core.v.val();
    }
}

fn bench() -> Bench {
    let mut b = Bench::default();
    let a = &mut b.slave.axi;
    a.awvalid.connect();
    a.awaddr.connect();
    a.wvalid.connect();
    a.wdata.connect();
    a.wstrb.connect();
    a.bready.connect();
    a.arvalid.connect();
    a.araddr.connect();
    a.rready.connect();
    b.slave.reset_n.connect();
    b.slave.id.connect();
    b.slave.configuration.connect();
    b.core.latency.connect();
    b.connect_all();
    b
}

type X = Box<Bench>;
type R<T> = Result<T, SimError>;

/// Stop the simulation with a message (the test then fails on `SimHalted`).
fn fail<T>(sim: &mut Sim<Bench>, x: X, msg: String) -> R<T> {
    eprintln!("FAIL: {msg}");
    sim.halt(x)?;
    Err(SimError::SimHalted)
}

/// Fail the simulation (not panic in its thread) when a condition does not hold.
macro_rules! check {
    ($sim:ident, $x:ident, $cond:expr) => {
        if !($cond) {
            return fail($sim, $x, format!("line {}: {}", line!(), stringify!($cond)));
        }
    };
}

macro_rules! check_eq {
    ($sim:ident, $x:ident, $got:expr, $want:expr) => {
        let (got, want) = ($got, $want);
        if got != want {
            return fail(
                $sim,
                $x,
                format!(
                    "line {}: {} = {:?}, expected {:?}",
                    line!(),
                    stringify!($got),
                    got,
                    want
                ),
            );
        }
    };
}

/// Maximum random delays (cycles) of the master on each channel; `ready` delays count from
/// the start of the transaction, so a ready may come before or after its valid.
#[derive(Clone, Copy, Default)]
struct Timing {
    aw: u32,
    w: u32,
    b: u32,
    ar: u32,
    r: u32,
}

const NO_DELAY: Timing = Timing {
    aw: 0,
    w: 0,
    b: 0,
    ar: 0,
    r: 0,
};

/// The AXI4-Lite master BFM. It acts between clock edges: it sets its outputs after a
/// rising edge, samples handshakes after the falling edge (inputs settled) and lets the next
/// rising edge commit them. It also checks the slave side of the protocol: a valid stays up
/// with stable payload until its handshake.
struct Master {
    rng: StdRng,
    timing: Timing,
    /// Use the delays of `timing` exactly instead of drawing up to them.
    exact: bool,
    cycles: u64,
}

struct WriteReq {
    addr: usize,
    data: u32,
    strb: u32,
}

/// (rresp, rdata) of a read.
type ReadResp = (u32, u32);

const TIMEOUT: u32 = 200;

impl Master {
    fn new(seed: u64, timing: Timing) -> Self {
        Self {
            rng: StdRng::seed_from_u64(seed),
            timing,
            exact: false,
            cycles: 0,
        }
    }

    fn exact(timing: Timing) -> Self {
        Self {
            exact: true,
            ..Self::new(0, timing)
        }
    }

    fn delay(&mut self, max: u32) -> u32 {
        if max == 0 || self.exact {
            max
        } else {
            self.rng.gen_range(0..=max)
        }
    }

    fn cycle(&mut self, sim: &mut Sim<Bench>, mut x: X) -> R<X> {
        wait_clock_cycle!(sim, clock, x);
        self.cycles += 1;
        Ok(x)
    }

    /// One write and/or one read, concurrently. Returns bresp and (rresp, rdata).
    fn transact(
        &mut self,
        sim: &mut Sim<Bench>,
        mut x: X,
        write: Option<WriteReq>,
        read: Option<usize>,
    ) -> R<(X, Option<u32>, Option<ReadResp>)> {
        let t = self.timing;
        let (aw_at, w_at, b_at) = (self.delay(t.aw), self.delay(t.w), self.delay(t.b));
        let (ar_at, r_at) = (self.delay(t.ar), self.delay(t.r));
        let (mut aw_done, mut w_done, mut b_got) = (write.is_none(), write.is_none(), None);
        let (mut ar_done, mut r_got) = (read.is_none(), None);
        let mut prev_b: Option<u32> = None;
        let mut prev_r: Option<(u32, u32)> = None;
        for k in 0..TIMEOUT {
            if aw_done
                && w_done
                && ar_done
                && (write.is_none() || b_got.is_some())
                && (read.is_none() || r_got.is_some())
            {
                return Ok((x, b_got, r_got));
            }
            {
                let a = &mut x.slave.axi;
                if let Some(w) = &write {
                    a.awvalid.next = !aw_done && k >= aw_at;
                    a.awaddr.next = (w.addr as u64).into();
                    a.wvalid.next = !w_done && k >= w_at;
                    a.wdata.next = (w.data as u64).into();
                    a.wstrb.next = (w.strb as u64).into();
                    a.bready.next = b_got.is_none() && k >= b_at;
                }
                if let Some(addr) = read {
                    a.arvalid.next = !ar_done && k >= ar_at;
                    a.araddr.next = (addr as u64).into();
                    a.rready.next = r_got.is_none() && k >= r_at;
                }
            }
            wait_clock_false!(sim, clock, x);
            let a = &x.slave.axi;
            let aw_hs = a.awvalid.val() && a.awready.val();
            let w_hs = a.wvalid.val() && a.wready.val();
            let b_now = a.bvalid.val().then(|| a.bresp.val().index() as u32);
            let b_hs = a.bvalid.val() && a.bready.val();
            let ar_hs = a.arvalid.val() && a.arready.val();
            let r_now = a
                .rvalid
                .val()
                .then(|| (a.rresp.val().index() as u32, a.rdata.val().index() as u32));
            let r_hs = a.rvalid.val() && a.rready.val();
            if write.is_some() && !aw_done && !w_done && b_now.is_some() && prev_b.is_none() {
                return fail(sim, x, "bvalid before the write was sent".into());
            }
            if read.is_some() && !ar_done && r_now.is_some() && prev_r.is_none() {
                return fail(sim, x, "rvalid before the read address was sent".into());
            }
            if prev_b.is_some() && b_now != prev_b {
                return fail(
                    sim,
                    x,
                    format!("bvalid/bresp changed before bready: {prev_b:?} -> {b_now:?}"),
                );
            }
            if prev_r.is_some() && r_now != prev_r {
                return fail(
                    sim,
                    x,
                    format!("rvalid/rdata changed before rready: {prev_r:?} -> {r_now:?}"),
                );
            }
            wait_clock_true!(sim, clock, x);
            self.cycles += 1;
            aw_done |= aw_hs;
            w_done |= w_hs;
            ar_done |= ar_hs;
            if write.is_some() && b_hs {
                if !(aw_done && w_done) {
                    return fail(sim, x, "write response before address and data".into());
                }
                b_got = b_now;
                prev_b = None;
            } else if write.is_some() {
                prev_b = b_now;
            }
            if read.is_some() && r_hs {
                r_got = r_now;
                prev_r = None;
            } else if read.is_some() {
                prev_r = r_now;
            }
            let a = &mut x.slave.axi;
            a.awvalid.next = false;
            a.wvalid.next = false;
            a.arvalid.next = false;
            a.bready.next = false;
            a.rready.next = false;
        }
        fail(
            sim,
            x,
            format!("transaction timed out after {TIMEOUT} cycles"),
        )
    }

    fn write_strb(
        &mut self,
        sim: &mut Sim<Bench>,
        x: X,
        addr: usize,
        data: u32,
        strb: u32,
    ) -> R<(X, u32)> {
        let (x, b, _) = self.transact(sim, x, Some(WriteReq { addr, data, strb }), None)?;
        Ok((x, b.expect("write response")))
    }

    /// A full-word write that must answer `resp`.
    fn write_expect(
        &mut self,
        sim: &mut Sim<Bench>,
        x: X,
        addr: usize,
        data: u32,
        resp: u32,
    ) -> R<X> {
        let (x, b) = self.write_strb(sim, x, addr, data, 0xF)?;
        if b != resp {
            return fail(
                sim,
                x,
                format!("write 0x{addr:02x}: bresp {b} expected {resp}"),
            );
        }
        Ok(x)
    }

    fn write(&mut self, sim: &mut Sim<Bench>, x: X, addr: usize, data: u32) -> R<X> {
        self.write_expect(sim, x, addr, data, regmap::RESP_OKAY)
    }

    fn read_resp(&mut self, sim: &mut Sim<Bench>, x: X, addr: usize) -> R<(X, u32, u32)> {
        let (x, _, r) = self.transact(sim, x, None, Some(addr))?;
        let (resp, data) = r.expect("read response");
        Ok((x, resp, data))
    }

    fn read(&mut self, sim: &mut Sim<Bench>, x: X, addr: usize) -> R<(X, u32)> {
        let (x, resp, data) = self.read_resp(sim, x, addr)?;
        if resp != regmap::RESP_OKAY {
            return fail(sim, x, format!("read 0x{addr:02x}: rresp {resp}"));
        }
        Ok((x, data))
    }

    fn expect(&mut self, sim: &mut Sim<Bench>, x: X, addr: usize, want: u32) -> R<X> {
        let (x, got) = self.read(sim, x, addr)?;
        if got != want {
            return fail(
                sim,
                x,
                format!("read 0x{addr:02x}: got 0x{got:08x} expected 0x{want:08x}"),
            );
        }
        Ok(x)
    }

    /// Poll the control register until ap_done (bounded). Returns the control word seen.
    fn poll_done(&mut self, sim: &mut Sim<Bench>, mut x: X) -> R<(X, u32)> {
        for _ in 0..100 {
            let (nx, ctrl) = self.read(sim, x, regmap::CONTROL)?;
            x = nx;
            if ctrl & regmap::AP_DONE != 0 {
                return Ok((x, ctrl));
            }
        }
        fail(sim, x, "ap_done never came".into())
    }
}

/// Reset the bench, then run `body` with a master of the given timing.
fn run<F>(seed: u64, timing: Timing, latency: u8, max_cycles: u64, body: F)
where
    F: Fn(&mut Sim<Bench>, X, &mut Master) -> R<X> + Send + std::panic::RefUnwindSafe + 'static,
{
    let mut sim = Simulation::new();
    sim.add_clock(5, |x: &mut Box<Bench>| x.clock.next = !x.clock.val());
    sim.add_testbench(move |mut sim: Sim<Bench>| {
        let mut x = sim.init()?;
        x.slave.reset_n.next = false;
        x.slave.id.next = (ID as u64).into();
        x.slave.configuration.next = (CONFIG as u64).into();
        x.core.latency.next = (latency as u64).into();
        wait_clock_true!(sim, clock, x);
        wait_clock_cycles!(sim, clock, x, 2);
        x.slave.reset_n.next = true;
        wait_clock_cycle!(sim, clock, x);
        let mut master = Master::new(seed, timing);
        let x = body(&mut sim, x, &mut master)?;
        sim_assert!(sim, !x.core.overlap.q.val(), x);
        sim_assert!(sim, !x.core.unstable.q.val(), x);
        sim.done(x)
    });
    sim.run(Box::new(bench()), max_cycles * 10).unwrap();
}

fn operand_value(i: usize, salt: u32) -> u32 {
    (i as u32 + 1).wrapping_mul(0x9E37_79B9) ^ salt
}

#[test]
fn registers_read_write_and_read_only() {
    run(1, NO_DELAY, 4, 4_000, |sim, mut x, m| {
        x = m.expect(sim, x, regmap::ID, ID)?;
        x = m.expect(sim, x, regmap::CONFIG, CONFIG)?;
        x = m.expect(sim, x, regmap::CONTROL, regmap::AP_IDLE)?;
        for (i, &off) in OPERANDS.iter().enumerate() {
            x = m.expect(sim, x, off, 0)?;
            x = m.write(sim, x, off, operand_value(i, 0))?;
        }
        for (i, &off) in OPERANDS.iter().enumerate() {
            x = m.expect(sim, x, off, operand_value(i, 0))?;
        }
        x = m.write(sim, x, regmap::GIE, 0xFFFF_FFFF)?;
        x = m.expect(sim, x, regmap::GIE, 1)?;
        x = m.write(sim, x, regmap::IER, 0xFFFF_FFFF)?;
        x = m.expect(sim, x, regmap::IER, 3)?;
        x = m.write(sim, x, regmap::IER, 2)?;
        x = m.expect(sim, x, regmap::IER, 2)?;
        // Read-only registers: SLVERR, unchanged.
        for off in [
            regmap::RESULT,
            regmap::T,
            regmap::U,
            regmap::V,
            regmap::ID,
            regmap::CONFIG,
        ] {
            let before = if off == regmap::ID {
                ID
            } else if off == regmap::CONFIG {
                CONFIG
            } else {
                0
            };
            x = m.write_expect(sim, x, off, 0xDEAD_BEEF, regmap::RESP_SLVERR)?;
            x = m.expect(sim, x, off, before)?;
        }
        // Unmapped offsets: SLVERR both ways, reads 0, no side effect on neighbours.
        for off in [0x68, 0x6C, 0x70, 0x7C] {
            x = m.write_expect(sim, x, off, 0x1234_5678, regmap::RESP_SLVERR)?;
            let (nx, resp, data) = m.read_resp(sim, x, off)?;
            x = nx;
            check_eq!(sim, x, resp, regmap::RESP_SLVERR);
            check_eq!(sim, x, data, 0);
        }
        x = m.expect(sim, x, regmap::V2_Z, operand_value(14, 0))?;
        x = m.expect(sim, x, regmap::RESULT, 0)?;
        // The low address bits are ignored.
        x = m.expect(sim, x, regmap::ORIG_Y + 3, operand_value(1, 0))?;
        Ok(x)
    });
}

#[test]
fn byte_strobes_select_lanes() {
    run(2, NO_DELAY, 4, 4_000, |sim, mut x, m| {
        for strb in 0..16u32 {
            x = m.write(sim, x, regmap::DIR_Y, 0xFFFF_FFFF)?;
            let (nx, b) = m.write_strb(sim, x, regmap::DIR_Y, 0x1122_3344, strb)?;
            x = nx;
            check_eq!(sim, x, b, regmap::RESP_OKAY);
            let mask = (0..4)
                .filter(|l| strb >> l & 1 == 1)
                .fold(0u32, |acc, l| acc | 0xFF << (8 * l));
            x = m.expect(sim, x, regmap::DIR_Y, (0x1122_3344 & mask) | !mask)?;
        }
        // Control registers take byte lane 0 only.
        let (nx, _) = m.write_strb(sim, x, regmap::GIE, 1, 0b1110)?;
        x = m.expect(sim, nx, regmap::GIE, 0)?;
        Ok(x)
    });
}

#[test]
fn address_and_data_in_either_order() {
    let cases = [
        Timing {
            aw: 0,
            w: 0,
            b: 0,
            ..NO_DELAY
        },
        Timing {
            aw: 0,
            w: 5,
            b: 0,
            ..NO_DELAY
        },
        Timing {
            aw: 5,
            w: 0,
            b: 0,
            ..NO_DELAY
        },
        Timing {
            aw: 3,
            w: 3,
            b: 9,
            ..NO_DELAY
        },
    ];
    run(3, NO_DELAY, 4, 6_000, move |sim, mut x, m| {
        for (n, timing) in cases.into_iter().enumerate() {
            let mut exact = Master::exact(timing);
            for (i, &off) in OPERANDS.iter().enumerate() {
                let data = operand_value(i, n as u32);
                let (nx, b) = exact.write_strb(sim, x, off, data, 0xF)?;
                x = nx;
                check_eq!(sim, x, b, regmap::RESP_OKAY);
            }
            for (i, &off) in OPERANDS.iter().enumerate() {
                x = m.expect(sim, x, off, operand_value(i, n as u32))?;
            }
        }
        Ok(x)
    });
}

#[test]
fn back_to_back_transactions_are_not_throttled() {
    run(4, NO_DELAY, 4, 3_000, |sim, mut x, m| {
        let start = m.cycles;
        for (i, &off) in OPERANDS.iter().enumerate() {
            x = m.write(sim, x, off, operand_value(i, 7))?;
        }
        let writes = m.cycles - start;
        let start = m.cycles;
        for (i, &off) in OPERANDS.iter().enumerate() {
            x = m.expect(sim, x, off, operand_value(i, 7))?;
        }
        let reads = m.cycles - start;
        let n = OPERAND_COUNT as u64;
        println!("{n} writes: {writes} cycles, {n} reads: {reads} cycles");
        // Address and data are taken in the first cycle, the register written in the
        // second, the response accepted in the third; a read answers the cycle after.
        check!(sim, x, writes <= n * 3);
        check!(sim, x, reads <= n * 2);
        // A write and a read at the same time, to different registers and to the same one.
        let (nx, b, r) = m.transact(
            sim,
            x,
            Some(WriteReq {
                addr: regmap::V0_X,
                data: 5,
                strb: 0xF,
            }),
            Some(regmap::V0_Y),
        )?;
        x = nx;
        check_eq!(sim, x, b, Some(regmap::RESP_OKAY));
        check_eq!(sim, x, r, Some((regmap::RESP_OKAY, operand_value(7, 7))));
        x = m.expect(sim, x, regmap::V0_X, 5)?;
        Ok(x)
    });
}

/// Drive one channel's valid (with its payload already set) until its handshake.
fn handshake(sim: &mut Sim<Bench>, mut x: X, m: &mut Master, aw: bool) -> R<X> {
    for _ in 0..TIMEOUT {
        wait_clock_false!(sim, clock, x);
        let a = &x.slave.axi;
        let done = if aw {
            a.awvalid.val() && a.awready.val()
        } else {
            a.wvalid.val() && a.wready.val()
        };
        wait_clock_true!(sim, clock, x);
        m.cycles += 1;
        if done {
            if aw {
                x.slave.axi.awvalid.next = false;
            } else {
                x.slave.axi.wvalid.next = false;
            }
            return Ok(x);
        }
    }
    fail(sim, x, "handshake timed out".into())
}

#[test]
fn a_second_address_waits_for_the_first_write() {
    // A master may send the next write address before the previous write is complete; the
    // slave holds one and must not take (and lose) a second until the first is written.
    run(10, NO_DELAY, 4, 2_000, |sim, mut x, m| {
        x.slave.axi.bready.next = true;
        x.slave.axi.wstrb.next = 0xF.into();
        x.slave.axi.awaddr.next = (regmap::ORIG_X as u64).into();
        x.slave.axi.awvalid.next = true;
        x = handshake(sim, x, m, true)?;
        x.slave.axi.awaddr.next = (regmap::ORIG_Y as u64).into();
        x.slave.axi.awvalid.next = true;
        for _ in 0..4 {
            x = m.cycle(sim, x)?;
            check!(sim, x, !x.slave.axi.awready.val());
        }
        x.slave.axi.wdata.next = 111.into();
        x.slave.axi.wvalid.next = true;
        x = handshake(sim, x, m, false)?;
        x = handshake(sim, x, m, true)?;
        x.slave.axi.wdata.next = 222.into();
        x.slave.axi.wvalid.next = true;
        x = handshake(sim, x, m, false)?;
        for _ in 0..4 {
            x = m.cycle(sim, x)?;
        }
        check!(sim, x, !x.slave.axi.bvalid.val());
        x.slave.axi.bready.next = false;
        x = m.expect(sim, x, regmap::ORIG_X, 111)?;
        x = m.expect(sim, x, regmap::ORIG_Y, 222)?;
        // The same with data first: a second data beat waits for the first address.
        x.slave.axi.bready.next = true;
        x.slave.axi.wdata.next = 333.into();
        x.slave.axi.wvalid.next = true;
        x = handshake(sim, x, m, false)?;
        x.slave.axi.wdata.next = 444.into();
        x.slave.axi.wvalid.next = true;
        for _ in 0..4 {
            x = m.cycle(sim, x)?;
            check!(sim, x, !x.slave.axi.wready.val());
        }
        x.slave.axi.awaddr.next = (regmap::ORIG_Z as u64).into();
        x.slave.axi.awvalid.next = true;
        x = handshake(sim, x, m, true)?;
        x = handshake(sim, x, m, false)?;
        x.slave.axi.awaddr.next = (regmap::V0_X as u64).into();
        x.slave.axi.awvalid.next = true;
        x = handshake(sim, x, m, true)?;
        for _ in 0..4 {
            x = m.cycle(sim, x)?;
        }
        x.slave.axi.bready.next = false;
        x = m.expect(sim, x, regmap::ORIG_Z, 333)?;
        x = m.expect(sim, x, regmap::V0_X, 444)?;
        Ok(x)
    });
}

/// The register file as software sees it while the core is not started: a reference model
/// for the random tests (every register but CONTROL is written at random).
struct Model {
    operands: [u32; OPERAND_COUNT],
    gie: u32,
    ier: u32,
    isr: u32,
}

impl Model {
    /// Apply a write; returns the expected response.
    fn write(&mut self, addr: usize, data: u32, strb: u32) -> u32 {
        let lane0 = strb & 1 == 1;
        let mask = (0..4)
            .filter(|l| strb >> l & 1 == 1)
            .fold(0u32, |acc, l| acc | 0xFF << (8 * l));
        match regmap::register_at(addr).map(|r| r.offset) {
            Some(regmap::GIE) => self.gie = if lane0 { data & 1 } else { self.gie },
            Some(regmap::IER) => self.ier = if lane0 { data & 3 } else { self.ier },
            Some(regmap::ISR) => self.isr ^= if lane0 { data & 3 } else { 0 },
            Some(off) if OPERANDS.contains(&off) => {
                let i = (off - regmap::ORIG_X) / 4;
                self.operands[i] = (self.operands[i] & !mask) | (data & mask);
            }
            Some(_) => return regmap::RESP_SLVERR,
            None => return regmap::RESP_SLVERR,
        }
        regmap::RESP_OKAY
    }

    fn read(&self, addr: usize) -> (u32, u32) {
        let ok = |v| (regmap::RESP_OKAY, v);
        match regmap::register_at(addr).map(|r| r.offset) {
            Some(regmap::CONTROL) => ok(regmap::AP_IDLE),
            Some(regmap::GIE) => ok(self.gie),
            Some(regmap::IER) => ok(self.ier),
            Some(regmap::ISR) => ok(self.isr),
            Some(regmap::ID) => ok(ID),
            Some(regmap::CONFIG) => ok(CONFIG),
            Some(off) if OPERANDS.contains(&off) => ok(self.operands[(off - regmap::ORIG_X) / 4]),
            Some(_) => ok(0),
            None => (regmap::RESP_SLVERR, 0),
        }
    }
}

/// Random writes and reads (together or alone) with random delays on all five channels,
/// checked against [`Model`]; the interrupt output follows GIE, IER and ISR.
fn random_traffic(seed: u64, transactions: usize) {
    let timing = Timing {
        aw: 4,
        w: 4,
        b: 4,
        ar: 4,
        r: 4,
    };
    run(
        seed,
        timing,
        4,
        60 * transactions as u64 + 1_000,
        move |sim, mut x, m| {
            let mut rng = StdRng::seed_from_u64(seed ^ 0x5eed);
            let mut model = Model {
                operands: [0; OPERAND_COUNT],
                gie: 0,
                ier: 0,
                isr: 0,
            };
            let addr = |rng: &mut StdRng| -> usize {
                if rng.gen_bool(0.8) {
                    regmap::REGISTERS[rng.gen_range(0..regmap::REGISTERS.len())].offset
                } else {
                    rng.gen_range(0..1usize << regmap::ADDR_BITS)
                }
            };
            for _ in 0..transactions {
                let write = rng.gen_bool(0.6).then(|| {
                    let mut a = addr(&mut rng);
                    while a & !3 == regmap::CONTROL {
                        a = addr(&mut rng);
                    }
                    WriteReq {
                        addr: a,
                        data: rng.gen(),
                        strb: if rng.gen_bool(0.5) {
                            0xF
                        } else {
                            rng.gen_range(0..16)
                        },
                    }
                });
                let read = (write.is_none() || rng.gen_bool(0.4)).then(|| addr(&mut rng));
                // A read that overlaps a write may see the register before or after it: only
                // check overlapping reads of other registers exactly.
                let same = matches!((&write, read), (Some(w), Some(r)) if w.addr & !3 == r & !3);
                let before = read.map(|r| model.read(r));
                let want_b = write.as_ref().map(|w| model.write(w.addr, w.data, w.strb));
                let after = read.map(|r| model.read(r));
                let (nx, b, r) = m.transact(sim, x, write, read)?;
                x = nx;
                if b != want_b {
                    return fail(sim, x, format!("bresp {b:?} expected {want_b:?}"));
                }
                if r.is_some() && r != after && !(same && r == before) {
                    return fail(sim, x, format!("read {read:?}: {r:?} expected {after:?}"));
                }
                let irq = model.gie == 1 && model.isr & model.ier != 0;
                check_eq!(sim, x, x.slave.interrupt.val(), irq);
            }
            for (i, &off) in OPERANDS.iter().enumerate() {
                x = m.expect(sim, x, off, model.operands[i])?;
            }
            Ok(x)
        },
    );
}

#[test]
fn random_timing_against_a_model() {
    random_traffic(5, 150);
}

/// `cargo test --release -p hdl --test integration -- --ignored axil_slave::random_soak`
#[test]
#[ignore]
fn random_soak() {
    for seed in 100..110 {
        random_traffic(seed, 1_000);
    }
}

fn expected_result(ops: &[u32; OPERAND_COUNT]) -> [u32; 4] {
    [ops[2] & 1, ops[0].wrapping_add(ops[1]), ops[3], ops[14]]
}

fn write_operands(
    sim: &mut Sim<Bench>,
    mut x: X,
    m: &mut Master,
    ops: &[u32; OPERAND_COUNT],
) -> R<X> {
    for (i, &off) in OPERANDS.iter().enumerate() {
        x = m.write(sim, x, off, ops[i])?;
    }
    Ok(x)
}

fn check_results(
    sim: &mut Sim<Bench>,
    mut x: X,
    m: &mut Master,
    ops: &[u32; OPERAND_COUNT],
) -> R<X> {
    let [hit, t, u, v] = expected_result(ops);
    x = m.expect(sim, x, regmap::RESULT, hit)?;
    x = m.expect(sim, x, regmap::T, t)?;
    x = m.expect(sim, x, regmap::U, u)?;
    m.expect(sim, x, regmap::V, v)
}

#[test]
fn register_mode_sequence_with_done_idle_ready() {
    run(
        6,
        Timing {
            aw: 1,
            w: 2,
            b: 1,
            ar: 1,
            r: 2,
        },
        12,
        8_000,
        |sim, mut x, m| {
            let ops: [u32; OPERAND_COUNT] = std::array::from_fn(|i| operand_value(i, 0xA5A5_0001));
            x = write_operands(sim, x, m, &ops)?;
            x = m.expect(sim, x, regmap::CONTROL, regmap::AP_IDLE)?;
            x = m.write(sim, x, regmap::CONTROL, regmap::AP_START)?;
            // Busy: ap_start still set, not idle, nothing done.
            x = m.expect(sim, x, regmap::CONTROL, regmap::AP_START)?;
            let (nx, ctrl) = m.poll_done(sim, x)?;
            x = nx;
            check_eq!(
                sim,
                x,
                ctrl,
                regmap::AP_DONE | regmap::AP_IDLE | regmap::AP_READY
            );
            // Clear on read.
            x = m.expect(sim, x, regmap::CONTROL, regmap::AP_IDLE)?;
            x = check_results(sim, x, m, &ops)?;
            check_eq!(sim, x, x.core.starts.q.val().index(), 1);
            // Writing 0 to ap_start does not start; a second run with other operands.
            x = m.write(sim, x, regmap::CONTROL, 0)?;
            let ops2: [u32; OPERAND_COUNT] = std::array::from_fn(|i| operand_value(i, 0x0F0F_0002));
            x = write_operands(sim, x, m, &ops2)?;
            check_eq!(sim, x, x.core.starts.q.val().index(), 1);
            x = m.write(sim, x, regmap::CONTROL, regmap::AP_START)?;
            let (nx, _) = m.poll_done(sim, x)?;
            x = check_results(sim, nx, m, &ops2)?;
            check_eq!(sim, x, x.core.starts.q.val().index(), 2);
            Ok(x)
        },
    );
}

#[test]
fn interrupts_follow_gie_ier_isr() {
    run(7, NO_DELAY, 6, 8_000, |sim, mut x, m| {
        let ops: [u32; OPERAND_COUNT] = std::array::from_fn(|i| operand_value(i, 3));
        x = write_operands(sim, x, m, &ops)?;
        // Events are recorded only when enabled.
        x = m.write(sim, x, regmap::CONTROL, regmap::AP_START)?;
        let (nx, _) = m.poll_done(sim, x)?;
        x = m.expect(sim, nx, regmap::ISR, 0)?;
        check!(sim, x, !x.slave.interrupt.val());
        // Done enabled, global disabled: ISR set, no interrupt.
        x = m.write(sim, x, regmap::IER, regmap::INT_DONE)?;
        x = m.write(sim, x, regmap::CONTROL, regmap::AP_START)?;
        let (nx, _) = m.poll_done(sim, x)?;
        x = m.expect(sim, nx, regmap::ISR, regmap::INT_DONE)?;
        check!(sim, x, !x.slave.interrupt.val());
        x = m.write(sim, x, regmap::GIE, 1)?;
        check!(sim, x, x.slave.interrupt.val());
        // Write 1 toggles: clear, then set again, then clear.
        x = m.write(sim, x, regmap::ISR, regmap::INT_DONE)?;
        x = m.expect(sim, x, regmap::ISR, 0)?;
        check!(sim, x, !x.slave.interrupt.val());
        x = m.write(sim, x, regmap::ISR, regmap::INT_DONE)?;
        check!(sim, x, x.slave.interrupt.val());
        x = m.write(sim, x, regmap::ISR, regmap::INT_DONE)?;
        // Writing 0 changes nothing.
        x = m.write(sim, x, regmap::ISR, 0)?;
        x = m.expect(sim, x, regmap::ISR, 0)?;
        // Ready only: wait for the interrupt line instead of polling.
        x = m.write(sim, x, regmap::IER, regmap::INT_READY)?;
        x = m.write(sim, x, regmap::CONTROL, regmap::AP_START)?;
        let mut waited = 0;
        while !x.slave.interrupt.val() {
            x = m.cycle(sim, x)?;
            waited += 1;
            check!(sim, x, waited < 100);
        }
        x = m.expect(sim, x, regmap::ISR, regmap::INT_READY)?;
        x = m.expect(
            sim,
            x,
            regmap::CONTROL,
            regmap::AP_DONE | regmap::AP_IDLE | regmap::AP_READY,
        )?;
        // IER masks a pending bit; GIE off silences everything.
        x = m.write(sim, x, regmap::IER, regmap::INT_DONE)?;
        check!(sim, x, !x.slave.interrupt.val());
        x = m.write(sim, x, regmap::IER, regmap::INT_DONE | regmap::INT_READY)?;
        check!(sim, x, x.slave.interrupt.val());
        x = m.write(sim, x, regmap::GIE, 0)?;
        check!(sim, x, !x.slave.interrupt.val());
        Ok(x)
    });
}

#[test]
fn auto_restart_and_operands_held_while_busy() {
    run(8, NO_DELAY, 100, 12_000, |sim, mut x, m| {
        let ops: [u32; OPERAND_COUNT] = std::array::from_fn(|i| operand_value(i, 11));
        x = write_operands(sim, x, m, &ops)?;
        x = m.write(
            sim,
            x,
            regmap::CONTROL,
            regmap::AP_START | regmap::AUTO_RESTART,
        )?;
        // Rewrite every operand while the core runs: the core must not see a change until
        // the next start (the stand-in core flags any change), and the run in flight
        // returns the old operands' result.
        let ops2: [u32; OPERAND_COUNT] = std::array::from_fn(|i| operand_value(i, 22));
        x = write_operands(sim, x, m, &ops2)?;
        check_eq!(sim, x, x.core.starts.q.val().index(), 1);
        let (nx, ctrl) = m.poll_done(sim, x)?;
        x = nx;
        check!(sim, x, ctrl & regmap::AUTO_RESTART != 0);
        // The first completion carries the first operands; the restarted run the new ones.
        let [hit, t, _, _] = expected_result(&ops);
        let (nx, got_t) = m.read(sim, x, regmap::T)?;
        x = nx;
        let (nx, got_hit) = m.read(sim, x, regmap::RESULT)?;
        x = nx;
        check_eq!(sim, x, (got_hit, got_t), (hit, t));
        let (nx, _) = m.poll_done(sim, x)?;
        x = check_results(sim, nx, m, &ops2)?;
        check!(sim, x, x.core.starts.q.val().index() >= 3);
        // Clear auto_restart: the run in flight finishes, then the core stays idle.
        x = m.write(sim, x, regmap::CONTROL, 0)?;
        let mut idle = false;
        for _ in 0..60 {
            let (nx, c) = m.read(sim, x, regmap::CONTROL)?;
            x = nx;
            if c & regmap::AP_IDLE != 0 {
                idle = true;
                break;
            }
        }
        check!(sim, x, idle);
        let starts = x.core.starts.q.val().index();
        for _ in 0..60 {
            x = m.cycle(sim, x)?;
        }
        check_eq!(sim, x, x.core.starts.q.val().index(), starts);
        x = m.expect(sim, x, regmap::CONTROL, regmap::AP_IDLE)?;
        Ok(x)
    });
}

#[test]
fn reset_clears_state() {
    run(9, NO_DELAY, 30, 3_000, |sim, mut x, m| {
        x = m.write(sim, x, regmap::ORIG_X, 42)?;
        x = m.write(sim, x, regmap::GIE, 1)?;
        x = m.write(sim, x, regmap::IER, 3)?;
        x = m.write(
            sim,
            x,
            regmap::CONTROL,
            regmap::AP_START | regmap::AUTO_RESTART,
        )?;
        x.slave.reset_n.next = false;
        x = m.cycle(sim, x)?;
        x = m.cycle(sim, x)?;
        x.slave.reset_n.next = true;
        x = m.cycle(sim, x)?;
        x = m.expect(sim, x, regmap::CONTROL, regmap::AP_IDLE)?;
        x = m.expect(sim, x, regmap::ORIG_X, 0)?;
        x = m.expect(sim, x, regmap::GIE, 0)?;
        x = m.expect(sim, x, regmap::IER, 0)?;
        x = m.expect(sim, x, regmap::ISR, 0)?;
        check!(sim, x, !x.slave.interrupt.val());
        Ok(x)
    });
}

fn slave_verilog(dir: &std::path::Path) -> std::path::PathBuf {
    let mut uut = AxiLiteSlave::default();
    uut.connect_all();
    let path = dir.join("top.v");
    std::fs::write(&path, generate_verilog(&uut)).unwrap();
    path
}

/// Documented waivers: rust-hdl puts every module of the design in one file; the two low
/// address bits are ignored by design (word registers with byte strobes); `interrupt` is the
/// name Vivado expects, although it is a C++ word.
const LINT_WAIVERS: &str = r#"`verilator_config
lint_off -rule DECLFILENAME
lint_off -rule UNUSEDSIGNAL -file "*" -match "Bits of signal are not used: 'axi$*addr'[1:0]"
lint_off -rule SYMRSVDWORD -file "*" -match "*'interrupt'"
"#;

#[test]
fn verilog_lints_clean_with_verilator() {
    let dir = tempfile::tempdir().unwrap();
    let top = slave_verilog(dir.path());
    let waivers = dir.path().join("waivers.vlt");
    std::fs::write(&waivers, LINT_WAIVERS).unwrap();
    let out = Command::new("verilator")
        .args(["--lint-only", "-Wall", "--top-module", "top"])
        .arg(&waivers)
        .arg(&top)
        .output()
        .expect("verilator is installed (scripts/ installs it)");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn verilog_synthesises_with_yosys() {
    let dir = tempfile::tempdir().unwrap();
    let top = slave_verilog(dir.path());
    let script = format!(
        "read_verilog {}; synth_xilinx -flatten -family xc7 -top top; stat",
        top.display()
    );
    let out = Command::new("yosys")
        .args(["-q", "-p", &script])
        .output()
        .expect("yosys is installed (scripts/ installs it)");
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}{}",
        log,
        String::from_utf8_lossy(&out.stderr)
    );
}
