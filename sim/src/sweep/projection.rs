//! The projected ZedBoard frame of every point: the board model is calibrated once on the
//! thesis' measurements and the frame's work counted once; each point then only changes the
//! stream design (lanes, pipeline latency, cycles per test), as `rtfpga project` builds it.

use anyhow::{Context, Result};

use crate::projection::{
    calibrate, project, Board, Design, Frontend, Traversal, Workload, Workloads,
};

use super::config::ProjectionSettings;
use super::point::Point;

pub struct Projector {
    settings: ProjectionSettings,
    board: Board,
    workload: Workload,
}

/// One point's projected frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    pub frame_s: f64,
    /// The modelled ARM-only (software, brute force) time of the frame over `frame_s`.
    pub speedup_vs_arm: f64,
}

impl Projector {
    /// Calibrates the board (fitting rows only) and counts the projected frame's work.
    pub fn new(settings: &ProjectionSettings) -> Result<Projector> {
        let mut workloads = Workloads::new(&settings.thesis_scenes);
        let calibration = calibrate(&mut workloads, |_| false)
            .context("calibrating the ZedBoard model on the thesis' measurements")?;
        let workload = workloads
            .get(&settings.scene, settings.width, settings.height)
            .with_context(|| {
                format!(
                    "counting the work of {} at {}x{}",
                    settings.scene, settings.width, settings.height
                )
            })?
            .clone();
        Ok(Projector {
            settings: settings.clone(),
            board: calibration.board,
            workload,
        })
    }

    /// The modelled ARM-only (software) time of the projected frame, brute force as the thesis.
    pub fn arm_only_s(&self) -> f64 {
        self.board.arm_only_s(&self.workload, Traversal::BruteForce)
    }

    pub fn project(
        &self,
        point: &Point,
        latency: usize,
        cycles_per_test: f64,
    ) -> Result<Projected> {
        let design = stream_design(&self.settings, point, latency, cycles_per_test)?;
        let frame_s = project(&self.workload, &design, &self.board)?.total_s();
        Ok(Projected {
            frame_s,
            speedup_vs_arm: self.arm_only_s() / frame_s,
        })
    }
}

/// The stream design of `point` on the board `settings` describe, checked.
pub fn stream_design(
    s: &ProjectionSettings,
    point: &Point,
    latency: usize,
    cycles_per_test: f64,
) -> Result<Design> {
    let d = Design {
        frontend: Frontend::Stream {
            lanes: u32::try_from(point.lanes)?,
            // The frontend's cycles are per lane: a lane takes a query every
            // `lanes × cycles per test` cycles of the whole accelerator.
            cycles_per_test: cycles_per_test * point.lanes as f64,
            pipeline_latency: u32::try_from(latency)?,
            hp_ports: s.hp_ports,
            dma_efficiency: s.dma_efficiency,
            pack_arm_cycles: s.pack_cycles,
        },
        traversal: Traversal::Bvh,
        fpl_mhz: s.fpl_mhz,
    };
    d.validate()?;
    Ok(d)
}
