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
        use rust_hdl::prelude::*;
        use $crate::axil::{AxiLiteSlave, AxiLiteSlavePort};
        #[allow(unused_imports)]
        use $crate::mt::Lane as _;
        use $crate::regmap::OPERAND_COUNT;
        use $crate::top::stream::{StreamFrontEnd, IN_LANE_BITS, OUT_LANE_BITS, QUERY_BITS};

        /// One lane behind a flat query port (rust-hdl cannot index an array port of an
        /// element of a `Vec` of blocks, so the accelerator drives the lanes through these).
        #[derive(LogicBlock)]
        pub struct LaneSlot {
            pub clock: Signal<In, Clock>,
            pub valid_in: Signal<In, Bit>,
            pub query: Signal<In, Bits<QUERY_BITS>>,
            pub valid_out: Signal<Out, Bit>,
            pub hit: Signal<Out, Bit>,
            pub t: Signal<Out, Bits<32>>,
            pub u: Signal<Out, Bits<32>>,
            pub v: Signal<Out, Bits<32>>,
            lane: $lane,
        }

        impl LaneSlot {
            pub fn new(depth: usize) -> Self {
                Self {
                    clock: Default::default(),
                    valid_in: Default::default(),
                    query: Default::default(),
                    valid_out: Default::default(),
                    hit: Default::default(),
                    t: Default::default(),
                    u: Default::default(),
                    v: Default::default(),
                    lane: <$lane>::new(depth),
                }
            }
        }

        impl Logic for LaneSlot {
            #[hdl_gen]
            fn update(&mut self) {
                self.lane.clock.next = self.clock.val();
                self.lane.valid_in.next = self.valid_in.val();
                for k in 0..OPERAND_COUNT {
                    self.lane.query[k].next = self.query.val().get_bits::<32>(k * 32);
                }
                self.valid_out.next = self.lane.valid_out.val();
                self.hit.next = self.lane.hit.val();
                self.t.next = self.lane.t.val();
                self.u.next = self.lane.u.val();
                self.v.next = self.lane.v.val();
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
                self.slave.clock.next = self.clock.val();
                self.slave.reset_n.next = self.reset_n.val();
                self.front.clock.next = self.clock.val();
                self.front.reset_n.next = self.reset_n.val();

                self.slave.axi.awvalid.next = self.axi.awvalid.val();
                self.axi.awready.next = self.slave.axi.awready.val();
                self.slave.axi.awaddr.next = self.axi.awaddr.val();
                self.slave.axi.wvalid.next = self.axi.wvalid.val();
                self.axi.wready.next = self.slave.axi.wready.val();
                self.slave.axi.wdata.next = self.axi.wdata.val();
                self.slave.axi.wstrb.next = self.axi.wstrb.val();
                self.axi.bvalid.next = self.slave.axi.bvalid.val();
                self.slave.axi.bready.next = self.axi.bready.val();
                self.axi.bresp.next = self.slave.axi.bresp.val();
                self.slave.axi.arvalid.next = self.axi.arvalid.val();
                self.axi.arready.next = self.slave.axi.arready.val();
                self.slave.axi.araddr.next = self.axi.araddr.val();
                self.axi.rvalid.next = self.slave.axi.rvalid.val();
                self.slave.axi.rready.next = self.axi.rready.val();
                self.axi.rdata.next = self.slave.axi.rdata.val();
                self.axi.rresp.next = self.slave.axi.rresp.val();
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
                self.slave.hit.next = self.slots[0].hit.val();
                self.slave.t.next = self.slots[0].t.val();
                self.slave.u.next = self.slots[0].u.val();
                self.slave.v.next = self.slots[0].v.val();

                self.front.lane_valid_out.next = self.slots[0].valid_out.val();
                for i in 0..self.slots.len() {
                    self.slots[i].clock.next = self.clock.val();
                    self.slots[i].valid_in.next = self.front.lane_valid_in[i].val();
                    self.slots[i].query.next = self.front.lane_query[i].val();
                    self.front.lane_hit[i].next = self.slots[i].hit.val();
                    self.front.lane_t[i].next = self.slots[i].t.val();
                    self.front.lane_u[i].next = self.slots[i].u.val();
                    self.front.lane_v[i].next = self.slots[i].v.val();
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
