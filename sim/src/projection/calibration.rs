//! The thesis' measured frame times, the fit of the board's constants on some of them and
//! the comparison with all the others.
//!
//! Four constants are fitted from four measurements, each pair exactly (two equations, two
//! unknowns): the ARM's per-ray and per-test costs from the software renders of Simple plane
//! and Utah teapot at 1080p, then the AXI4-Lite access (fixed ns + fabric cycles) from the
//! accelerator renders of Simple plane at 1080p at 100 MHz (Run 1) and 214 MHz (Run 7).
//! Every other published time is a held-out check.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use sw_renderer::scene::Scene;

use super::cost::{project, Board, Design, Frontend};
use super::workload::{Traversal, Workload};
use super::ProjectionError;

/// Whether a measurement determines a constant or only checks the model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Fit,
    Check,
}

/// What ran on the board.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Setup {
    /// The software renderer on the ARM.
    Arm,
    /// `units` HLS accelerators at `fpl_mhz` whose latency the HLS report gives as
    /// `latency` = (min, max) cycles; a call takes on average the midpoint (see the docs).
    Accelerator {
        fpl_mhz: f64,
        units: u32,
        latency: (f64, f64),
    },
}

/// One published frame time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    pub label: &'static str,
    /// Where the thesis gives it.
    pub source: &'static str,
    /// Directory under the thesis scene root.
    pub scene: &'static str,
    pub width: u32,
    pub height: u32,
    pub setup: Setup,
    pub seconds: f64,
    pub role: Role,
}

const SP: &str = "Simple_plane_scene";
const SP2: &str = "Simple_plane2_scene";
const TP: &str = "Utah_teapot_scene";
/// HLS latencies (cycles, min and max) of Table 4.10.
const RUN1: (f64, f64) = (32.0, 110.0);
const RUN2: (f64, f64) = (62.0, 220.0);
const RUN5: (f64, f64) = (25.0, 85.0);
const RUN6: (f64, f64) = (30.0, 106.0);
const RUN7: (f64, f64) = (74.0, 259.0);

const fn arm(
    scene: &'static str,
    width: u32,
    height: u32,
    seconds: f64,
    role: Role,
) -> Measurement {
    Measurement {
        label: "ARM software",
        source: "Table 4.5",
        scene,
        width,
        height,
        setup: Setup::Arm,
        seconds,
        role,
    }
}

#[allow(clippy::too_many_arguments)]
const fn hw(
    label: &'static str,
    source: &'static str,
    scene: &'static str,
    height: u32,
    fpl_mhz: f64,
    units: u32,
    latency: (f64, f64),
    seconds: f64,
    role: Role,
) -> Measurement {
    let width = if height == 1080 { 1920 } else { 1280 };
    Measurement {
        label,
        source,
        scene,
        width,
        height,
        setup: Setup::Accelerator {
            fpl_mhz,
            units,
            latency,
        },
        seconds,
        role,
    }
}

