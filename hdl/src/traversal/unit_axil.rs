//! The traversal unit under AXI4-Lite control: the unit's top (`unit_top`, unchanged)
//! beside a register slave of the unit's map (`regmap::unit`, docs/traversal-unit.md
//! "Control registers") on the shared bus logic (`axil::bus`). Rays, answers and the scene
//! image stay on the unit's AXI4-Stream ports; the scene-start pulse, the reset and the
//! status and counter ports become registers.

use hw_model::traversal::schedule::UnitTiming;
use rust_hdl::prelude::*;

use super::config::{UnitConfig, UnitConfigError};
use super::ports::{ControlMaster, CounterReader};
use super::scene_memory::ERROR_CODE_BITS;
use crate::axil::bus::{mask, word, AxiLiteBus, WORD_BITS};
use crate::axil::AxiLiteSlavePort;
use crate::regmap::unit::{self as map, MemoryWord, COUNTERS};
use crate::regmap::ConfigWord;
use crate::top::with_build_stack;
use crate::top::wrapper::TopPort;

/// Number of counters (`regmap::unit::COUNTERS`).
const COUNTER_COUNT: usize = COUNTERS.len();
/// Bits of the reset counter, holding [`map::RESET_CYCLES`].
const RESET_COUNT_BITS: usize = 8;
const _: () = assert!(map::RESET_CYCLES < 1 << RESET_COUNT_BITS);

/// What the CONFIG register reads: the lane's format, its effective depth (a depth beyond
/// the format's maximum builds the same lane) and the lanes.
pub fn config_word(config: &UnitConfig) -> ConfigWord {
    let depth = config.depth.min(crate::mt::max_depth(config.format));
    ConfigWord {
        format_code: config.format.code(),
        depth: depth as u8,
        lanes: config.lanes as u8,
    }
}

/// What the MEMORY register reads (of a checked configuration: every size fits a byte).
pub fn memory_word(config: &UnitConfig) -> MemoryWord {
    MemoryWord {
        node_bits: config.memory.node_bits as u8,
        triangle_bits: config.memory.triangle_bits as u8,
        stack_depth: config.stack_depth as u8,
        slots: config.slots as u8,
    }
}

/// The longest step a reset must outlast (docs/traversal-unit.md "Ports": a step in flight
/// finishes into its slot): a ray's setup, a box test, a leaf's last answer (the lane and
/// the far end) or a pop.
pub fn longest_step(timing: &UnitTiming) -> u64 {
    [
        timing.setup_latency,
        timing.box_latency,
        timing.mt_latency,
        timing.pop_latency,
    ]
    .into_iter()
    .max()
    .unwrap_or(0)
}

/// The unit's register slave: decodes `regmap::unit` on the shared bus logic, turns
/// LOAD_START into the unit's `scene_start` pulse and RESET into [`map::RESET_CYCLES`]
/// cycles of `unit_reset_n` low, counts the scene stream's words and reads the unit's
/// status and counter ports.
#[derive(LogicBlock)]
pub struct UnitControl {
    pub clock: Signal<In, Clock>,
    /// The bus reset (`ap_rst_n`), synchronous, active low; it resets the unit too.
    pub reset_n: Signal<In, Bit>,
    pub axi: AxiLiteSlavePort,
    // Unit side.
    pub unit: ControlMaster,
    pub counters: CounterReader,
    pub unit_reset_n: Signal<Out, Bit>,
    /// A scene word is taken this cycle (the scene stream's `tvalid & tready`).
    pub scene_take: Signal<In, Bit>,
    bus: AxiLiteBus,
    /// The counters in [`COUNTERS`] order.
    counter_value: [Signal<Local, Bits<32>>; COUNTER_COUNT],
    start_q: DFF<Bit>,
    reset_count: DFF<Bits<RESET_COUNT_BITS>>,
    scene_words: DFF<Bits<32>>,
    resetting: Signal<Local, Bit>,
    r_mapped: Signal<Local, Bit>,
    r_mux: Signal<Local, Bits<32>>,
    w_writable: Signal<Local, Bit>,
    word_control: Constant<Bits<WORD_BITS>>,
    word_status: Constant<Bits<WORD_BITS>>,
    word_id: Constant<Bits<WORD_BITS>>,
    word_config: Constant<Bits<WORD_BITS>>,
    word_memory: Constant<Bits<WORD_BITS>>,
    word_scene_words: Constant<Bits<WORD_BITS>>,
    word_error_word: Constant<Bits<WORD_BITS>>,
    word_error_value: Constant<Bits<WORD_BITS>>,
    word_overflow_ray: Constant<Bits<WORD_BITS>>,
    word_counter: [Constant<Bits<WORD_BITS>>; COUNTER_COUNT],
    id_value: Constant<Bits<32>>,
    config_value: Constant<Bits<32>>,
    memory_value: Constant<Bits<32>>,
    mask_idle: Constant<Bits<32>>,
    mask_loaded: Constant<Bits<32>>,
    mask_error: Constant<Bits<32>>,
    mask_overflow: Constant<Bits<32>>,
    mask_resetting: Constant<Bits<32>>,
    error_code_lsb: Constant<Bits<32>>,
    reset_cycles: Constant<Bits<RESET_COUNT_BITS>>,
}

