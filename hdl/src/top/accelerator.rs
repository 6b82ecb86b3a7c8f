//! The accelerator's body: `lanes` MT lanes, the AXI4-Lite slave (register mode on lane 0)
//! and the AXI4-Stream front end, written once as a macro over the lane type (rust-hdl needs
//! concrete types) and instantiated for every format of [`crate::formats`].
//!
//! Port names of the body (rust-hdl flattens them with `$`): `clock`, `reset_n`,
//! `axi$<signal>`, `interrupt`, `s_tdata$<lane>`, `s_tvalid`, `s_tready`, `s_tlast`,
//! `m_tdata$<lane>`, `m_tvalid`, `m_tready`, `m_tlast`; [`super::wrapper`] renames them.

/// Defines `LaneSlot` and `Accelerator` over the lane type `$lane`, which has the MT lane's
/// ports (`clock`, `valid_in`, `query: [_; 16]`, `valid_out`, `hit`, `t`, `u`, `v`) and
/// `new(depth)` / `latency(depth)`.
#[macro_export]
macro_rules! accelerator {
    ($lane:ty) => {
        use $crate::axil::{AxiLiteSlave, AxiLiteSlavePort};
        use $crate::macros::prelude::*;
        #[allow(unused_imports)]
        use $crate::mt::Lane as _;
        use $crate::regmap::OPERAND_COUNT;
        use $crate::top::stream::{StreamFrontEnd, IN_LANE_BITS, OUT_LANE_BITS};

        /// One lane behind a packed query port (rust-hdl cannot index an array port of an
        /// element of a `Vec` of blocks, so the accelerator and the traversal unit drive the
        /// lanes through these).
        #[derive(LogicBlock)]
        pub struct LaneSlot {
            pub clock: Signal<In, Clock>,
            pub port: $crate::mt::LaneTarget,
            pub valid_out: Signal<Out, Bit>,
            lane: $lane,
        }

        impl LaneSlot {
            pub fn new(depth: usize) -> Self {
                Self {
                    clock: Default::default(),
                    port: Default::default(),
                    valid_out: Default::default(),
                    lane: <$lane>::new(depth),
                }
            }
        }

        impl Logic for LaneSlot {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, lane);
                self.lane.valid_in.next = self.port.valid.val();
                for k in 0..OPERAND_COUNT {
                    self.lane.query[k].next = self.port.query.val().get_bits::<32>(k * 32);
                }
                self.valid_out.next = self.lane.valid_out.val();
                self.port.hit.next = self.lane.hit.val();
                self.port.t.next = self.lane.t.val();
                self.port.u.next = self.lane.u.val();
                self.port.v.next = self.lane.v.val();
            }
        }

        #[derive(LogicBlock)]
        pub struct Accelerator {
            pub clock: Signal<In, Clock>,
            /// Synchronous, active low (`ap_rst_n`).
            pub reset_n: Signal<In, Bit>,
            pub axi: AxiLiteSlavePort,
            pub interrupt: Signal<Out, Bit>,
            pub s_tdata: Vec<Signal<In, Bits<IN_LANE_BITS>>>,
            pub s_tvalid: Signal<In, Bit>,
            pub s_tready: Signal<Out, Bit>,
            pub s_tlast: Signal<In, Bit>,
            pub m_tdata: Vec<Signal<Out, Bits<OUT_LANE_BITS>>>,
            pub m_tvalid: Signal<Out, Bit>,
            pub m_tready: Signal<In, Bit>,
            pub m_tlast: Signal<Out, Bit>,
            slave: AxiLiteSlave,
            front: StreamFrontEnd,
            slots: Vec<LaneSlot>,
            id: Constant<Bits<32>>,
            configuration: Constant<Bits<32>>,
        }

        impl Accelerator {
            /// `lanes` lanes at pipeline `depth`; `configuration` is what the CONFIG register reads.
            pub fn new(depth: usize, lanes: usize, configuration: u32) -> Self {
                Self {
                    clock: Default::default(),
                    reset_n: Default::default(),
                    axi: Default::default(),
                    interrupt: Default::default(),
                    s_tdata: (0..lanes).map(|_| Default::default()).collect(),
                    s_tvalid: Default::default(),
                    s_tready: Default::default(),
                    s_tlast: Default::default(),
                    m_tdata: (0..lanes).map(|_| Default::default()).collect(),
                    m_tvalid: Default::default(),
                    m_tready: Default::default(),
                    m_tlast: Default::default(),
                    slave: Default::default(),
                    front: StreamFrontEnd::new(lanes, Self::latency(depth)),
                    slots: (0..lanes).map(|_| LaneSlot::new(depth)).collect(),
                    id: Constant::new(($crate::regmap::ID_VALUE as u64).into()),
                    configuration: Constant::new((configuration as u64).into()),
                }
            }

            /// Cycles from a query entering a lane to its result (the lane's latency).
            pub fn latency(depth: usize) -> usize {
                <$lane>::latency(depth)
            }
        }

        impl Logic for Accelerator {
            #[hdl_gen]
            fn update(&mut self) {
                clock!(self, clock, slave, front);
                self.slave.reset_n.next = self.reset_n.val();
                self.front.reset_n.next = self.reset_n.val();
                AxiLiteSlavePort::link(&mut self.axi, &mut self.slave.axi);
                self.interrupt.next = self.slave.interrupt.val();
                self.slave.id.next = self.id.val();
                self.slave.configuration.next = self.configuration.val();

                self.front.s_tvalid.next = self.s_tvalid.val();
                self.s_tready.next = self.front.s_tready.val();
                self.front.s_tlast.next = self.s_tlast.val();
                self.m_tvalid.next = self.front.m_tvalid.val();
                self.front.m_tready.next = self.m_tready.val();
                self.m_tlast.next = self.front.m_tlast.val();
                for i in 0..self.s_tdata.len() {
                    self.front.s_tdata[i].next = self.s_tdata[i].val();
                    self.m_tdata[i].next = self.front.m_tdata[i].val();
                }

                // Register mode runs on lane 0.
                self.front.reg_start.next = self.slave.start.val();
                for k in 0..OPERAND_COUNT {
                    self.front.reg_operands[k].next = self.slave.operands[k].val();
                }
                self.slave.done.next = self.front.reg_done.val();
                self.slave.hit.next = self.slots[0].port.hit.val();
                self.slave.t.next = self.slots[0].port.t.val();
                self.slave.u.next = self.slots[0].port.u.val();
                self.slave.v.next = self.slots[0].port.v.val();

                self.front.lane_valid_out.next = self.slots[0].valid_out.val();
                for i in 0..self.slots.len() {
                    clock!(self, clock, slots[i]);
                    self.slots[i].port.valid.next = self.front.lane_valid_in[i].val();
                    self.slots[i].port.query.next = self.front.lane_query[i].val();
                    self.front.lane_hit[i].next = self.slots[i].port.hit.val();
                    self.front.lane_t[i].next = self.slots[i].port.t.val();
                    self.front.lane_u[i].next = self.slots[i].port.u.val();
                    self.front.lane_v[i].next = self.slots[i].port.v.val();
                }
            }
        }
    };
}

/// `per_format!` over the `hw_model::hw_formats!` list: a module `name` with the accelerator
/// over `formats::name::MtLane` for every format, and [`body_verilog`] dispatching on it.
macro_rules! per_format {
    ($($name:ident: $kind:ident($($arg:tt),*), $description:literal;)*) => {
        $(
            pub mod $name {
                $crate::accelerator!($crate::formats::$name::MtLane);
            }
        )*

        /// Verilog generators of the bodies, in catalogue order.
        static BODIES: &[fn(usize, usize, u32) -> String] = &[$(|depth, lanes, configuration| {
            use rust_hdl::prelude::{generate_verilog, Block};
            let mut top = $name::Accelerator::new(depth, lanes, configuration);
            top.connect_all();
            generate_verilog(&top)
        }),*];
    };
}

hw_model::hw_formats!(per_format);

/// Verilog of the accelerator body (top module `top`) in `format`. The caller validates the
/// configuration.
pub fn body_verilog(
    format: hw_model::HwFormat,
    depth: usize,
    lanes: usize,
    configuration: u32,
) -> String {
    BODIES[usize::from(format.code())](depth, lanes, configuration)
}
