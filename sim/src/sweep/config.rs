//! The sweep's configuration file (SWEEP.toml), parsed and checked before any work starts:
//! every mistake is reported with the file, the line, the key and what was expected.

use std::path::{Path, PathBuf};

use hdl::top::{TopConfig, TopError};
use hw_model::dual::FormatPair;
use hw_model::precision::SpawnChoice;
use hw_model::{Advance, HwFormat, NamedChoice};
use serde::{Deserialize, Serialize};
use sw_renderer::scene::{builtin, Scene};
use toml::Spanned;

use super::point::Point;
use super::projection::stream_design;

/// What a sweep does at each of its points; `stages = [...]` in the file picks a subset.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    /// Generate the accelerator's Verilog (kept in the point's directory with `keep_verilog`).
    Verilog,
    /// yosys resources and logic depth of the points `[synth]` selects.
    Synth,
    /// Model-engine renders of every scene in every format and variant (spawn policy and
    /// origin advance), and of every dual-precision pair, against the f32 reference.
    Quality,
    /// Verilated renders of the `[cosim]` points, compared with the model engine.
    Cosim,
    /// Projected ZedBoard frame time of every point (at merge time).
    Projection,
}

pub const ALL_STAGES: [Stage; 5] = [
    Stage::Verilog,
    Stage::Synth,
    Stage::Quality,
    Stage::Cosim,
    Stage::Projection,
];

/// How the quality stage renders a format: a spawn policy and where the model lane starts
/// each query's ray (docs/precision.md, "Advancing the origin").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Variant {
    pub policy: SpawnChoice,
    pub advance: Advance,
}

impl Variant {
    /// Folder and file names: the policy's name, `+ADVANCE` when the origin is advanced.
    pub fn name(self) -> String {
        match self.advance {
            Advance::None => self.policy.name().to_string(),
            a => format!("{}+{a}", self.policy),
        }
    }

    /// The hardware lanes' variant: they do not advance the origin.
    pub fn in_hardware(self) -> bool {
        self.advance == Advance::None
    }
}

impl std::fmt::Display for Variant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} policy, advance {}", self.policy, self.advance)
    }
}

/// A scene of the sweep: how to load it and the label its files are named after.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SceneSpec {
    /// File-name-safe label, unique within the sweep.
    pub label: String,
    /// What `Scene::load` takes: a built-in name or an absolute path.
    pub spec: String,
}

impl SceneSpec {
    pub fn load(&self) -> anyhow::Result<Scene> {
        Ok(Scene::load(&self.spec)?)
    }
}

/// The ZedBoard frame the sweep projects for every point (see `sim::projection`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProjectionSettings {
    /// Directory of the thesis scenes the board model is calibrated on.
    pub thesis_scenes: PathBuf,
    /// Scene directory (under `thesis_scenes`) of the projected frame.
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub fpl_mhz: f64,
    pub hp_ports: u32,
    pub dma_efficiency: f64,
    /// ARM cycles to pack one query into the DMA buffer.
    pub pack_cycles: f64,
}

/// A checked sweep configuration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepConfig {
    /// The file it was read from (absolute).
    pub path: PathBuf,
    /// Formats with hardware: the points' formats.
    pub formats: Vec<HwFormat>,
    /// Formats only the model engine renders (any `hw_model::lookup` spelling, e.g. `e8m19`):
    /// quality without hardware, to see where the quality threshold lies between catalogue formats.
    pub model_formats: Vec<String>,
    /// Spawn policies the quality stage renders each format with.
    pub policies: Vec<SpawnChoice>,
    /// Origin advances of the model lane the quality stage renders each format with
    /// ([`SweepConfig::variants`] says under which policies).
    pub advances: Vec<Advance>,
    /// Dual-precision pairs (`FILTER/FALLBACK`, as `FormatPair` prints them): quality and the
    /// forwarded share; the pair built in hardware also its resources and co-simulation
    /// (`sweep::dual`), not as a point.
    pub pairs: Vec<String>,
    /// Write every point's generated files to its directory (else only their size is kept).
    pub keep_verilog: bool,
    /// Depths per format ("max" already replaced by the format's maximum).
    pub points: Vec<Point>,
    pub scenes: Vec<SceneSpec>,
    pub width: u32,
    pub height: u32,
    pub stages: Vec<Stage>,
    /// Points whose accelerator yosys synthesises.
    pub synth_points: Vec<String>,
    /// Points co-simulated, and on which scenes.
    pub cosim_points: Vec<String>,
    pub cosim_scenes: Vec<SceneSpec>,
    pub projection: ProjectionSettings,
}

