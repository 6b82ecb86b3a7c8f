//! Inputs found by the fuzz target `sweep_config` of `fuzz/` (`make fuzz`) that broke the sweep
//! config's contract: `Ok`, or an error naming the file, the line, the key and what was
//! expected; never a panic. Each test fails without its fix.

use std::path::Path;

use sim::sweep;

/// A carriage return not followed by a line feed gave a syntax error with an empty message
/// (the toml crate has none for it).
#[test]
fn stray_carriage_return_is_named() {
    let path = Path::new("dir/stray_cr.toml");
    for (text, line) in [
        ("\r", 1),
        ("\rformats = [\"fp32\"]", 1),
        ("width = 1\n\r", 2),
    ] {
        let err = sweep::parse(text, path).expect_err("a stray \\r is not TOML");
        assert_eq!(err.line, line, "{text:?}: {err}");
        assert_eq!(err.key, "(syntax)", "{text:?}: {err}");
        assert!(err.message.contains("carriage return"), "{text:?}: {err}");
    }
}
