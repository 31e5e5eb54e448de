//! Shadow maps of the real triangles for lights of no size (points, spots, the sun): the
//! views each light's maps are rasterised from, and the f64 twin of what they measure —
//! whether the segment from a receiver to the light is free — by ray casts on the bake's
//! BVH (`shaders/logsh.wgsl`, `shadow_map_visibility`).
//!
//! Views: a spot whose cone's cosine is at least [`SINGLE_VIEW_SPOT_MIN_COS`] gets one
//! perspective view along its axis; a point light, or a wider spot, a cube of six 90°
//! views (+x, −x, +y, −y, +z, −z; a receiver reads the face of its direction's largest
//! component, ties to the earlier axis); the sun one orthographic view over the scene's
//! bounding sphere. Each perspective view is widened by [`FACE_MARGIN_TEXELS`] texels on
//! every side, so the filter's taps near a cube face's edge stay inside that face. Depth
//! runs 0 at the near plane to 1 at the far one (wgpu's clip space).
//!
//! What the GPU adds to the exact visibility, and how it converges: the map quantises
//! blockers' depths into texels of the receiver's view, so edges are placed within about
//! a texel (a texel is `2·tan(half-fov)/size` of the distance to the light) and softened
//! by the percentage-closer filter over 3 × 3 texels; receivers are pushed toward the light
//! and along their normal by about a texel against self-shadowing (acne). All three
//! shrink with the map's size (`ShadowSettings::shadow_map_size`).

use glam::{DVec3, Vec3};

use super::gpu_types::{GpuLight, GpuShadowView, LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT};
use crate::bake::scene_bvh::SceneBvh;
use crate::scene::Aabb;

/// A spot whose cos(outer cone) is at least this (a cone of at most 60°) is drawn in one
/// view; a wider one in a cube (WGSL `SINGLE_VIEW_SPOT_MIN_COS`).
pub const SINGLE_VIEW_SPOT_MIN_COS: f32 = 0.5;

/// Texels added on each side of a perspective view beyond its nominal field of view.
pub const FACE_MARGIN_TEXELS: f32 = 4.0;

/// The cube faces' forward axes and up vectors, in face order.
const CUBE_FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::NEG_Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::NEG_Z),
    (Vec3::Z, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_Y),
];

/// How many views the maps of `light` take; None for a light that gets none (extended
/// lights: spheres and area lights).
pub fn view_count(light: &GpuLight) -> Option<usize> {
    match light.kind {
        LIGHT_DIRECTIONAL => Some(1),
        LIGHT_SPOT if light.source_size == 0.0 => Some(if single_view_spot(light) { 1 } else { 6 }),
        LIGHT_POINT if light.source_size == 0.0 => Some(6),
        _ => None,
    }
}

fn single_view_spot(light: &GpuLight) -> bool {
    light.spot_cone[0] >= SINGLE_VIEW_SPOT_MIN_COS
}

/// The views of every light with a shadow map (`first_shadow_view` set by
/// `shading_lights`), in view order, for a scene within `bounds`, maps `size` texels on a
/// side. Views of lights without a map are left out; the result is as long as the
/// largest view index used plus one.
pub fn shadow_views(lights: &[GpuLight], bounds: &Aabb, size: u32) -> Vec<GpuShadowView> {
    let mut views: Vec<GpuShadowView> = Vec::new();
    let (centre, radius) = bounding_sphere(bounds);
    for light in lights {
        let (Some(count), first) = (view_count(light), light.first_shadow_view as usize) else {
            continue;
        };
        if light.shadow_path != super::gpu_types::SHADOW_PATH_MAP {
            continue;
        }
        let needed = first + count;
        if views.len() < needed {
            views.resize(needed, bytemuck::Zeroable::zeroed());
        }
        let position = Vec3::from_slice(&light.position[..3]);
        let direction = Vec3::from_slice(&light.direction_range[..3]).normalize_or(Vec3::NEG_Y);
        match light.kind {
            LIGHT_DIRECTIONAL => views[first] = orthographic_view(direction, centre, radius, size),
            LIGHT_SPOT if count == 1 => {
                let half_angle = light.spot_cone[0].clamp(-1.0, 1.0).acos();
                let up = if direction.y.abs() > 0.9 { Vec3::X } else { Vec3::Y };
                views[first] = perspective_view(position, direction, up, half_angle.tan(), centre, radius, size);
            }
            _ => {
                for (k, (forward, up)) in CUBE_FACES.iter().enumerate() {
                    views[first + k] = perspective_view(position, *forward, *up, 1.0, centre, radius, size);
                }
            }
        }
    }
    views
}

