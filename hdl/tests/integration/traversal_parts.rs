//! The traversal unit's control parts (slot scheduler, slot stacks, hit update) as Verilog:
//! generated and through Verilator's lint. Their behaviour is tested in rust-hdl's simulator
//! beside them (`hdl/src/traversal/{arbiter,stack,hit_update}.rs`).

use hdl::traversal::arbiter::RoundRobin;
use hdl::traversal::banked_stack::BankedStacks;
use hdl::traversal::config::{
    stack_entry_bits, SLOT_BITS, STACK_ADDRESS_BITS, STACK_POINTER_BITS, UNIT_SLOTS,
};
use hdl::traversal::hit_update::HitUpdate;
use hdl::traversal::leaf_port::LeafPort;
use hdl::traversal::scene_records::{link_count_bits, link_first_bits};
use hdl::traversal::slot_ports::{
    BoxGrantSource, Entered, LeafGrantSource, LeafStepSink, LinkStep, LinkStepSink, OutGrantSource,
    PopGrantSource, PushSink, SetUp,
};
use hdl::traversal::slots::SlotState;
use hdl::traversal::stack::SlotStacks;
use hdl::traversal::stack_port::StackPort;
use hdl::verilog::verilator_lint;
use hw_model::HwFormat;
use rust_hdl::prelude::*;
use sim::verilator::Direction;

