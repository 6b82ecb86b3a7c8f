//! The frame engine (`hdl::frame::engine`, docs/frame.md "The frame engine (design)")
//! co-simulated through Verilator, its traversal unit played in Rust by the frame model's own
//! (`hw_model::frame::Frame::cast`: the traversal unit's model, as the frame model casts its
//! rays): each ray packet taken is answered after a random delay, the answers handed back in
//! a random order, the pixel stream under random back-pressure. The image and the counters
//! are then the frame model's to compare bit for bit.
//!
//! A watchdog turns an engine that stops making progress into an error describing its state
//! instead of a hang; a packet or a pixel that breaks the ports' contract (an unknown or
//! duplicate id, a pixel twice or out of the frame) is an error naming it.

mod verilated;

pub use verilated::{engine_model, EngineModel, In, Out, VerilatedEngine};

use hdl::frame::engine::{EngineError, EngineFrame, LoadTarget, COUNTERS};
use hdl::frame::id_queue::IDS;
use hw_model::fp32::{Fp32, Vec3};
use hw_model::frame::accumulate::Contribution;
use hw_model::frame::{Frame, FrameError, FrameRay, FrameStats, Load, RayKind};
use hw_model::traversal::packet::hit_to_words;
use hw_model::traversal::UnitRay;
use image::RgbImage;
use rand::{rngs::StdRng, Rng, SeedableRng};
use sw_renderer::hit::Hit;

use crate::SimError;

/// What the engine is built with: its operators' depth and its triangle memory's address
/// bits (12: 4,096 triangles; 14: `FrameLimits::HW`'s 16,384).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EngineConfig {
    pub depth: usize,
    pub triangle_bits: usize,
}

/// Cycles without progress (a handshake on any stream) after which the engine is declared
/// hung. The longest quiet stretch is the escape's census (`escape::CENSUS_CYCLES`) and
/// the played unit's delay, far below this.
pub const WATCHDOG_CYCLES: u64 = 20_000;

#[derive(Debug, thiserror::Error)]
pub enum FrameSimError {
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error("the frame engine: {0}")]
    Engine(#[from] EngineError),
    #[error(transparent)]
    Frame(#[from] FrameError),
    #[error("frame engine, cycle {cycle}: {message}")]
    Protocol { cycle: u64, message: String },
    #[error("frame engine hangs: no progress for {cycles} cycles while {state}")]
    Timeout { cycles: u64, state: String },
    #[error("frame engine: {0}")]
    Usage(String),
}

/// The played traversal unit's and the pixel consumer's behaviour, reproducible from the
/// seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traffic {
    /// Probability that the ray stream's `tready` is low in a cycle.
    pub ray_stall: f64,
    /// An answer is ready 0 to `max_delay` cycles after its ray (uniformly), and ready
    /// answers are handed back in a random order.
    pub max_delay: u64,
    /// Probability that the pixel stream's `tready` is low in a cycle.
    pub pixel_stall: f64,
    pub seed: u64,
}

impl Traffic {
    fn check(&self) -> Result<(), FrameSimError> {
        for (name, p) in [
            ("ray_stall", self.ray_stall),
            ("pixel_stall", self.pixel_stall),
        ] {
            if !(0.0..1.0).contains(&p) {
                return Err(FrameSimError::Usage(format!(
                    "traffic {name} = {p}: a probability in [0, 1) is needed (1 would never let a beat through)"
                )));
            }
        }
        Ok(())
    }
}

/// A frame's counts, as the engine's counters give them and as the frame model's stats do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameCounts {
    pub pixels: u64,
    /// Rays by kind, `RayKind::ALL`'s order.
    pub rays: [u64; 4],
    pub hits: u64,
    pub occluded: u64,
    pub zero_shadows: u64,
    pub past_depth: u64,
    pub total_internal: u64,
}

impl FrameCounts {
    /// The frame model's counts of a `pixels`-pixel frame.
    pub fn of_model(stats: &FrameStats, pixels: u64) -> FrameCounts {
        FrameCounts {
            pixels,
            rays: RayKind::ALL.map(|k| stats.of_kind(k)),
            hits: stats.hits,
            occluded: stats.occluded,
            zero_shadows: stats.zero_shadows,
            past_depth: stats.past_depth,
            total_internal: stats.total_internal,
        }
    }
}

