//! The frame unit's blocks (issue 40, docs/frame.md "Hardware blocks"), each bit for bit its
//! part of `hw_model::frame`, in fp32.
//!
//! - [`normalise`]: v → v·recip(sqrt((x·x + y·y) + z·z)), one vector a cycle (ray
//!   generation's, later shading's).
//! - [`raygen`]: pixel (i, j) → primary ray, one a cycle, valid/ready on both sides.
//! - [`coord`]: a pixel coordinate → fp32, exactly (ray generation's).
//! - [`contribution`]: an fp32 RGB → its contribution in fixed point (`fl(255·c)` in
//!   fx<28,12>), one a cycle: the values the accumulator's settle records sum.
//! - [`accumulate`]: per-pixel sums and counts of rays out in block RAM, one record (open a
//!   pixel, or settle one of its shaded rays) a cycle; finished pixels out in 8 bits.
//! - [`shader`]: the shader core, shading programs run by interleaved threads on one fp32
//!   datapath.
//! - [`escape`]: the escape pixel, designated until it finishes, its cast rays in flight
//!   counted by depth (a census of the ray store's tags, then live).
//! - [`ray_ids`]: the ray store's free entries (a ray's id in the traversal unit) and the
//!   running threads' reservations of them; the spawn and escape reserves' decisions.
//! - [`thread_start`]: a returned cast ray and its answer → the shader core's thread start
//!   (the triangle's object and normals, the object's program), one a cycle; its triangle
//!   memory's size a parameter.
//! - [`id_queue`]: a FIFO of ray ids, `valid` from a register: the frame engine's queues.
//! - [`trace_queues`]: ids waiting for the traversal unit, spawned rays before primary ones.
//! - [`waiting_queue`]: answered cast rays waiting for a thread; a deferred start back to
//!   the tail.
//! - [`pixel_slots`]: whether the next pixel's slot is free (two parity tables); a finished
//!   slot's pixel index, the pixel stream out.
//! - [`ray_store`]: the rays in flight and their answers, a RAM per field group and reader.
//! - [`records`]: the accumulator's three sources (opens, shadow answers settled beside the
//!   core, threads' settles), one record a cycle.
//! - [`engine`]: the frame engine, every block above wired around the traversal unit's ray
//!   and hit streams: pixels in order to an 8-bit pixel stream.

pub mod accumulate;
pub mod contribution;
pub mod coord;
pub mod engine;
pub mod escape;
pub mod id_queue;
pub mod normalise;
pub mod pixel_slots;
pub mod ray_ids;
pub mod ray_store;
pub mod raygen;
pub mod records;
pub mod shader;
pub mod thread_start;
pub mod trace_queues;
pub mod waiting_queue;

use hw_model::frame::schedule::FrameUnit;
use hw_model::traversal::schedule::UnitTiming;

/// The frame schedule model's unit for these blocks with their operators at `depth`: their
/// latencies, ray generation's interval and the accumulator's slots, beside a traversal unit
/// timed `traversal`; the sizes a frame unit is configured with.
pub fn schedule_unit(
    traversal: UnitTiming,
    depth: usize,
    ray_store: usize,
    spawn_reserve: usize,
    shader_cores: usize,
    threads: usize,
) -> FrameUnit {
    FrameUnit {
        traversal,
        ray_store,
        spawn_reserve,
        shader_cores,
        threads,
        pixel_slots: accumulate::PIXEL_SLOTS,
        raygen_latency: raygen::latency(depth) as u64,
        raygen_interval: raygen::INTERVAL,
        accumulate_latency: accumulate::latency() as u64,
    }
}
