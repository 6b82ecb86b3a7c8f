//! The frame engine: the frame unit without its traversal unit (docs/frame.md "The frame
//! engine (design)"), every block of `hdl::frame` wired around a ray stream out and a hit
//! stream in (the traversal unit's `RayStream` and `HitStream`, mirrored). Its image and
//! counters are `hw_model::frame::engine`'s bit for bit (tested through Verilator,
//! `sim::frame_unit`).
//!
//! ```text
//! pixel counter ─► PixelSlots (slot free?), RayIds (an id), Records (the open), RayGen
//! RayGen ─► ray (with the id from the primary-id queue) ─► RayStore ─► TraceQueues
//! ShaderCore pushes ─► RayStore (first: one write port) ─► TraceQueues
//! TraceQueues ─► packet stage (its id read from the store, held while offered) ─► ray stream
//! hit stream ─► answer into the store, its tag and payload read ─► shadow: Records (settle)
//!                                                               └► cast: WaitingQueue
//! WaitingQueue ─► start stage (the entry read) ─► ThreadStart (decision) ─► ShaderCore
//! ShaderCore settles ─► Records ─► Accumulate ─► PixelSlots ─► pixel stream
//! ```
//!
//! - **The pixel counter** moves when the pixel's slot is free (`PixelSlots.pixel_ready`), an
//!   id is above the spawn reserve (`RayIds.primary_ready`), the open can be recorded
//!   (`Records.open_ready`) and ray generation takes the pixel: all four take it at once.
//! - **A pushed ray is counted at once**: the core pushes a thread's rays while it runs and
//!   settles it at its end, so a pushed shadow ray may come back and settle before its
//!   parent's settle has counted it (its pixel would finish early, then again). So each push
//!   sends the accumulator its own record through `Records`' settle port (sum 0, spawned 2:
//!   the ray out, less the one a settle retires), taken when the core's settle is not (the
//!   core holds a push until then), and the thread's settle goes with spawned 0. Records
//!   reach the accumulator in order, and a pushed ray's own records come after its push's.
//! - **The ray store's write port**: a pushed ray first (its id from its thread's
//!   reservation); a generated ray when no push is written and its id, queued when its
//!   pixel was taken, is shown. A written ray's id joins its trace queue in the same cycle
//!   (spawned or primary).
//! - **The ray packet** is the trace queues' head read from the store and held (its id in a
//!   register, the store's reader kept on it) until the ray stream takes it.
//! - **The answer** is written into its entry as the hit stream hands it over, and its tag
//!   and payload read; the next cycle a shadow answer goes to `Records` (its id freed when
//!   taken), a cast answer's id to the waiting queue.
//! - **The escape census** needs to know which entries hold a cast ray in flight, which the
//!   store's tags do not say once an entry is freed: a bit per entry, set when a cast ray is
//!   written, cleared when its thread starts, read beside the census's tag.
//!
//! Held while a frame runs: `width`, `height`, the camera (RayGen's sixteen words, see
//! [`CAMERA_BITS`]), the miss entry and its cast flag, the max depth, M (`reservation`) and
//! the two reserves. The memories are loaded through one port between frames (the shader
//! core's program and constants, the thread start's triangles and objects; their words as
//! the blocks' own load functions make them, [`LoadWord`]). `start` (a pulse while `idle`)
//! runs a frame; `done` rises when its last pixel has left, and stays until the next start.
//! Counters, cleared at a start: pixels out, rays written by kind, hits of cast rays,
//! occluded shadow rays, thread starts by the escape below the reserve, cycles running; the
//! core's own three counters (zero shadows, past depth, total internal) count from power-on.
//!
//! No reset: every block starts empty from the flip-flops' power-on zeros.

use hw_model::traversal::packet::{hit_word, ray_word, ANY_HIT};
use rust_hdl::prelude::*;

use super::accumulate::{Accumulate, PIXEL_SLOT_BITS, SETTLE_BITS, SPAWNED_BITS};
use super::coord::COORD_BITS;
use super::escape::EscapePixel;
use super::id_queue::{Count, Id, IdQueue, IDS, ID_BITS};
use super::pixel_slots::PixelSlots;
use super::ray_ids::{RayIds, RESERVATION_BITS};
use super::ray_store::{RayStore, TAG_BITS};
use super::raygen::{RayGen, PIXEL_BITS};
use super::records::Records;
use super::shader::core::{ShaderCore, COUNTER_BITS, DEPTH_BITS, PC_BITS};
use super::thread_start::{ThreadStart, OBJECT_BITS, TRIANGLE_WORD_BITS};
use super::trace_queues::TraceQueues;
use super::waiting_queue::WaitingQueue;
use crate::harness::built_verilog;
use crate::macros::{clock, dff_setup};
use crate::traversal::ports::{AxisIn, AxisOut, HIT_BITS, RAY_BITS};

type Lanes = Bits<96>;

