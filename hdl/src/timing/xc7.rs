//! Delays of the Xilinx 7-series primitives that `synth_xilinx` emits, in picoseconds.
//!
//! Every number is from the `specify` blocks of yosys 0.23's own cell library,
//! `share/yosys/xilinx/cells_sim.v`, whose comments cite the prjxray database's Artix-7 SDF
//! files (`prjxray-db/artix7/timings/*.sdf`, slow corner): the delays `sta` and `abc9` use.
//! The Zynq-7020's programmable logic is Artix-7 fabric, so they stand for the XC7Z020 as is.
//! Where yosys' table has a gap, the entry says what fills it.

use super::netlist::Cell;
use super::TimingError;

/// A cell pin: a port and a bit (`None`: every bit of the port).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Pin {
    pub port: &'static str,
    pub bit: Option<usize>,
}

impl Pin {
    fn all(port: &'static str) -> Self {
        Pin { port, bit: None }
    }
    fn bit(port: &'static str, bit: usize) -> Self {
        Pin {
            port,
            bit: Some(bit),
        }
    }
    /// Whether this pin is `port[bit]`.
    pub fn matches(&self, port: &str, bit: usize) -> bool {
        self.port == port && self.bit.is_none_or(|b| b == bit)
    }
}

/// How a cell's pins take part in timing.
#[derive(Debug, Default)]
pub(crate) struct CellModel {
    /// Combinational arcs: input pin, output pin, delay.
    pub arcs: Vec<(Pin, Pin, u32)>,
    /// Outputs launched by the clock, and the clock-to-output delay.
    pub clock_to_out: Vec<(Pin, u32)>,
    /// Inputs captured by the clock, and their setup time.
    pub setup: Vec<(Pin, u32)>,
    /// The inputs are one LUT's: the place-and-route tool may permute them (see
    /// [`LUT6_PIN_DELAYS`]).
    pub lut: bool,
}

impl CellModel {
    fn arc(&mut self, from: Pin, to: Pin, ps: u32) {
        self.arcs.push((from, to, ps));
    }
    fn launch(&mut self, pin: Pin, ps: u32) {
        self.clock_to_out.push((pin, ps));
    }
    fn capture(&mut self, pin: Pin, ps: u32) {
        self.setup.push((pin, ps));
    }
}

/// LUT6 input I0…I5 to O. A LUTk uses the last k entries (I0 of a LUT2 is a LUT6's I4):
/// the same physical pins, A1 (slowest) to A6 (fastest). Distributed RAM and SRL address
/// bits have the same delays, bit 0 on the slowest pin.
pub(crate) const LUT6_PIN_DELAYS: [u32; 6] = [642, 631, 472, 407, 238, 127];

/// The delay of input `i` of a `k`-input LUT.
fn lut_pin(k: usize, i: usize) -> u32 {
    LUT6_PIN_DELAYS[6 - k + i]
}

/// Flip-flop clock to Q (CLBLL_L.sdf).
const FF_CLOCK_TO_Q: u32 = 303;
/// Setup of D: yosys writes 0 because the SDF's −46 ps is negative.
const FF_SETUP_D: u32 = 0;
const FF_SETUP_CE: u32 = 109;
/// Synchronous set/reset; also the recovery time of an asynchronous clear or preset (a reset
/// is timed as a signal captured by the clock, its asynchronous path to Q is not a data path).
const FF_SETUP_SR: u32 = 404;

