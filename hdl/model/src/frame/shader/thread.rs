//! The frame's rays as the shader core's threads and back: a returned cast ray and its
//! answer → a [`ThreadInput`]; a [`ThreadOutput`] → the frame model's spawned rays, counters
//! and [`Settle`] record. Shadow rays need no program: [`shade`] settles them itself (their
//! contribution if nothing occluded them), as the frame unit does beside the core.

use sw_renderer::hit::Hit;

use super::compile::ProgramKind;
use super::interpret::{run, Program, RunError, ThreadInput, ThreadOutput};
use super::isa::{Counter, PushKind, Word3};
use crate::fp32::{Fp32, Vec3};
use crate::frame::accumulate::{Contribution, Settle};
use crate::frame::constants::FrameConstants;
use crate::frame::shade::{FrameRay, Load, RayKind, Shaded};

fn words(v: Vec3) -> Word3 {
    v.components().map(Fp32::bits)
}

fn vec3(w: Word3) -> Vec3 {
    let [x, y, z] = w.map(Fp32::from_bits);
    Vec3::new(x, y, z)
}

/// What shades a returned cast ray: the miss program or its hit material's.
pub fn program_kind(c: &FrameConstants, hit: Option<&Hit>) -> ProgramKind {
    match hit {
        None => ProgramKind::Miss,
        Some(h) => {
            let object = c.triangles[h.triangle as usize].object;
            ProgramKind::of(c.materials[object as usize].kind)
        }
    }
}

/// The thread a returned cast ray runs (`program` compiled from `c`); `None` for a shadow
/// ray, which runs none.
pub fn input(
    program: &Program,
    c: &FrameConstants,
    ray: &FrameRay,
    hit: Option<&Hit>,
) -> Option<ThreadInput> {
    let Load::Cast { depth, weight, .. } = ray.load else {
        return None;
    };
    let mut registers = [[0; 3]; 7];
    registers[0] = words(ray.orig);
    registers[1] = words(ray.dir);
    registers[2] = words(weight);
    let (entry, material) = match hit {
        None => (program.miss_entry, 0),
        Some(h) => {
            let tri = &c.triangles[h.triangle as usize];
            registers[3] = [h.t, h.u, h.v].map(|x| Fp32::new(x).bits());
            for (r, n) in registers[4..].iter_mut().zip(tri.normals) {
                *r = words(n);
            }
            (program.material_entry[tri.object as usize], tri.object)
        }
    };
    Some(ThreadInput {
        entry,
        material,
        registers,
        past_depth: depth + 1 > c.max_depth,
    })
}

/// A thread of `ray` as the frame model's records: its pushed rays appended to
/// `out.spawned` (its pixel; cast rays one deeper, `t_max` = `Fp32::MAX`), its counters added
/// to `out`'s; its settle record.
pub fn settle(ray: &FrameRay, thread: &ThreadOutput, out: &mut Shaded) -> Settle {
    let depth = match ray.load {
        Load::Cast { depth, .. } => depth + 1,
        Load::Shadow { .. } => 0,
    };
    for p in &thread.pushed {
        let (load, t_max) = match p.kind {
            PushKind::Shadow => (
                Load::Shadow {
                    contribution: Contribution(p.payload.map(|w| w as i32)),
                },
                Fp32::from_bits(p.t_max),
            ),
            PushKind::Reflection | PushKind::Refraction => (
                Load::Cast {
                    kind: if p.kind == PushKind::Reflection {
                        RayKind::Reflection
                    } else {
                        RayKind::Refraction
                    },
                    depth,
                    weight: vec3(p.payload),
                },
                Fp32::MAX,
            ),
        };
        out.spawned.push(FrameRay {
            pixel: ray.pixel,
            orig: vec3(p.origin),
            dir: vec3(p.direction),
            t_max,
            load,
        });
    }
    for (counter, &n) in Counter::ALL.iter().zip(&thread.counters) {
        *match counter {
            Counter::ZeroShadow => &mut out.zero_shadows,
            Counter::PastDepth => &mut out.past_depth,
            Counter::TotalInternal => &mut out.total_internal,
        } += u64::from(n);
    }
    Settle {
        sum: thread.sum.map(i64::from),
        spawned: thread.pushed.len() as u32,
    }
}

/// A thread the shader core ran: its program's kind and the instructions it issued.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Issued {
    pub kind: ProgramKind,
    pub instructions: u32,
}

/// Shades a returned ray as the frame unit does: a shadow ray beside the shader core (its
/// contribution if unoccluded, nothing spawned), a cast ray by its thread of `program`
/// (compiled from `c`). Spawned rays and counters go to `out`; the ray's settle record and
/// the thread, if one ran.
pub fn shade(
    program: &Program,
    c: &FrameConstants,
    ray: &FrameRay,
    hit: Option<&Hit>,
    out: &mut Shaded,
) -> Result<(Settle, Option<Issued>), RunError> {
    let Some(thread) = input(program, c, ray, hit) else {
        let settle = match (ray.load, hit) {
            (Load::Shadow { contribution }, None) => Settle::of(&[contribution], 0),
            _ => Settle::default(),
        };
        return Ok((settle, None));
    };
    let output = run(program, &thread)?;
    let issued = Issued {
        kind: program_kind(c, hit),
        instructions: output.instructions,
    };
    Ok((settle(ray, &output, out), Some(issued)))
}
