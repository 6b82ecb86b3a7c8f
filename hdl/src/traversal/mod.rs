//! The traversal unit in rust-hdl: its parts, each checked against `hw_model::traversal`.

pub mod arbiter;
