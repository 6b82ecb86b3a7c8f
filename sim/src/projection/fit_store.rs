//! The board's fitted constants kept between runs: fitting renders the thesis scenes (a few
//! seconds), a projection needs only the four numbers. The store is one small JSON file that
//! records what the fit depends on: the program that fitted (its calibration code, the
//! renderer that counts the work, the measurements: [`program_key`]) and the files of the
//! thesis scenes it rendered ([`scenes_key`]). A fit by another program is never used; one
//! on other scenes is replaced when the scenes are here to check.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::calibration::{Role, THESIS_MEASUREMENTS};
use super::cost::Board;
use super::ProjectionError;

/// File name of the store in the cache directory.
pub const FILE_NAME: &str = "projection-fit.json";

/// A stored fit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StoredFit {
    /// [`program_key`] of the program that fitted.
    pub program: String,
    /// [`scenes_key`] of the thesis scenes it rendered.
    pub scenes: String,
    pub board: Board,
}

fn hex(digest: impl AsRef<[u8]>) -> String {
    digest.as_ref().iter().map(|b| format!("{b:02x}")).collect()
}

fn io(path: &Path, e: impl std::fmt::Display) -> ProjectionError {
    ProjectionError::Fit(format!("{}: {e}", path.display()))
}

/// The running program's identity: the SHA-256 of its executable, so that a rebuilt program
/// (whose calibration or renderer may have changed) fits anew.
pub fn program_key() -> Result<String, ProjectionError> {
    let exe = std::env::current_exe().map_err(|e| io(Path::new("the running program"), e))?;
    let bytes = std::fs::read(&exe).map_err(|e| io(&exe, e))?;
    Ok(hex(Sha256::digest(bytes)))
}

/// The SHA-256 of every file of the thesis scenes the fit renders (`thesis`/SCENE/FILE, in
/// name order).
pub fn scenes_key(thesis: &Path) -> Result<String, ProjectionError> {
    let mut scenes: Vec<&str> = THESIS_MEASUREMENTS
        .iter()
        .filter(|m| m.role == Role::Fit)
        .map(|m| m.scene)
        .collect();
    scenes.sort_unstable();
    scenes.dedup();
    let mut h = Sha256::new();
    for scene in scenes {
        let dir = thesis.join(scene);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .map_err(|e| io(&dir, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file())
            .collect();
        files.sort();
        for file in files {
            let bytes = std::fs::read(&file).map_err(|e| io(&file, e))?;
            let name = file.strip_prefix(thesis).unwrap_or(&file);
            for part in [name.to_string_lossy().as_bytes(), &bytes[..]] {
                h.update((part.len() as u64).to_le_bytes());
                h.update(part);
            }
        }
    }
    Ok(hex(h.finalize()))
}

/// The stored fit a projection may use: one fitted by `program` on the thesis scenes of key
/// `scenes` (`None` when the scenes are not here to check: then any fit by `program`), and
/// none when asked to `refit`.
pub fn usable(
    stored: Option<StoredFit>,
    program: &str,
    scenes: Option<&str>,
    refit: bool,
) -> Option<StoredFit> {
    stored.filter(|f| {
        !refit && f.program == program && scenes.is_none_or(|scenes| f.scenes == scenes)
    })
}

/// The fit stored at `path`, if there is one that parses.
pub fn load(path: &Path) -> Option<StoredFit> {
    let text = std::fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

/// Stores `fit` at `path` (written beside it, then renamed: a reader never sees half a file).
pub fn save(path: &Path, fit: &StoredFit) -> Result<(), ProjectionError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let text = serde_json::to_string_pretty(fit).map_err(|e| io(path, e))?;
    let tmp = tempfile::NamedTempFile::new_in(dir).map_err(|e| io(dir, e))?;
    std::fs::write(tmp.path(), text).map_err(|e| io(tmp.path(), e))?;
    tmp.persist(path).map_err(|e| io(path, e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fit_round_trips_and_a_damaged_store_reads_as_none() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join(FILE_NAME);
        assert_eq!(load(&path), None);
        let fit = StoredFit {
            program: "p".into(),
            scenes: "s".into(),
            board: Board {
                arm_ray_ns: 1.5,
                arm_test_ns: 2.25,
                access_fixed_ns: 3.0,
                access_pl_cycles: 4.125,
            },
        };
        save(&path, &fit).unwrap();
        assert_eq!(load(&path), Some(fit));
        std::fs::write(&path, "{ not json").unwrap();
        assert_eq!(load(&path), None);
    }

    #[test]
    fn a_stored_fit_is_used_only_by_its_program_on_its_scenes() {
        let fit = StoredFit {
            program: "p".into(),
            scenes: "s".into(),
            board: Board {
                arm_ray_ns: 1.0,
                arm_test_ns: 1.0,
                access_fixed_ns: 1.0,
                access_pl_cycles: 1.0,
            },
        };
        let use_it = |program, scenes, refit| usable(Some(fit.clone()), program, scenes, refit);
        assert_eq!(use_it("p", Some("s"), false), Some(fit.clone()));
        assert_eq!(use_it("p", None, false), Some(fit.clone()), "scenes absent");
        assert_eq!(use_it("p", Some("other"), false), None, "other scenes");
        assert_eq!(use_it("q", Some("s"), false), None, "another program");
        assert_eq!(use_it("q", None, false), None, "another program");
        assert_eq!(use_it("p", Some("s"), true), None, "--recalibrate");
        assert_eq!(usable(None, "p", Some("s"), false), None);
    }

    #[test]
    fn the_scenes_key_follows_the_fit_scenes_files() {
        let dir = tempfile::tempdir().unwrap();
        for scene in ["Simple_plane_scene", "Utah_teapot_scene"] {
            std::fs::create_dir_all(dir.path().join(scene)).unwrap();
            std::fs::write(dir.path().join(scene).join("objects.txt"), scene).unwrap();
        }
        let before = scenes_key(dir.path()).unwrap();
        assert_eq!(scenes_key(dir.path()).unwrap(), before);
        std::fs::write(dir.path().join("Utah_teapot_scene/objects.txt"), "edited").unwrap();
        assert_ne!(scenes_key(dir.path()).unwrap(), before);
        // A scene the fit does not render is not part of it.
        std::fs::create_dir_all(dir.path().join("Glasses_scene")).unwrap();
        std::fs::write(dir.path().join("Glasses_scene/objects.txt"), "x").unwrap();
        let edited = scenes_key(dir.path()).unwrap();
        std::fs::write(dir.path().join("Glasses_scene/objects.txt"), "y").unwrap();
        assert_eq!(scenes_key(dir.path()).unwrap(), edited);
    }
}