/// The camera port: RayGen's words dx, x0, dy, y0, rows 0 to 2 (x, y, z each), the origin,
/// word k at bits 32k.
pub const CAMERA_WORDS: usize = 16;
pub const CAMERA_BITS: usize = 32 * CAMERA_WORDS;
/// The load port's address (a program word's, a constant's, a triangle's, an object's).
pub const LOAD_ADDRESS_BITS: usize = 16;
/// The load port's data: the widest word, the thread start's triangle.
pub const LOAD_DATA_BITS: usize = TRIANGLE_WORD_BITS;
/// The engine's counters, in this order (each wraps at [`COUNTER_BITS`]).
pub const COUNTERS: [&str; 9] = [
    "pixels",
    "primary_rays",
    "reflection_rays",
    "refraction_rays",
    "shadow_rays",
    "hits",
    "occluded",
    "escape_starts",
    "cycles",
];

const _: () = {
    assert!(LOAD_DATA_BITS >= 96 && LOAD_ADDRESS_BITS >= PC_BITS);
    assert!(LOAD_ADDRESS_BITS >= OBJECT_BITS);
    // The kernel's literal offsets: the tag (pixel, depth, kind), the packets' words.
    assert!(PIXEL_BITS == 21 && DEPTH_BITS == 4 && TAG_BITS == 27 && PIXEL_SLOT_BITS == 10);
    assert!(ray_word::ORIG == 0 && ray_word::DIR == 3 && ray_word::T_MAX == 6);
    assert!(ray_word::FLAGS == 8 && ray_word::ID == 10 && ANY_HIT == 1);
    assert!(hit_word::ID == 0 && hit_word::FLAGS == 1 && hit_word::TRIANGLE == 2);
    assert!(hit_word::T == 3 && hit_word::U == 4 && hit_word::V == 5);
    assert!(SETTLE_BITS == 31 && COUNTER_BITS == 32 && IDS == 512);
};

/// fp32's largest finite value: a generated or a pushed cast ray's t_max.
const FLT_MAX: u32 = 0x7f7f_ffff;
/// fp32 1.0: each lane of a generated ray's weight.
const ONE: u32 = 0x3f80_0000;

/// The frame engine with a triangle memory of `TB` address bits.
#[derive(LogicBlock)]
pub struct FrameEngine<const TB: usize> {
    pub clock: Signal<In, Clock>,
    // The load port, between frames: one of the four memories' words at `load_address`.
    pub load_program: Signal<In, Bit>,
    pub load_constant: Signal<In, Bit>,
    pub load_triangle: Signal<In, Bit>,
    pub load_object: Signal<In, Bit>,
    pub load_address: Signal<In, Bits<LOAD_ADDRESS_BITS>>,
    pub load_data: Signal<In, Bits<LOAD_DATA_BITS>>,
    // Held while a frame runs.
    pub width: Signal<In, Bits<COORD_BITS>>,
    pub height: Signal<In, Bits<COORD_BITS>>,
    pub camera: Signal<In, Bits<CAMERA_BITS>>,
    pub miss_entry: Signal<In, Bits<PC_BITS>>,
    pub miss_casts: Signal<In, Bit>,
    pub max_depth: Signal<In, Bits<DEPTH_BITS>>,
    pub reservation: Signal<In, Bits<RESERVATION_BITS>>,
    pub spawn_reserve: Signal<In, Count>,
    pub escape_reserve: Signal<In, Count>,
    // Control.
    pub start: Signal<In, Bit>,
    pub idle: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    // The traversal unit's streams.
    pub ray: AxisOut<Bits<RAY_BITS>>,
    pub hit: AxisIn<Bits<HIT_BITS>>,
    // The pixel stream: the pixel's index, its colour (r from bit 0, g, b).
    pub pixel_valid: Signal<Out, Bit>,
    pub pixel_ready: Signal<In, Bit>,
    pub pixel_index: Signal<Out, Bits<PIXEL_BITS>>,
    pub pixel_rgb: Signal<Out, Bits<24>>,
    /// [`COUNTERS`]' order.
    pub counters: [Signal<Out, Bits<COUNTER_BITS>>; 9],
    /// The shader core's `Counter::ALL`, from power-on.
    pub core_counters: [Signal<Out, Bits<COUNTER_BITS>>; 3],
    raygen: RayGen,
    core: ShaderCore,
    accumulate: Accumulate,
    records: Records,
    slots: PixelSlots,
    ray_ids: RayIds,
    escape: EscapePixel,
    store: RayStore<TB>,
    thread_start: ThreadStart<TB>,
    trace: TraceQueues,
    waiting: WaitingQueue,
    primary_ids: IdQueue,
    // The pixel counter.
    running: DFF<Bit>,
    finished: DFF<Bit>,
    i: DFF<Bits<COORD_BITS>>,
    j: DFF<Bits<COORD_BITS>>,
    next_pixel: DFF<Bits<PIXEL_BITS>>,
    pixels_out: DFF<Bits<PIXEL_BITS>>,
    // The ray packet, the answer and the start stages.
    packet_valid: DFF<Bit>,
    packet_id: DFF<Id>,
    answer_valid: DFF<Bit>,
    answer_id: DFF<Id>,
    answer_hit: DFF<Bit>,
    start_valid: DFF<Bit>,
    start_id: DFF<Id>,
    // Entries holding a cast ray in flight; the bit of the census's address.
    cast: DFF<Bits<IDS>>,
    scan_cast: DFF<Bit>,
    counts: [DFF<Bits<COUNTER_BITS>>; 9],
    flt_max: Constant<Bits<32>>,
    two: Constant<Bits<SPAWNED_BITS>>,
    one: Constant<Lanes>,
    bit0: Constant<Bits<IDS>>,
    any_hit: Constant<Bits<RAY_BITS>>,
    // Locals.
    go: Signal<Local, Bit>,
    push: Signal<Local, Bit>,
    generated: Signal<Local, Bit>,
    w_pixel: Signal<Local, Bits<PIXEL_BITS>>,
    w_depth: Signal<Local, Bits<DEPTH_BITS>>,
    w_kind: Signal<Local, Bits<2>>,
    w_id: Signal<Local, Id>,
    w_cast: Signal<Local, Bit>,
    packet_take: Signal<Local, Bit>,
    packet: Signal<Local, Bits<RAY_BITS>>,
    packet_kind: Signal<Local, Bits<2>>,
    answer_kind: Signal<Local, Bits<2>>,
    answer_take: Signal<Local, Bit>,
    answer_shadow: Signal<Local, Bit>,
    answer_leaves: Signal<Local, Bit>,
    start_take: Signal<Local, Bit>,
    set_cast: Signal<Local, Bits<IDS>>,
    clear_cast: Signal<Local, Bits<IDS>>,
    scanned: Signal<Local, Bits<IDS>>,
}