/// CARRY4 (input, output, delay), every arc of yosys' table.
const CARRY4: &[(&str, usize, &str, usize, u32)] = &[
    ("CYINIT", 0, "O", 0, 482),
    ("S", 0, "O", 0, 223),
    ("CI", 0, "O", 0, 222),
    ("CYINIT", 0, "O", 1, 598),
    ("DI", 0, "O", 1, 407),
    ("S", 0, "O", 1, 400),
    ("S", 1, "O", 1, 205),
    ("CI", 0, "O", 1, 334),
    ("CYINIT", 0, "O", 2, 584),
    ("DI", 0, "O", 2, 556),
    ("DI", 1, "O", 2, 537),
    ("S", 0, "O", 2, 523),
    ("S", 1, "O", 2, 558),
    ("S", 2, "O", 2, 226),
    ("CI", 0, "O", 2, 239),
    ("CYINIT", 0, "O", 3, 642),
    ("DI", 0, "O", 3, 615),
    ("DI", 1, "O", 3, 596),
    ("DI", 2, "O", 3, 438),
    ("S", 0, "O", 3, 582),
    ("S", 1, "O", 3, 618),
    ("S", 2, "O", 3, 330),
    ("S", 3, "O", 3, 227),
    ("CI", 0, "O", 3, 313),
    ("CYINIT", 0, "CO", 0, 536),
    ("DI", 0, "CO", 0, 379),
    ("S", 0, "CO", 0, 340),
    ("CI", 0, "CO", 0, 271),
    ("CYINIT", 0, "CO", 1, 494),
    ("DI", 0, "CO", 1, 465),
    ("DI", 1, "CO", 1, 445),
    ("S", 0, "CO", 1, 433),
    ("S", 1, "CO", 1, 469),
    ("CI", 0, "CO", 1, 157),
    ("CYINIT", 0, "CO", 2, 592),
    ("DI", 0, "CO", 2, 540),
    ("DI", 1, "CO", 2, 520),
    ("DI", 2, "CO", 2, 356),
    ("S", 0, "CO", 2, 512),
    ("S", 1, "CO", 2, 548),
    ("S", 2, "CO", 2, 292),
    ("CI", 0, "CO", 2, 228),
    ("CYINIT", 0, "CO", 3, 580),
    ("DI", 0, "CO", 3, 526),
    ("DI", 1, "CO", 3, 507),
    ("DI", 2, "CO", 3, 398),
    ("DI", 3, "CO", 3, 385),
    ("S", 0, "CO", 3, 508),
    ("S", 1, "CO", 3, 528),
    ("S", 2, "CO", 3, 378),
    ("S", 3, "CO", 3, 380),
    ("CI", 0, "CO", 3, 114),
];

/// Distributed RAM: write clock to the read outputs, and the setups of data, write enable
/// and write address (the largest of yosys' per-bit values for each).
struct LutRam {
    clock_to_out: u32,
    setup_data: u32,
    setup_we: u32,
    setup_address: u32,
}

const RAM32: LutRam = LutRam {
    clock_to_out: 1190,
    setup_data: 461,
    setup_we: 654,
    setup_address: 245,
};
const RAM64: LutRam = LutRam {
    clock_to_out: 1163,
    setup_data: 453,
    setup_we: 654,
    setup_address: 362,
};
/// RAM128X1D: the RAM64's LUTs plus the F7 mux to SPO (193 + 175) or DPO (223 + 174).
const RAM128: LutRam = LutRam {
    clock_to_out: 1153 + 223 + 174,
    setup_data: 453,
    setup_we: 654,
    setup_address: 616,
};

fn lut_ram(m: &mut CellModel, ram: &LutRam, data_in: &[&'static str], outs: &[&'static str]) {
    for &o in outs {
        m.launch(Pin::all(o), ram.clock_to_out);
    }
    for &d in data_in {
        m.capture(Pin::all(d), ram.setup_data);
    }
    m.capture(Pin::all("WE"), ram.setup_we);
}

/// Block RAM (BRAM_L.sdf): clock to DO without the output register and with it.
const BRAM_CLOCK_TO_OUT: u32 = 2454;
const BRAM_CLOCK_TO_OUT_REG: u32 = 882;
const BRAM_SETUP_ADDR: u32 = 566;
/// Write enable; also the port enables, which yosys' table leaves out.
const BRAM_SETUP_WE: u32 = 532;
const BRAM_SETUP_DI: u32 = 737;
const BRAM_SETUP_REGCE: u32 = 360;
const BRAM_SETUP_RSTREG: u32 = 342;

