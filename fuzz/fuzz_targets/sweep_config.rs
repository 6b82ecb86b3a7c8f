//! The sweep configuration (SWEEP.toml) on arbitrary text: parse and check. The file's
//! directory does not exist, so relative scene and thesis-scene paths are refused after one
//! `stat` instead of being read; built-in scene names load their embedded TOML.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::text;
use sim::sweep::config::parse;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("/nonexistent-rtfpga-fuzz/sweep.toml");
    match parse(&text, path) {
        Ok(config) => {
            assert!(!config.points.is_empty() && !config.scenes.is_empty());
            assert!(config.width >= 1 && config.height >= 1);
        }
        Err(e) => {
            assert_eq!(e.file, path.display().to_string());
            assert!(
                !e.message.is_empty() && !e.key.is_empty(),
                "unclear error: {e}"
            );
            // 0 only for a TOML syntax error without a position.
            let lines = text.matches('\n').count() + 1;
            assert!(e.line <= lines, "line {} outside the text: {e}", e.line);
            assert!(e.line >= 1 || e.key == "(syntax)", "line 0: {e}");
        }
    }
});
