//! The frame engine's thread start: a returned cast ray (its ray-store entry and the
//! traversal unit's answer) → the shader core's thread start, bit for bit
//! `hw_model::frame::shader::thread::input`, and whether its program may push reflection or
//! refraction rays (the ray store's escape rule reads it; docs/frame.md "The frame engine").
//!
//! ```text
//! stage A   the ray and its answer; the triangle memory reads the hit triangle's word
//!           (its object and three vertex normals)
//! stage B   the start: the object table reads the object's word (its program's entry
//!           point and cast flag); a miss takes the miss entry and zeros
//! ```
//!
//! The start, as `thread::input` makes it: r0..r2 = origin, direction, weight; a hit: r3 =
//! (t, u, v), r4..r6 = the triangle's vertex normals, material = its object, the object's
//! entry point; a miss: r3..r6 = 0, material 0, the miss entry; past depth = depth + 1 >
//! max depth. The tag (pixel, depth) passes through.
//!
//! **The start decision**, at stage B (docs/frame.md "Why it cannot deadlock"): a start
//! may go if `fits` (the ray ids: M available) and either `fits_above_reserve` (M and the
//! escape reserve), or its program pushes no reflection or refraction ray, or it is the
//! escape (the escape pixel's slot and its deepest depth in flight): the schedule model's
//! `can_start`, with the ray ids' M for its M − 1. Decided once: a start that may go is
//! committed (`started`: its entry freed, M reserved, its cast ray leaves the escape count)
//! and offered to the core until taken (the core claims a thread and loads it over several
//! cycles, so an offer must hold); one that may not is `deferred` (its `id` back to the
//! waiting queue's tail) and leaves stage B at once.
//!
//! One ray a cycle, valid/ready: a stage moves on when the one after it is free, and a
//! stalled stage keeps its memory's address, so the word it read stays shown. `in_ready`
//! follows `out_ready` in the same cycle (two stages, no queue). The ray's id passes through.
//!
//! The memories are loaded through the load port between frames ([`loads`]): a triangle's
//! word at its index, an object's at its index; the miss entry, its cast flag and the max
//! depth are inputs held while a frame runs. No reset: the stages start empty from the
//! flip-flops' power-on zeros.

use hw_model::frame::shader::Program;
use hw_model::frame::{FrameConstants, FrameLimits};
use rust_hdl::prelude::*;
use thiserror::Error;

use super::accumulate::PIXEL_SLOT_BITS;
use super::id_queue::Id;
use super::ray_store::{stored_answer, StoreError, StoredRay};
use super::raygen::PIXEL_BITS;
use super::shader::core::{DEPTH_BITS, MATERIAL_BITS, PC_BITS};
use crate::harness::{built_verilog, simulate_driven, Stepped};
use crate::macros::dff_setup;
use hw_model::frame::shader::isa::{Word3, CODE};
use hw_model::frame::shader::ThreadInput;
use hw_model::frame::FrameRay;
use sw_renderer::hit::Hit;

type Lanes = Bits<96>;

/// Address bits of the object table: `FrameLimits::HW`'s objects.
pub const OBJECT_BITS: usize = 6;
/// Objects the table holds.
pub const OBJECTS: usize = 1 << OBJECT_BITS;
/// A triangle's word: its three vertex normals (96 bits each, from bit 0), its object above.
pub const TRIANGLE_WORD_BITS: usize = 3 * 96 + OBJECT_BITS;
/// An object's word: its program's entry point, the cast flag above it.
const OBJECT_WORD_BITS: usize = PC_BITS + 1;
const _: () = {
    assert!(OBJECTS == FrameLimits::HW.objects);
    assert!(OBJECT_BITS <= MATERIAL_BITS && 1 << PC_BITS == CODE);
    // The kernel's literal offsets and widths.
    assert!(TRIANGLE_WORD_BITS == 294 && OBJECT_WORD_BITS == 12 && PC_BITS == 11);
};

/// Cycles from a ray taken to its start shown, the output free.
pub const LATENCY: usize = 2;

/// Triangles a triangle memory of `bits` address bits holds.
pub const fn triangles(bits: usize) -> usize {
    1 << bits
}

