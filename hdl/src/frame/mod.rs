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
//!   (the triangle's object and normals, the object's program), one a cycle.

pub mod accumulate;
pub mod contribution;
pub mod coord;
pub mod escape;
pub mod normalise;
pub mod ray_ids;
pub mod raygen;
pub mod shader;
pub mod thread_start;
