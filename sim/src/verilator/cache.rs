//! The on-disk cache of built models and of Verilator's compiled runtime.
//!
//! An entry is a directory named by a SHA-256 key. It is built in a temporary directory beside
//! it and renamed into place, so readers only ever see complete entries and concurrent builders
//! of one key both succeed (the loser of the rename discards its copy).
//!
//! A build that fails removes its temporary directory (it is dropped); one that is interrupted
//! does too when the program calls [`remove_unfinished_builds`] from its signal handler. What
//! neither can catch (SIGKILL, a power cut) the next build sweeps: temporary directories older
//! than [`STALE_AFTER`] belong to no running build.

use crate::SimError;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;

/// Prefix of the temporary directory of a build in progress.
const TMP_PREFIX: &str = ".tmp-";

/// Age after which a temporary directory is a leftover: no build takes hours (the largest,
/// the traversal unit's, takes minutes), and its directory's time is that of its start.
pub const STALE_AFTER: Duration = Duration::from_secs(6 * 3600);

/// The temporary directories of this process's builds in progress.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn unfinished() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    UNFINISHED.lock().unwrap_or_else(|p| p.into_inner())
}

/// Removes the temporary directories of this process's builds in progress: for a program's
/// Ctrl-C handler, just before it exits. The compilers it started may still be writing into
/// them (they get the terminal's SIGINT too), so a removal is retried briefly.
pub fn remove_unfinished_builds() {
    remove_unfinished(|_| true);
}

/// Removes the temporary directories of this process's builds in progress that `which`
/// accepts.
fn remove_unfinished(which: impl Fn(&Path) -> bool) {
    let dirs: Vec<PathBuf> = {
        let mut all = unfinished();
        let (gone, kept) = all.drain(..).partition(|d| which(d));
        *all = kept;
        gone
    };
    for dir in dirs {
        for _ in 0..20 {
            if std::fs::remove_dir_all(&dir).is_ok() || !dir.exists() {
                break;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

/// Removes the temporary directories in `root` older than [`STALE_AFTER`]: builds that were
/// killed. Best effort: a directory that cannot be read or removed is left.
fn sweep_stale(root: &Path) {
    let Ok(entries) = std::fs::read_dir(root) else {
        return;
    };
    for entry in entries.flatten() {
        let stale = entry.file_name().to_string_lossy().starts_with(TMP_PREFIX)
            && entry
                .metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age > STALE_AFTER);
        if stale {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

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
    sweep_stale(root);
    let tmp = tempfile::Builder::new()
        .prefix(&format!("{TMP_PREFIX}{name}-"))
        .tempdir_in(root)
        .map_err(|e| SimError::io(root, e))?;
    unfinished().push(tmp.path().to_path_buf());
    let filled = fill(tmp.path());
    unfinished().retain(|d| d != tmp.path());
    filled?;
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

    #[test]
    fn a_failed_or_interrupted_build_leaves_no_temporary_directory() {
        let root = tempfile::tempdir().unwrap();
        let fail = |d: &Path| Err(SimError::io(d, std::io::Error::other("compiler died")));
        assert!(get_or_build(root.path(), "k", fail).is_err());
        // Interrupted: the handler removes the directory while the build still runs.
        let interrupted = |d: &Path| {
            std::fs::write(d.join("half.o"), "x").unwrap();
            // (Only this test's: other tests build in parallel in this process.)
            remove_unfinished(|dir| dir.starts_with(root.path()));
            assert!(!d.exists(), "the handler removed the build's directory");
            Err(SimError::io(d, std::io::Error::other("interrupted")))
        };
        assert!(get_or_build(root.path(), "k", interrupted).is_err());
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_stale_temporary_directory_is_swept_by_the_next_build() {
        let root = tempfile::tempdir().unwrap();
        let (stale, fresh) = (
            root.path().join(".tmp-x-old"),
            root.path().join(".tmp-y-new"),
        );
        std::fs::create_dir_all(stale.join("obj")).unwrap();
        std::fs::create_dir_all(&fresh).unwrap();
        let old = std::time::SystemTime::now() - STALE_AFTER - Duration::from_secs(60);
        std::fs::File::open(&stale)
            .unwrap()
            .set_modified(old)
            .unwrap();
        let write = |d: &Path| std::fs::write(d.join("f"), "1").map_err(|e| SimError::io(d, e));
        get_or_build(root.path(), "k", write).unwrap();
        assert!(!stale.exists(), "a killed build's leftover is swept");
        assert!(fresh.exists(), "a running build's directory is not");
    }
}