/// Returned cast rays in, the shader core's thread starts out; a triangle memory of `TB`
/// address bits ([`triangles`]`(TB)` triangles, at least [`OBJECTS`]: the load port's
/// address is the triangle's), a parameter: `FrameLimits::HW`'s 16,384 (`TB` = 14) are 132
/// RAMB36, the whole XC7Z020.
#[derive(LogicBlock, Default)]
pub struct ThreadStart<const TB: usize> {
    pub clock: Signal<In, Clock>,
    // The load port, between frames: a triangle's or an object's word at `load_address`.
    pub load_triangle: Signal<In, Bit>,
    pub load_object: Signal<In, Bit>,
    pub load_address: Signal<In, Bits<TB>>,
    pub load_data: Signal<In, Bits<TRIANGLE_WORD_BITS>>,
    // Held while a frame runs.
    pub miss_entry: Signal<In, Bits<PC_BITS>>,
    pub miss_casts: Signal<In, Bit>,
    pub max_depth: Signal<In, Bits<DEPTH_BITS>>,
    // Returned cast rays: the ray-store entry's fields and the answer.
    pub in_valid: Signal<In, Bit>,
    pub in_ready: Signal<Out, Bit>,
    pub in_pixel: Signal<In, Bits<PIXEL_BITS>>,
    pub in_depth: Signal<In, Bits<DEPTH_BITS>>,
    pub in_origin: Signal<In, Lanes>,
    pub in_direction: Signal<In, Lanes>,
    pub in_weight: Signal<In, Lanes>,
    pub in_hit: Signal<In, Bit>,
    pub in_triangle: Signal<In, Bits<TB>>,
    pub in_tuv: Signal<In, Lanes>,
    pub in_id: Signal<In, Id>,
    // The start decision's inputs: the ray ids' and the escape pixel's.
    pub fits: Signal<In, Bit>,
    pub fits_above_reserve: Signal<In, Bit>,
    pub escape_valid: Signal<In, Bit>,
    pub escape_slot: Signal<In, Bits<PIXEL_SLOT_BITS>>,
    pub escape_in_flight: Signal<In, Bit>,
    pub escape_deepest: Signal<In, Bits<DEPTH_BITS>>,
    /// The start at stage B committed this cycle, or deferred (its `id` back to the tail).
    pub started: Signal<Out, Bit>,
    pub deferred: Signal<Out, Bit>,
    pub id: Signal<Out, Id>,
    // Thread starts (the core's start port) and the program's cast flag.
    pub out_valid: Signal<Out, Bit>,
    pub out_ready: Signal<In, Bit>,
    pub entry: Signal<Out, Bits<PC_BITS>>,
    pub material: Signal<Out, Bits<MATERIAL_BITS>>,
    pub registers: [Signal<Out, Lanes>; 7],
    pub past_depth: Signal<Out, Bit>,
    pub pixel: Signal<Out, Bits<PIXEL_BITS>>,
    pub depth: Signal<Out, Bits<DEPTH_BITS>>,
    /// The program may push reflection or refraction rays.
    pub casts: Signal<Out, Bit>,
    triangles: RAM<Bits<TRIANGLE_WORD_BITS>, TB>,
    objects: RAM<Bits<OBJECT_WORD_BITS>, OBJECT_BITS>,
    // Stage A.
    a_valid: DFF<Bit>,
    a_pixel: DFF<Bits<PIXEL_BITS>>,
    a_depth: DFF<Bits<DEPTH_BITS>>,
    a_ray: [DFF<Lanes>; 3],
    a_hit: DFF<Bit>,
    a_triangle: DFF<Bits<TB>>,
    a_tuv: DFF<Lanes>,
    a_id: DFF<Id>,
    // Stage B.
    b_valid: DFF<Bit>,
    b_pixel: DFF<Bits<PIXEL_BITS>>,
    b_depth: DFF<Bits<DEPTH_BITS>>,
    b_registers: [DFF<Lanes>; 7],
    b_hit: DFF<Bit>,
    b_object: DFF<Bits<OBJECT_BITS>>,
    b_id: DFF<Id>,
    /// Stage B's start is committed and offered.
    committed: DFF<Bit>,
    allowed: Signal<Local, Bit>,
    undecided: Signal<Local, Bit>,
    taken: Signal<Local, Bit>,
    accept: Signal<Local, Bit>,
    a_to_b: Signal<Local, Bit>,
    b_free: Signal<Local, Bit>,
}

