//! The tests of hdl's blocks and helpers, one module per source file (the same path under
//! `tests/blocks/`). They live in this one integration binary rather than in `#[cfg(test)]`
//! modules because a unit-test harness compiles the whole macro-heavy crate a second time
//! (about 9 CPU-minutes of the cold CI build); hdl's lib sets `test = false`.

mod dual {
    mod translate;
}
mod float {
    mod leading_zeros;
}
mod formats;
mod intmul;
mod mt {
    mod delay;
    mod schedule;
}
mod pipe;
mod regmap;
mod synth;
mod top;
mod traversal {
    mod arbiter;
    mod box_test;
    mod far_end;
    mod hit_update;
    mod ray_setup;
    mod scene_memory_driver;
    mod stack;
    mod timing;
    mod unit_axil;
}