impl SweepConfig {
    /// Every format the quality stage renders: the hardware formats, then the model-only ones.
    pub fn quality_formats(&self) -> Vec<String> {
        self.formats
            .iter()
            .map(|f| f.name().to_string())
            .chain(self.model_formats.iter().cloned())
            .collect()
    }

    /// Every (policy, advance) the quality stage renders, policy by policy: each policy with
    /// the hardware's lane (advance none, what the points' rows and co-simulation are
    /// compared with) and with the lane `rtfpga render` gives it by default
    /// (`hw_model::advance::default_for`), of those `advances` lists. So triangle-box only
    /// under format-aware: the thesis policy's narrow formats fail from self-intersection at
    /// the spawn point, which moving the origin does not touch.
    pub fn variants(&self) -> Vec<Variant> {
        variants(&self.policies, &self.advances)
    }

    pub fn runs(&self, stage: Stage) -> bool {
        self.stages.contains(&stage)
    }

    pub fn point(&self, id: &str) -> Option<&Point> {
        self.points.iter().find(|p| p.id() == id)
    }

    pub fn synthesises(&self, p: &Point) -> bool {
        self.runs(Stage::Synth) && self.synth_points.contains(&p.id())
    }

    pub fn cosimulates(&self, p: &Point) -> bool {
        self.runs(Stage::Cosim) && self.cosim_points.contains(&p.id())
    }
}

/// A configuration mistake: where it is and what was expected.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("{file}:{line}: `{key}`: {message}")]
pub struct ConfigError {
    pub file: String,
    pub line: usize,
    pub key: String,
    pub message: String,
}

/// A depth as written: a number, or "max" for each format's deepest pipeline.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
enum DepthSpec {
    Number(usize),
    Word(String),
}

type List<T> = Spanned<Vec<Spanned<T>>>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    formats: List<String>,
    model_formats: Option<List<String>>,
    policies: Option<List<String>>,
    advances: Option<List<String>>,
    pairs: Option<List<String>>,
    #[serde(default)]
    keep_verilog: bool,
    depths: List<DepthSpec>,
    lanes: List<usize>,
    scenes: List<String>,
    width: Spanned<u32>,
    height: Spanned<u32>,
    stages: Option<List<String>>,
    #[serde(default)]
    synth: RawSynth,
    #[serde(default)]
    cosim: RawCosim,
    projection: Option<Spanned<RawProjection>>,
}

/// Which points to synthesise: the product of these subsets (each defaults to everything),
/// plus the listed `points`.
#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSynth {
    formats: Option<List<String>>,
    depths: Option<List<DepthSpec>>,
    lanes: Option<List<usize>>,
    /// Point ids (`fp32_d1_l2`) synthesised as well.
    points: Option<List<String>>,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCosim {
    /// Point ids (`fp32_d1_l1`).
    points: Option<List<String>>,
    /// Scenes of the sweep to co-simulate (default: all).
    scenes: Option<List<String>>,
}

#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProjection {
    thesis_scenes: Option<Spanned<String>>,
    scene: Option<String>,
    width: Option<u32>,
    height: Option<u32>,
    fpl_mhz: Option<f64>,
    hp_ports: Option<u32>,
    dma_efficiency: Option<f64>,
    pack_cycles: Option<f64>,
}

/// Where errors point: the file's name and text.
struct Source<'a> {
    file: String,
    text: &'a str,
}