#[test]
fn control_parts_pass_verilator_lint() {
    let mut arbiter = RoundRobin::<32>::default();
    arbiter.connect_all();
    let v = generate_verilog(&arbiter);
    assert!(v.contains("grant") && v.contains("request"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("round robin: {e}"));

    // 32 slots of 32 entries (a link and an entry distance: 64 bits).
    let mut stacks = SlotStacks::<32, 5, 6, 10, 64>::new(32);
    stacks.connect_all();
    let v = generate_verilog(&stacks);
    assert!(v.contains("overflow_slot") && v.contains("pop_data"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("slot stacks: {e}"));

    let mut update = HitUpdate::default();
    update.connect_all();
    let v = generate_verilog(&update);
    assert!(v.contains("closer") && v.contains("best_triangle"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("hit update: {e}"));
}

/// The wide unit's stacks: 64 slots of 32 entries over 8 banks (a link of 13 + 4 bits, t0 and
/// a width exponent: 59 bits).
#[test]
fn banked_stacks_pass_verilator_lint() {
    let mut stacks = BankedStacks::<64, 6, 6, 8, 59>::new(8, 32);
    stacks.connect_all();
    let v = generate_verilog(&stacks);
    assert!(v.contains("push_count") && v.contains("pop_data"));
    verilator_lint(&v).unwrap_or_else(|e| panic!("banked stacks: {e}"));
}

/// yosys xc7 resources and register-to-register logic depth of the control parts at the
/// default 32 slots:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture traversal_parts::control_parts_resources`
#[test]
#[ignore]
fn control_parts_resources() {
    fn verilog<B: Block>(mut block: B) -> String {
        block.connect_all();
        generate_verilog(&block)
    }
    let parts = [
        (
            "round robin, 32 slots".to_string(),
            verilog(RoundRobin::<32>::default()),
        ),
        (
            "slot stacks, 32 × 32 entries of 64 bits".to_string(),
            verilog(SlotStacks::<32, 5, 6, 10, 64>::new(32)),
        ),
        ("hit update".to_string(), verilog(HitUpdate::default())),
    ];
    println!("{}", hdl::synth::markdown_table(&parts).unwrap());
}

/// The ray slots and the stack port wired as in the unit (the pop scheduler's grant into the
/// stack port, its steps back), every other port of theirs a port of this block.
#[derive(LogicBlock)]
struct PopPath {
    pub clock: Signal<In, Clock>,
    pub reset_n: Signal<In, Bit>,
    pub has_triangles: Signal<In, Bit>,
    pub free: Signal<Out, Bit>,
    pub enter_slot: Signal<Out, Bits<SB>>,
    pub occupied: Signal<Out, Bit>,
    pub entered: Entered<SB>,
    pub set_up: SetUp<SB>,
    pub box_grant: BoxGrantSource<SB, LF>,
    pub box_step: LinkStepSink<SB, LF, LC>,
    pub leaf_grant: LeafGrantSource<SB, LF>,
    pub leaf_step: LeafStepSink<SB>,
    pub out_grant: OutGrantSource<SB>,
    pub push: PushSink<SB, W>,
    pub overflow: Signal<Out, Bit>,
    pub overflow_ray: Signal<Out, Bits<32>>,
    slots: SlotState<UNIT_SLOTS, SB, LF, LC>,
    stack_port: StackPort<UNIT_SLOTS, SB, STACK_POINTER_BITS, STACK_ADDRESS_BITS, W, LF, LC>,
}

const SB: usize = SLOT_BITS;
/// The default unit's scene memory: node and triangle address bits.
const NB: usize = 12;
const TB: usize = 13;
const LF: usize = link_first_bits(NB, TB);
const LC: usize = link_count_bits(TB);
const W: usize = stack_entry_bits(NB, TB);

impl Default for PopPath {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset_n: Default::default(),
            has_triangles: Default::default(),
            free: Default::default(),
            enter_slot: Default::default(),
            occupied: Default::default(),
            entered: Default::default(),
            set_up: Default::default(),
            box_grant: Default::default(),
            box_step: Default::default(),
            leaf_grant: Default::default(),
            leaf_step: Default::default(),
            out_grant: Default::default(),
            push: Default::default(),
            overflow: Default::default(),
            overflow_ray: Default::default(),
            slots: SlotState::new(1, false),
            stack_port: StackPort::new(hw_model::traversal::DEFAULT_STACK_DEPTH),
        }
    }
}

impl Logic for PopPath {
    #[hdl_gen]
    fn update(&mut self) {
        self.slots.clock.next = self.clock.val();
        self.stack_port.clock.next = self.clock.val();
        self.slots.reset_n.next = self.reset_n.val();
        self.stack_port.reset_n.next = self.reset_n.val();
        self.slots.has_triangles.next = self.has_triangles.val();
        self.free.next = self.slots.free.val();
        self.enter_slot.next = self.slots.enter_slot.val();
        self.occupied.next = self.slots.occupied.val();
        Entered::<SB>::link(&mut self.entered, &mut self.slots.entered);
        Entered::<SB>::link(&mut self.entered, &mut self.stack_port.entered);
        SetUp::<SB>::link(&mut self.set_up, &mut self.slots.set_up);
        BoxGrantSource::<SB, LF>::link(&mut self.box_grant, &mut self.slots.box_grant);
        LinkStepSink::<SB, LF, LC>::link(&mut self.box_step, &mut self.slots.box_step);
        LeafGrantSource::<SB, LF>::link(&mut self.leaf_grant, &mut self.slots.leaf_grant[0]);
        LeafStepSink::<SB>::link(&mut self.leaf_step, &mut self.slots.leaf_step[0]);
        OutGrantSource::<SB>::link(&mut self.out_grant, &mut self.slots.out_grant);
        PushSink::<SB, W>::link(&mut self.push, &mut self.stack_port.push);
        PopGrantSource::<SB>::join(&mut self.slots.pop_grant, &mut self.stack_port.grant);
        LinkStep::<SB, LF, LC>::join(&mut self.stack_port.step, &mut self.slots.pop_step);
        self.overflow.next = self.stack_port.overflow.val();
        self.overflow_ray.next = self.stack_port.overflow_ray.val();
    }
}

/// `verilog` with its top module `top` between registers: every input port (but `clock`)
/// through a flip-flop into the block, every output port out of one, so that the timing
/// estimate, which leaves module ports unconstrained, times the block's paths to and from its
/// neighbours as if they were registers.
fn between_registers(verilog: &str) -> String {
    let ports = sim::verilator::parse_ports(verilog, "top").expect("a top module");
    let (mut decls, mut regs, mut body_ports) = (vec![], vec![], vec![]);
    for port in &ports {
        let name = &port.name;
        if name == "clock" {
            decls.push("    input wire clock;".to_string());
            body_ports.push(".clock(clock)".to_string());
            continue;
        }
        let range = match port.width {
            1 => String::new(),
            w => format!("[{}:0]", w - 1),
        };
        let r = format!("r_{}", name.replace('$', "_"));
        match port.direction {
            Direction::Input => {
                decls.push(format!(
                    "    input wire {range} {name};\n    reg {range} {r};"
                ));
                regs.push(format!("        {r} <= {name};"));
            }
            Direction::Output => {
                decls.push(format!(
                    "    output reg {range} {name};\n    wire {range} {r};"
                ));
                regs.push(format!("        {name} <= {r};"));
            }
        }
        body_ports.push(format!(".{name}({r})"));
    }
    let names: Vec<&str> = ports.iter().map(|p| p.name.as_str()).collect();
    format!(
        "{}\nmodule top({});\n{}\n    always @(posedge clock) begin\n{}\n    end\n    top_body body({});\nendmodule\n",
        verilog.replacen("module top(", "module top_body(", 1),
        names.join(","),
        decls.join("\n"),
        regs.join("\n"),
        body_ports.join(", ")
    )
}

/// The Fmax estimate of the slots and the stack port between registers (the pop path: the
/// stack-pop scheduler's grant, the stack read, the popped entry's step back into the
/// slots), with its critical path:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture traversal_parts::pop_path_timing`
#[test]
#[ignore]
fn pop_path_timing() {
    let mut path = PopPath::default();
    path.connect_all();
    print_timing(&generate_verilog(&path));
}

/// The same for a leaf port of the default unit (fp32 lane at depth 5): the lane's answer
/// judged against the slot's nearest hit, next_up of the new bound, the far end:
/// `cargo test --release -p hdl --test integration -- --ignored --nocapture traversal_parts::leaf_port_timing`
#[test]
#[ignore]
fn leaf_port_timing() {
    let depth = 5;
    let lane_latency = hdl::mt::latency(HwFormat::named("fp32"), depth);
    let mut port = LeafPort::<SB, TB, LF>::new(depth, lane_latency);
    port.connect_all();
    print_timing(&generate_verilog(&port));
}

/// yosys' timing estimate of `verilog`'s top with every port registered.
fn print_timing(verilog: &str) {
    let verilog = between_registers(verilog);
    let report =
        hdl::synth::synthesize(&verilog, "top", &hdl::synth::SynthOptions::default()).unwrap();
    let critical = report.critical_path.as_ref().unwrap();
    println!(
        "fmax_mhz_estimate={:.0} delay_ns={:.2} cell_ns={:.2} routing_ns={:.2} levels={} lut={} ff={}\nfrom {} to {}\n{}",
        critical.fmax_mhz(),
        critical.delay_ps as f64 / 1000.0,
        critical.cell_ps as f64 / 1000.0,
        critical.routing_ps as f64 / 1000.0,
        critical.levels,
        report.lut,
        report.ff,
        critical.start,
        critical.end,
        critical.steps_markdown()
    );
}
