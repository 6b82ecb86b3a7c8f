//! The frame engine's ray store (docs/frame.md "The frame engine (design)", "The ray store's
//! entry"): [`IDS`] entries, an entry's address its ray's id in the traversal unit, each the
//! model's ray in flight (`FrameRay`) and, once traced, its answer.
//!
//! Each field group is a block RAM with one write port, read at one edge and shown the next
//! cycle (the word before that edge's write). A group with several readers is held once per
//! reader, every copy written together:
//!
//! | group | bits | written by | read by (a copy each) |
//! |---|---:|---|---|
//! | tag: pixel, depth, kind | 27 | a ray (generated or pushed) | the ray packet, the answer, the thread start, the escape census |
//! | geometry: origin, direction | 192 | a ray | the ray packet, the thread start |
//! | t_max | 32 | a ray | the ray packet |
//! | payload: weight (cast), contribution (shadow) | 96 | a ray | the answer, the thread start |
//! | answer: t, u, v | 96 | the hit packet | the thread start |
//! | hit | 1 | the hit packet | the thread start |
//! | triangle | `TB` | the hit packet | the thread start |
//!
//! The payload's lanes are fp32 words for a cast ray's weight and, for a shadow ray, its
//! three 28-bit contributions each sign-extended to 32 bits, as the shader core pushes them.
//! A ray's id enters its queue in the cycle its entry is written, and a queue shows an id two
//! cycles later, so no read meets a write to its entry at the same edge. No reset, no
//! initial contents: an entry is read only once written.

use hw_model::fp32::{Fp32, Vec3};
use hw_model::frame::accumulate::Contribution;
use hw_model::frame::shader::isa::Word3;
use hw_model::frame::{FrameRay, Load, RayKind};
use rust_hdl::prelude::*;
use thiserror::Error;

use super::id_queue::{Id, ID_BITS};
use super::raygen::PIXEL_BITS;
use super::shader::core::DEPTH_BITS;
use super::thread_start::{lanes, of_lanes, triangles};
use crate::harness::{built_verilog, simulate_driven, Stepped};

/// A tag: the pixel from bit 0, the depth above it, the kind (`RayKind::ALL`'s index) on top.
pub const TAG_BITS: usize = PIXEL_BITS + DEPTH_BITS + 2;
const _: () = assert!(TAG_BITS == 27 && RayKind::ALL.len() == 4);

type Tag = Bits<TAG_BITS>;
type Lanes = Bits<96>;
type Ram<T> = RAM<T, ID_BITS>;

/// Rays and answers in; four readers' words out.
#[derive(LogicBlock, Default)]
pub struct RayStore<const TB: usize> {
    pub clock: Signal<In, Clock>,
    // A ray written at its entry.
    pub ray_write: Signal<In, Bit>,
    pub ray_id: Signal<In, Id>,
    pub ray_tag: Signal<In, Tag>,
    pub ray_origin: Signal<In, Lanes>,
    pub ray_direction: Signal<In, Lanes>,
    pub ray_t_max: Signal<In, Bits<32>>,
    pub ray_payload: Signal<In, Lanes>,
    // An answer written at its ray's entry.
    pub answer_write: Signal<In, Bit>,
    pub answer_id: Signal<In, Id>,
    pub answer_hit: Signal<In, Bit>,
    pub answer_triangle: Signal<In, Bits<TB>>,
    pub answer_tuv: Signal<In, Lanes>,
    // The ray packet's reader.
    pub packet_id: Signal<In, Id>,
    pub packet_tag: Signal<Out, Tag>,
    pub packet_origin: Signal<Out, Lanes>,
    pub packet_direction: Signal<Out, Lanes>,
    pub packet_t_max: Signal<Out, Bits<32>>,
    // The answer's reader (the hit packet's id).
    pub returned_id: Signal<In, Id>,
    pub returned_tag: Signal<Out, Tag>,
    pub returned_payload: Signal<Out, Lanes>,
    // The thread start's reader.
    pub start_id: Signal<In, Id>,
    pub start_tag: Signal<Out, Tag>,
    pub start_origin: Signal<Out, Lanes>,
    pub start_direction: Signal<Out, Lanes>,
    pub start_payload: Signal<Out, Lanes>,
    pub start_hit: Signal<Out, Bit>,
    pub start_triangle: Signal<Out, Bits<TB>>,
    pub start_tuv: Signal<Out, Lanes>,
    // The escape census's reader.
    pub scan_id: Signal<In, Id>,
    pub scan_tag: Signal<Out, Tag>,
    /// The packet's, the answer's, the start's and the census's copies.
    tags: [Ram<Tag>; 4],
    /// The packet's and the start's copies: origin from bit 0, direction from bit 96.
    geometry: [Ram<Bits<192>>; 2],
    t_max: Ram<Bits<32>>,
    /// The answer's and the start's copies.
    payload: [Ram<Lanes>; 2],
    /// t, u, v.
    answer: Ram<Lanes>,
    hit: Ram<Bit>,
    triangle: Ram<Bits<TB>>,
}