impl<const TB: usize> FrameEngine<TB> {
    /// The engine with its operators (ray generation's, the shader core's) at `depth`.
    pub fn new(depth: usize) -> Self {
        const { assert!(TB >= OBJECT_BITS && TB <= LOAD_ADDRESS_BITS) };
        Self {
            clock: Default::default(),
            load_program: Default::default(),
            load_constant: Default::default(),
            load_triangle: Default::default(),
            load_object: Default::default(),
            load_address: Default::default(),
            load_data: Default::default(),
            width: Default::default(),
            height: Default::default(),
            camera: Default::default(),
            miss_entry: Default::default(),
            miss_casts: Default::default(),
            max_depth: Default::default(),
            reservation: Default::default(),
            spawn_reserve: Default::default(),
            escape_reserve: Default::default(),
            start: Default::default(),
            idle: Default::default(),
            done: Default::default(),
            ray: Default::default(),
            hit: Default::default(),
            pixel_valid: Default::default(),
            pixel_ready: Default::default(),
            pixel_index: Default::default(),
            pixel_rgb: Default::default(),
            counters: Default::default(),
            core_counters: Default::default(),
            raygen: RayGen::new(depth),
            core: ShaderCore::new(depth),
            accumulate: Default::default(),
            records: Default::default(),
            slots: Default::default(),
            ray_ids: Default::default(),
            escape: Default::default(),
            store: Default::default(),
            thread_start: Default::default(),
            trace: Default::default(),
            waiting: Default::default(),
            primary_ids: Default::default(),
            running: Default::default(),
            finished: Default::default(),
            i: Default::default(),
            j: Default::default(),
            next_pixel: Default::default(),
            pixels_out: Default::default(),
            packet_valid: Default::default(),
            packet_id: Default::default(),
            answer_valid: Default::default(),
            answer_id: Default::default(),
            answer_hit: Default::default(),
            start_valid: Default::default(),
            start_id: Default::default(),
            cast: Default::default(),
            scan_cast: Default::default(),
            counts: Default::default(),
            flt_max: Constant::new(u64::from(FLT_MAX).into()),
            two: Constant::new(2.into()),
            one: Constant::new(
                Lanes::from(u64::from(ONE))
                    | (Lanes::from(u64::from(ONE)) << 32)
                    | (Lanes::from(u64::from(ONE)) << 64),
            ),
            bit0: Constant::new(1.into()),
            any_hit: Constant::new(
                Bits::<RAY_BITS>::from(u64::from(ANY_HIT)) << (32 * ray_word::FLAGS as u64),
            ),
            go: Default::default(),
            push: Default::default(),
            generated: Default::default(),
            w_pixel: Default::default(),
            w_depth: Default::default(),
            w_kind: Default::default(),
            w_id: Default::default(),
            w_cast: Default::default(),
            packet_take: Default::default(),
            packet: Default::default(),
            packet_kind: Default::default(),
            answer_kind: Default::default(),
            answer_take: Default::default(),
            answer_shadow: Default::default(),
            answer_leaves: Default::default(),
            start_take: Default::default(),
            set_cast: Default::default(),
            clear_cast: Default::default(),
            scanned: Default::default(),
        }
    }
}

