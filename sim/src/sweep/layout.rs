//! Where a sweep's files go inside its output directory.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use hw_model::precision::SpawnChoice;
use serde::{de::DeserializeOwned, Serialize};

use super::config::Variant;

#[derive(Clone, Debug)]
pub struct Layout {
    root: PathBuf,
}

impl Layout {
    pub fn new(root: &Path) -> Layout {
        Layout {
            root: root.to_path_buf(),
        }
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    pub fn manifest(&self) -> PathBuf {
        self.root.join("manifest.json")
    }

    pub fn jobs_txt(&self) -> PathBuf {
        self.root.join("jobs.txt")
    }

    /// The checked configuration the jobs ran with (what the merge reads).
    pub fn config(&self) -> PathBuf {
        self.root.join("sweep.json")
    }

    pub fn reference(&self, scene: &str) -> PathBuf {
        self.root.join("reference").join(format!("{scene}.png"))
    }

    pub fn quality_dir(&self, format: &str, variant: Variant) -> PathBuf {
        self.root.join("quality").join(format).join(variant.name())
    }

    pub fn quality_result(&self, format: &str, variant: Variant) -> PathBuf {
        self.quality_dir(format, variant).join("result.json")
    }

    /// A dual-precision pair's renders (`bfp18/fp32` in the folder `bfp18_fp32`).
    pub fn dual_dir(&self, pair: &str, policy: SpawnChoice) -> PathBuf {
        self.root
            .join("dual")
            .join(pair.replace('/', "_"))
            .join(policy.name())
    }

    pub fn dual_result(&self, pair: &str, policy: SpawnChoice) -> PathBuf {
        self.dual_dir(pair, policy).join("result.json")
    }

    pub fn point_dir(&self, id: &str) -> PathBuf {
        self.root.join("points").join(id)
    }

    pub fn point_result(&self, id: &str) -> PathBuf {
        self.point_dir(id).join("result.json")
    }

    /// yosys reports kept across re-runs, one per point.
    pub fn synth_cache(&self, id: &str) -> PathBuf {
        self.root.join("synth-cache").join(format!("{id}.json"))
    }

    pub fn grid(&self, format: &str, variant: Variant) -> PathBuf {
        self.root
            .join("grids")
            .join(format!("{format}_{}.png", variant.name()))
    }

    pub fn plot(&self, name: &str, ext: &str) -> PathBuf {
        self.root.join("plots").join(format!("{name}.{ext}"))
    }

    pub fn results(&self, ext: &str) -> PathBuf {
        self.root.join(format!("results.{ext}"))
    }

    /// One line per format or dual-precision pair, policy, advance and scene.
    pub fn quality_csv(&self) -> PathBuf {
        self.root.join("quality.csv")
    }
}

/// Writes `value` as pretty JSON, through a temporary file so readers never see half a file.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    parent_dir(path)?;
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, serde_json::to_string_pretty(value)? + "\n")
        .with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("writing {}", path.display()))
}

pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))
}

/// Creates the parent directory of `path`.
pub fn parent_dir(path: &Path) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    Ok(())
}