fn bounding_sphere(bounds: &Aabb) -> (Vec3, f32) {
    if bounds.is_empty() {
        return (Vec3::ZERO, 1.0);
    }
    let centre = bounds.center();
    (centre, ((bounds.max - bounds.min).length() * 0.5).max(1e-3))
}

/// A perspective view from `eye` along `forward` whose half-width is `tan_half` (at unit
/// distance) widened by the face margin, with near and far planes around the scene's
/// bounding sphere.
fn perspective_view(
    eye: Vec3,
    forward: Vec3,
    up: Vec3,
    tan_half: f32,
    centre: Vec3,
    radius: f32,
    size: u32,
) -> GpuShadowView {
    let size = size.max(1) as f32;
    // Widened so that the nominal field of view keeps FACE_MARGIN_TEXELS texels on each side.
    let tan_wide = tan_half * size / (size - 2.0 * FACE_MARGIN_TEXELS).max(1.0);
    let far = ((centre - eye).length() + radius) * 1.01 + 1e-3;
    let near = (far * 1e-4).max(1e-3);
    let view = glam::camera::rh::view::look_to_mat4(eye, forward, up);
    let projection = glam::camera::rh::proj::directx::perspective(2.0 * tan_wide.atan(), 1.0, near, far);
    GpuShadowView {
        view_proj: (projection * view).to_cols_array_2d(),
        texel: [2.0 * tan_wide / size, 0.0, 1.0, 0.0],
        eye: eye.extend(1.0).to_array(),
    }
}

/// An orthographic view along `direction` covering the scene's bounding sphere.
fn orthographic_view(direction: Vec3, centre: Vec3, radius: f32, size: u32) -> GpuShadowView {
    let up = if direction.y.abs() > 0.9 { Vec3::X } else { Vec3::Y };
    let eye = centre - direction * (radius * 1.01 + 1e-3);
    let view = glam::camera::rh::view::look_at_mat4(eye, centre, up);
    let depth = 2.0 * (radius * 1.01 + 1e-3);
    let projection = glam::camera::rh::proj::directx::orthographic(-radius, radius, -radius, radius, 0.0, depth);
    GpuShadowView {
        view_proj: (projection * view).to_cols_array_2d(),
        texel: [0.0, 2.0 * radius / size.max(1) as f32, 0.0, 0.0],
        eye: direction.extend(0.0).to_array(),
    }
}

/// The cube face a receiver at `offset` from a point light reads (see the module's
/// documentation): 2·axis, plus 1 on the negative side.
pub fn cube_face(offset: Vec3) -> usize {
    let a = offset.abs();
    let (axis, component) = if a.x >= a.y && a.x >= a.z {
        (0, offset.x)
    } else if a.y >= a.z {
        (1, offset.y)
    } else {
        (2, offset.z)
    };
    2 * axis + usize::from(component < 0.0)
}