impl<const TB: usize> Logic for FrameEngine<TB> {
    #[hdl_gen]
    fn update(&mut self) {
        clock!(self, clock, raygen, core, accumulate, records, slots, ray_ids, escape, store);
        clock!(self, clock, thread_start, trace, waiting, primary_ids);
        dff_setup!(self, clock, running, finished, i, j, next_pixel, pixels_out);
        dff_setup!(
            self,
            clock,
            packet_valid,
            packet_id,
            answer_valid,
            answer_id,
            answer_hit
        );
        dff_setup!(self, clock, start_valid, start_id, cast, scan_cast);
        for k in 0..9 {
            dff_setup!(self, clock, counts[k]);
        }

        // The load port and the held inputs.
        self.core.load_program.next = self.load_program.val();
        self.core.load_constant.next = self.load_constant.val();
        self.core.load_address.next = self.load_address.val().get_bits::<PC_BITS>(0);
        self.core.load_data.next = self.load_data.val().get_bits::<96>(0);
        self.thread_start.load_triangle.next = self.load_triangle.val();
        self.thread_start.load_object.next = self.load_object.val();
        self.thread_start.load_address.next = self.load_address.val().get_bits::<TB>(0);
        self.thread_start.load_data.next = self.load_data.val();
        self.thread_start.miss_entry.next = self.miss_entry.val();
        self.thread_start.miss_casts.next = self.miss_casts.val();
        self.thread_start.max_depth.next = self.max_depth.val();
        self.ray_ids.reservation.next = self.reservation.val();
        self.ray_ids.spawn_reserve.next = self.spawn_reserve.val();
        self.ray_ids.escape_reserve.next = self.escape_reserve.val();
        self.raygen.dx.next = self.camera.val().get_bits::<32>(0);
        self.raygen.x0.next = self.camera.val().get_bits::<32>(32);
        self.raygen.dy.next = self.camera.val().get_bits::<32>(64);
        self.raygen.y0.next = self.camera.val().get_bits::<32>(96);
        for k in 0..3 {
            self.raygen.row0[k].next = self.camera.val().get_bits::<32>(128 + 32 * k);
            self.raygen.row1[k].next = self.camera.val().get_bits::<32>(224 + 32 * k);
            self.raygen.row2[k].next = self.camera.val().get_bits::<32>(320 + 32 * k);
            self.raygen.camera_origin[k].next = self.camera.val().get_bits::<32>(416 + 32 * k);
        }

        // The pixel counter: a pixel taken by the slots, the ids, the records and ray
        // generation at once.
        self.go.next = self.running.q.val()
            & (self.j.q.val() != self.height.val())
            & self.slots.pixel_ready.val()
            & self.ray_ids.primary_ready.val()
            & self.records.open_ready.val()
            & self.raygen.pixel_ready.val();
        self.slots.pixel_valid.next = self.go.val();
        self.slots.pixel.next = self.next_pixel.q.val();
        self.ray_ids.primary_valid.next = self.go.val();
        self.records.open_valid.next = self.go.val();
        self.records.open_slot.next = self.next_pixel.q.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.raygen.pixel_valid.next = self.go.val();
        self.raygen.i.next = self.i.q.val();
        self.raygen.j.next = self.j.q.val();
        self.raygen.pixel.next = self.next_pixel.q.val();
        self.primary_ids.write.next = self.go.val();
        self.primary_ids.data_in.next = self.ray_ids.id.val();
        if self.go.val() {
            self.next_pixel.d.next = self.next_pixel.q.val() + 1;
            self.i.d.next = self.i.q.val() + 1;
            if (self.i.q.val() + 1) == self.width.val() {
                self.i.d.next = 0.into();
                self.j.d.next = self.j.q.val() + 1;
            }
        }

        // A push is taken when the records' settle port is free of the core's settle: its
        // record counts the pushed ray out at once. The ray store's write port: a push
        // first, else a generated ray with its id.
        self.core.ray_ready.next = !self.core.settle_valid.val() & self.records.settle_ready.val();
        self.push.next = self.core.ray_valid.val() & self.core.ray_ready.val();
        self.generated.next =
            self.raygen.ray_valid.val() & self.primary_ids.valid.val() & !self.push.val();
        self.raygen.ray_ready.next = self.primary_ids.valid.val() & !self.push.val();
        self.primary_ids.read.next = self.generated.val();
        self.ray_ids.push.next = self.push.val();
        self.w_id.next = self.primary_ids.head.val();
        self.w_pixel.next = self.raygen.ray_pixel.val();
        self.w_depth.next = 0.into();
        self.w_kind.next = 0.into();
        self.store.ray_origin.next = bit_cast::<96, 32>(self.raygen.origin[0].val())
            | (bit_cast::<96, 32>(self.raygen.origin[1].val()) << 32)
            | (bit_cast::<96, 32>(self.raygen.origin[2].val()) << 64);
        self.store.ray_direction.next = bit_cast::<96, 32>(self.raygen.direction[0].val())
            | (bit_cast::<96, 32>(self.raygen.direction[1].val()) << 32)
            | (bit_cast::<96, 32>(self.raygen.direction[2].val()) << 64);
        self.store.ray_t_max.next = self.flt_max.val();
        self.store.ray_payload.next = self.one.val();
        if self.push.val() {
            // The core's kinds are `PushKind::ALL`'s (shadow 0, reflection 1, refraction 2),
            // the store's `RayKind::ALL`'s (shadow 3); a cast push is a level deeper.
            self.w_id.next = self.ray_ids.id.val();
            self.w_pixel.next = self.core.ray_pixel.val();
            self.w_kind.next = self.core.ray_kind.val();
            self.w_depth.next = self.core.ray_depth.val() + 1;
            // A shadow ray's t_max is the core's, a cast ray's `FLT_MAX` (`thread::settle`).
            if !self.core.ray_kind.val().any() {
                self.w_kind.next = 3.into();
                self.w_depth.next = 0.into();
                self.store.ray_t_max.next = self.core.ray_t_max.val();
            }
            self.store.ray_origin.next = self.core.ray_origin.val();
            self.store.ray_direction.next = self.core.ray_direction.val();
            self.store.ray_payload.next = self.core.ray_payload.val();
        }
        self.w_cast.next =
            self.generated.val() | (self.push.val() & self.core.ray_kind.val().any());
        self.store.ray_write.next = self.push.val() | self.generated.val();
        self.store.ray_id.next = self.w_id.val();
        self.store.ray_tag.next = bit_cast::<TAG_BITS, PIXEL_BITS>(self.w_pixel.val())
            | (bit_cast::<TAG_BITS, DEPTH_BITS>(self.w_depth.val()) << 21)
            | (bit_cast::<TAG_BITS, 2>(self.w_kind.val()) << 25);
        self.trace.spawned.next = self.push.val();
        self.trace.spawned_id.next = self.ray_ids.id.val();
        self.trace.primary.next = self.generated.val();
        self.trace.primary_id.next = self.primary_ids.head.val();
        self.escape.enter.next = self.w_cast.val();
        self.escape.enter_id.next = self.w_id.val();
        self.escape.enter_slot.next = self.w_pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.escape.enter_depth.next = self.w_depth.val();

        // The ray packet: the trace queues' head read from the store, held until taken.
        self.packet_take.next = !self.packet_valid.q.val() | self.ray.tready.val();
        self.trace.out_ready.next = self.packet_take.val();
        self.store.packet_id.next = self.packet_id.q.val();
        if self.packet_take.val() {
            self.packet_valid.d.next = self.trace.out_valid.val();
            if self.trace.out_valid.val() {
                self.packet_id.d.next = self.trace.out_id.val();
                self.store.packet_id.next = self.trace.out_id.val();
            }
        }
        self.packet.next = bit_cast::<RAY_BITS, 96>(self.store.packet_origin.val())
            | (bit_cast::<RAY_BITS, 96>(self.store.packet_direction.val()) << 96)
            | (bit_cast::<RAY_BITS, 32>(self.store.packet_t_max.val()) << 192)
            | (bit_cast::<RAY_BITS, ID_BITS>(self.packet_id.q.val()) << 320);
        self.packet_kind.next = self.store.packet_tag.val().get_bits::<2>(25);
        if self.packet_kind.val().all() {
            self.packet.next = self.packet.val() | self.any_hit.val();
        }
        self.ray.tdata.next = self.packet.val();
        self.ray.tvalid.next = self.packet_valid.q.val();

        // The answer: written into its entry as it is taken, its tag and payload read; the
        // next cycle, a shadow's to the records, a cast's id to the waiting queue.
        self.answer_kind.next = self.store.returned_tag.val().get_bits::<2>(25);
        self.answer_shadow.next = self.answer_kind.val().all();
        self.answer_leaves.next = self.answer_valid.q.val()
            & ((self.answer_shadow.val() & self.records.shadow_ready.val())
                | (!self.answer_shadow.val() & self.waiting.answer_ready.val()));
        self.hit.tready.next = !self.answer_valid.q.val() | self.answer_leaves.val();
        self.answer_take.next = self.hit.tvalid.val() & self.hit.tready.val();
        self.store.answer_write.next = self.answer_take.val();
        self.store.answer_id.next = self.hit.tdata.val().get_bits::<ID_BITS>(0);
        self.store.answer_hit.next = self.hit.tdata.val().get_bit(32);
        self.store.answer_triangle.next = self.hit.tdata.val().get_bits::<TB>(64);
        self.store.answer_tuv.next = self.hit.tdata.val().get_bits::<96>(96);
        self.store.returned_id.next = self.answer_id.q.val();
        self.answer_valid.d.next =
            self.answer_take.val() | (self.answer_valid.q.val() & !self.answer_leaves.val());
        if self.answer_take.val() {
            self.answer_id.d.next = self.hit.tdata.val().get_bits::<ID_BITS>(0);
            self.answer_hit.d.next = self.hit.tdata.val().get_bit(32);
            self.store.returned_id.next = self.hit.tdata.val().get_bits::<ID_BITS>(0);
        }
        self.records.shadow_valid.next = self.answer_valid.q.val() & self.answer_shadow.val();
        self.records.shadow_slot.next =
            self.store.returned_tag.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.records.shadow_occluded.next = self.answer_hit.q.val();
        self.records.shadow_payload.next = self.store.returned_payload.val();
        self.ray_ids.shadow_free.next = self.answer_leaves.val() & self.answer_shadow.val();
        self.ray_ids.shadow_id.next = self.answer_id.q.val();
        self.waiting.answer_valid.next = self.answer_valid.q.val() & !self.answer_shadow.val();
        self.waiting.answer_id.next = self.answer_id.q.val();

        // The start stage: the waiting head's entry read, then the thread start.
        self.start_take.next = !self.start_valid.q.val() | self.thread_start.in_ready.val();
        self.waiting.out_ready.next = self.start_take.val();
        self.store.start_id.next = self.start_id.q.val();
        if self.start_take.val() {
            self.start_valid.d.next = self.waiting.out_valid.val();
            if self.waiting.out_valid.val() {
                self.start_id.d.next = self.waiting.out_id.val();
                self.store.start_id.next = self.waiting.out_id.val();
            }
        }
        self.thread_start.in_valid.next = self.start_valid.q.val();
        self.thread_start.in_pixel.next = self.store.start_tag.val().get_bits::<PIXEL_BITS>(0);
        self.thread_start.in_depth.next = self.store.start_tag.val().get_bits::<DEPTH_BITS>(21);
        self.thread_start.in_origin.next = self.store.start_origin.val();
        self.thread_start.in_direction.next = self.store.start_direction.val();
        self.thread_start.in_weight.next = self.store.start_payload.val();
        self.thread_start.in_hit.next = self.store.start_hit.val();
        self.thread_start.in_triangle.next = self.store.start_triangle.val();
        self.thread_start.in_tuv.next = self.store.start_tuv.val();
        self.thread_start.in_id.next = self.start_id.q.val();
        self.thread_start.fits.next = self.ray_ids.fits.val();
        self.thread_start.fits_above_reserve.next = self.ray_ids.fits_above_reserve.val();
        self.thread_start.escape_valid.next = self.escape.escape_valid.val();
        self.thread_start.escape_slot.next = self.escape.escape_slot.val();
        self.thread_start.escape_in_flight.next = self.escape.in_flight.val();
        self.thread_start.escape_deepest.next = self.escape.deepest.val();
        self.waiting.deferred.next = self.thread_start.deferred.val();
        self.waiting.deferred_id.next = self.thread_start.id.val();
        self.ray_ids.start.next = self.thread_start.started.val();
        self.ray_ids.start_id.next = self.thread_start.id.val();
        self.escape.leave.next = self.thread_start.started.val();
        self.escape.leave_id.next = self.thread_start.id.val();
        self.escape.leave_slot.next = self.thread_start.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.escape.leave_depth.next = self.thread_start.depth.val();
        self.escape.candidate.next = self.thread_start.deferred.val();
        self.escape.candidate_slot.next =
            self.thread_start.pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);