impl Source<'_> {
    fn err<T>(&self, at: &Spanned<T>, key: &str, message: impl Into<String>) -> ConfigError {
        let line = self.text[..at.span().start.min(self.text.len())]
            .matches('\n')
            .count()
            + 1;
        self.err_line(line, key, message)
    }

    fn err_line(&self, line: usize, key: &str, message: impl Into<String>) -> ConfigError {
        ConfigError {
            file: self.file.clone(),
            line,
            key: key.to_string(),
            message: message.into(),
        }
    }

    fn non_empty<'l, T>(
        &self,
        list: &'l List<T>,
        key: &str,
    ) -> Result<&'l [Spanned<T>], ConfigError> {
        if list.get_ref().is_empty() {
            return Err(self.err(list, key, "empty list: expected at least one entry"));
        }
        Ok(list.get_ref())
    }
}

/// Reads and checks `path`.
pub fn load(path: &Path) -> anyhow::Result<SweepConfig> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::anyhow!("reading sweep config {}: {e}", path.display()))?;
    Ok(parse(&text, path)?)
}

/// Parses and checks the text of a sweep config; `path` names it in errors and anchors
/// relative paths (to its directory).
pub fn parse(text: &str, path: &Path) -> Result<SweepConfig, ConfigError> {
    let src = Source {
        file: path.display().to_string(),
        text,
    };
    let raw: RawConfig = toml::from_str(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1)
            .unwrap_or(0);
        ConfigError {
            file: src.file.clone(),
            line,
            key: "(syntax)".into(),
            message: sw_renderer::scene::toml_scene::syntax_message(text, &e),
        }
    })?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let base = std::path::absolute(&base).unwrap_or(base);

    let formats = check_formats(&src, &raw.formats, "formats")?;
    let model_formats = match &raw.model_formats {
        Some(list) => check_model_formats(&src, list, &formats)?,
        None => Vec::new(),
    };
    let policies = match &raw.policies {
        Some(list) => check_choices(&src, list, "policies", "spawn policy")?,
        None => SpawnChoice::ALL.to_vec(),
    };
    let advances = match &raw.advances {
        Some(list) => {
            let advances = check_choices(&src, list, "advances", "origin advance")?;
            let rendered = variants(&policies, &advances);
            if let Some(p) = policies
                .iter()
                .find(|&&p| !rendered.iter().any(|v| v.policy == p))
            {
                return Err(src.err(list, "advances", format!(
                    "the {p} policy would have no render: it takes the origin advance {} only (the hardware's, and its default in `rtfpga render`); add it or drop the policy",
                    hw_model::advance::default_for(*p)
                )));
            }
            advances
        }
        None => Advance::ALL.to_vec(),
    };
    let pairs = match &raw.pairs {
        Some(list) => check_pairs(&src, list)?,
        None => Vec::new(),
    };
    let lanes = check_lanes(&src, &raw.lanes, "lanes")?;
    let depths = src.non_empty(&raw.depths, "depths")?;
    let mut points = Vec::new();
    for &format in &formats {
        for depth in depths {
            let depth = resolve_depth(&src, depth, format, "depths")?;
            for &(l, spanned) in &lanes {
                let config = TopConfig::new(format, depth, l);
                // The hardware's own rules (format, depth and lane checks above name the line).
                config
                    .validate()
                    .map_err(|e| src.err(spanned, "lanes", e.to_string()))?;
                let p = Point::new(format, depth, l);
                if !points.contains(&p) {
                    points.push(p);
                }
            }
        }
    }

    let scenes = check_scenes(&src, &raw.scenes, &base)?;
    for (key, v) in [("width", &raw.width), ("height", &raw.height)] {
        if *v.get_ref() == 0 {
            return Err(src.err(v, key, "0 pixels: expected a positive size"));
        }
    }
    let stages = match &raw.stages {
        None => ALL_STAGES.to_vec(),
        Some(list) => {
            let mut stages = Vec::new();
            for s in src.non_empty(list, "stages")? {
                let stage: Stage = toml::Value::String(s.get_ref().clone())
                    .try_into()
                    .map_err(|_| {
                        src.err(s, "stages", format!(
                            "unknown stage `{}`: expected verilog, synth, quality, cosim or projection",
                            s.get_ref()
                        ))
                    })?;
                stages.push(stage);
            }
            stages.sort();
            stages.dedup();
            stages
        }
    };

    let synth_points = synth_selection(&src, &raw.synth, &points)?;
    let (cosim_points, cosim_scenes) = cosim_selection(&src, &raw.cosim, &points, &scenes)?;
    let projection = projection_settings(&src, &raw.projection, &base, &stages, &points[0])?;
    Ok(SweepConfig {
        path: std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()),
        formats,
        model_formats,
        policies,
        advances,
        pairs,
        keep_verilog: raw.keep_verilog,
        points,
        scenes,
        width: *raw.width.get_ref(),
        height: *raw.height.get_ref(),
        stages,
        synth_points,
        cosim_points,
        cosim_scenes,
        projection,
    })
}