impl<const TB: usize> Logic for RayStore<TB> {
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..4 {
            self.tags[k].read_clock.next = self.clock.val();
            self.tags[k].write_clock.next = self.clock.val();
            self.tags[k].write_enable.next = self.ray_write.val();
            self.tags[k].write_address.next = self.ray_id.val();
            self.tags[k].write_data.next = self.ray_tag.val();
        }
        for k in 0..2 {
            self.geometry[k].read_clock.next = self.clock.val();
            self.geometry[k].write_clock.next = self.clock.val();
            self.geometry[k].write_enable.next = self.ray_write.val();
            self.geometry[k].write_address.next = self.ray_id.val();
            self.geometry[k].write_data.next = bit_cast::<192, 96>(self.ray_origin.val())
                | (bit_cast::<192, 96>(self.ray_direction.val()) << 96);
            self.payload[k].read_clock.next = self.clock.val();
            self.payload[k].write_clock.next = self.clock.val();
            self.payload[k].write_enable.next = self.ray_write.val();
            self.payload[k].write_address.next = self.ray_id.val();
            self.payload[k].write_data.next = self.ray_payload.val();
        }
        self.t_max.read_clock.next = self.clock.val();
        self.t_max.write_clock.next = self.clock.val();
        self.t_max.write_enable.next = self.ray_write.val();
        self.t_max.write_address.next = self.ray_id.val();
        self.t_max.write_data.next = self.ray_t_max.val();
        self.answer.read_clock.next = self.clock.val();
        self.answer.write_clock.next = self.clock.val();
        self.answer.write_enable.next = self.answer_write.val();
        self.answer.write_address.next = self.answer_id.val();
        self.answer.write_data.next = self.answer_tuv.val();
        self.hit.read_clock.next = self.clock.val();
        self.hit.write_clock.next = self.clock.val();
        self.hit.write_enable.next = self.answer_write.val();
        self.hit.write_address.next = self.answer_id.val();
        self.hit.write_data.next = self.answer_hit.val();
        self.triangle.read_clock.next = self.clock.val();
        self.triangle.write_clock.next = self.clock.val();
        self.triangle.write_enable.next = self.answer_write.val();
        self.triangle.write_address.next = self.answer_id.val();
        self.triangle.write_data.next = self.answer_triangle.val();

        // The readers.
        self.tags[0].read_address.next = self.packet_id.val();
        self.geometry[0].read_address.next = self.packet_id.val();
        self.t_max.read_address.next = self.packet_id.val();
        self.packet_tag.next = self.tags[0].read_data.val();
        self.packet_origin.next = self.geometry[0].read_data.val().get_bits::<96>(0);
        self.packet_direction.next = self.geometry[0].read_data.val().get_bits::<96>(96);
        self.packet_t_max.next = self.t_max.read_data.val();
        self.tags[1].read_address.next = self.returned_id.val();
        self.payload[0].read_address.next = self.returned_id.val();
        self.returned_tag.next = self.tags[1].read_data.val();
        self.returned_payload.next = self.payload[0].read_data.val();
        self.tags[2].read_address.next = self.start_id.val();
        self.geometry[1].read_address.next = self.start_id.val();
        self.payload[1].read_address.next = self.start_id.val();
        self.answer.read_address.next = self.start_id.val();
        self.hit.read_address.next = self.start_id.val();
        self.triangle.read_address.next = self.start_id.val();
        self.start_tag.next = self.tags[2].read_data.val();
        self.start_origin.next = self.geometry[1].read_data.val().get_bits::<96>(0);
        self.start_direction.next = self.geometry[1].read_data.val().get_bits::<96>(96);
        self.start_payload.next = self.payload[1].read_data.val();
        self.start_hit.next = self.hit.read_data.val();
        self.start_triangle.next = self.triangle.read_data.val();
        self.start_tuv.next = self.answer.read_data.val();
        self.tags[3].read_address.next = self.scan_id.val();
        self.scan_tag.next = self.tags[3].read_data.val();
    }
}

