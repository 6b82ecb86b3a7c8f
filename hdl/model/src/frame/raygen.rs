//! Ray generation: pixel (i, j), j from the top, → the primary ray through its centre.
//!
//! In fp32, operation by operation (the RTL's order):
//! 1. x = i·dx + x0, y = j·dy + y0 (i and j exact in fp32; the constants from
//!    [`CameraConstants`]);
//! 2. d = (x·r00 + y·r10) + (−r20), and likewise for the y and z components with columns 1
//!    and 2 (the reference's `multDirMatrix` of (x, y, −1): the product by −1 is exact);
//! 3. direction = normalise(d) ([`Vec3::normalized`]: recip(sqrt(d·d)) times each component);
//!
//! the origin is the camera's. The reference evaluated x and y in double and normalised with
//! a double reciprocal square root: those are the two places a primary ray may differ from
//! the reference's in the last bits.

use super::constants::CameraConstants;
use crate::fp32::{Fp32, Vec3};

/// Cycles between two primary rays of the frame unit's ray generation (`hdl::frame::raygen`:
/// its operators time-shared by two, a pixel taken every other cycle); the frame schedule
/// model's ray generation takes the same.
pub const INTERVAL: u64 = 2;

/// The primary ray through pixel (i, j): origin and normalised direction.
pub fn primary(camera: &CameraConstants, i: u32, j: u32) -> (Vec3, Vec3) {
    let x = Fp32::of_int(i) * camera.dx + camera.x0;
    let y = Fp32::of_int(j) * camera.dy + camera.y0;
    let [r0, r1, r2] = camera.rows;
    let d = r0.scale(x) + r1.scale(y) - r2;
    (camera.origin, d.normalized())
}

#[cfg(test)]
mod tests {
    use super::*;
    use sw_renderer::camera::Camera;
    use sw_renderer::scene::Mat44;

    #[test]
    fn primary_rays_are_the_reference_cameras_within_a_few_ulps() {
        let m = Mat44::from_row_major([
            0.999945, 0.0, 0.0104718, 0.0, 0.00104703, 0.994989, -0.0999803, 0.0, -0.0104193,
            0.0999858, 0.994934, 0.0, -0.978596, 17.911879, 75.483_37, 1.0,
        ]);
        let (w, h, fov) = (320, 180, 36.87f32);
        let reference = Camera::new(m, fov, w, h);
        let camera = CameraConstants::new(&m, fov, w, h);
        let mut worst = 0;
        for j in 0..h {
            for i in 0..w {
                let (o, d) = primary(&camera, i, j);
                assert_eq!(o.to_f32(), reference.origin.to_array());
                let want = reference.direction(i, j).to_array();
                for (got, want) in d.to_f32().into_iter().zip(want) {
                    // Components near zero may differ by more of their own ulps, not of 1's.
                    let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
                    let close = (got - want).abs() <= f32::EPSILON;
                    assert!(ulps <= 4 || close, "({i}, {j}): {got:e} vs {want:e}");
                    worst = worst.max(if close { 0 } else { ulps });
                }
            }
        }
        // Not the reference's bits (double x, y and a double 1/sqrt), but within a few ulps.
        assert!(worst > 0, "expected some last-bit differences");
    }
}
