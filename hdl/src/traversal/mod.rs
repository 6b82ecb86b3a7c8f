//! The traversal unit's datapath in rust-hdl, block by block against
//! `hw_model::traversal` (the reference model, bit for bit).

pub mod box_test;