/// The exact visibility a shadow map approximates: 1 when nothing in `occluders` cuts the
/// segment from `p` (lifted off its surface along `n` by a millionth of the scene's
/// scale, `lift_m`) toward the light `to_light` at `distance_m` (infinite for the sun),
/// else 0.
pub fn ray_visibility(occluders: &SceneBvh, p: DVec3, n: DVec3, to_light: DVec3, distance_m: f64, lift_m: f64) -> f64 {
    let origin = p + n * lift_m.copysign(n.dot(to_light));
    let t_max = if distance_m.is_finite() {
        (distance_m - 2.0 * lift_m).max(0.0)
    } else {
        f64::INFINITY
    };
    let blocked = occluders.occluded(
        origin.as_vec3(),
        to_light.as_vec3(),
        lift_m as f32,
        t_max.min(f32::MAX as f64) as f32,
    );
    if blocked { 0.0 } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use glam::Mat4;

    use super::*;

    fn mapped(kind: crate::scene::LightKind, position: Vec3, direction: Vec3) -> GpuLight {
        let mut light = GpuLight::new(&crate::scene::Light {
            name: "light".into(),
            kind,
            color: Vec3::ONE,
            intensity: 1.0,
            position,
            direction,
            range: None,
        });
        light.shadow_path = super::super::gpu_types::SHADOW_PATH_MAP;
        light.first_shadow_view = 0;
        light
    }

    fn clip(view: &GpuShadowView, p: Vec3) -> Vec3 {
        let c = Mat4::from_cols_array_2d(&view.view_proj) * p.extend(1.0);
        c.truncate() / c.w
    }

    #[test]
    fn a_point_lights_faces_see_each_direction_in_the_face_cube_face_picks() {
        let light = mapped(crate::scene::LightKind::Point, Vec3::new(0.5, 1.0, -0.25), Vec3::NEG_Y);
        let bounds = Aabb::from_points(&[Vec3::splat(-3.0), Vec3::splat(3.0)]);
        let views = shadow_views(&[light], &bounds, 256);
        assert_eq!(views.len(), 6);
        let eye = Vec3::new(0.5, 1.0, -0.25);
        // Directions spread over the sphere, edges and corners included.
        for i in 0..200 {
            let z = -1.0 + 2.0 * (i as f32 + 0.5) / 200.0;
            let phi = i as f32 * 2.399_963;
            let d = Vec3::new((1.0 - z * z).sqrt() * phi.cos(), z, (1.0 - z * z).sqrt() * phi.sin());
            let p = eye + d * 1.7;
            let q = clip(&views[cube_face(d)], p);
            assert!(
                q.x.abs() <= 1.0 && q.y.abs() <= 1.0,
                "{d} lands at {q} on face {}",
                cube_face(d)
            );
            assert!((0.0..=1.0).contains(&q.z), "depth {}", q.z);
        }
    }

    #[test]
    fn depth_grows_with_distance_along_a_view() {
        let light = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
        let bounds = Aabb::from_points(&[Vec3::splat(-2.0), Vec3::splat(2.0)]);
        let views = shadow_views(&[light], &bounds, 512);
        let near = clip(&views[0], Vec3::new(0.5, 0.0, 0.0)).z;
        let far = clip(&views[0], Vec3::new(2.5, 0.0, 0.0)).z;
        assert!(0.0 < near && near < far && far < 1.0, "{near} {far}");
    }

    #[test]
    fn the_suns_view_covers_the_scene() {
        let light = mapped(
            crate::scene::LightKind::Directional,
            Vec3::ZERO,
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
        let view = shadow_views(&[light], &bounds, 1024)[0];
        for corner in 0..8 {
            let p = Vec3::new(
                if corner & 1 == 0 { -4.0 } else { 4.0 },
                if corner & 2 == 0 { 0.0 } else { 3.0 },
                if corner & 4 == 0 { -2.0 } else { 2.0 },
            );
            let q = clip(&view, p);
            assert!(
                q.x.abs() <= 1.0 && q.y.abs() <= 1.0 && (0.0..=1.0).contains(&q.z),
                "{p} → {q}"
            );
        }
        // Nearer the sun is shallower.
        assert!(clip(&view, Vec3::new(0.0, 3.0, 0.0)).z < clip(&view, Vec3::ZERO).z);
    }
}