        // The shader core: starts in, settles to the records.
        self.core.start_valid.next = self.thread_start.out_valid.val();
        self.thread_start.out_ready.next = self.core.start_ready.val();
        self.core.start_entry.next = self.thread_start.entry.val();
        self.core.start_material.next = self.thread_start.material.val();
        for k in 0..7 {
            self.core.start_registers[k].next = self.thread_start.registers[k].val();
        }
        self.core.start_past_depth.next = self.thread_start.past_depth.val();
        self.core.start_pixel.next = self.thread_start.pixel.val();
        self.core.start_depth.next = self.thread_start.depth.val();
        // The records' settle port: the core's settle (its pushes already counted: spawned
        // 0), else a push's record (sum 0, spawned 2: the pushed ray out, less the one a
        // settle retires), so that no pushed ray's own records reach the accumulator before
        // the ray is counted, and a pixel's count reaches 0 once.
        self.records.settle_valid.next = self.core.settle_valid.val() | self.core.ray_valid.val();
        self.core.settle_ready.next = self.records.settle_ready.val();
        self.records.settle_slot.next = self.core.ray_pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.records.settle_spawned.next = self.two.val();
        if self.core.settle_valid.val() {
            self.records.settle_slot.next =
                self.core.settle_pixel.val().get_bits::<PIXEL_SLOT_BITS>(0);
            self.records.settle_spawned.next = 0.into();
        }
        for k in 0..3 {
            self.records.settle_sum[k].next = 0.into();
            if self.core.settle_valid.val() {
                self.records.settle_sum[k].next =
                    self.core.settle_sum.val().get_bits::<SETTLE_BITS>(32 * k);
            }
            self.core_counters[k].next = self.core.counters[k].val();
        }
        self.ray_ids.settle.next = self.core.settle_valid.val() & self.records.settle_ready.val();
        self.ray_ids.settle_spawned.next = self.core.settle_spawned.val();

