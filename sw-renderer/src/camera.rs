//! Primary rays, evaluated as the reference did, including where C++ silently used `double`.

use crate::math::{mult_dir, mult_point, V3};
use crate::scene::Mat44;

#[derive(Clone, Debug)]
pub struct Camera {
    pub origin: V3,
    camera_to_world: Mat44,
    width: u32,
    height: u32,
    /// `width / (float)height`, a float division.
    aspect: f32,
    scale: f32,
}

impl Camera {
    pub fn new(camera_to_world: Mat44, fov_deg: f32, width: u32, height: u32) -> Camera {
        Camera {
            origin: mult_point(&camera_to_world, V3::ZERO),
            camera_to_world,
            width,
            height,
            aspect: width as f32 / height as f32,
            scale: fov_scale(fov_deg),
        }
    }

    /// Normalised direction of the ray through the centre of pixel (i, j), j from the top.
    pub fn direction(&self, i: u32, j: u32) -> V3 {
        let (x, y) = self.screen(i, j);
        mult_dir(&self.camera_to_world, V3::new(x, y, -1.0)).normalized()
    }

    /// Screen-plane coordinates: x = float((2(i+0.5)/width − 1)·aspect·scale) and
    /// y = float((1 − 2(j+0.5)/height)·scale), every operation in double.
    pub fn screen(&self, i: u32, j: u32) -> (f32, f32) {
        let w = f64::from(self.width as f32);
        let h = f64::from(self.height as f32);
        let x =
            (2.0 * (f64::from(i) + 0.5) / w - 1.0) * f64::from(self.aspect) * f64::from(self.scale);
        let y = (1.0 - 2.0 * (f64::from(j) + 0.5) / h) * f64::from(self.scale);
        (x as f32, y as f32)
    }
}

/// `scale = tan(deg2rad(fov * 0.5))`: `fov * 0.5` in double rounded to float (the parameter
/// of `deg2rad`), `deg * M_PI / 180` in double rounded to float (its return), then the double
/// `tan` rounded to float.
pub fn fov_scale(fov_deg: f32) -> f32 {
    let half = (f64::from(fov_deg) * 0.5) as f32;
    let radians = (f64::from(half) * std::f64::consts::PI / 180.0) as f32;
    f64::from(radians).tan() as f32
}