/// What a co-simulated frame gave.
#[derive(Clone, Debug)]
pub struct FrameRun {
    pub image: RgbImage,
    pub counts: FrameCounts,
    /// The engine's cycles from its start to its last pixel out (its counter).
    pub cycles: u64,
    /// Thread starts that went by the escape below the escape reserve (its counter).
    pub escape_starts: u64,
    /// The most rays the played unit held at once.
    pub peak_in_unit: usize,
    /// Every simulated cycle, the loads included.
    pub sim_cycles: u64,
}

/// The engine's constants for `frame` (TB from `config`).
pub fn engine_frame(
    config: &EngineConfig,
    frame: &Frame,
    store: Option<usize>,
) -> Result<EngineFrame, FrameSimError> {
    let (c, p) = (frame.constants(), frame.program());
    Ok(match config.triangle_bits {
        12 => EngineFrame::new::<12>(c, p, store)?,
        14 => EngineFrame::new::<14>(c, p, store)?,
        bits => {
            return Err(FrameSimError::Usage(format!(
                "a triangle memory of {bits} address bits: the co-simulation builds 12 or 14"
            )))
        }
    })
}

/// A ray packet as the frame model's traversal unit takes it (`frame::engine::unit_ray`
/// reads the geometry and whether it is a shadow ray).
fn packet_ray(r: &UnitRay) -> FrameRay {
    let v = |a: [f32; 3]| {
        let [x, y, z] = a.map(Fp32::new);
        Vec3::new(x, y, z)
    };
    FrameRay {
        pixel: 0,
        orig: v(r.orig),
        dir: v(r.dir),
        t_max: Fp32::new(r.t_max),
        load: if r.any_hit {
            Load::Shadow {
                contribution: Contribution([0; 3]),
            }
        } else {
            Load::Cast {
                kind: RayKind::Primary,
                depth: 0,
                weight: Vec3::ZERO,
            }
        },
    }
}

