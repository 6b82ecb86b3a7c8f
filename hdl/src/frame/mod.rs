//! The frame unit's blocks (issue 40, docs/frame.md "Hardware blocks"), each bit for bit its
//! part of `hw_model::frame`, in fp32.
//!
//! - [`normalise`]: v → v·recip(sqrt((x·x + y·y) + z·z)), one vector a cycle (ray
//!   generation's, later shading's).

pub mod normalise;