fn check_formats(
    src: &Source,
    list: &List<String>,
    key: &str,
) -> Result<Vec<HwFormat>, ConfigError> {
    let mut out = Vec::new();
    for f in src.non_empty(list, key)? {
        if f.get_ref().contains('/') {
            // A valid pair is still refused here: a point is an accelerator of one format.
            let why = match FormatPair::parse(f.get_ref()) {
                Ok(pair) => format!(
                    "`{pair}` is a dual-precision pair, not an accelerator format: list it \
                     under `pairs`, which gives its quality and forwarded share (and for the \
                     pair built in hardware its resources and co-simulation)"
                ),
                Err(e) => e.to_string(),
            };
            return Err(src.err(f, key, why));
        }
        let format: HwFormat = f
            .get_ref()
            .parse()
            .map_err(|e: hw_model::FormatError| src.err(f, key, e.to_string()))?;
        if !out.contains(&format) {
            out.push(format);
        }
    }
    Ok(out)
}

fn check_model_formats(
    src: &Source,
    list: &List<String>,
    hardware: &[HwFormat],
) -> Result<Vec<String>, ConfigError> {
    let mut out = Vec::new();
    for f in src.non_empty(list, "model_formats")? {
        let name = f.get_ref();
        if let Err(e) = hw_model::lookup(name) {
            return Err(src.err(
                f,
                "model_formats",
                format!("{e} (or a generic spelling such as e8m19)"),
            ));
        }
        if hardware.iter().any(|h| h.name() == name) || out.contains(name) {
            return Err(src.err(
                f,
                "model_formats",
                format!("format `{name}` is listed twice"),
            ));
        }
        out.push(name.clone());
    }
    Ok(out)
}

/// A list of named choices (`policies`, `advances`), each once.
fn check_choices<T: NamedChoice + PartialEq + std::fmt::Display>(
    src: &Source,
    list: &List<String>,
    key: &str,
    what: &str,
) -> Result<Vec<T>, ConfigError> {
    let mut out = Vec::new();
    for p in src.non_empty(list, key)? {
        let choice: T = p
            .get_ref()
            .parse()
            .map_err(|e: String| src.err(p, key, e))?;
        if out.contains(&choice) {
            return Err(src.err(p, key, format!("{what} `{choice}` is listed twice")));
        }
        out.push(choice);
    }
    Ok(out)
}

fn variants(policies: &[SpawnChoice], advances: &[Advance]) -> Vec<Variant> {
    let mut out = Vec::new();
    for &policy in policies {
        for &advance in advances {
            if advance == Advance::None || advance == hw_model::advance::default_for(policy) {
                out.push(Variant { policy, advance });
            }
        }
    }
    out
}

/// The pairs as `FormatPair` prints them, each checked by `FormatPair::parse`.
fn check_pairs(src: &Source, list: &List<String>) -> Result<Vec<String>, ConfigError> {
    let mut out: Vec<String> = Vec::new();
    for p in src.non_empty(list, "pairs")? {
        let pair =
            FormatPair::parse(p.get_ref()).map_err(|e| src.err(p, "pairs", e.to_string()))?;
        let name = pair.to_string();
        if out.contains(&name) {
            return Err(src.err(p, "pairs", format!("pair `{name}` is listed twice")));
        }
        out.push(name);
    }
    Ok(out)
}