fn block_ram(m: &mut CellModel, cell: &Cell) {
    for (port, reg) in [("A", "DOA_REG"), ("B", "DOB_REG")] {
        let ps = if cell.int_parameter(reg, 0) != 0 {
            BRAM_CLOCK_TO_OUT_REG
        } else {
            BRAM_CLOCK_TO_OUT
        };
        let (data, parity) = if port == "A" {
            ("DOADO", "DOPADOP")
        } else {
            ("DOBDO", "DOPBDOP")
        };
        m.launch(Pin::all(data), ps);
        m.launch(Pin::all(parity), ps);
    }
    for (port, ps) in [
        ("ADDRARDADDR", BRAM_SETUP_ADDR),
        ("ADDRBWRADDR", BRAM_SETUP_ADDR),
        ("WEA", BRAM_SETUP_WE),
        ("WEBWE", BRAM_SETUP_WE),
        ("ENARDEN", BRAM_SETUP_WE),
        ("ENBWREN", BRAM_SETUP_WE),
        ("DIADI", BRAM_SETUP_DI),
        ("DIBDI", BRAM_SETUP_DI),
        ("DIPADIP", BRAM_SETUP_DI),
        ("DIPBDIP", BRAM_SETUP_DI),
        ("REGCEAREGCE", BRAM_SETUP_REGCE),
        ("REGCEB", BRAM_SETUP_REGCE),
        ("RSTREGARSTREG", BRAM_SETUP_RSTREG),
        ("RSTREGB", BRAM_SETUP_RSTREG),
    ] {
        m.capture(Pin::all(port), ps);
    }
}

/// DSP48E1: the functions `A.required`, `P.arrival`, `A.P.comb`… of cells_sim.v, which
/// depend on the pipeline registers and the multiplier/pre-adder use. Control inputs
/// (OPMODE, ALUMODE, INMODE, CARRYIN, clock enables, resets) have no entry there and are
/// not timed.
fn dsp48e1(m: &mut CellModel, cell: &Cell) {
    let reg = |name: &str| cell.int_parameter(name, 1) != 0;
    let (areg, breg, creg, dreg, adreg, mreg, preg) = (
        reg("AREG"),
        reg("BREG"),
        reg("CREG"),
        reg("DREG"),
        reg("ADREG"),
        reg("MREG"),
        reg("PREG"),
    );
    let mult = cell.parameter("USE_MULT").unwrap_or("MULTIPLY") != "NONE";
    let dport = cell.parameter("USE_DPORT").unwrap_or("FALSE") == "TRUE";
    let patdet = cell.parameter("USE_PATTERN_DETECT").unwrap_or("NO_PATDET") != "NO_PATDET";
    let pick = |with: u32, without: u32| if patdet { with } else { without };

    let a_required = if areg {
        Some(254)
    } else if mult && !dport {
        if mreg {
            Some(1416)
        } else if preg {
            Some(pick(3030, 2739))
        } else {
            None
        }
    } else if mult && dport {
        if mreg {
            Some(2400)
        } else if adreg {
            Some(1283)
        } else if preg {
            Some(3723)
        } else {
            None
        }
    } else if preg {
        Some(pick(1730, 1441))
    } else {
        None
    };
    let b_required = if breg {
        Some(324)
    } else if mreg {
        Some(1285)
    } else if preg {
        Some(if mult {
            pick(2898, 2608)
        } else {
            pick(1718, 1428)
        })
    } else {
        None
    };
    let c_required = if creg {
        Some(168)
    } else if preg {
        Some(pick(1534, 1244))
    } else {
        None
    };
    let d_required = if !(mult && dport) {
        None
    } else if dreg {
        Some(248)
    } else if adreg {
        Some(1195)
    } else if mreg {
        Some(2310)
    } else if preg {
        Some(pick(3925, 3635))
    } else {
        None
    };
    // (P, PCOUT) clock-to-out: the worst register that feeds them.
    let arrival = if preg {
        Some((329, 435))
    } else if creg {
        Some((1687, 1835))
    } else if mult && mreg {
        Some((1671, 1819))
    } else if mult && !dport && areg {
        Some((2952, 3098))
    } else if mult && dport && areg {
        Some((3935, 4083))
    } else if mult && dport && dreg {
        Some((3908, 4056))
    } else if mult && dport && adreg {
        Some((2958, 2859))
    } else if mult && breg {
        Some((2813, 2960))
    } else if !mult && areg {
        Some((1632, 1780))
    } else if !mult && breg {
        Some((1616, 1765))
    } else {
        None
    };
    // Combinational (P, PCOUT) delays from each input.
    let a_comb = match (mult, dport) {
        (true, false) => (2823, 2970),
        (true, true) => (3806, 3954),
        (false, _) => (1523, 1671),
    };
    let b_comb = if mult { (2690, 2838) } else { (1509, 1658) };
    let c_comb = (1325, 1474);
    let d_comb = (3717, 3700);

    let mut input = |port: &'static str, comb: bool, delays: (u32, u32), required: Option<u32>| {
        if comb {
            m.arc(Pin::all(port), Pin::all("P"), delays.0);
            m.arc(Pin::all(port), Pin::all("PCOUT"), delays.1);
        } else if let Some(ps) = required {
            m.capture(Pin::all(port), ps);
        }
    };
    input("A", !preg && !mreg && !areg && !adreg, a_comb, a_required);
    input("B", !preg && !mreg && !breg, b_comb, b_required);
    input("C", !preg && !creg, c_comb, c_required);
    if mult && dport {
        input("D", !preg && !mreg && !adreg && !dreg, d_comb, d_required);
    }
    input("PCIN", !preg, (1107, 1255), Some(pick(1315, 1025)));
    if let Some((p, pcout)) = arrival {
        m.launch(Pin::all("P"), p);
        m.launch(Pin::all("PCOUT"), pcout);
    }
}

