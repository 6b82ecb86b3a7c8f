//! The traversal unit in rust-hdl, block by block, each checked bit for bit against
//! `hw_model::traversal` (the reference model).

pub mod arbiter;
pub mod box_test;
pub mod far_end;
pub mod hit_update;
pub mod leaf_advance;
pub mod ray_setup;
pub mod scene_memory;
pub mod scene_memory_driver;
pub mod stack;
pub mod timing;
pub mod unit;
pub mod unit_axil;
pub mod unit_top;
pub mod wide;