        // Records → accumulator → pixel slots → the pixel stream.
        self.accumulate.record_valid.next = self.records.record_valid.val();
        self.records.record_ready.next = self.accumulate.record_ready.val();
        self.accumulate.slot.next = self.records.slot.val();
        self.accumulate.open.next = self.records.open.val();
        for k in 0..3 {
            self.accumulate.sum[k].next = self.records.sum[k].val();
            self.slots.in_rgb[k].next = self.accumulate.rgb[k].val();
        }
        self.accumulate.spawned.next = self.records.spawned.val();
        self.slots.in_valid.next = self.accumulate.pixel_valid.val();
        self.accumulate.pixel_ready.next = self.slots.in_ready.val();
        self.slots.in_slot.next = self.accumulate.pixel_slot.val();
        self.escape.finish.next = self.accumulate.pixel_valid.val() & self.slots.in_ready.val();
        self.escape.finish_slot.next = self.accumulate.pixel_slot.val();
        self.pixel_valid.next = self.slots.out_valid.val();
        self.slots.out_ready.next = self.pixel_ready.val();
        self.pixel_index.next = self.slots.out_index.val();
        self.pixel_rgb.next = bit_cast::<24, 8>(self.slots.out_rgb[0].val())
            | (bit_cast::<24, 8>(self.slots.out_rgb[1].val()) << 8)
            | (bit_cast::<24, 8>(self.slots.out_rgb[2].val()) << 16);