/// A ray's entry: the model's ray in flight as the store's fields hold it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StoredRay {
    pub tag: StoredTag,
    pub origin: Word3,
    pub direction: Word3,
    pub t_max: u32,
    pub payload: Word3,
}

/// A ray's tag.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StoredTag {
    /// `RayKind::ALL`'s index.
    pub kind: usize,
    pub pixel: u32,
    pub depth: u32,
}

/// A ray the store cannot hold.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum StoreError {
    #[error("pixel {pixel} does not fit the ray store's {PIXEL_BITS} bits")]
    Pixel { pixel: u32 },
    #[error("depth {depth} does not fit the ray store's {DEPTH_BITS} bits")]
    Depth { depth: u32 },
    #[error("triangle {triangle}: the frame engine's triangle memory holds {capacity}")]
    Triangle { triangle: u32, capacity: usize },
}

fn words(v: Vec3) -> Word3 {
    v.components().map(Fp32::bits)
}

fn vec3(w: Word3) -> Vec3 {
    let [x, y, z] = w.map(Fp32::from_bits);
    Vec3::new(x, y, z)
}

impl StoredRay {
    /// The entry of the model's ray `ray`.
    pub fn of(ray: &FrameRay) -> Result<StoredRay, StoreError> {
        if ray.pixel >= 1 << PIXEL_BITS {
            return Err(StoreError::Pixel { pixel: ray.pixel });
        }
        let (kind, depth, payload) = match ray.load {
            Load::Cast {
                kind,
                depth,
                weight,
            } => (kind, depth, words(weight)),
            Load::Shadow { contribution } => (RayKind::Shadow, 0, contribution.0.map(|c| c as u32)),
        };
        if depth >= 1 << DEPTH_BITS {
            return Err(StoreError::Depth { depth });
        }
        Ok(StoredRay {
            tag: StoredTag {
                kind: RayKind::ALL
                    .iter()
                    .position(|&k| k == kind)
                    .expect("a kind"),
                pixel: ray.pixel,
                depth,
            },
            origin: words(ray.orig),
            direction: words(ray.dir),
            t_max: ray.t_max.bits(),
            payload,
        })
    }

    /// The model's ray the entry holds.
    pub fn frame_ray(&self) -> FrameRay {
        let kind = RayKind::ALL[self.tag.kind];
        FrameRay {
            pixel: self.tag.pixel,
            orig: vec3(self.origin),
            dir: vec3(self.direction),
            t_max: Fp32::from_bits(self.t_max),
            load: match kind {
                RayKind::Shadow => Load::Shadow {
                    contribution: Contribution(self.payload.map(|w| w as i32)),
                },
                _ => Load::Cast {
                    kind,
                    depth: self.tag.depth,
                    weight: vec3(self.payload),
                },
            },
        }
    }
}

/// An answer as the store holds it: the hit triangle and (t, u, v), or a miss.
pub type StoredAnswer = Option<(usize, Word3)>;

/// The answer of a store of `TB` triangle address bits for the traversal model's hit.
pub fn stored_answer<const TB: usize>(
    hit: Option<&sw_renderer::hit::Hit>,
) -> Result<StoredAnswer, StoreError> {
    match hit {
        None => Ok(None),
        Some(h) if h.triangle as usize >= triangles(TB) => Err(StoreError::Triangle {
            triangle: h.triangle,
            capacity: triangles(TB),
        }),
        Some(h) => Ok(Some((
            h.triangle as usize,
            [h.t, h.u, h.v].map(|x| Fp32::new(x).bits()),
        ))),
    }
}

/// One cycle's inputs: a ray and an answer written, the four readers' ids.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StoreInput {
    pub ray: Option<(usize, StoredRay)>,
    pub answer: Option<(usize, StoredAnswer)>,
    /// The packet's, the answer's, the start's and the census's ids.
    pub read: [usize; 4],
}

