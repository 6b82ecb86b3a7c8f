//! The on-disk cache of built models and of Verilator's compiled runtime.
//!
//! An entry is a directory named by a SHA-256 key. It is built in a temporary directory beside
//! it and renamed into place, so readers only ever see complete entries and concurrent builders
//! of one key both succeed (the loser of the rename discards its copy).

use crate::SimError;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// `$RTFPGA_CACHE`, else `verilator-cache/` in the Cargo target directory this program runs
/// from (found by walking up from the executable to a directory holding `CACHEDIR.TAG`), else
/// one in the system's temporary directory.
pub fn default_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("RTFPGA_CACHE") {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(dir).join("verilator-cache");
    }
    std::env::current_exe()
        .ok()
        .and_then(|exe| {
            exe.ancestors()
                .find(|d| d.join("CACHEDIR.TAG").is_file())
                .map(Path::to_path_buf)
        })
        .map_or_else(
            || std::env::temp_dir().join("rtfpga-verilator-cache"),
            |t| t.join("verilator-cache"),
        )
}

/// Hex SHA-256 of the parts, each length-prefixed so that boundaries matter.
pub fn key(parts: &[&[u8]]) -> String {
    let mut h = Sha256::new();
    for p in parts {
        h.update((p.len() as u64).to_le_bytes());
        h.update(p);
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Returns `root/name`, building it with `fill(tmp_dir)` first if it is missing.
/// The boolean is true when the entry was already there.
pub fn get_or_build(
    root: &Path,
    name: &str,
    fill: impl FnOnce(&Path) -> Result<(), SimError>,
) -> Result<(PathBuf, bool), SimError> {
    let entry = root.join(name);
    if entry.is_dir() {
        return Ok((entry, true));
    }
    std::fs::create_dir_all(root).map_err(|e| SimError::io(root, e))?;
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".tmp-{name}-"))
        .tempdir_in(root)
        .map_err(|e| SimError::io(root, e))?;
    fill(tmp.path())?;
    match std::fs::rename(tmp.path(), &entry) {
        Ok(()) => {
            // The directory now lives under its final name; nothing is left to delete.
            let _ = tmp.keep();
            Ok((entry, false))
        }
        // Another builder published the same key first: use theirs, drop ours.
        Err(_) if entry.is_dir() => Ok((entry, false)),
        Err(e) => Err(SimError::io(&entry, e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_depends_on_boundaries_and_content() {
        assert_ne!(key(&[b"ab", b"c"]), key(&[b"a", b"bc"]));
        assert_eq!(key(&[b"x"]), key(&[b"x"]));
        assert_eq!(key(&[b"x"]).len(), 64);
    }

    #[test]
    fn second_lookup_is_cached_and_concurrent_builds_agree() {
        let root = tempfile::tempdir().unwrap();
        let write = |d: &Path| std::fs::write(d.join("f"), "1").map_err(|e| SimError::io(d, e));
        let (p, cached) = get_or_build(root.path(), "k", write).unwrap();
        assert!(!cached && p.join("f").is_file());
        let (_, cached) = get_or_build(root.path(), "k", |_| panic!("must not rebuild")).unwrap();
        assert!(cached);

        std::thread::scope(|s| {
            let handles: Vec<_> = (0..4)
                .map(|_| s.spawn(|| get_or_build(root.path(), "race", write)))
                .collect();
            for h in handles {
                let (p, _) = h.join().unwrap().unwrap();
                assert_eq!(std::fs::read_to_string(p.join("f")).unwrap(), "1");
            }
        });
        let leftovers = std::fs::read_dir(root.path()).unwrap().count();
        assert_eq!(leftovers, 2, "temporary directories must be cleaned up");
    }
}
