//! The frame pipeline's bit-accurate model: pixels in, an 8-bit image out, no cycles
//! (docs/frame.md). It is the specification of the frame unit's hardware: ray generation,
//! shading and accumulation around the traversal unit, in the hardware's arithmetic
//! ([`crate::fp32`]).
//!
//! - [`constants`]: what the scene memory holds beside the triangles (camera, lights,
//!   per-object material, per-triangle vertex normals), computed once on the host, checked
//!   against the configuration's [`FrameLimits`] and for NaN/Inf.
//! - [`raygen`]: pixel → primary ray.
//! - [`shade`]: a returned ray (its hit or miss) → contributions to its pixel and spawned rays.
//!   No recursion stack: a ray carries its pixel, its kind, its depth and an fp32 RGB weight;
//!   a shadow ray carries the contribution it adds if it arrives unoccluded.
//! - [`accumulate`]: per-pixel sums in fixed point, so a pixel's sum does not depend on the
//!   order its rays return in; a pixel is final when its last ray has returned.
//! - [`shader`]: shading as programs of the shader core: its instruction set, its
//!   interpreter, the compiler from the constants, and the glue to the frame's rays.
//! - [`engine`]: runs a frame, its rays answered by the traversal unit's model and shaded by
//!   the compiled programs.
//! - [`schedule`]: the frame's cycles on the planned frame unit, stage by stage (the frame
//!   schedule model: the traversal unit's schedule model fed continuously, barrel shader
//!   cores, a bounded ray store).

pub mod accumulate;
pub mod constants;
pub mod engine;
pub mod raygen;
pub mod schedule;
pub mod shade;
pub mod shader;

pub use accumulate::{Accumulator, Contribution, Settle};
pub use constants::FrameConstants;
pub use engine::{Frame, FrameOutput, FrameStats, RayOrder, ShaderLoad, WAVEFRONT};
pub use shade::{FrameRay, Load, RayKind};

use sw_renderer::rays::EngineError;
use thiserror::Error;

/// The sizes the frame unit is configured for: its constant memories, its ray fields and
/// its framebuffer addressing. A scene beyond them is a load error naming the sizes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameLimits {
    pub width: u32,
    pub height: u32,
    /// Light records (a shaded hit spawns one shadow ray per light).
    pub lights: usize,
    /// Objects, one material record each.
    pub objects: usize,
    /// Per-triangle records (object and three vertex normals).
    pub triangles: usize,
    /// Largest `max_depth` (a ray's depth field holds 0 to it).
    pub max_depth: u32,
    /// Largest Phong exponent (an integer: square-and-multiply, one bit per step).
    pub phong_exponent: u32,
}

impl FrameLimits {
    /// The configuration the hardware is built for: 1080p; 8 lights (All materials has 7);
    /// 64 objects; 16,384 triangle records (All materials has 14,560); depth up to 15, a
    /// 4-bit field (four thesis scenes use 10); Phong exponents up to 255, 8 bits (the thesis
    /// uses 10 and 20).
    pub const HW: FrameLimits = FrameLimits {
        width: 1920,
        height: 1080,
        lights: 8,
        objects: 64,
        triangles: 16_384,
        max_depth: 15,
        phong_exponent: 255,
    };
}

/// A scene the frame unit cannot render, or its traversal unit failing.
#[derive(Debug, Error)]
pub enum FrameError {
    #[error("scene `{scene}` has {count} {what}; the frame unit holds at most {limit}")]
    TooMany {
        scene: String,
        what: &'static str,
        count: usize,
        limit: usize,
    },
    #[error("scene `{scene}` at {width}×{height}: the frame unit renders 1×1 to {max_width}×{max_height}")]
    ImageSize {
        scene: String,
        width: u32,
        height: u32,
        max_width: u32,
        max_height: u32,
    },
    #[error(
        "scene `{scene}` has max depth {depth}; the frame unit's rays hold depths up to {limit}"
    )]
    MaxDepth {
        scene: String,
        depth: u32,
        limit: u32,
    },
    #[error("scene `{scene}`: {what} is {value}; every scene constant must be finite")]
    NotFinite {
        scene: String,
        what: String,
        value: f32,
    },
    #[error("scene `{scene}`: object `{object}` has Phong exponent {value}; the frame unit raises to whole exponents 0 to {limit}")]
    PhongExponent {
        scene: String,
        object: String,
        value: f32,
        limit: u32,
    },
    #[error("scene `{scene}`: the shader core: {source}")]
    Compile {
        scene: String,
        source: shader::CompileError,
    },
    #[error("scene `{scene}`: a shader core thread: {source}")]
    Thread {
        scene: String,
        source: shader::RunError,
    },
    #[error("scene `{scene}`: the traversal unit: {source}")]
    Traversal { scene: String, source: EngineError },
}
