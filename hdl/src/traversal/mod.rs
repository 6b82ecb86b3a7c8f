//! The traversal unit in rust-hdl, block by block, each checked bit for bit against
//! `hw_model::traversal` (the reference model).
//!
//! The unit (`unit::TraversalCore`, `unit_top`, `unit_axil`) is built from: the scene
//! memory, the ray entry (with the ray setup), the slots (state, schedulers, next-state
//! logic), the box port (with the box test), the stack port (with the slot stacks), a leaf
//! port per lane (with the hit update and the far end), the hit output and the counters,
//! wired by the bundles of `ports` (outside) and `slot_ports` (inside).

pub mod arbiter;
pub mod banked_stack;
pub mod box_port;
pub mod box_test;
pub mod config;
pub mod counters;
pub mod far_end;
pub mod hit_output;
pub mod hit_update;
pub mod leaf_advance;
pub mod leaf_port;
pub mod live_table;
pub mod lut_ram;
pub mod ports;
pub mod ray_entry;
pub mod ray_setup;
pub mod scene_memory;
pub mod scene_memory_driver;
pub mod scene_records;
pub mod slot_banks;
pub mod slot_ports;
pub mod slots;
pub mod stack;
pub mod stack_port;
pub mod timing;
pub mod unit;
pub mod unit_axil;
pub mod unit_top;
pub mod wide;
pub mod wide_box_port;
pub mod wide_scene_memory;
pub mod wide_set_up;
pub mod wide_stack_port;
pub mod wide_unit;