impl<const TB: usize> Logic for ThreadStart<TB> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, a_valid, a_pixel, a_depth, a_hit, a_triangle, a_tuv);
        dff_setup!(self, clock, b_valid, b_pixel, b_depth, b_hit, b_object);
        dff_setup!(self, clock, a_id, b_id, committed);
        self.triangles.read_clock.next = self.clock.val();
        self.triangles.write_clock.next = self.clock.val();
        self.objects.read_clock.next = self.clock.val();
        self.objects.write_clock.next = self.clock.val();

        // The load port.
        self.triangles.write_enable.next = self.load_triangle.val();
        self.triangles.write_address.next = self.load_address.val();
        self.triangles.write_data.next = self.load_data.val();
        self.objects.write_enable.next = self.load_object.val();
        self.objects.write_address.next = self.load_address.val().get_bits::<OBJECT_BITS>(0);
        self.objects.write_data.next = self.load_data.val().get_bits::<OBJECT_WORD_BITS>(0);

        // The start shown.
        self.pixel.next = self.b_pixel.q.val();
        self.depth.next = self.b_depth.q.val();
        self.past_depth.next = self.b_depth.q.val() >= self.max_depth.val();
        self.material.next = bit_cast::<MATERIAL_BITS, OBJECT_BITS>(self.b_object.q.val());
        for k in 0..7 {
            self.registers[k].next = self.b_registers[k].q.val();
        }
        self.entry.next = self.miss_entry.val();
        self.casts.next = self.miss_casts.val();
        if self.b_hit.q.val() {
            self.entry.next = self.objects.read_data.val().get_bits::<PC_BITS>(0);
            self.casts.next = self.objects.read_data.val().get_bit(11);
        }

        // The start decision.
        self.allowed.next = self.fits.val()
            & (self.fits_above_reserve.val()
                | !self.casts.val()
                | (self.escape_valid.val()
                    & self.escape_in_flight.val()
                    & (self.escape_slot.val()
                        == self.b_pixel.q.val().get_bits::<PIXEL_SLOT_BITS>(0))
                    & (self.escape_deepest.val() == self.b_depth.q.val())));
        self.undecided.next = self.b_valid.q.val() & !self.committed.q.val();
        self.started.next = self.undecided.val() & self.allowed.val();
        self.deferred.next = self.undecided.val() & !self.allowed.val();
        self.out_valid.next = self.committed.q.val() | self.started.val();
        self.taken.next = self.out_valid.val() & self.out_ready.val();
        self.committed.d.next = self.out_valid.val() & !self.out_ready.val();
        self.id.next = self.b_id.q.val();

        // Handshakes: a stage moves on when the one after it is free.
        self.b_free.next = !self.b_valid.q.val() | self.taken.val() | self.deferred.val();
        self.a_to_b.next = self.a_valid.q.val() & self.b_free.val();
        self.in_ready.next = !self.a_valid.q.val() | self.a_to_b.val();
        self.accept.next = self.in_valid.val() & self.in_ready.val();

        // Stage A: the ray taken; the triangle memory reads its triangle (a stalled stage
        // its own, so the word stays shown).
        self.a_valid.d.next = self.accept.val() | (self.a_valid.q.val() & !self.a_to_b.val());
        self.triangles.read_address.next = self.a_triangle.q.val();
        if self.accept.val() {
            self.a_pixel.d.next = self.in_pixel.val();
            self.a_depth.d.next = self.in_depth.val();
            self.a_hit.d.next = self.in_hit.val();
            self.a_triangle.d.next = self.in_triangle.val();
            self.a_tuv.d.next = self.in_tuv.val();
            self.a_id.d.next = self.in_id.val();
            self.triangles.read_address.next = self.in_triangle.val();
        }
        for k in 0..3 {
            dff_setup!(self, clock, a_ray[k]);
        }
        if self.accept.val() {
            self.a_ray[0].d.next = self.in_origin.val();
            self.a_ray[1].d.next = self.in_direction.val();
            self.a_ray[2].d.next = self.in_weight.val();
        }

        // Stage B: the start; the object table reads the object (a stalled stage its own).
        self.b_valid.d.next = self.a_to_b.val() | (self.b_valid.q.val() & !self.b_free.val());
        self.objects.read_address.next = self.b_object.q.val();
        for k in 0..7 {
            dff_setup!(self, clock, b_registers[k]);
        }
        if self.a_to_b.val() {
            self.b_pixel.d.next = self.a_pixel.q.val();
            self.b_id.d.next = self.a_id.q.val();
            self.b_depth.d.next = self.a_depth.q.val();
            self.b_hit.d.next = self.a_hit.q.val();
            self.b_object.d.next = 0.into();
            self.b_registers[3].d.next = 0.into();
            self.b_registers[4].d.next = 0.into();
            self.b_registers[5].d.next = 0.into();
            self.b_registers[6].d.next = 0.into();
            if self.a_hit.q.val() {
                self.b_object.d.next = self.triangles.read_data.val().get_bits::<OBJECT_BITS>(288);
                self.b_registers[3].d.next = self.a_tuv.q.val();
                self.b_registers[4].d.next = self.triangles.read_data.val().get_bits::<96>(0);
                self.b_registers[5].d.next = self.triangles.read_data.val().get_bits::<96>(96);
                self.b_registers[6].d.next = self.triangles.read_data.val().get_bits::<96>(192);
            }
            self.objects.read_address.next =
                self.triangles.read_data.val().get_bits::<OBJECT_BITS>(288);
        }
        for k in 0..3 {
            if self.a_to_b.val() {
                self.b_registers[k].d.next = self.a_ray[k].q.val();
            }
        }
    }
}