/// Runs one frame of `frame` (its constants loaded first) on a fresh engine of `model`,
/// its reserves for a store of `store` entries (`None`: the defaults; see
/// `EngineFrame::new`), its traversal unit played with `traffic`.
pub fn run_frame(
    model: &EngineModel,
    frame: &Frame,
    store: Option<usize>,
    traffic: Traffic,
) -> Result<FrameRun, FrameSimError> {
    traffic.check()?;
    let setup = engine_frame(&model.config, frame, store)?;
    let mut e = VerilatedEngine::new(model)?;
    for word in &setup.loads {
        let strobe = match word.target {
            LoadTarget::Program => In::LoadProgram,
            LoadTarget::Constant => In::LoadConstant,
            LoadTarget::Triangle => In::LoadTriangle,
            LoadTarget::Object => In::LoadObject,
        };
        e.set(strobe, 1);
        e.set(In::LoadAddress, word.address as u32);
        e.load_data().copy_from_slice(&word.data);
        e.cycle()?;
        e.set(strobe, 0);
    }
    e.set(In::Width, setup.width);
    e.set(In::Height, setup.height);
    e.camera().copy_from_slice(&setup.camera);
    e.set(In::MissEntry, u32::from(setup.miss_entry));
    e.set(In::MissCasts, u32::from(setup.miss_casts));
    e.set(In::MaxDepth, setup.max_depth);
    e.set(In::Reservation, setup.reservation as u32);
    e.set(In::SpawnReserve, setup.spawn_reserve as u32);
    e.set(In::EscapeReserve, setup.escape_reserve as u32);
    e.cycle()?;
    let before = e.core_counters();
    e.set(In::Start, 1);
    e.cycle()?;
    e.set(In::Start, 0);

    let (w, h) = (setup.width, setup.height);
    let pixels = (w * h) as usize;
    let mut image: Vec<Option<[u8; 3]>> = vec![None; pixels];
    let mut rng = StdRng::seed_from_u64(traffic.seed);
    // Rays in the played unit: (due cycle, id, answer); an id in flight at most once.
    let mut in_unit: Vec<(u64, u32, Option<Hit>)> = Vec::new();
    let mut flying = vec![false; IDS];
    let mut presenting: Option<u32> = None;
    let (mut peak, mut last_progress, mut out) = (0, e.cycles(), 0usize);
    let mut hits = Vec::new();
    while e.get(Out::Done) == 0 || e.get(Out::Idle) == 0 {
        let now = e.cycles();
        if presenting.is_none() {
            let due: Vec<usize> = (0..in_unit.len())
                .filter(|&k| in_unit[k].0 <= now)
                .collect();
            if !due.is_empty() {
                let (_, id, hit) = in_unit.swap_remove(due[rng.gen_range(0..due.len())]);
                e.hit_data().copy_from_slice(&hit_to_words(id, hit));
                presenting = Some(id);
            }
        }
        let ray_ready = !(traffic.ray_stall > 0.0 && rng.gen_bool(traffic.ray_stall));
        let pixel_ready = !(traffic.pixel_stall > 0.0 && rng.gen_bool(traffic.pixel_stall));
        e.set(In::HitTvalid, u32::from(presenting.is_some()));
        e.set(In::RayTready, u32::from(ray_ready));
        e.set(In::PixelReady, u32::from(pixel_ready));
        e.cycle()?;
        let cycle = e.cycles();
        let protocol = |message| FrameSimError::Protocol { cycle, message };
        let mut progress = false;
        if let Some(id) = presenting {
            if e.get(Out::HitTready) == 1 {
                flying[id as usize] = false;
                presenting = None;
                progress = true;
            }
        }
        if ray_ready && e.get(Out::RayTvalid) == 1 {
            let r = UnitRay::from_words(&e.ray_data());
            if r.id as usize >= IDS || flying[r.id as usize] {
                return Err(protocol(format!(
                    "a ray packet with id {}, {}",
                    r.id,
                    if r.id as usize >= IDS {
                        format!("beyond the store's {IDS} entries")
                    } else {
                        "already in the traversal unit".into()
                    }
                )));
            }
            if r.t_min != 0.0 || r.exclude.is_some() {
                return Err(protocol(format!(
                    "ray {}: t_min {} and excluded triangle {:?}; the frame's rays have 0 and none",
                    r.id, r.t_min, r.exclude
                )));
            }
            frame.cast(&[packet_ray(&r)], &mut hits)?;
            flying[r.id as usize] = true;
            in_unit.push((cycle + rng.gen_range(0..=traffic.max_delay), r.id, hits[0]));
            peak = peak.max(in_unit.len() + usize::from(presenting.is_some()));
            progress = true;
        }
        if pixel_ready && e.get(Out::PixelValid) == 1 {
            let index = e.get(Out::PixelIndex) as usize;
            let rgb = e.get(Out::PixelRgb).to_le_bytes();
            match image.get_mut(index) {
                None => return Err(protocol(format!("pixel {index} of a {w}×{h} frame"))),
                Some(Some(_)) => return Err(protocol(format!("pixel {index} twice"))),
                Some(p) => *p = Some([rgb[0], rgb[1], rgb[2]]),
            }
            out += 1;
            progress = true;
        }
        if progress {
            last_progress = cycle;
        } else if cycle - last_progress > WATCHDOG_CYCLES {
            return Err(FrameSimError::Timeout {
                cycles: WATCHDOG_CYCLES,
                state: format!(
                    "running a {w}×{h} frame: {out} pixels out, {} rays in the traversal unit, an answer offered: {}; counters {:?}",
                    in_unit.len(),
                    presenting.is_some(),
                    COUNTERS.iter().zip(e.counters()).collect::<Vec<_>>()
                ),
            });
        }
    }
    let cycle = e.cycles();
    let missing = image.iter().filter(|p| p.is_none()).count();
    if missing > 0 || !in_unit.is_empty() || presenting.is_some() {
        return Err(FrameSimError::Protocol {
            cycle,
            message: format!(
                "done with {missing} of {pixels} pixels missing and {} rays unanswered",
                in_unit.len() + usize::from(presenting.is_some())
            ),
        });
    }
    let mut img = RgbImage::new(w, h);
    for (k, p) in image.into_iter().enumerate() {
        let rgb = p.expect("every pixel was checked");
        img.put_pixel(k as u32 % w, k as u32 / w, image::Rgb(rgb));
    }
    let n = e.counters().map(u64::from);
    let core = e.core_counters();
    let delta = |k: usize| u64::from(core[k].wrapping_sub(before[k]));
    Ok(FrameRun {
        image: img,
        counts: FrameCounts {
            pixels: n[0],
            rays: [n[1], n[2], n[3], n[4]],
            hits: n[5],
            occluded: n[6],
            zero_shadows: delta(0),
            past_depth: delta(1),
            total_internal: delta(2),
        },
        escape_starts: n[7],
        cycles: n[8],
        peak_in_unit: peak,
        sim_cycles: e.cycles(),
    })
}
