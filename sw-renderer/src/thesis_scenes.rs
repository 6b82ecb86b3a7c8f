//! Where the thesis' 7 scene directories are, for the tests that compare against them and for
//! the defaults of `rtfpga project` and the sweep's projection stage.
//!
//! The scenes are not part of the repository. They are looked for in this order:
//!
//! 1. `RTFPGA_THESIS_SCENES=DIR` when the variable is set (and not empty). DIR must then hold
//!    every one of [`SCENE_DIRS`] with its `objects.txt`; anything missing is an error naming
//!    DIR and what is missing, never a silent skip. A relative DIR is relative to the current
//!    directory of the process (cargo runs tests in their crate's directory), so give an
//!    absolute path; CI (`.ci/run`) does.
//! 2. Else `../shared/scenes/thesis` beside the repository ([`fallback_dir`]), if that
//!    directory exists (then it is checked as DIR above).
//! 3. Else they are absent: tests print one `SKIPPED` line ([`for_test`]) and pass; the CLI
//!    asks for `--thesis-scenes` or the variable.
//!
//! The repository of the fallback is the source tree this crate was compiled from
//! (`CARGO_MANIFEST_DIR` at compile time), not the current directory: cargo runs each test
//! binary in its own crate's directory (`sw-renderer/`, `sim/`), and `rtfpga` is run from
//! anywhere, so the current directory would point at a different place for each of them. A
//! binary moved away from its source tree (or installed) finds no fallback and needs the
//! variable or an explicit path.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The environment variable naming the thesis scenes' directory.
pub const ENV_VAR: &str = "RTFPGA_THESIS_SCENES";

/// The thesis' 7 scene directories, in the order of the built-in scenes (`glass_pen`,
/// `simple_plane`, `glasses`, `glasses_point`, `simple_plane2`, `utah_teapot`,
/// `all_materials`). Each holds an `objects.txt`.
pub const SCENE_DIRS: [&str; 7] = [
    "Glass_pen_scene",
    "Simple_plane_scene",
    "Glasses_scene",
    "Glasses_point_scene",
    "Simple_plane2_scene",
    "Utah_teapot_scene",
    "All_materials_scene",
];

/// The thesis scenes' directory is named but unusable.
#[derive(Debug, thiserror::Error)]
pub enum LocateError {
    #[error("thesis scenes ({source_of}): {} is not a directory", path.display())]
    NotADirectory { source_of: String, path: PathBuf },
    #[error("thesis scenes ({source_of}): {} lacks {}", path.display(), missing.join(", "))]
    Incomplete {
        source_of: String,
        path: PathBuf,
        /// `Name_scene` (no directory) or `Name_scene/objects.txt`.
        missing: Vec<String>,
    },
}

/// `<repository>/../shared/scenes/thesis`, the repository being the source tree this crate was
/// compiled from. It need not exist.
pub fn fallback_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let repo = manifest.parent().unwrap_or(manifest);
    repo.parent().unwrap_or(repo).join("shared/scenes/thesis")
}

/// `$RTFPGA_THESIS_SCENES` if set and not empty.
fn from_env() -> Option<PathBuf> {
    std::env::var_os(ENV_VAR)
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
}

/// The directory the scenes are looked for in: `$RTFPGA_THESIS_SCENES` if set, else
/// [`fallback_dir`]. It need not exist; [`locate`] checks.
pub fn default_dir() -> PathBuf {
    from_env().unwrap_or_else(fallback_dir)
}

/// Every scene directory of [`SCENE_DIRS`] with its `objects.txt` is in `dir`. `source_of`
/// says where the path came from, for the error.
pub fn check(dir: &Path, source_of: &str) -> Result<(), LocateError> {
    if !dir.is_dir() {
        return Err(LocateError::NotADirectory {
            source_of: source_of.into(),
            path: dir.to_path_buf(),
        });
    }
    let missing: Vec<String> = SCENE_DIRS
        .iter()
        .filter_map(|name| {
            if !dir.join(name).is_dir() {
                Some(name.to_string())
            } else if !dir.join(name).join("objects.txt").is_file() {
                Some(format!("{name}/objects.txt"))
            } else {
                None
            }
        })
        .collect();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(LocateError::Incomplete {
            source_of: source_of.into(),
            path: dir.to_path_buf(),
            missing,
        })
    }
}

/// The thesis scenes' directory: `Ok(Some(dir))` when found and complete, `Ok(None)` when
/// absent (no variable, no fallback directory), an error when the variable (or an existing
/// fallback) names a directory that is missing or incomplete.
pub fn locate() -> Result<Option<PathBuf>, LocateError> {
    if let Some(dir) = from_env() {
        check(&dir, ENV_VAR)?;
        return Ok(Some(dir));
    }
    let dir = fallback_dir();
    if !dir.is_dir() {
        return Ok(None);
    }
    check(&dir, "the default beside the repository")?;
    Ok(Some(dir))
}

/// What to do when the scenes are absent, for messages.
pub const NOT_FOUND: &str =
    "thesis scenes not found; set RTFPGA_THESIS_SCENES=DIR or put them at ../shared/scenes/thesis";

/// For a test that needs the thesis scenes: their directory, or `None` after writing
/// `SKIPPED <what>: ...` to the process' real stderr (not captured by the test harness, so the
/// skip shows in `cargo test`'s output). Panics with the [`LocateError`] when
/// `RTFPGA_THESIS_SCENES` is set but wrong, so the test fails naming the path.
pub fn for_test(what: &str) -> Option<PathBuf> {
    match locate() {
        Ok(Some(dir)) => Some(dir),
        Ok(None) => {
            let _ = writeln!(std::io::stderr(), "SKIPPED {what}: {NOT_FOUND}");
            None
        }
        Err(e) => panic!("{what}: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fallback_is_beside_the_repository() {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        assert!(repo.join("Cargo.toml").is_file());
        assert_eq!(
            fallback_dir(),
            repo.parent().unwrap().join("shared/scenes/thesis")
        );
    }

    #[test]
    fn check_names_the_directory_and_what_is_missing() {
        let e = check(Path::new("/nonexistent/thesis"), ENV_VAR).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/thesis"), "{e}");
        assert!(e.to_string().contains(ENV_VAR), "{e}");

        let dir = std::env::temp_dir().join(format!("rtfpga_locator_{}", std::process::id()));
        for name in &SCENE_DIRS[..6] {
            std::fs::create_dir_all(dir.join(name)).unwrap();
            std::fs::write(dir.join(name).join("objects.txt"), "").unwrap();
        }
        std::fs::remove_file(dir.join(SCENE_DIRS[2]).join("objects.txt")).unwrap();
        let e = check(&dir, ENV_VAR).unwrap_err().to_string();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(e.contains(&dir.display().to_string()), "{e}");
        assert!(
            e.ends_with("lacks Glasses_scene/objects.txt, All_materials_scene"),
            "{e}"
        );
    }
}