/// Every frame time the thesis publishes for the ZedBoard (the fp16 run is left out: its
/// latency is not reported). Table 4.6's accelerator is Run 1's (100 MHz, same times as
/// Table 4.7); Table 4.15's units at 187 MHz are Run 7's, at 100 MHz Run 1's.
pub const THESIS_MEASUREMENTS: &[Measurement] = &[
    arm(SP, 1920, 1080, 1.54, Role::Fit),
    arm(TP, 1920, 1080, 2200.64, Role::Fit),
    arm(SP, 1280, 720, 0.6871, Role::Check),
    arm(SP2, 1920, 1080, 1.5432, Role::Check),
    arm(SP2, 1280, 720, 0.686, Role::Check),
    arm(TP, 1280, 720, 977.49, Role::Check),
    arm("Glass_pen_scene", 1920, 1080, 3406.54, Role::Check),
    arm("Glass_pen_scene", 1280, 720, 1514.191, Role::Check),
    arm("Glasses_scene", 1920, 1080, 1518.185, Role::Check),
    arm("Glasses_scene", 1280, 720, 675.041, Role::Check),
    arm("Glasses_point_scene", 1920, 1080, 2224.497, Role::Check),
    arm("Glasses_point_scene", 1280, 720, 989.516, Role::Check),
    arm("All_materials_scene", 1920, 1080, 50479.0, Role::Check),
    arm("All_materials_scene", 1280, 720, 36723.0, Role::Check),
    hw(
        "Run 1",
        "Table 4.7",
        SP,
        1080,
        100.0,
        1,
        RUN1,
        23.94,
        Role::Fit,
    ),
    hw(
        "Run 7",
        "Table 4.7",
        SP,
        1080,
        214.0,
        1,
        RUN7,
        17.36,
        Role::Fit,
    ),
    hw(
        "Run 2",
        "Table 4.7",
        SP,
        1080,
        100.0,
        1,
        RUN2,
        26.87,
        Role::Check,
    ),
    hw(
        "Run 3",
        "Table 4.7",
        SP,
        1080,
        250.0,
        1,
        RUN1,
        21.95,
        Role::Check,
    ),
    hw(
        "Run 4",
        "Table 4.7",
        SP,
        1080,
        250.0,
        1,
        RUN2,
        23.17,
        Role::Check,
    ),
    hw(
        "Run 5",
        "Table 4.7",
        SP,
        1080,
        250.0,
        1,
        RUN5,
        15.33,
        Role::Check,
    ),
    hw(
        "Run 6",
        "Table 4.7",
        SP,
        1080,
        250.0,
        1,
        RUN6,
        14.66,
        Role::Check,
    ),
    hw(
        "HW baseline",
        "Table 4.6",
        SP,
        1080,
        100.0,
        1,
        RUN1,
        24.0236,
        Role::Check,
    ),
    hw(
        "HW baseline",
        "Table 4.6",
        SP,
        720,
        100.0,
        1,
        RUN1,
        10.71,
        Role::Check,
    ),
    hw(
        "HW baseline",
        "Table 4.6",
        SP2,
        1080,
        100.0,
        1,
        RUN1,
        23.9776,
        Role::Check,
    ),
    hw(
        "HW baseline",
        "Table 4.6",
        SP2,
        720,
        100.0,
        1,
        RUN1,
        10.69,
        Role::Check,
    ),
    hw(
        "x2",
        "Table 4.15",
        SP,
        1080,
        187.0,
        2,
        RUN7,
        17.03,
        Role::Check,
    ),
    hw(
        "x2",
        "Table 4.15",
        SP,
        1080,
        100.0,
        2,
        RUN1,
        24.70,
        Role::Check,
    ),
    hw(
        "x4",
        "Table 4.15",
        SP,
        1080,
        100.0,
        4,
        RUN1,
        21.46,
        Role::Check,
    ),
    hw(
        "x8",
        "Table 4.15",
        SP,
        1080,
        100.0,
        8,
        RUN1,
        26.81,
        Role::Check,
    ),
];

/// Workloads of the thesis scenes, rendered once each.
pub struct Workloads {
    root: PathBuf,
    cache: HashMap<(String, u32, u32), Workload>,
}

impl Workloads {
    /// `root` holds the thesis scene directories (`sw_renderer::thesis_scenes::locate` finds
    /// them).
    pub fn new(root: &Path) -> Workloads {
        Workloads {
            root: root.to_path_buf(),
            cache: HashMap::new(),
        }
    }

    pub fn get(
        &mut self,
        scene: &str,
        width: u32,
        height: u32,
    ) -> Result<&Workload, ProjectionError> {
        let key = (scene.to_string(), width, height);
        if !self.cache.contains_key(&key) {
            let dir = self.root.join(scene);
            let loaded = Scene::load(&dir.to_string_lossy())
                .map_err(|e| ProjectionError::Scene(format!("{}: {e}", dir.display())))?;
            self.cache
                .insert(key.clone(), Workload::measure(&loaded, width, height)?);
        }
        Ok(&self.cache[&key])
    }
}

/// The model's time for measurement `m` with constants `b`.
pub fn modelled_s(m: &Measurement, w: &Workload, b: &Board) -> Result<f64, ProjectionError> {
    match m.setup {
        Setup::Arm => Ok(b.arm_only_s(w, Traversal::BruteForce)),
        Setup::Accelerator {
            fpl_mhz,
            units,
            latency,
        } => {
            let design = Design {
                frontend: Frontend::Thesis {
                    units,
                    cycles_per_test: (latency.0 + latency.1) / 2.0,
                },
                traversal: Traversal::BruteForce,
                fpl_mhz,
            };
            Ok(project(w, &design, b)?.total_s())
        }
    }
}