/// The timing model of `cell` (instance `name`).
pub(crate) fn model(cell: &Cell, name: &str) -> Result<CellModel, TimingError> {
    let mut m = CellModel::default();
    let kind = cell.kind.as_str();
    match kind {
        "LUT1" | "LUT2" | "LUT3" | "LUT4" | "LUT5" | "LUT6" => {
            let k = (kind.as_bytes()[3] - b'0') as usize;
            const INPUTS: [&str; 6] = ["I0", "I1", "I2", "I3", "I4", "I5"];
            for (i, input) in INPUTS.iter().take(k).enumerate() {
                m.arc(Pin::all(input), Pin::all("O"), lut_pin(k, i));
            }
            m.lut = true;
        }
        // yosys 0.23 leaves inverters as INV cells for the vendor tool, whose opt_design
        // absorbs each into the LUT or flip-flop it drives: no delay here, and no net into it
        // (see `TimingGraph::route`).
        "INV" => m.arc(Pin::all("I"), Pin::all("O"), 0),
        "MUXF7" => {
            m.arc(Pin::all("I0"), Pin::all("O"), 217);
            m.arc(Pin::all("I1"), Pin::all("O"), 223);
            m.arc(Pin::all("S"), Pin::all("O"), 296);
        }
        "MUXF8" => {
            m.arc(Pin::all("I0"), Pin::all("O"), 104);
            m.arc(Pin::all("I1"), Pin::all("O"), 94);
            m.arc(Pin::all("S"), Pin::all("O"), 273);
        }
        "CARRY4" => {
            for &(from, fb, to, tb, ps) in CARRY4 {
                m.arc(Pin::bit(from, fb), Pin::bit(to, tb), ps);
            }
        }
        "FDRE" | "FDSE" | "FDCE" | "FDPE" => {
            m.launch(Pin::all("Q"), FF_CLOCK_TO_Q);
            m.capture(Pin::all("D"), FF_SETUP_D);
            m.capture(Pin::all("CE"), FF_SETUP_CE);
            for reset in ["R", "S", "CLR", "PRE"] {
                m.capture(Pin::all(reset), FF_SETUP_SR);
            }
        }
        "SRL16E" => {
            m.launch(Pin::all("Q"), 1472);
            m.capture(Pin::all("D"), 173);
            m.capture(Pin::all("CE"), FF_SETUP_CE);
            for (i, a) in ["A0", "A1", "A2", "A3"].into_iter().enumerate() {
                m.arc(Pin::all(a), Pin::all("Q"), lut_pin(5, i));
            }
        }
        "SRLC32E" => {
            m.launch(Pin::all("Q"), 1472);
            m.launch(Pin::all("Q31"), 1114);
            m.capture(Pin::all("D"), 173);
            m.capture(Pin::all("CE"), FF_SETUP_CE);
            for i in 0..5 {
                m.arc(Pin::bit("A", i), Pin::all("Q"), lut_pin(6, i));
            }
        }
        "RAM32X1D" | "RAM64X1D" => {
            let (ram, bits) = if kind == "RAM32X1D" {
                (&RAM32, 5)
            } else {
                (&RAM64, 6)
            };
            const A: [&str; 6] = ["A0", "A1", "A2", "A3", "A4", "A5"];
            const DPRA: [&str; 6] = ["DPRA0", "DPRA1", "DPRA2", "DPRA3", "DPRA4", "DPRA5"];
            for i in 0..bits {
                m.arc(Pin::all(A[i]), Pin::all("SPO"), LUT6_PIN_DELAYS[i]);
                m.arc(Pin::all(DPRA[i]), Pin::all("DPO"), LUT6_PIN_DELAYS[i]);
                m.capture(Pin::all(A[i]), ram.setup_address);
            }
            lut_ram(&mut m, ram, &["D"], &["SPO", "DPO"]);
        }
        "RAM128X1D" => {
            for (i, &ps) in LUT6_PIN_DELAYS.iter().enumerate() {
                m.arc(Pin::bit("A", i), Pin::all("SPO"), ps + 193 + 175);
                m.arc(Pin::bit("DPRA", i), Pin::all("DPO"), ps + 223 + 174);
            }
            m.arc(Pin::bit("A", 6), Pin::all("SPO"), 276 + 175);
            m.arc(Pin::bit("DPRA", 6), Pin::all("DPO"), 296 + 174);
            m.capture(Pin::all("A"), RAM128.setup_address);
            lut_ram(&mut m, &RAM128, &["D"], &["SPO", "DPO"]);
        }
        "RAM32M" | "RAM64M" => {
            let (ram, bits) = if kind == "RAM32M" {
                (&RAM32, 5)
            } else {
                (&RAM64, 6)
            };
            const PORTS: [(&str, &str, &str); 4] = [
                ("ADDRA", "DOA", "DIA"),
                ("ADDRB", "DOB", "DIB"),
                ("ADDRC", "DOC", "DIC"),
                ("ADDRD", "DOD", "DID"),
            ];
            for (addr, out, _) in PORTS {
                // yosys lists bits 0–4 of a RAM64M; bit 5 is the LUT's fastest pin.
                for (i, &ps) in LUT6_PIN_DELAYS.iter().enumerate().take(bits) {
                    m.arc(Pin::bit(addr, i), Pin::all(out), ps);
                }
            }
            m.capture(Pin::all("ADDRD"), ram.setup_address);
            lut_ram(
                &mut m,
                ram,
                &["DIA", "DIB", "DIC", "DID"],
                &["DOA", "DOB", "DOC", "DOD"],
            );
        }
        "RAMB18E1" | "RAMB36E1" => block_ram(&mut m, cell),
        "DSP48E1" => dsp48e1(&mut m, cell),
        _ => {
            return Err(TimingError::UnknownCell {
                cell_type: kind.to_string(),
                instance: name.to_string(),
            })
        }
    }
    Ok(m)
}