fn check_lanes<'l>(
    src: &Source,
    list: &'l List<usize>,
    key: &str,
) -> Result<Vec<(usize, &'l Spanned<usize>)>, ConfigError> {
    let mut out: Vec<(usize, &Spanned<usize>)> = Vec::new();
    for l in src.non_empty(list, key)? {
        let n = *l.get_ref();
        if n == 0 {
            return Err(src.err(l, key, "0 lanes: expected at least 1"));
        }
        if n > hdl::top::MAX_LANES {
            return Err(src.err(l, key, TopError::TooManyLanes(n).to_string()));
        }
        if !out.iter().any(|(m, _)| *m == n) {
            out.push((n, l));
        }
    }
    Ok(out)
}

fn resolve_depth(
    src: &Source,
    d: &Spanned<DepthSpec>,
    format: HwFormat,
    key: &str,
) -> Result<usize, ConfigError> {
    let max = hdl::mt::max_depth(format);
    match d.get_ref() {
        DepthSpec::Number(n) if *n > max => Err(src.err(d, key, format!(
            "impossible depth {n} for format {format}: its operators have pipeline registers for depth 0 to {max} (write \"max\" for each format's deepest)"
        ))),
        DepthSpec::Number(n) => Ok(*n),
        DepthSpec::Word(w) if w == "max" => Ok(max),
        DepthSpec::Word(w) => Err(src.err(d, key, format!(
            "depth `{w}`: expected a number of pipeline registers per operator or \"max\""
        ))),
    }
}

fn check_scenes(
    src: &Source,
    list: &List<String>,
    base: &Path,
) -> Result<Vec<SceneSpec>, ConfigError> {
    let mut out: Vec<SceneSpec> = Vec::new();
    for s in src.non_empty(list, "scenes")? {
        let name = s.get_ref();
        let spec = if builtin::names().contains(&name.as_str()) {
            name.clone()
        } else {
            let p = base.join(name);
            if !p.exists() {
                return Err(src.err(s, "scenes", format!(
                    "`{name}` is neither a built-in scene ({}) nor a scene directory or .toml file ({} does not exist)",
                    builtin::names().join(", "),
                    p.display()
                )));
            }
            p.display().to_string()
        };
        Scene::load(&spec)
            .map_err(|e| src.err(s, "scenes", format!("scene `{name}` does not load: {e}")))?;
        let stem = Path::new(name)
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| name.clone());
        let label: String = stem
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        if out.iter().any(|o| o.label == label) {
            return Err(src.err(
                s,
                "scenes",
                format!("scene `{name}` is listed twice (or two scenes share the name `{label}`)"),
            ));
        }
        out.push(SceneSpec { label, spec });
    }
    Ok(out)
}

fn synth_selection(
    src: &Source,
    raw: &RawSynth,
    points: &[Point],
) -> Result<Vec<String>, ConfigError> {
    let formats = match &raw.formats {
        Some(list) => Some(check_formats(src, list, "synth.formats")?),
        None => None,
    };
    let lanes = match &raw.lanes {
        Some(list) => Some(
            check_lanes(src, list, "synth.lanes")?
                .into_iter()
                .map(|(n, _)| n)
                .collect::<Vec<_>>(),
        ),
        None => None,
    };
    let mut selected = Vec::new();
    for p in points {
        let depth_ok = match &raw.depths {
            None => true,
            Some(list) => {
                let mut any = false;
                for d in src.non_empty(list, "synth.depths")? {
                    any |= resolve_depth(src, d, p.format, "synth.depths")? == p.depth;
                }
                any
            }
        };
        let format_ok = formats.as_ref().is_none_or(|f| f.contains(&p.format));
        let lanes_ok = lanes.as_ref().is_none_or(|l| l.contains(&p.lanes));
        if depth_ok && format_ok && lanes_ok {
            selected.push(p.id());
        }
    }
    for id in point_ids(src, &raw.points, points, "synth.points")? {
        if !selected.contains(&id) {
            selected.push(id);
        }
    }
    Ok(selected)
}

