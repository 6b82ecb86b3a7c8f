//! sim's integration tests, one binary (one module per former test file): a release build
//! monomorphises the hdl designs and rust-hdl's generic blocks again in every test binary and
//! links the whole crate into each, and one process shares the Verilated models that
//! `sim::accel_model` keeps between its tests. A module's tests run alone with `cargo test -p
//! sim --release --test integration <module>::`.

mod box_test_verilator;
mod cosim_bus;
mod cosim_equivalence;
mod cosim_scenes;
mod dual_pair_verilator;
mod frame_engine_verilator;
mod fuzz_regressions;
mod mt_lane_verilator;
mod operators_verilator;
mod projection;
mod ray_setup_verilator;
mod scene_memory_verilator;
mod sweep;
mod traversal_unit_verilator;
mod verilator_builder;
mod wide_box_stage_verilator;
mod wide_traversal_unit_verilator;