/// Constants the block cannot hold.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum StartLoadError {
    #[error("{count} triangles: the frame engine's triangle memory holds {capacity}")]
    Triangles { count: usize, capacity: usize },
    #[error("{count} objects: the frame engine's object table holds {OBJECTS}")]
    Objects { count: usize },
    #[error("triangle {triangle} has object {object}; the scene has {objects} objects")]
    TriangleObject {
        triangle: usize,
        object: u32,
        objects: usize,
    },
    #[error("{count} material entry points for {objects} objects")]
    Entries { count: usize, objects: usize },
    #[error("entry point {entry}: the program memory holds {CODE} instructions")]
    Entry { entry: u16 },
    #[error("max depth {depth}: the thread start holds depths up to {}", (1 << DEPTH_BITS) - 1)]
    MaxDepth { depth: u32 },
}

/// One word through the load port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartLoad {
    Triangle {
        index: usize,
        object: u32,
        normals: [Word3; 3],
    },
    Object {
        index: usize,
        entry: u16,
        casts: bool,
    },
}

/// What the block holds for a frame: the load port's words and the held inputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StartConstants {
    pub loads: Vec<StartLoad>,
    pub miss_entry: u16,
    pub miss_casts: bool,
    pub max_depth: u32,
}

fn entry_point(entry: u16) -> Result<u16, StartLoadError> {
    if entry as usize >= CODE {
        return Err(StartLoadError::Entry { entry });
    }
    Ok(entry)
}

/// Whether a thread entering at `entry` may push reflection or refraction rays.
fn casts(program: &Program, entry: u16) -> bool {
    program.pushes_from(entry).cast > 0
}