        // The census: which entries hold a cast ray, read beside the tag.
        self.set_cast.next = 0.into();
        if self.w_cast.val() {
            self.set_cast.next = self.bit0.val() << self.w_id.val();
        }
        self.clear_cast.next = 0.into();
        if self.thread_start.started.val() {
            self.clear_cast.next = self.bit0.val() << self.thread_start.id.val();
        }
        self.cast.d.next = (self.cast.q.val() & !self.clear_cast.val()) | self.set_cast.val();
        self.scanned.next = self.cast.q.val() >> self.escape.scan_address.val();
        self.scan_cast.d.next = self.scanned.val().get_bit(0);
        self.store.scan_id.next = self.escape.scan_address.val();
        self.escape.scan_cast.next = self.scan_cast.q.val();
        self.escape.scan_slot.next = self.store.scan_tag.val().get_bits::<PIXEL_SLOT_BITS>(0);
        self.escape.scan_depth.next = self.store.scan_tag.val().get_bits::<DEPTH_BITS>(21);

        // Counters (`COUNTERS`' order): what happened this cycle.
        if self.pixel_valid.val() & self.pixel_ready.val() {
            self.counts[0].d.next = self.counts[0].q.val() + 1;
        }
        if self.generated.val() {
            self.counts[1].d.next = self.counts[1].q.val() + 1;
        }
        if self.push.val() & self.core.ray_kind.val().get_bit(0) {
            self.counts[2].d.next = self.counts[2].q.val() + 1;
        }
        if self.push.val() & self.core.ray_kind.val().get_bit(1) {
            self.counts[3].d.next = self.counts[3].q.val() + 1;
        }
        if self.push.val() & !self.core.ray_kind.val().any() {
            self.counts[4].d.next = self.counts[4].q.val() + 1;
        }
        if self.answer_leaves.val() & self.answer_hit.q.val() & !self.answer_shadow.val() {
            self.counts[5].d.next = self.counts[5].q.val() + 1;
        }
        if self.answer_leaves.val() & self.answer_hit.q.val() & self.answer_shadow.val() {
            self.counts[6].d.next = self.counts[6].q.val() + 1;
        }
        if self.thread_start.started.val()
            & self.thread_start.casts.val()
            & !self.ray_ids.fits_above_reserve.val()
        {
            self.counts[7].d.next = self.counts[7].q.val() + 1;
        }
        if self.running.q.val() {
            self.counts[8].d.next = self.counts[8].q.val() + 1;
        }
        for k in 0..9 {
            self.counters[k].next = self.counts[k].q.val();
        }

        // Control: a start while idle clears the counters and runs a frame, which is done
        // when its last pixel has left.
        self.idle.next = !self.running.q.val();
        self.done.next = self.finished.q.val();
        if self.running.q.val()
            & (self.j.q.val() == self.height.val())
            & (self.pixels_out.q.val() == self.next_pixel.q.val())
        {
            self.running.d.next = false;
            self.finished.d.next = true;
        }
        if self.pixel_valid.val() & self.pixel_ready.val() {
            self.pixels_out.d.next = self.pixels_out.q.val() + 1;
        }
        if self.start.val() & !self.running.q.val() {
            self.running.d.next = true;
            self.finished.d.next = false;
            self.i.d.next = 0.into();
            self.j.d.next = 0.into();
            self.next_pixel.d.next = 0.into();
            self.pixels_out.d.next = 0.into();
            for k in 0..9 {
                self.counts[k].d.next = 0.into();
            }
        }
    }
}

/// Which memory a load word goes to (the port's four strobes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadTarget {
    Program,
    Constant,
    Triangle,
    Object,
}

/// One word through the engine's load port: its memory, address and data (32-bit words,
/// the first from bit 0, [`LOAD_DATA_BITS`] in all).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadWord {
    pub target: LoadTarget,
    pub address: u64,
    pub data: Vec<u32>,
}

/// Words of the load port's data.
pub const LOAD_DATA_WORDS: usize = LOAD_DATA_BITS.div_ceil(32);

fn data_words<const N: usize>(data: Bits<N>) -> Vec<u32> {
    let mut words = vec![0; LOAD_DATA_WORDS];
    for b in (0..N).filter(|&b| data.get_bit(b)) {
        words[b / 32] |= 1 << (b % 32);
    }
    words
}

/// What the engine holds for a frame: the load port's words and the held inputs.
#[derive(Clone, Debug, PartialEq)]
pub struct EngineFrame {
    pub loads: Vec<LoadWord>,
    pub width: u32,
    pub height: u32,
    /// RayGen's words, [`CAMERA_WORDS`] of them (see [`CAMERA_BITS`]).
    pub camera: [u32; CAMERA_WORDS],
    pub miss_entry: u16,
    pub miss_casts: bool,
    pub max_depth: u32,
    /// M: the most rays a thread of the scene's programs pushes.
    pub reservation: usize,
    pub spawn_reserve: usize,
    pub escape_reserve: usize,
}

