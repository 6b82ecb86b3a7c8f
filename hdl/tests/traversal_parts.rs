//! The traversal unit's control parts (slot scheduler, slot stacks, hit update) as Verilog:
//! generated and through Verilator's lint. Their behaviour is tested in rust-hdl's simulator
//! beside them (`hdl/src/traversal/{arbiter,stack,hit_update}.rs`).

use hdl::traversal::arbiter::RoundRobin;
use hdl::traversal::hit_update::HitUpdate;
use hdl::traversal::stack::SlotStacks;
use hdl::verilog::verilator_lint;
use rust_hdl::prelude::*;

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

/// yosys xc7 resources and register-to-register logic depth of the control parts at the
/// default 32 slots:
/// `cargo test --release -p hdl --test traversal_parts -- --ignored --nocapture control_parts_resources`
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