/// The constants of a block of `TB` triangle address bits for frames of `c`, shaded by
/// `program` (compiled from `c`).
pub fn loads<const TB: usize>(
    c: &FrameConstants,
    program: &Program,
) -> Result<StartConstants, StartLoadError> {
    if c.triangles.len() > triangles(TB) {
        return Err(StartLoadError::Triangles {
            count: c.triangles.len(),
            capacity: triangles(TB),
        });
    }
    if c.materials.len() > OBJECTS {
        return Err(StartLoadError::Objects {
            count: c.materials.len(),
        });
    }
    if program.material_entry.len() != c.materials.len() {
        return Err(StartLoadError::Entries {
            count: program.material_entry.len(),
            objects: c.materials.len(),
        });
    }
    if c.max_depth >= 1 << DEPTH_BITS {
        return Err(StartLoadError::MaxDepth { depth: c.max_depth });
    }
    let mut loads = Vec::new();
    for (index, t) in c.triangles.iter().enumerate() {
        if t.object as usize >= c.materials.len() {
            return Err(StartLoadError::TriangleObject {
                triangle: index,
                object: t.object,
                objects: c.materials.len(),
            });
        }
        loads.push(StartLoad::Triangle {
            index,
            object: t.object,
            normals: t.normals.map(|n| n.components().map(|x| x.bits())),
        });
    }
    for (index, &entry) in program.material_entry.iter().enumerate() {
        loads.push(StartLoad::Object {
            index,
            entry: entry_point(entry)?,
            casts: casts(program, entry),
        });
    }
    Ok(StartConstants {
        loads,
        miss_entry: entry_point(program.miss_entry)?,
        miss_casts: casts(program, program.miss_entry),
        max_depth: c.max_depth,
    })
}

/// A returned cast ray as the block takes it: the ray-store entry's fields and the answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Returned {
    pub pixel: u32,
    pub depth: u32,
    pub origin: Word3,
    pub direction: Word3,
    pub weight: Word3,
    /// The hit triangle and (t, u, v).
    pub hit: Option<(usize, Word3)>,
}

/// A ray the block cannot take.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum ReturnedError {
    #[error("a shadow ray runs no thread")]
    Shadow,
    #[error(transparent)]
    Store(#[from] StoreError),
}

impl Returned {
    /// A cast ray of the frame model and its answer, as the ray store of an engine of `TB`
    /// triangle address bits holds them.
    pub fn of<const TB: usize>(
        ray: &FrameRay,
        hit: Option<&Hit>,
    ) -> Result<Returned, ReturnedError> {
        if ray.kind() == hw_model::frame::RayKind::Shadow {
            return Err(ReturnedError::Shadow);
        }
        let stored = StoredRay::of(ray)?;
        Ok(Returned {
            pixel: stored.tag.pixel,
            depth: stored.tag.depth,
            origin: stored.origin,
            direction: stored.direction,
            weight: stored.payload,
            hit: stored_answer::<TB>(hit)?,
        })
    }
}

/// The start decision's inputs in a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Decision {
    pub fits: bool,
    pub fits_above_reserve: bool,
    /// The escape pixel's slot and its deepest depth in flight (if any), once known.
    pub escape: Option<(usize, Option<u32>)>,
}

impl Decision {
    /// Every start may go.
    pub const GO: Decision = Decision {
        fits: true,
        fits_above_reserve: true,
        escape: None,
    };

    /// Whether a start of `casts`, tag (`pixel`, `depth`) may go: the hardware's rule.
    pub fn allows(&self, casts: bool, pixel: u32, depth: u32) -> bool {
        let escape =
            self.escape == Some((pixel as usize % super::accumulate::PIXEL_SLOTS, Some(depth)));
        self.fits && (self.fits_above_reserve || !casts || escape)
    }
}

/// One cycle's inputs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StartInput {
    pub load: Option<StartLoad>,
    pub miss_entry: u16,
    pub miss_casts: bool,
    pub max_depth: u32,
    /// A returned ray and its id.
    pub ray: Option<Returned>,
    pub id: usize,
    pub decision: Decision,
    pub out_ready: bool,
}

/// A thread start shown: the core's start and the tag, and the program's cast flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Started {
    pub input: ThreadInput,
    pub pixel: u32,
    pub depth: u32,
    pub casts: bool,
}

/// What the outputs show in a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StartOutput {
    pub in_ready: bool,
    /// Stage B's start (offered, or deferred this cycle) and its id.
    pub start: Option<Started>,
    pub id: usize,
    /// The start offered to the core (`out_valid`).
    pub offered: bool,
    pub started: bool,
    pub deferred: bool,
}

/// Three 32-bit words in a 96-bit signal, the first from bit 0.
pub(crate) fn lanes(w: Word3) -> Lanes {
    Lanes::from(u64::from(w[0]))
        | (Lanes::from(u64::from(w[1])) << 32)
        | (Lanes::from(u64::from(w[2])) << 64)
}

