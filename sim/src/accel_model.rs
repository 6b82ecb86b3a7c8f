//! The accelerator top `rtfpga_top` of one configuration as a Verilated model: generation and
//! build (cached on disk by the builder and per process here), reset, named access to its
//! ports in the packed cycle buffers, and an optional VCD window.

use crate::cosim_error::CosimError;
use crate::verilator::{Direction, Interface, Port};
use crate::{build, BuildOptions, Model, ModelSpec, SimError, VerilatedModel};
use hdl::top::stream::{IN_LANE_BITS, OUT_LANE_BITS};
use hdl::top::wrapper::{self, TOP};
use hdl::top::TopConfig;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

/// Cycles `ap_rst_n` is held low by [`Accel::reset`] (the reset is synchronous).
const RESET_CYCLES: u64 = 2;

/// A built model of `rtfpga_top` and what it was built from.
pub struct TopModel {
    pub config: TopConfig,
    pub model: Model,
    /// Cycles from a query entering a lane to its result.
    pub lane_latency: usize,
    /// Time spent generating the Verilog and building (or loading) the model.
    pub build_time: Duration,
}

type ModelKey = (hw_model::HwFormat, usize, usize, bool);

/// Models built by this process, so tests and engines share one build per configuration.
fn built() -> &'static Mutex<HashMap<ModelKey, Arc<TopModel>>> {
    static BUILT: OnceLock<Mutex<HashMap<ModelKey, Arc<TopModel>>>> = OnceLock::new();
    BUILT.get_or_init(Default::default)
}

/// Generates `rtfpga_top` for `config` and builds it (`trace`: the VCD-capable variant). One
/// build per configuration and process; the builder's disk cache spans processes. Builds are
/// serialised: each one already uses every core.
pub fn top_model(config: &TopConfig, trace: bool) -> Result<Arc<TopModel>, CosimError> {
    top_model_with(
        config,
        &BuildOptions {
            trace,
            ..BuildOptions::default()
        },
    )
}

/// [`top_model`] with explicit build options (tool names, cache directory, PATH).
pub fn top_model_with(
    config: &TopConfig,
    options: &BuildOptions,
) -> Result<Arc<TopModel>, CosimError> {
    config.validate()?;
    let key = (config.format, config.depth, config.lanes, options.trace);
    // Only builds with the default tools and cache are shared; others are one-offs.
    let shared = format!("{options:?}")
        == format!(
            "{:?}",
            BuildOptions {
                trace: options.trace,
                ..BuildOptions::default()
            }
        );
    let mut cache = built()
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(m) = cache.get(&key).filter(|_| shared) {
        return Ok(m.clone());
    }
    let start = Instant::now();
    let ports: Vec<Port> = wrapper::ports(config.lanes)
        .iter()
        .map(|p| {
            let dir = match p.direction {
                wrapper::Direction::Input => Direction::Input,
                wrapper::Direction::Output => Direction::Output,
            };
            Port::new(p.name.clone(), dir, p.width as u32)
        })
        .collect();
    let verilog = hdl::top::top_verilog(config)?;
    let spec = ModelSpec {
        verilog,
        top: TOP.to_string(),
        ports: Some(ports),
        clock: Some("ap_clk".into()),
    };
    let model = build(&spec, options)?;
    let top = Arc::new(TopModel {
        config: config.clone(),
        lane_latency: config.lane_latency()?,
        model,
        build_time: start.elapsed(),
    });
    if shared {
        cache.insert(key, top.clone());
    }
    Ok(top)
}

/// The 1-bit and narrow inputs of `rtfpga_top` the drivers set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum In {
    RstN,
    AwValid,
    AwAddr,
    WValid,
    WData,
    WStrb,
    BReady,
    ArValid,
    ArAddr,
    RReady,
    STValid,
    STLast,
    MTReady,
}

/// The 1-bit and narrow outputs of `rtfpga_top` the drivers read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Out {
    AwReady,
    WReady,
    BValid,
    BResp,
    ArReady,
    RValid,
    RData,
    RResp,
    Interrupt,
    STReady,
    MTValid,
    MTLast,
}