/// The ids of `list`, each checked to be a point of the sweep.
fn point_ids(
    src: &Source,
    list: &Option<List<String>>,
    points: &[Point],
    key: &str,
) -> Result<Vec<String>, ConfigError> {
    let mut ids = Vec::new();
    for id in list.iter().flat_map(|l| l.get_ref()) {
        if !points.iter().any(|p| &p.id() == id.get_ref()) {
            let known: Vec<String> = points.iter().map(Point::id).collect();
            return Err(src.err(
                id,
                key,
                format!(
                    "`{}` is not a point of this sweep: expected one of {}",
                    id.get_ref(),
                    known.join(", ")
                ),
            ));
        }
        ids.push(id.get_ref().clone());
    }
    Ok(ids)
}

fn cosim_selection(
    src: &Source,
    raw: &RawCosim,
    points: &[Point],
    scenes: &[SceneSpec],
) -> Result<(Vec<String>, Vec<SceneSpec>), ConfigError> {
    let ids = point_ids(src, &raw.points, points, "cosim.points")?;
    let chosen = match &raw.scenes {
        None => scenes.to_vec(),
        Some(list) => {
            let mut chosen = Vec::new();
            for s in src.non_empty(list, "cosim.scenes")? {
                let label_of =
                    |spec: &SceneSpec| spec.label == *s.get_ref() || spec.spec == *s.get_ref();
                match scenes.iter().find(|spec| label_of(spec)) {
                    Some(spec) => chosen.push(spec.clone()),
                    None => {
                        let known: Vec<&str> = scenes.iter().map(|s| s.label.as_str()).collect();
                        return Err(src.err(
                            s,
                            "cosim.scenes",
                            format!(
                                "`{}` is not a scene of this sweep: expected one of {}",
                                s.get_ref(),
                                known.join(", ")
                            ),
                        ));
                    }
                }
            }
            chosen
        }
    };
    Ok((ids, chosen))
}

/// Defaults: the thesis' Simple plane at 1080p, one HP port at 80 % and 40 ARM cycles per
/// query (the defaults of `rtfpga project`), fabric at 100 MHz. Checked when the projection
/// stage runs: the thesis scenes must be there and the design must be one the model takes.
fn projection_settings(
    src: &Source,
    raw: &Option<Spanned<RawProjection>>,
    base: &Path,
    stages: &[Stage],
    first: &Point,
) -> Result<ProjectionSettings, ConfigError> {
    let default = RawProjection::default();
    let r = raw.as_ref().map_or(&default, Spanned::get_ref);
    // Errors point at the [projection] table, or the file's first line when it is absent.
    let err = |key: &str, message: String| match raw {
        Some(t) => src.err(t, key, message),
        None => src.err_line(1, key, message),
    };
    let thesis_scenes = match &r.thesis_scenes {
        Some(p) => base.join(p.get_ref()),
        // $RTFPGA_THESIS_SCENES, else ../shared/scenes/thesis beside the repository.
        None => sw_renderer::thesis_scenes::default_dir(),
    };
    let settings = ProjectionSettings {
        thesis_scenes,
        scene: r
            .scene
            .clone()
            .unwrap_or_else(|| "Simple_plane_scene".into()),
        width: r.width.unwrap_or(1920),
        height: r.height.unwrap_or(1080),
        fpl_mhz: r.fpl_mhz.unwrap_or(100.0),
        hp_ports: r.hp_ports.unwrap_or(1),
        dma_efficiency: r.dma_efficiency.unwrap_or(0.8),
        pack_cycles: r.pack_cycles.unwrap_or(40.0),
    };
    if !stages.contains(&Stage::Projection) {
        return Ok(settings);
    }
    let scene_dir = settings.thesis_scenes.join(&settings.scene);
    if !scene_dir.is_dir() {
        return Err(err("projection.thesis_scenes", format!(
            "{} is not a directory: expected the thesis' scene directories (set thesis_scenes, relative to this file, or RTFPGA_THESIS_SCENES, and scene)",
            scene_dir.display()
        )));
    }
    let latency = hdl::mt::latency(first.format, first.depth);
    stream_design(&settings, first, latency, 1.0 / first.lanes as f64)
        .map_err(|e| err("projection", format!("{e:#}")))?;
    Ok(settings)
}