/// What the readers show: the words read at the last edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StoreOutput {
    /// The ray packet's: tag, origin, direction, t_max.
    pub packet: StoredRay,
    /// The answer's: tag and payload.
    pub returned: StoredRay,
    /// The thread start's: tag, origin, direction, payload, answer.
    pub start: (StoredRay, StoredAnswer),
    pub scan: StoredTag,
}

fn tag_bits(t: &StoredTag) -> Tag {
    (u64::from(t.pixel) | u64::from(t.depth) << PIXEL_BITS | (t.kind as u64) << (TAG_BITS - 2))
        .into()
}

fn of_tag(t: Tag) -> StoredTag {
    let t = t.to_u64();
    StoredTag {
        kind: (t >> (TAG_BITS - 2)) as usize,
        pixel: (t & ((1 << PIXEL_BITS) - 1)) as u32,
        depth: ((t >> PIXEL_BITS) & ((1 << DEPTH_BITS) - 1)) as u32,
    }
}

impl<const TB: usize> Stepped for RayStore<TB> {
    type Input = StoreInput;
    type Output = StoreOutput;

    fn idle() -> StoreInput {
        StoreInput::default()
    }

    fn clock_input(&mut self) -> &mut Signal<In, Clock> {
        &mut self.clock
    }

    fn apply(&mut self, input: &StoreInput) {
        let (id, ray) = input.ray.unwrap_or_default();
        self.ray_write.next = input.ray.is_some();
        self.ray_id.next = (id as u64).into();
        self.ray_tag.next = tag_bits(&ray.tag);
        self.ray_origin.next = lanes(ray.origin);
        self.ray_direction.next = lanes(ray.direction);
        self.ray_t_max.next = u64::from(ray.t_max).into();
        self.ray_payload.next = lanes(ray.payload);
        let (id, answer) = input.answer.unwrap_or_default();
        self.answer_write.next = input.answer.is_some();
        self.answer_id.next = (id as u64).into();
        self.answer_hit.next = answer.is_some();
        let (triangle, tuv) = answer.unwrap_or_default();
        self.answer_triangle.next = (triangle as u64).into();
        self.answer_tuv.next = lanes(tuv);
        self.packet_id.next = (input.read[0] as u64).into();
        self.returned_id.next = (input.read[1] as u64).into();
        self.start_id.next = (input.read[2] as u64).into();
        self.scan_id.next = (input.read[3] as u64).into();
    }

    fn observe(&self) -> StoreOutput {
        StoreOutput {
            packet: StoredRay {
                tag: of_tag(self.packet_tag.val()),
                origin: of_lanes(self.packet_origin.val()),
                direction: of_lanes(self.packet_direction.val()),
                t_max: self.packet_t_max.val().to_u64() as u32,
                ..StoredRay::default()
            },
            returned: StoredRay {
                tag: of_tag(self.returned_tag.val()),
                payload: of_lanes(self.returned_payload.val()),
                ..StoredRay::default()
            },
            start: (
                StoredRay {
                    tag: of_tag(self.start_tag.val()),
                    origin: of_lanes(self.start_origin.val()),
                    direction: of_lanes(self.start_direction.val()),
                    payload: of_lanes(self.start_payload.val()),
                    ..StoredRay::default()
                },
                self.start_hit.val().then(|| {
                    (
                        self.start_triangle.val().index(),
                        of_lanes(self.start_tuv.val()),
                    )
                }),
            ),
            scan: of_tag(self.scan_tag.val()),
        }
    }
}

/// Runs a freshly built block in rust-hdl's simulator, the inputs of each cycle chosen by
/// `drive` from the outputs of the cycle before (see [`simulate_driven`]).
pub fn simulate_ray_store<const TB: usize>(
    drive: impl FnMut(Option<&StoreOutput>) -> Option<StoreInput> + Send + 'static,
) -> Vec<(StoreInput, StoreOutput)> {
    simulate_driven(RayStore::<TB>::default, drive)
}

/// Verilog of the block, top module `top`.
pub fn ray_store_verilog<const TB: usize>() -> String {
    built_verilog(RayStore::<TB>::default)
}