const IN_NAMES: [(In, &str); 13] = [
    (In::RstN, "ap_rst_n"),
    (In::AwValid, "s_axi_control_awvalid"),
    (In::AwAddr, "s_axi_control_awaddr"),
    (In::WValid, "s_axi_control_wvalid"),
    (In::WData, "s_axi_control_wdata"),
    (In::WStrb, "s_axi_control_wstrb"),
    (In::BReady, "s_axi_control_bready"),
    (In::ArValid, "s_axi_control_arvalid"),
    (In::ArAddr, "s_axi_control_araddr"),
    (In::RReady, "s_axi_control_rready"),
    (In::STValid, "s_axis_tvalid"),
    (In::STLast, "s_axis_tlast"),
    (In::MTReady, "m_axis_tready"),
];

const OUT_NAMES: [(Out, &str); 12] = [
    (Out::AwReady, "s_axi_control_awready"),
    (Out::WReady, "s_axi_control_wready"),
    (Out::BValid, "s_axi_control_bvalid"),
    (Out::BResp, "s_axi_control_bresp"),
    (Out::ArReady, "s_axi_control_arready"),
    (Out::RValid, "s_axi_control_rvalid"),
    (Out::RData, "s_axi_control_rdata"),
    (Out::RResp, "s_axi_control_rresp"),
    (Out::Interrupt, "interrupt"),
    (Out::STReady, "s_axis_tready"),
    (Out::MTValid, "m_axis_tvalid"),
    (Out::MTLast, "m_axis_tlast"),
];

/// Word offsets of the ports in the packed input and output buffers.
#[derive(Clone, Debug)]
struct Layout {
    inputs: [usize; IN_NAMES.len()],
    outputs: [usize; OUT_NAMES.len()],
    s_tdata: usize,
    m_tdata: usize,
}

impl Layout {
    fn new(iface: &Interface, lanes: usize) -> Result<Self, SimError> {
        let mut inputs = [0; IN_NAMES.len()];
        for (i, (port, name)) in IN_NAMES.iter().enumerate() {
            debug_assert_eq!(*port as usize, i);
            inputs[i] = iface.word_offset(Direction::Input, name, None)?;
        }
        let mut outputs = [0; OUT_NAMES.len()];
        for (i, (port, name)) in OUT_NAMES.iter().enumerate() {
            debug_assert_eq!(*port as usize, i);
            outputs[i] = iface.word_offset(Direction::Output, name, None)?;
        }
        Ok(Layout {
            inputs,
            outputs,
            s_tdata: iface.word_offset(
                Direction::Input,
                "s_axis_tdata",
                Some((IN_LANE_BITS * lanes) as u32),
            )?,
            m_tdata: iface.word_offset(
                Direction::Output,
                "m_axis_tdata",
                Some((OUT_LANE_BITS * lanes) as u32),
            )?,
        })
    }
}

/// Words of one lane's slot in an input beat.
pub const IN_LANE_WORDS: usize = IN_LANE_BITS / 32;
/// Words of one lane's slot in an output beat.
pub const OUT_LANE_WORDS: usize = OUT_LANE_BITS / 32;

/// Cycles of a waveform to record: from cycle `from` (counted since the instance was created)
/// for `cycles` cycles.
#[derive(Clone, Debug)]
pub struct VcdWindow {
    pub path: PathBuf,
    pub from: u64,
    pub cycles: u64,
}

/// One simulated accelerator: the inputs held for the next cycle and the outputs of the last.
pub struct Accel {
    sim: VerilatedModel,
    layout: Layout,
    input: Vec<u32>,
    output: Vec<u32>,
    lanes: usize,
    lane_latency: usize,
    vcd: Option<VcdWindow>,
    vcd_open: bool,
}

