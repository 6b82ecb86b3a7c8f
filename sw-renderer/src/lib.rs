//! The golden software renderer: the thesis' scenes and Whitted shading, a BVH, and the one
//! seam where hardware plugs in, [`intersect::Intersector`].

pub mod bvh;
pub mod camera;
pub mod compare;
pub mod golden;
pub mod hit;
pub mod intersect;
pub mod math;
pub mod model_engine;
pub mod render;
pub mod scene;
pub mod shade;
pub mod thesis_scenes;
pub mod trace;
pub mod world;