/// A frame the engine cannot run.
#[derive(Clone, Debug, thiserror::Error, PartialEq, Eq)]
pub enum EngineError {
    #[error("the shader core: {0}")]
    Core(#[from] super::shader::core::LoadError),
    #[error("the thread start: {0}")]
    Start(#[from] super::thread_start::StartLoadError),
    #[error("a {width}×{height} frame: the engine's pixel counter runs 1×1 to {max}×{max}", max = (1 << COORD_BITS) - 1)]
    ImageSize { width: u32, height: u32 },
    #[error("the scene's threads push up to {pushes} rays: the reservation holds at most {}", (1 << RESERVATION_BITS) - 1)]
    Reservation { pushes: usize },
    #[error("a ray store of {entries} entries: this scene's threads push up to {pushes} rays, {cast} of them reflection or refraction rays, {depth} deep, so it needs {needed} ({cast}·{depth} + {pushes} + 1) to {IDS}")]
    Store {
        entries: usize,
        pushes: usize,
        cast: usize,
        depth: u32,
        needed: usize,
    },
}

impl EngineFrame {
    /// The engine's constants for frames of `c`, shaded by `program` (compiled from `c`).
    /// The reserves (docs/frame.md "Why it cannot deadlock"): with `store` `None`, the
    /// schedule model's defaults, a spawn reserve of a quarter of the store and the escape
    /// reserve C·D + M; with `Some(r)`, both raised by [`IDS`] − r, so that ray generation
    /// and the threads that push reflection or refraction rays see a store of r entries
    /// (from C·D + M + 1, the least the argument allows, to [`IDS`]). The words are the
    /// blocks' own: `shader::core::loads` and `thread_start::loads`, through their load
    /// ports' encodings.
    pub fn new<const TB: usize>(
        c: &hw_model::frame::FrameConstants,
        program: &hw_model::frame::shader::Program,
        store: Option<usize>,
    ) -> Result<EngineFrame, EngineError> {
        use super::shader::core::CoreInput;
        use super::thread_start::{StartInput, StartLoad};
        use crate::harness::Stepped;
        if c.width == 0
            || c.height == 0
            || c.width >= 1 << COORD_BITS
            || c.height >= 1 << COORD_BITS
        {
            return Err(EngineError::ImageSize {
                width: c.width,
                height: c.height,
            });
        }
        let entries =
            std::iter::once(program.miss_entry).chain(program.material_entry.iter().copied());
        let pushes: Vec<_> = entries.map(|e| program.pushes_from(e)).collect();
        let most = pushes.iter().map(|p| p.total()).max().unwrap_or(0);
        let cast = pushes.iter().map(|p| p.cast).max().unwrap_or(0);
        if most >= 1 << RESERVATION_BITS {
            return Err(EngineError::Reservation { pushes: most });
        }
        let needed = cast * c.max_depth as usize + most;
        let (spawn_reserve, escape_reserve) = match store {
            None => (IDS / 4, needed),
            Some(entries) => (
                IDS.saturating_sub(entries) + needed,
                IDS.saturating_sub(entries) + needed,
            ),
        };
        if store.is_some_and(|r| r <= needed || r > IDS) || spawn_reserve < needed {
            return Err(EngineError::Store {
                entries: store.unwrap_or(IDS),
                pushes: most,
                cast,
                depth: c.max_depth,
                needed: needed + 1,
            });
        }
        let mut loads = Vec::new();
        let mut core = ShaderCore::new(0);
        for load in super::shader::core::loads(program)? {
            core.apply(&CoreInput {
                load: Some(load),
                ..CoreInput::default()
            });
            let target = if core.load_program.next {
                LoadTarget::Program
            } else {
                LoadTarget::Constant
            };
            loads.push(LoadWord {
                target,
                address: core.load_address.next.to_u64(),
                data: data_words(core.load_data.next),
            });
        }
        let start = super::thread_start::loads::<TB>(c, program)?;
        let mut block = ThreadStart::<TB>::default();
        for load in &start.loads {
            block.apply(&StartInput {
                load: Some(*load),
                ..StartInput::default()
            });
            let target = match load {
                StartLoad::Triangle { .. } => LoadTarget::Triangle,
                StartLoad::Object { .. } => LoadTarget::Object,
            };
            loads.push(LoadWord {
                target,
                address: block.load_address.next.to_u64(),
                data: data_words(block.load_data.next),
            });
        }
        let k = &c.camera;
        let mut camera = [0; CAMERA_WORDS];
        let words = [k.dx, k.x0, k.dy, k.y0].into_iter().chain(
            k.rows
                .iter()
                .chain([&k.origin])
                .flat_map(|v| v.components()),
        );
        for (w, x) in camera.iter_mut().zip(words) {
            *w = x.bits();
        }
        Ok(EngineFrame {
            loads,
            width: c.width,
            height: c.height,
            camera,
            miss_entry: start.miss_entry,
            miss_casts: start.miss_casts,
            max_depth: start.max_depth,
            reservation: most,
            spawn_reserve,
            escape_reserve,
        })
    }
}

/// Verilog of the engine with its operators at `depth`, top module `top`.
pub fn frame_engine_verilog<const TB: usize>(depth: usize) -> String {
    built_verilog(move || FrameEngine::<TB>::new(depth))
}
