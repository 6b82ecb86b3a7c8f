//! The golden software renderer: the thesis' scenes and Whitted shading, a BVH, and the one
//! seam where hardware plugs in, [`intersect::Intersector`].

pub mod scene;
