use hdl::traversal::config::{BuiltUnit, BUILT_MEMORY_BITS, BUILT_WIDE_MEMORY_BITS};

/// `BuiltUnit::ALL` and the memory lists the CLI names are one set of sizes.
#[test]
fn the_built_units_are_the_built_memories() {
    let binary: Vec<(usize, usize)> = (BuiltUnit::ALL.iter())
        .filter(|(_, width, _)| width.is_none())
        .map(|(_, _, bits)| *bits)
        .collect();
    assert_eq!(binary, BUILT_MEMORY_BITS);
    let wide: Vec<(usize, usize, usize)> = (BuiltUnit::ALL.iter())
        .filter_map(|(_, width, (n, t))| width.map(|k| (k, *n, *t)))
        .collect();
    assert_eq!(wide, BUILT_WIDE_MEMORY_BITS);
}
