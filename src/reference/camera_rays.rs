//! Primary rays through the pixels of a camera, matching the rasteriser's projection: the
//! ray through a point of the image starts on the near plane (nothing nearer is drawn) and
//! ends at the far plane if the camera has one.

use glam::{Mat4, Vec3};

use crate::scene::Camera;

/// A ray from the camera: unit `direction`, valid between `t_min` and `t_max` metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraRay {
    pub origin: Vec3,
    pub direction: Vec3,
    pub t_min: f32,
    pub t_max: f32,
}

/// The rays of a `width` × `height` image seen by one camera.
#[derive(Debug, Clone)]
pub struct CameraRays {
    inverse_view_projection: Mat4,
    position: Vec3,
    has_far_plane: bool,
    width: f64,
    height: f64,
}

impl CameraRays {
    pub fn new(camera: &Camera, width: u32, height: u32) -> CameraRays {
        let aspect = width.max(1) as f32 / height.max(1) as f32;
        CameraRays {
            inverse_view_projection: camera.view_projection(aspect).inverse(),
            position: camera.position,
            has_far_plane: camera.zfar.is_some(),
            width: width.max(1) as f64,
            height: height.max(1) as f64,
        }
    }

    /// The ray through image point (`x`, `y`) in pixels from the top-left corner (pixel
    /// (i, j) covers [i, i + 1) × [j, j + 1)).
    pub fn through(&self, x: f64, y: f64) -> CameraRay {
        let ndc_x = (2.0 * x / self.width - 1.0) as f32;
        let ndc_y = (1.0 - 2.0 * y / self.height) as f32;
        // wgpu's clip space: depth 0 on the near plane, 1 on the far plane.
        let near = self
            .inverse_view_projection
            .project_point3(Vec3::new(ndc_x, ndc_y, 0.0));
        let offset = near - self.position;
        let t_min = offset.length();
        let direction = offset.normalize_or(Vec3::NEG_Z);
        let t_max = if self.has_far_plane {
            let far = self
                .inverse_view_projection
                .project_point3(Vec3::new(ndc_x, ndc_y, 1.0));
            (far - self.position).length()
        } else {
            f32::INFINITY
        };
        CameraRay {
            origin: self.position,
            direction,
            t_min,
            t_max,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            position: Vec3::new(0.0, 1.0, 5.0),
            forward: Vec3::NEG_Z,
            up: Vec3::Y,
            yfov_rad: std::f32::consts::FRAC_PI_2,
            znear: 0.1,
            zfar: Some(100.0),
        }
    }

    #[test]
    fn the_centre_ray_looks_forward_from_the_near_to_the_far_plane() {
        let ray = CameraRays::new(&camera(), 200, 100).through(100.0, 50.0);
        assert!((ray.direction - Vec3::NEG_Z).length() < 1e-5, "{ray:?}");
        assert!(
            (ray.t_min - 0.1).abs() < 1e-4 && (ray.t_max - 100.0).abs() < 0.1,
            "{ray:?}"
        );
    }

    #[test]
    fn corner_rays_span_the_field_of_view() {
        // A 90° vertical field: the top edge is 45° up; the aspect ratio 2 makes the right
        // edge atan(2) to the side.
        let rays = CameraRays::new(&camera(), 200, 100);
        let top = rays.through(100.0, 0.0).direction;
        assert!(
            (top.y.atan2(-top.z) - std::f32::consts::FRAC_PI_4).abs() < 1e-4,
            "{top}"
        );
        let right = rays.through(200.0, 50.0).direction;
        assert!((right.x.atan2(-right.z) - 2.0f32.atan()).abs() < 1e-4, "{right}");
        assert!(
            rays.through(0.0, 100.0).direction.y < 0.0,
            "the bottom-left ray looks down"
        );
    }

    #[test]
    fn an_infinite_camera_has_no_far_limit() {
        let infinite = Camera { zfar: None, ..camera() };
        assert_eq!(
            CameraRays::new(&infinite, 10, 10).through(5.0, 5.0).t_max,
            f32::INFINITY
        );
    }
}