impl Accel {
    /// A fresh instance of `top`, reset and with every bus idle.
    pub fn new(top: &TopModel) -> Result<Self, CosimError> {
        let sim = top.model.instantiate();
        let iface = sim.interface().clone();
        let layout = Layout::new(&iface, top.config.lanes)?;
        let mut accel = Accel {
            input: vec![0; iface.in_words()],
            output: vec![0; iface.out_words()],
            sim,
            layout,
            lanes: top.config.lanes,
            lane_latency: top.lane_latency,
            vcd: None,
            vcd_open: false,
        };
        accel.reset()?;
        Ok(accel)
    }

    pub fn lanes(&self) -> usize {
        self.lanes
    }

    pub fn lane_latency(&self) -> usize {
        self.lane_latency
    }

    /// Holds `ap_rst_n` low for a few cycles with every valid low, releases it, and idles
    /// until the stream front end is ready. After reset it refuses beats for a lane latency
    /// (the lanes may still hold queries from before), a cost a board pays once at start-up;
    /// left to the first batch, it was charged once per simulated instance, so a render's
    /// cycles depended on how many threads rayon gave it.
    pub fn reset(&mut self) -> Result<(), CosimError> {
        self.input.fill(0);
        for _ in 0..RESET_CYCLES {
            self.cycle()?;
        }
        self.set(In::RstN, 1);
        let budget = 2 * self.lane_latency as u64 + 2 * RESET_CYCLES + 8;
        let released = self.cycles();
        while self.get(Out::STReady) == 0 {
            if self.cycles() - released > budget {
                return Err(CosimError::Timeout {
                    what: "s_axis_tready after reset".into(),
                    cycles: budget,
                });
            }
            self.cycle()?;
        }
        Ok(())
    }

    /// Records cycles `window.from .. window.from + window.cycles` to a VCD file (the model
    /// must be a trace build).
    pub fn record_vcd(&mut self, window: VcdWindow) -> Result<(), CosimError> {
        if window.from <= self.sim.cycles() {
            self.sim.open_trace(&window.path)?;
            self.vcd_open = true;
        }
        self.vcd = Some(window);
        Ok(())
    }

    /// Sets a narrow input for the following cycles.
    #[inline]
    pub fn set(&mut self, port: In, value: u32) {
        self.input[self.layout.inputs[port as usize]] = value;
    }

    /// A narrow output as sampled in the last cycle (before its rising edge).
    #[inline]
    pub fn get(&self, port: Out) -> u32 {
        self.output[self.layout.outputs[port as usize]]
    }

    /// Lane `lane`'s slot of `s_axis_tdata` (the query's words, then the control word).
    #[inline]
    pub fn in_slot(&mut self, lane: usize) -> &mut [u32] {
        let at = self.layout.s_tdata + lane * IN_LANE_WORDS;
        &mut self.input[at..at + IN_LANE_WORDS]
    }

    /// Lane `lane`'s slot of `m_axis_tdata` as sampled in the last cycle (flags, t, u, v).
    #[inline]
    pub fn out_slot(&self, lane: usize) -> &[u32] {
        let at = self.layout.m_tdata + lane * OUT_LANE_WORDS;
        &self.output[at..at + OUT_LANE_WORDS]
    }

    /// One clock cycle with the held inputs; the outputs are sampled before its rising edge,
    /// so a handshake seen in them happens at this edge.
    #[inline]
    pub fn cycle(&mut self) -> Result<(), CosimError> {
        self.sim.step(&self.input, &mut self.output)?;
        if let Some(w) = &self.vcd {
            let now = self.sim.cycles();
            if !self.vcd_open && now == w.from {
                self.sim.open_trace(&w.path)?;
                self.vcd_open = true;
            } else if self.vcd_open && now >= w.from + w.cycles {
                self.sim.close_trace();
                self.vcd_open = false;
                self.vcd = None;
            }
        }
        Ok(())
    }

    /// Cycles since the instance was created (reset included).
    pub fn cycles(&self) -> u64 {
        self.sim.cycles()
    }

    /// Ends a VCD recording early (also done on drop).
    pub fn close_vcd(&mut self) {
        if self.vcd_open {
            self.sim.close_trace();
            self.vcd_open = false;
        }
        self.vcd = None;
    }
}