/// A 96-bit signal's three 32-bit words.
pub(crate) fn of_lanes(l: Lanes) -> Word3 {
    let v = l.to_u128();
    [0, 1, 2].map(|k| (v >> (32 * k)) as u32)
}

impl<const TB: usize> Stepped for ThreadStart<TB> {
    type Input = StartInput;
    type Output = StartOutput;

    fn idle() -> StartInput {
        StartInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &StartInput) {
        self.load_triangle.next = matches!(input.load, Some(StartLoad::Triangle { .. }));
        self.load_object.next = matches!(input.load, Some(StartLoad::Object { .. }));
        let (address, data) = match input.load {
            Some(StartLoad::Triangle {
                index,
                object,
                normals,
            }) => {
                let mut data =
                    Bits::<TRIANGLE_WORD_BITS>::from(u64::from(object)) << Bits::<9>::from(288);
                for (k, n) in normals.iter().enumerate() {
                    data = data
                        | (bit_cast::<TRIANGLE_WORD_BITS, 96>(lanes(*n))
                            << Bits::<9>::from(96 * k as u64));
                }
                (index, data)
            }
            Some(StartLoad::Object {
                index,
                entry,
                casts,
            }) => (
                index,
                Bits::from(u64::from(entry) | u64::from(casts) << PC_BITS),
            ),
            None => (0, Bits::default()),
        };
        self.load_address.next = (address as u64).into();
        self.load_data.next = data;
        self.miss_entry.next = u64::from(input.miss_entry).into();
        self.miss_casts.next = input.miss_casts;
        self.max_depth.next = u64::from(input.max_depth).into();
        self.in_valid.next = input.ray.is_some();
        let ray = input.ray.unwrap_or(Returned {
            pixel: 0,
            depth: 0,
            origin: [0; 3],
            direction: [0; 3],
            weight: [0; 3],
            hit: None,
        });
        self.in_pixel.next = u64::from(ray.pixel).into();
        self.in_depth.next = u64::from(ray.depth).into();
        self.in_origin.next = lanes(ray.origin);
        self.in_direction.next = lanes(ray.direction);
        self.in_weight.next = lanes(ray.weight);
        self.in_hit.next = ray.hit.is_some();
        let (triangle, tuv) = ray.hit.unwrap_or((0, [0; 3]));
        self.in_triangle.next = (triangle as u64).into();
        self.in_tuv.next = lanes(tuv);
        self.in_id.next = (input.id as u64).into();
        let d = input.decision;
        self.fits.next = d.fits;
        self.fits_above_reserve.next = d.fits_above_reserve;
        self.escape_valid.next = d.escape.is_some();
        let (slot, deepest) = d.escape.unwrap_or_default();
        self.escape_slot.next = (slot as u64).into();
        self.escape_in_flight.next = deepest.is_some();
        self.escape_deepest.next = u64::from(deepest.unwrap_or(0)).into();
        self.out_ready.next = input.out_ready;
    }

    fn observe(&self) -> StartOutput {
        let shown = self.out_valid.val() | self.deferred.val();
        let start = shown.then(|| Started {
            input: ThreadInput {
                entry: self.entry.val().to_u64() as u16,
                material: self.material.val().to_u64() as u32,
                registers: std::array::from_fn(|k| of_lanes(self.registers[k].val())),
                past_depth: self.past_depth.val(),
            },
            pixel: self.pixel.val().to_u64() as u32,
            depth: self.depth.val().to_u64() as u32,
            casts: self.casts.val(),
        });
        StartOutput {
            in_ready: self.in_ready.val(),
            start,
            id: self.id.val().index(),
            offered: self.out_valid.val(),
            started: self.started.val(),
            deferred: self.deferred.val(),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_thread_start<const TB: usize>(
    drive: impl FnMut(Option<&StartOutput>) -> Option<StartInput> + Send + 'static,
) -> Vec<(StartInput, StartOutput)> {
    const { assert!(TB >= OBJECT_BITS) };
    simulate_driven(ThreadStart::<TB>::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn thread_start_verilog<const TB: usize>() -> String {
    const { assert!(TB >= OBJECT_BITS) };
    built_verilog(ThreadStart::<TB>::default)
}
