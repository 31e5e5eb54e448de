use glam::{Mat4, Vec3};

use super::Aabb;

/// A perspective camera in world space (right-handed, looking down `forward`).
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    /// Unit up vector (orthogonal to `forward`).
    pub up: Vec3,
    /// Vertical field of view, full angle, radians.
    pub yfov_rad: f32,
    /// Near plane distance, metres (> 0).
    pub znear: f32,
    /// Far plane distance, metres; `None` = infinite.
    pub zfar: Option<f32>,
}

/// Direction a framing camera looks from (towards the scene centre), before normalising.
const FRAMING_DIRECTION: Vec3 = Vec3::new(0.55, 0.45, 0.70);

impl Camera {
    /// A camera that looks at the whole box from above and to the front-right.
    pub fn framing(bounds: &Aabb) -> Camera {
        OrbitCamera::framing(bounds).camera()
    }

    /// A camera at `position` looking at `target` (not straight up or down), its up
    /// vector in the plane of the view direction and world +y; no far plane.
    pub fn looking_at(position: Vec3, target: Vec3, yfov_rad: f32, znear: f32) -> Camera {
        let forward = (target - position).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        Camera {
            position,
            forward,
            up: right.cross(forward),
            yfov_rad,
            znear,
            zfar: None,
        }
    }

    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_to_mat4(self.position, self.forward, self.up)
    }

    /// Projection to wgpu clip space (the Direct3D convention: y up, depth 0..1).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        use glam::camera::rh::proj::directx;
        match self.zfar {
            Some(zfar) => directx::perspective(self.yfov_rad, aspect, self.znear, zfar),
            None => directx::perspective_infinite(self.yfov_rad, aspect, self.znear),
        }
    }

    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view()
    }

    /// The distance from the eye to the near plane's corners (`aspect` width over height),
    /// metres: the near plane clips nothing farther from the eye than this.
    pub fn near_plane_reach_m(&self, aspect: f32) -> f32 {
        let half_height = (0.5 * self.yfov_rad).tan();
        self.znear * (1.0 + half_height * half_height * (1.0 + aspect * aspect)).sqrt()
    }
}

/// The editor's orbit camera: a point of interest and spherical coordinates around it
/// (yaw about +y, pitch above the horizon).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrbitCamera {
    pub target: Vec3,
    pub distance: f32,
    pub yaw_rad: f32,
    pub pitch_rad: f32,
    pub yfov_rad: f32,
}

/// Pitch stays short of the poles so `up` never aligns with the view direction.
const MAX_PITCH_RAD: f32 = 1.55;

impl OrbitCamera {
    pub fn framing(bounds: &Aabb) -> OrbitCamera {
        let yfov_rad = 45f32.to_radians();
        let radius = bounds.radius().max(1e-3);
        let from = FRAMING_DIRECTION.normalize();
        OrbitCamera {
            target: bounds.center(),
            // Far enough that the bounding sphere fits the vertical field of view.
            distance: radius / (0.5 * yfov_rad).sin(),
            yaw_rad: from.x.atan2(from.z),
            pitch_rad: from.y.asin(),
            yfov_rad,
        }
    }

