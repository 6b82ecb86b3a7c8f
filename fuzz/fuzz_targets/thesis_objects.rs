//! The thesis `objects.txt` list (geometry-file object-file pairs) on arbitrary text.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use rtfpga_fuzz::{check_thesis_error, text};
use sw_renderer::scene::thesis::parse_object_list;

fuzz_target!(|data: &[u8]| {
    let text = text(data);
    let path = Path::new("fuzz/objects.txt");
    match parse_object_list(&text, path) {
        Ok(entries) => {
            assert!(!entries.is_empty());
            for (geo, ood) in entries {
                assert!(!geo.is_empty() && !ood.is_empty());
                assert!(!geo.contains(char::is_whitespace) && !ood.contains(char::is_whitespace));
            }
        }
        Err(e) => check_thesis_error(&text, path, &e),
    }
});