impl UnitControl {
    /// The slave of a unit built from `config` (its ID, CONFIG and MEMORY words).
    pub fn new(config: &UnitConfig) -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            axi: Default::default(),
            unit: Default::default(),
            counters: Default::default(),
            unit_reset_n: Default::default(),
            scene_take: Default::default(),
            bus: Default::default(),
            counter_value: Default::default(),
            start_q: Default::default(),
            reset_count: Default::default(),
            scene_words: Default::default(),
            resetting: Default::default(),
            r_mapped: Default::default(),
            r_mux: Default::default(),
            w_writable: Default::default(),
            word_control: word(map::CONTROL),
            word_status: word(map::STATUS),
            word_id: word(map::ID),
            word_config: word(map::CONFIG),
            word_memory: word(map::MEMORY),
            word_scene_words: word(map::SCENE_WORDS),
            word_error_word: word(map::SCENE_ERROR_WORD),
            word_error_value: word(map::SCENE_ERROR_VALUE),
            word_overflow_ray: word(map::OVERFLOW_RAY),
            word_counter: COUNTERS.map(word),
            id_value: mask(map::ID_VALUE),
            config_value: mask(config_word(config).pack()),
            memory_value: mask(memory_word(config).pack()),
            mask_idle: mask(map::IDLE),
            mask_loaded: mask(map::SCENE_LOADED),
            mask_error: mask(map::SCENE_ERROR),
            mask_overflow: mask(map::OVERFLOW),
            mask_resetting: mask(map::RESETTING),
            error_code_lsb: mask(map::ERROR_CODE_LSB),
            reset_cycles: Constant::new(u64::from(map::RESET_CYCLES).into()),
        }
    }
}