    /// The orbit camera that reproduces `camera`, pivoting at `pivot_distance` ahead of it.
    pub fn from_camera(camera: &Camera, pivot_distance: f32) -> OrbitCamera {
        let back = -camera.forward;
        OrbitCamera {
            target: camera.position + camera.forward * pivot_distance,
            distance: pivot_distance,
            yaw_rad: back.x.atan2(back.z),
            pitch_rad: back.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH_RAD, MAX_PITCH_RAD),
            yfov_rad: camera.yfov_rad,
        }
    }

    /// Unit vector from the target to the eye.
    fn back(&self) -> Vec3 {
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sp, cp) = self.pitch_rad.sin_cos();
        Vec3::new(cp * sy, sp, cp * cy)
    }

    pub fn camera(&self) -> Camera {
        let back = self.back();
        let right = Vec3::Y.cross(back).normalize();
        let distance = self.distance.max(1e-4);
        Camera {
            position: self.target + back * distance,
            forward: -back,
            up: back.cross(right),
            yfov_rad: self.yfov_rad,
            znear: distance * 1e-3,
            zfar: None,
        }
    }

    /// Rotates around the target; angles in radians.
    pub fn orbit(&mut self, delta_yaw_rad: f32, delta_pitch_rad: f32) {
        self.yaw_rad = (self.yaw_rad + delta_yaw_rad).rem_euclid(std::f32::consts::TAU);
        self.pitch_rad = (self.pitch_rad + delta_pitch_rad).clamp(-MAX_PITCH_RAD, MAX_PITCH_RAD);
    }

    /// Whether every value is usable: finite, positive distance, field of view in (0, π).
    pub fn is_valid(&self) -> bool {
        self.target.is_finite()
            && self.distance.is_finite()
            && self.distance > 0.0
            && self.yaw_rad.is_finite()
            && self.pitch_rad.is_finite()
            && self.yfov_rad > 0.0
            && self.yfov_rad < std::f32::consts::PI
    }

    /// Moves the target in the view plane; the offsets are fractions of the view height.
    pub fn pan(&mut self, right_fraction: f32, up_fraction: f32) {
        let camera = self.camera();
        let right = camera.forward.cross(camera.up);
        let view_height = 2.0 * self.distance * (0.5 * self.yfov_rad).tan();
        self.target += (right * right_fraction + camera.up * up_fraction) * view_height;
    }

    /// Scales the distance to the target by `factor` (< 1 zooms in).
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(1e-4, 1e7);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_near_plane_reach_is_the_distance_to_its_unprojected_corners() {
        let camera = Camera::looking_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, 0.9, 0.05);
        let aspect = 16.0 / 9.0;
        let to_world = camera.view_projection(aspect).inverse();
        for corner in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
            // Depth 0: the near plane (wgpu's clip space).
            let p = to_world.project_point3(Vec3::new(corner.0, corner.1, 0.0));
            let distance = p.distance(camera.position);
            assert!(
                (distance - camera.near_plane_reach_m(aspect)).abs() < 1e-5 * distance,
                "{distance}"
            );
        }
    }

    #[test]
    fn framing_camera_sees_the_box_centre_in_the_middle() {
        let bounds = Aabb::from_points(&[Vec3::new(-2.0, 0.0, -1.0), Vec3::new(4.0, 3.0, 5.0)]);
        let camera = Camera::framing(&bounds);
        let clip = camera.view_projection(1.5) * bounds.center().extend(1.0);
        assert!((clip.x / clip.w).abs() < 1e-5 && (clip.y / clip.w).abs() < 1e-5);
        // Every corner lies inside the view volume.
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { bounds.min.x } else { bounds.max.x },
                if i & 2 == 0 { bounds.min.y } else { bounds.max.y },
                if i & 4 == 0 { bounds.min.z } else { bounds.max.z },
            );
            let clip = camera.view_projection(1.0) * corner.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(clip.w > 0.0 && ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{ndc}");
        }
    }

    #[test]
    fn orbit_round_trips_through_a_camera() {
        let orbit = OrbitCamera {
            target: Vec3::new(1.0, 2.0, 3.0),
            distance: 7.0,
            yaw_rad: 0.8,
            pitch_rad: 0.4,
            yfov_rad: 0.9,
        };
        let back = OrbitCamera::from_camera(&orbit.camera(), 7.0);
        assert!((back.target - orbit.target).length() < 1e-4);
        assert!((back.yaw_rad - orbit.yaw_rad).abs() < 1e-5);
        assert!((back.pitch_rad - orbit.pitch_rad).abs() < 1e-5);
    }

    #[test]
    fn pitch_is_clamped_short_of_the_pole() {
        let mut orbit = OrbitCamera::framing(&Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]));
        orbit.orbit(0.0, 10.0);
        let camera = orbit.camera();
        assert!(camera.up.is_finite() && camera.forward.is_finite());
        assert!(camera.forward.dot(camera.up).abs() < 1e-5);
    }
}