/// One line of the calibration table.
#[derive(Clone, Debug, PartialEq)]
pub struct CalibrationRow {
    pub measurement: Measurement,
    pub modelled_s: f64,
}

impl CalibrationRow {
    pub fn error_pct(&self) -> f64 {
        100.0 * (self.modelled_s / self.measurement.seconds - 1.0)
    }
}

#[derive(Clone, Debug)]
pub struct Calibration {
    pub board: Board,
    pub rows: Vec<CalibrationRow>,
}

/// Fits the board's constants and models every measurement `include` accepts (the fit's
/// own measurements are always used and listed).
pub fn calibrate(
    workloads: &mut Workloads,
    include: impl Fn(&Measurement) -> bool,
) -> Result<Calibration, ProjectionError> {
    let fits: Vec<&Measurement> = THESIS_MEASUREMENTS
        .iter()
        .filter(|m| m.role == Role::Fit)
        .collect();
    let (arm_fits, hw_fits): (Vec<&Measurement>, Vec<&Measurement>) =
        fits.iter().partition(|m| m.setup == Setup::Arm);
    let mut board = Board {
        arm_ray_ns: 0.0,
        arm_test_ns: 0.0,
        access_fixed_ns: 0.0,
        access_pl_cycles: 0.0,
    };
    let [ray, test] = fit_pair(workloads, &arm_fits, |p| Board {
        arm_ray_ns: p[0],
        arm_test_ns: p[1],
        ..board
    })?;
    board.arm_ray_ns = ray;
    board.arm_test_ns = test;
    let [fixed, cycles] = fit_pair(workloads, &hw_fits, |p| Board {
        access_fixed_ns: p[0],
        access_pl_cycles: p[1],
        ..board
    })?;
    board.access_fixed_ns = fixed;
    board.access_pl_cycles = cycles;

    let mut rows = Vec::new();
    for m in THESIS_MEASUREMENTS
        .iter()
        .filter(|m| m.role == Role::Fit || include(m))
    {
        let w = workloads.get(m.scene, m.width, m.height)?;
        rows.push(CalibrationRow {
            measurement: *m,
            modelled_s: modelled_s(m, w, &board)?,
        });
    }
    Ok(Calibration { board, rows })
}

/// Solves two measurements for the two constants `with` sets. The model is affine in them
/// on the branch the fit lands on, so three evaluations give the system; the solution is
/// then checked to reproduce both measurements (it would not if the branch changed).
fn fit_pair(
    workloads: &mut Workloads,
    fits: &[&Measurement],
    with: impl Fn([f64; 2]) -> Board,
) -> Result<[f64; 2], ProjectionError> {
    let [m0, m1] = fits else {
        return Err(ProjectionError::Fit(format!(
            "expected 2 measurements to fit 2 constants, got {}",
            fits.len()
        )));
    };
    let w0 = workloads.get(m0.scene, m0.width, m0.height)?.clone();
    let w1 = workloads.get(m1.scene, m1.width, m1.height)?.clone();
    let eval = |p: [f64; 2]| -> Result<[f64; 2], ProjectionError> {
        let b = with(p);
        Ok([modelled_s(m0, &w0, &b)?, modelled_s(m1, &w1, &b)?])
    };
    let base = eval([0.0, 0.0])?;
    let e0 = eval([1.0, 0.0])?;
    let e1 = eval([0.0, 1.0])?;
    let (a, b, c, d) = (
        e0[0] - base[0],
        e1[0] - base[0],
        e0[1] - base[1],
        e1[1] - base[1],
    );
    let (r0, r1) = (m0.seconds - base[0], m1.seconds - base[1]);
    let det = a * d - b * c;
    if det.abs() < 1e-12 * (a.abs() + b.abs()) * (c.abs() + d.abs()) {
        return Err(ProjectionError::Fit(format!(
            "{} and {} cannot separate the two constants",
            m0.label, m1.label
        )));
    }
    let p = [(r0 * d - b * r1) / det, (a * r1 - r0 * c) / det];
    let check = eval(p)?;
    for (m, got) in [(m0, check[0]), (m1, check[1])] {
        if (got / m.seconds - 1.0).abs() > 1e-6 {
            return Err(ProjectionError::Fit(format!(
                "{} ({}): the fitted constants {p:?} give {got} s, not {} s",
                m.label, m.source, m.seconds
            )));
        }
    }
    Ok(p)
}
