//! The tests of hdl's blocks and helpers, one module per source file (the same path under
//! `tests/integration/blocks/`). They live in the integration binary rather than in
//! `#[cfg(test)]` modules because a unit-test harness compiles the whole macro-heavy crate a
//! second time (about 9 CPU-minutes of the cold CI build); hdl's lib sets `test = false`.

mod dual {
    mod common;
    mod cross_block;
    mod decide;
    mod dot;
    mod filter;
    mod margin;
    mod pair;
    mod plucker;
    mod plucker_filter;
    mod round;
    mod sign_decide;
    mod to_block;
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
    mod banked_stack;
    mod box_test;
    mod config;
    mod far_end;
    mod hit_update;
    mod leaf_advance;
    mod ray_setup;
    mod scene_memory_driver;
    mod slot_banks;
    mod stack;
    mod timing;
    mod unit_axil;
}

/// hdl's lib is built with `test = false`, so a `#[cfg(test)]` module under src/ would
/// compile in no build and run in none: this names any, so that its tests move here.
#[test]
fn no_unit_tests_hide_in_the_lib() {
    fn sources(dir: &std::path::Path, found: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                sources(&path, found);
            } else if path.extension().is_some_and(|e| e == "rs") {
                found.push(path);
            }
        }
    }
    let mut files = Vec::new();
    sources(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut files,
    );
    assert!(files.len() > 20, "{} sources found", files.len());
    let hidden: Vec<_> = files
        .iter()
        .filter(|f| std::fs::read_to_string(f).unwrap().contains("#[cfg(test)]"))
        .collect();
    assert!(
        hidden.is_empty(),
        "unit tests in {hidden:?} never run: move them to hdl/tests/integration/blocks/"
    );
}
