//! The view frustum of a camera as planes, for culling objects the view cannot see.
//!
//! The planes are read off the rows of the view-projection matrix M (Gribb and Hartmann,
//! "Fast extraction of viewing frustum planes from the world-view-projection matrix",
//! 2001): a point p is inside where −w ≤ x ≤ w, −w ≤ y ≤ w and 0 ≤ z ≤ w for
//! (x, y, z, w) = M·(p, 1) (wgpu's clip space), so each plane is a row of M added to or
//! taken from its last row, r₄ ± r₁, r₄ ± r₂, r₃ and r₄ − r₃, with the inside where
//! n·p + d ≥ 0. An infinite far plane (r₄ − r₃ = 0 up to rounding) is left out.
//!
//! The box test is conservative: a box is culled only when its corner farthest along a
//! plane's normal lies outside that plane, so no box that reaches into the view is culled
//! (some wholly outside beside a corner of the frustum are kept).

use glam::{Mat4, Vec3, Vec4};

use super::{Aabb, Camera};

/// Planes (n, d) with the inside where n·p + d ≥ 0, world space.
#[derive(Debug, Clone, PartialEq)]
pub struct Frustum {
    planes: Vec<Vec4>,
}

impl Frustum {
    /// The frustum of `view_projection` (wgpu's clip space: depth 0 to 1).
    pub fn from_view_projection(view_projection: Mat4) -> Frustum {
        let row = |i: usize| view_projection.row(i);
        let candidates = [
            row(3) + row(0),
            row(3) - row(0),
            row(3) + row(1),
            row(3) - row(1),
            row(2),
            row(3) - row(2),
        ];
        let planes = candidates
            .into_iter()
            // The far plane of an infinite projection has (almost) no normal: no plane.
            .filter(|plane| plane.truncate().length() > 1e-6 * plane.w.abs().max(1.0))
            .map(|plane| plane / plane.truncate().length())
            .collect();
        Frustum { planes }
    }

    /// The frustum `camera` sees through an image of `aspect` (width over height).
    pub fn of_camera(camera: &Camera, aspect: f32) -> Frustum {
        Frustum::from_view_projection(camera.view_projection(aspect))
    }

    /// False only when `bounds` lies wholly outside one of the planes (an empty box is
    /// outside; a box or frustum with NaN in it is kept).
    pub fn may_see(&self, bounds: &Aabb) -> bool {
        if bounds.is_empty() {
            return false;
        }
        self.planes.iter().all(|plane| {
            let normal = plane.truncate();
            // The corner farthest along the normal.
            let farthest = Vec3::select(normal.cmpge(Vec3::ZERO), bounds.max, bounds.min);
            // Outside only when the distance is below 0: NaN keeps the box.
            let distance = normal.dot(farthest) + plane.w;
            distance.partial_cmp(&0.0) != Some(std::cmp::Ordering::Less)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(zfar: Option<f32>) -> Camera {
        Camera {
            zfar,
            ..Camera::looking_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 60f32.to_radians(), 0.1)
        }
    }

    fn cube(center: Vec3, half: f32) -> Aabb {
        Aabb {
            min: center - Vec3::splat(half),
            max: center + Vec3::splat(half),
        }
    }

    #[test]
    fn an_infinite_projection_has_five_planes_and_a_finite_one_six() {
        assert_eq!(Frustum::of_camera(&camera(None), 1.5).planes.len(), 5);
        assert_eq!(Frustum::of_camera(&camera(Some(50.0)), 1.5).planes.len(), 6);
    }

    /// The camera at z = 5 looks down −z with a 60° vertical field: at distance t the
    /// view reaches t·tan 30° up and down and aspect times that sideways.
    #[test]
    fn boxes_just_beyond_each_edge_are_culled_and_boxes_just_within_are_kept() {
        let aspect = 1.5;
        let frustum = Frustum::of_camera(&camera(None), aspect);
        let t = 5.0; // the box centres lie in the plane z = 0, 5 m ahead
        let half_height = t * 30f32.to_radians().tan();
        let half_width = aspect * half_height;
        let half = 0.05;
        for (direction, reach) in [
            (Vec3::X, half_width),
            (Vec3::NEG_X, half_width),
            (Vec3::Y, half_height),
            (Vec3::NEG_Y, half_height),
        ] {
            // The box's near face (z = +half) sees a little more than the plane z = 0.
            let slack = half * reach / t + 2.0 * half;
            assert!(
                !frustum.may_see(&cube(direction * (reach + slack), half)),
                "{direction}"
            );
            assert!(
                frustum.may_see(&cube(direction * (reach + 0.5 * half), half)),
                "{direction}"
            );
        }
        assert!(frustum.may_see(&cube(Vec3::ZERO, 0.1)));
    }

    #[test]
    fn boxes_behind_the_camera_or_before_the_near_plane_or_beyond_the_far_one_are_culled() {
        let near_and_far = Frustum::of_camera(&camera(Some(20.0)), 1.0);
        assert!(!near_and_far.may_see(&cube(Vec3::new(0.0, 0.0, 7.0), 0.5)));
        assert!(!near_and_far.may_see(&cube(Vec3::new(0.0, 0.0, 4.95), 0.02)));
        assert!(!near_and_far.may_see(&cube(Vec3::new(0.0, 0.0, -16.0), 0.5)));
        assert!(near_and_far.may_see(&cube(Vec3::new(0.0, 0.0, -14.0), 0.5)));
        // Without a far plane, nothing ahead is too far.
        let infinite = Frustum::of_camera(&camera(None), 1.0);
        assert!(infinite.may_see(&cube(Vec3::new(0.0, 0.0, -1.0e5), 0.5)));
    }

    #[test]
    fn a_box_around_the_camera_or_across_the_view_is_kept_and_an_empty_one_is_not() {
        let frustum = Frustum::of_camera(&camera(None), 1.0);
        assert!(frustum.may_see(&cube(Vec3::new(0.0, 0.0, 5.0), 1.0)));
        let wall = Aabb {
            min: Vec3::new(-100.0, -100.0, -1.0),
            max: Vec3::new(100.0, 100.0, -0.9),
        };
        assert!(frustum.may_see(&wall));
        assert!(!frustum.may_see(&Aabb::EMPTY));
    }

    proptest::proptest! {
        /// Conservative: a box holding a point the camera sees is never culled.
        #[test]
        fn a_box_around_a_seen_point_is_kept(
            ndc_x in -0.999f32..0.999,
            ndc_y in -0.999f32..0.999,
            depth_m in 0.2f32..500.0,
            half in 0.0f32..3.0,
            yaw in -3.1f32..3.1,
            pitch in -1.4f32..1.4,
            aspect in 0.3f32..4.0,
        ) {
            let forward = Vec3::new(pitch.cos() * yaw.sin(), pitch.sin(), -pitch.cos() * yaw.cos());
            let camera = Camera::looking_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 3.0) + forward, 50f32.to_radians(), 0.1);
            let view_projection = camera.view_projection(aspect);
            // The seen point: back from normalised device coordinates at a view depth.
            let ahead = camera.position + camera.forward * depth_m;
            let clip = view_projection * ahead.extend(1.0);
            let ndc_depth = clip.z / clip.w;
            let point = view_projection.inverse().project_point3(Vec3::new(ndc_x, ndc_y, ndc_depth));
            let frustum = Frustum::from_view_projection(view_projection);
            proptest::prop_assert!(frustum.may_see(&cube(point, half)), "{point} half {half}");
        }
    }
}
