//! The traversal unit's bit-accurate model: the scene on chip, rays in, hits out.

pub mod box_test;
