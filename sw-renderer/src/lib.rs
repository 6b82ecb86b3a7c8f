//! The golden software renderer: the thesis' scenes and Whitted shading, a BVH, and the one
//! seams where hardware plugs in: rays ([`rays::RayEngine`]) and ray-triangle queries
//! ([`intersect::Intersector`]).

pub mod bvh;
pub mod camera;
pub mod compare;
pub mod golden;
pub mod hit;
pub mod intersect;
pub mod math;
pub mod rays;
pub mod render;
pub mod scene;
pub mod shade;
pub mod spawn;
pub mod thesis_scenes;
pub mod trace;
pub mod world;