impl Logic for UnitControl {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, start_q, reset_count, scene_words);
        clock!(self, clock, bus);
        self.bus.reset_n.next = self.reset_n.val();
        AxiLiteSlavePort::link(&mut self.axi, &mut self.bus.axi);
        self.resetting.next = self.reset_count.q.val().any();
        self.unit_reset_n.next = self.reset_n.val() & !self.resetting.val();
        self.unit.scene_start.next = self.start_q.q.val();
        self.counter_value[0].next = self.counters.rays.val();
        self.counter_value[1].next = self.counters.node_visits.val();
        self.counter_value[2].next = self.counters.box_tests.val();
        self.counter_value[3].next = self.counters.mt_tests.val();
        self.counter_value[4].next = self.counters.busy_cycles.val();

        // Read: the bus answers `r_mux` the next cycle; CONTROL's pulse bits read 0.
        self.r_mapped.next = false;
        self.r_mux.next = 0.into();
        if self.bus.read_word.val() == self.word_control.val() {
            self.r_mapped.next = true;
        }
        if self.bus.read_word.val() == self.word_status.val() {
            self.r_mapped.next = true;
            self.r_mux.next = bit_cast::<32, ERROR_CODE_BITS>(self.unit.scene_error_code.val())
                << self.error_code_lsb.val();
            if self.unit.idle.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_idle.val();
            }
            if self.unit.scene_loaded.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_loaded.val();
            }
            if self.unit.scene_error.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_error.val();
            }
            if self.unit.overflow.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_overflow.val();
            }
            if self.resetting.val() {
                self.r_mux.next = self.r_mux.val() | self.mask_resetting.val();
            }
        }
        if self.bus.read_word.val() == self.word_id.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.id_value.val();
        }
        if self.bus.read_word.val() == self.word_config.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.config_value.val();
        }
        if self.bus.read_word.val() == self.word_memory.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.memory_value.val();
        }
        if self.bus.read_word.val() == self.word_scene_words.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.scene_words.q.val();
        }
        if self.bus.read_word.val() == self.word_error_word.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.unit.scene_error_word.val();
        }
        if self.bus.read_word.val() == self.word_error_value.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.unit.scene_error_value.val();
        }
        if self.bus.read_word.val() == self.word_overflow_ray.val() {
            self.r_mapped.next = true;
            self.r_mux.next = self.unit.overflow_ray.val();
        }
        for i in 0..COUNTER_COUNT {
            if self.bus.read_word.val() == self.word_counter[i].val() {
                self.r_mapped.next = true;
                self.r_mux.next = self.counter_value[i].val();
            }
        }
        self.bus.read_data.next = self.r_mux.val();
        self.bus.read_ok.next = self.r_mapped.val();

        // Write: CONTROL is the one writable register (byte lane 0); every other mapped
        // register is read-only, so the bus answers SLVERR for it as for an unmapped one.
        self.w_writable.next = self.bus.write_word.val() == self.word_control.val();
        self.bus.write_ok.next = self.w_writable.val();
        self.start_q.d.next = false;
        if self.resetting.val() {
            self.reset_count.d.next = self.reset_count.q.val() - 1;
        }
        // A RESET written during a reset starts it over.
        if self.bus.write.val() & self.w_writable.val() & self.bus.write_byte0.val() {
            if self.bus.write_data.val().get_bit(0) {
                self.start_q.d.next = true;
            }
            if self.bus.write_data.val().get_bit(1) {
                self.reset_count.d.next = self.reset_cycles.val();
            }
        }

        // Scene words since the last load start.
        if self.start_q.q.val() {
            self.scene_words.d.next = 0.into();
        } else if self.scene_take.val() {
            self.scene_words.d.next = self.scene_words.q.val() + 1;
        }

        if !self.reset_n.val() {
            self.start_q.d.next = false;
            self.reset_count.d.next = 0.into();
            self.scene_words.d.next = 0.into();
        }
    }
}

/// Defines the AXI4-Lite top `$name` around the unit top `$unit` (a wide unit's with its node
/// width first).
macro_rules! axil_top {
    ($name:ident, $unit:ty $(, $width:literal)?) => {
        /// The unit under AXI4-Lite control: `axi` (the unit's register map), the scene,
        /// ray and hit streams of docs/traversal-unit.md.
        #[derive(LogicBlock)]
        pub struct $name {
            pub clock: Signal<In, Clock>,
            /// Synchronous, active low (`ap_rst_n`).
            pub reset_n: Signal<In, Bit>,
            pub axi: AxiLiteSlavePort,
            pub scene: SceneStream,
            pub ray: RayStream,
            pub hit: HitStream,
            control: UnitControl,
            unit: $unit,
        }

        impl $name {
            /// The unit of `config` (its format, depth and stack; the memory size is the
            /// type's).
            pub fn new(config: &UnitConfig) -> Self {
                Self {
                    clock: Default::default(),
                    reset_n: Default::default(),
                    axi: Default::default(),
                    scene: Default::default(),
                    ray: Default::default(),
                    hit: Default::default(),
                    control: UnitControl::new(config),
                    unit: <$unit>::new(
                        $($width,)?
                        config.depth,
                        config.stack_depth,
                        config.lanes,
                        config.advance,
                    ),
                }
            }
        }

        impl Logic for $name {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, control, unit);
                self.control.reset_n.next = self.reset_n.val();
                AxiLiteSlavePort::link(&mut self.axi, &mut self.control.axi);
                self.unit.reset_n.next = self.control.unit_reset_n.val();
                SceneStream::link(&mut self.scene, &mut self.unit.scene);
                self.control.scene_take.next = self.scene.tvalid.val() & self.scene.tready.val();
                RayStream::link(&mut self.ray, &mut self.unit.ray);
                HitStream::link(&mut self.hit, &mut self.unit.hit);
                ControlPort::join(&mut self.unit.control, &mut self.control.unit);
                CounterPort::join(&mut self.unit.counters, &mut self.control.counters);
            }
        }
    };
}

