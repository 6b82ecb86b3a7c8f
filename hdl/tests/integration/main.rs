//! hdl's integration tests, one binary: the tests of the blocks and helpers (`blocks`, one
//! module per source file) and of the assembled designs (one module each). One binary
//! because a release build monomorphises rust-hdl's generic blocks again in every test
//! binary and links the whole crate into each: the twenty binaries this replaces took 185 s
//! of rustc time on an idle machine, this one about 100 s. A module's tests run alone with
//! `cargo test -p hdl --release --test integration <module>::`.

mod axil_slave;
mod blocks;
mod box_test;
#[macro_use]
mod common;
mod fixed_ops;
mod float_ops;
mod float_sqrt;
mod frame_accumulate;
mod frame_contribution;
mod frame_engine;
mod frame_escape;
mod frame_normalise;
mod frame_pixel_slots;
mod frame_queues;
mod frame_ray_ids;
mod frame_ray_store;
mod frame_raygen;
mod frame_records;
mod frame_shader;
mod frame_thread_start;
mod fusesoc_core;
mod mt_lane;
mod ray_setup;
mod regmap_cgen;
mod scene_memory;
mod synth_report;
mod timing;
mod top_generated;
mod top_system;
mod top_verilog;
mod traversal_parts;
mod traversal_unit;
mod traversal_unit_axil;
mod wide_box_stage;
mod wide_scene_memory;
mod wide_traversal_unit;