/// `per_format!` over the `hw_model::hw_formats!` list: a module `name` with the AXI4-Lite
/// top at each scene memory size of `unit_top::name`, and [`verilog`] dispatching on it.
macro_rules! per_format {
    ($($name:ident: $kind:ident($($arg:tt),*), $description:literal;)*) => {
        $(
            pub mod $name {
                use rust_hdl::prelude::*;
                use super::{AxilTop, UnitControl};
                use $crate::generate::block_ports;
                use $crate::axil::AxiLiteSlavePort;
                use $crate::traversal::config::{BuiltUnit, UnitConfig};
                use $crate::traversal::ports::{
                    ControlPort, CounterPort, HitStream, RayStream, SceneStream,
                };
                use $crate::traversal::unit_top::$name as tops;

                axil_top!(Axil4x5, tops::Unit4x5);
                axil_top!(Axil9x10, tops::Unit9x10);
                axil_top!(Axil11x12, tops::Unit11x12);
                axil_top!(Axil12x13, tops::Unit12x13);
                axil_top!(AxilWide4w4x5, tops::WideUnit4w4x5, 4);
                axil_top!(AxilWide8w4x5, tops::WideUnit8w4x5, 8);
                axil_top!(AxilWide8w11x13, tops::WideUnit8w11x13, 8);

                /// The top of a checked configuration around its unit
                /// (`UnitConfig::built`, as `unit_top::verilog` builds it): its ports and,
                /// with `verilog`, its Verilog.
                pub fn build(config: &UnitConfig, verilog: bool) -> AxilTop {
                    fn of<U: Block>(unit: U, verilog: bool) -> AxilTop {
                        let mut unit = Box::new(unit);
                        unit.connect_all();
                        AxilTop {
                            ports: block_ports(unit.as_ref()),
                            verilog: verilog.then(|| generate_verilog(unit.as_ref())),
                        }
                    }
                    let c = config;
                    match config.built().expect("a checked configuration") {
                        BuiltUnit::Binary4x5 => of(Axil4x5::new(c), verilog),
                        BuiltUnit::Binary9x10 => of(Axil9x10::new(c), verilog),
                        BuiltUnit::Binary11x12 => of(Axil11x12::new(c), verilog),
                        BuiltUnit::Binary12x13 => of(Axil12x13::new(c), verilog),
                        BuiltUnit::Wide4w4x5 => of(AxilWide4w4x5::new(c), verilog),
                        BuiltUnit::Wide8w4x5 => of(AxilWide8w4x5::new(c), verilog),
                        BuiltUnit::Wide8w11x13 => of(AxilWide8w11x13::new(c), verilog),
                    }
                }
            }
        )*

        /// The AXI4-Lite tops' builders, in catalogue order.
        static UNITS: &[fn(&UnitConfig, bool) -> AxilTop] = &[$($name::build),*];
    };
}

hw_model::hw_formats!(per_format);

/// A built AXI4-Lite top of the unit (top module `top`, rust-hdl's port names: `axi$…`,
/// `scene_…`, `ray_…`, `hit_…`).
pub struct AxilTop {
    pub ports: Vec<TopPort>,
    /// Its Verilog, if asked for.
    pub verilog: Option<String>,
}

/// The unit of `config` under AXI4-Lite control: its ports and, with `verilog`, its Verilog
/// (`UnitConfig::check` first).
pub fn unit_axil(config: &UnitConfig, verilog: bool) -> Result<AxilTop, UnitConfigError> {
    config.check()?;
    let config = *config;
    Ok(with_build_stack(move || {
        UNITS[usize::from(config.format.code())](&config, verilog)
    }))
}
