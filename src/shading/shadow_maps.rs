//! Shadow maps of the real triangles for points, spots, the sun, and sphere and area
//! lights up to [`MAX_MAPPED_HALF_ANGLE_DEG`]: the views each light's maps are
//! rasterised from (`shaders/shadow_lookup.wgsl`, `shadow_map_visibility`, reads them).
//! The f64 twin of what they measure — the share of the light a receiver sees past the
//! scene's triangles, by ray casts on the bake's BVH — is `cpu::mapped_visibility`.
//!
//! Views: the sun one orthographic view over the scene's bounding sphere; a spot whose
//! cone's cosine is at least [`SINGLE_VIEW_SPOT_MIN_COS`] one perspective view along its
//! axis; any other light far enough outside the scene's bounding sphere that it sees it
//! within 45° one perspective view aimed at it; the rest a cube of six 90° views (+x, −x,
//! +y, −y, +z, −z; a receiver reads the face of its direction's largest component, ties
//! to the earlier axis). Each perspective view is widened by [`FACE_MARGIN_TEXELS`]
//! texels on every side, so taps near a cube face's edge stay inside that face. Depth is
//! reversed: 1 at the near plane (at the scene's bounding sphere when the light is
//! outside it) and 0 at the far one. A perspective depth z/w crowds its float steps
//! toward 1, and reversing puts that end where the distance is small, so the steps stay
//! about a constant share of the distance (Reed 2015, "Depth precision visualized"); with
//! depth 0 at the near plane a light inside the scene (near plane at 1 mm) had steps of
//! 1.5 mm at 5 m, coarser than a 4096² map's texels, and its receivers shadowed
//! themselves in speckles.
//!
//! What the GPU adds to the exact visibility, and how it converges: the map quantises
//! blockers' depths into texels of the receiver's view, so edges are placed within about
//! a texel (a texel is `2·tan(half-fov)/size` of the distance to the light) and, for
//! lights of no size, softened by the bilinear comparison over 2 × 2 texels; receivers
//! are pushed toward the light and along their normal by about a texel against
//! self-shadowing (acne). All three shrink with the map's size
//! (`ShadowSettings::shadow_map_size`). Sized lights add the penumbra filter's own
//! approximations (one mean blocker depth per receiver, 48 taps; see the WGSL), which do
//! not shrink with the size: the study's small-light suites measure them against the
//! path tracer.

use glam::Vec3;

use super::gpu_types::{GpuLight, GpuShadowView, LIGHT_DIRECTIONAL, LIGHT_SPOT};
use super::shadow_atlas::{ShadowAtlas, WantedView};
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

/// How many views the maps of `light` take in a scene whose bounding sphere is `centre`,
/// `radius_m` (a radius of 0: unknown), or None for a light that takes no maps (a sphere
/// or area light wider than [`MAX_MAPPED_HALF_ANGLE_DEG`] seen from `centre`): one for
/// the sun and for a spot of at most 60°; one aimed at the scene for a light far enough
/// outside it that the scene fits in a cone of at most 45° half-angle (a cube face's
/// width, so the view is no coarser than a face); a cube of six otherwise.
pub fn view_count(light: &GpuLight, centre: Vec3, radius_m: f32) -> Option<usize> {
    match light.kind {
        LIGHT_DIRECTIONAL => return Some(1),
        LIGHT_SPOT if single_view_spot(light) => return Some(1),
        LIGHT_SPOT => {}
        _ if light.source_size > 0.0 => {
            let half_angle_deg = super::cpu::incidence(light, centre.as_dvec3())
                .cap_ratio
                .clamp(0.0, 1.0)
                .asin()
                .to_degrees();
            if half_angle_deg > MAX_MAPPED_HALF_ANGLE_DEG {
                return None;
            }
        }
        _ => {}
    }
    Some(if fitted_view(light, centre, radius_m).is_some() {
        1
    } else {
        6
    })
}

/// The widest sphere or area light (angular radius at the scene's centre, degrees) that
/// takes shadow maps with penumbrae: wider ones keep the sphere blockers' exact or SH
/// shadows, since the filter's one average blocker depth and its sparse taps stop
/// describing a penumbra that spans much of the scene (measured in the study's
/// small-light suites).
pub const MAX_MAPPED_HALF_ANGLE_DEG: f64 = 20.0;

/// Whether a light at `light`'s position sees the whole bounding sphere within 45° of its
/// axis: the axis and the tangent of that half-angle.
fn fitted_view(light: &GpuLight, centre: Vec3, radius_m: f32) -> Option<(Vec3, f32)> {
    if radius_m <= 0.0 || light.kind == LIGHT_DIRECTIONAL {
        return None;
    }
    let to_centre = centre - Vec3::from_slice(&light.position[..3]);
    let distance = to_centre.length();
    // The sphere's tangent cone: sin = r/d; at most 45° when d ≥ √2·r.
    (distance >= std::f32::consts::SQRT_2 * radius_m).then(|| {
        let tan_half = radius_m / (distance * distance - radius_m * radius_m).sqrt();
        (to_centre / distance, tan_half)
    })
}

fn single_view_spot(light: &GpuLight) -> bool {
    light.spot_cone[0] >= SINGLE_VIEW_SPOT_MIN_COS
}

/// The views of the lights' shadow maps and where they lie in the map array.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ShadowViews {
    /// In view order (`GpuLight::first_shadow_view`); a slot no light uses is zeroed (its
    /// atlas square has side 0 and is not drawn).
    pub views: Vec<GpuShadowView>,
    pub atlas: ShadowAtlas,
}

impl ShadowViews {
    /// The narrowest texel, in metres, any of these views lays on a box `bounds`: a
    /// perspective view's at the box's point nearest its eye, an orthographic view's
    /// everywhere; infinite without views. A surface drawn inside the true one by less
    /// than about that does not shadow itself (shadow_lookup.wgsl pushes each receiver
    /// out by more): it bounds how far the levels of detail may lie from the meshes the
    /// maps were drawn from (`scene::detail_levels::MAX_SHADOW_TEXEL_SHARE`).
    pub fn finest_texel_m(&self, bounds: &Aabb) -> f32 {
        self.views
            .iter()
            // A slot no light uses is zeroed.
            .filter(|view| view.depth_range[2] > 0.0)
            .map(|view| {
                if view.texel[2] > 0.5 {
                    view.texel[0] * bounds.distance_to(Vec3::from_slice(&view.eye[..3]))
                } else {
                    view.texel[1]
                }
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// These views, with each single view whose light moved since `drawn` was drawn (its
    /// view differs) as its [`drafted`] form, and each one `drawn` already holds as a
    /// draft kept so: what the editor draws while a light is dragged, since a whole
    /// doubled layer takes four times a face's raster work (`render --time-frames`, the
    /// frame after a light moved; docs/performance.md), and what it redraws in full once
    /// the drag ends.
    pub fn drafted_where_moved(&self, drawn: &[GpuShadowView]) -> ShadowViews {
        let views = self
            .views
            .iter()
            .enumerate()
            .map(|(k, view)| {
                let draft = drafted(view);
                match drawn.get(k) {
                    _ if draft == *view => *view,
                    Some(before) if *before == draft => draft,
                    Some(before) if before.view_proj != view.view_proj => draft,
                    _ => *view,
                }
            })
            .collect();
        ShadowViews {
            views,
            atlas: self.atlas.clone(),
        }
    }
}

/// A single view (one taking a whole layer) drawn at half its resolution into the top-left
/// quadrant of its layer: the same projection, texels twice as wide. Views in a quadrant
/// already are returned unchanged.
pub fn drafted(view: &GpuShadowView) -> GpuShadowView {
    if view.atlas[2] != 1.0 {
        return *view;
    }
    let mut draft = *view;
    draft.texel[0] *= 2.0;
    draft.texel[1] *= 2.0;
    draft.depth_range[2] = (view.depth_range[2] / 2.0).max(1.0);
    draft.atlas[2] = 0.5;
    draft
}

/// The views of every light with a shadow map (`first_shadow_view` and
/// `shadow_view_count` set by `shading_lights`), in view order, for a scene within
/// `bounds`, cube faces `size` texels on a side and single views as the atlas allows
/// ([`super::shadow_atlas`]). Views of lights without a map are left out; the list is as
/// long as the largest view index used plus one.
pub fn shadow_views(lights: &[GpuLight], bounds: &Aabb, size: u32) -> ShadowViews {
    let mapped: Vec<&GpuLight> = lights
        .iter()
        .filter(|light| light.shadow_path == super::gpu_types::SHADOW_PATH_MAP && light.shadow_view_count > 0)
        .collect();
    let (centre, radius) = bounding_sphere(bounds);
    let view_slots = mapped
        .iter()
        .map(|light| (light.first_shadow_view + light.shadow_view_count) as usize)
        .max()
        .unwrap_or(0);
    // What each slot asks of the atlas; slots no light uses ask for nothing.
    let mut wanted: Vec<Option<WantedView>> = vec![None; view_slots];
    for light in &mapped {
        let first = light.first_shadow_view as usize;
        let cube_face = light.shadow_view_count == 6;
        let range_share = range_m(light).map(|range| range / radius);
        for slot in &mut wanted[first..first + light.shadow_view_count as usize] {
            *slot = Some(WantedView { cube_face, range_share });
        }
    }
    let asked: Vec<WantedView> = wanted.iter().flatten().copied().collect();
    let atlas = ShadowAtlas::new(&asked, size);
    // Slot k's index among the views asked.
    let mut asked_index = vec![usize::MAX; view_slots];
    for (index, slot) in wanted
        .iter()
        .enumerate()
        .filter(|(_, w)| w.is_some())
        .map(|(k, _)| k)
        .enumerate()
    {
        asked_index[slot] = index;
    }
    let mut views: Vec<GpuShadowView> = vec![bytemuck::Zeroable::zeroed(); view_slots];
    for light in mapped {
        let (count, first) = (light.shadow_view_count as usize, light.first_shadow_view as usize);
        let position = Vec3::from_slice(&light.position[..3]);
        let direction = Vec3::from_slice(&light.direction_range[..3]).normalize_or(Vec3::NEG_Y);
        let up_for = |forward: Vec3| if forward.y.abs() > 0.9 { Vec3::X } else { Vec3::Y };
        let side = atlas.view_size(asked_index[first]);
        let reach = Reach {
            centre,
            radius,
            range_m: range_m(light),
        };
        match (light.kind, count) {
            (LIGHT_DIRECTIONAL, _) => views[first] = orthographic_view(direction, centre, radius, side),
            (LIGHT_SPOT, 1) if single_view_spot(light) => {
                let half_angle = light.spot_cone[0].clamp(-1.0, 1.0).acos();
                views[first] = perspective_view(position, direction, up_for(direction), half_angle.tan(), &reach, side);
            }
            (_, 1) => {
                // Aimed at the scene; a scene that grew around the light since falls back
                // to a 45° view, which the lookup leaves unshadowed outside.
                let (forward, tan_half) =
                    fitted_view(light, centre, radius).unwrap_or(((centre - position).normalize_or(Vec3::NEG_Y), 1.0));
                views[first] = perspective_view(position, forward, up_for(forward), tan_half, &reach, side);
            }
            _ => {
                for (k, (forward, up)) in CUBE_FACES.iter().enumerate() {
                    views[first + k] = perspective_view(position, *forward, *up, 1.0, &reach, side);
                }
            }
        }
        for (k, view) in views.iter_mut().enumerate().skip(first).take(count) {
            view.atlas = atlas.squares[asked_index[k]];
        }
    }
    ShadowViews { views, atlas }
}

/// A point or spot light's range in metres (glTF `range`), None without one.
fn range_m(light: &GpuLight) -> Option<f32> {
    let range = light.direction_range[3];
    (light.kind != LIGHT_DIRECTIONAL && range > 0.0 && range.is_finite()).then_some(range)
}

/// What a perspective view has to see: the scene's bounding sphere, and no farther from
/// the light than its range.
#[derive(Clone, Copy)]
struct Reach {
    centre: Vec3,
    radius: f32,
    range_m: Option<f32>,
}

/// The sphere the maps' views cover: the centre of `bounds` and half their diagonal
/// (the origin and 1 m for empty bounds).
pub fn bounding_sphere(bounds: &Aabb) -> (Vec3, f32) {
    if bounds.is_empty() {
        return (Vec3::ZERO, 1.0);
    }
    (bounds.center(), bounds.radius().max(1e-3))
}

/// A perspective view from `eye` along `forward` whose half-width is `tan_half` (at unit
/// distance) widened by the face margin, with near and far planes around the scene's
/// bounding sphere, the far one no farther than the light's range: past it the light
/// shadows nothing, and a far plane there keeps the depths finer and leaves out of the
/// view (and of its drawing) what the light cannot reach.
fn perspective_view(eye: Vec3, forward: Vec3, up: Vec3, tan_half: f32, reach: &Reach, size: u32) -> GpuShadowView {
    let Reach {
        centre,
        radius,
        range_m,
    } = *reach;
    let size = size.max(1) as f32;
    // Widened so that the nominal field of view keeps FACE_MARGIN_TEXELS texels on each side.
    let tan_wide = tan_half * size / (size - 2.0 * FACE_MARGIN_TEXELS).max(1.0);
    let scene_far = ((centre - eye).length() + radius) * 1.01 + 1e-3;
    // Along the view's axis a receiver within the range is at most the range away.
    let far = range_m.map_or(scene_far, |range| scene_far.min(range * 1.01 + 1e-3));
    // Nothing nearer than the scene's bounding sphere casts: starting the depth range
    // there keeps a far light's depths fine (a near plane at far·10⁻⁴ left a light 200 m
    // away with depth steps of 10 cm, which showed as speckled self-shadowing).
    let nearest_m = (centre - eye).length() - radius;
    let near = (far * 1e-4).max(1e-3).max(0.99 * nearest_m);
    // A range that ends before the scene begins: a valid (empty) depth range all the same.
    let near = if far < scene_far { near.min(0.5 * far) } else { near };
    let view = glam::camera::rh::view::look_to_mat4(eye, forward, up);
    // Near and far swapped: reversed depth (the module's documentation).
    let projection = glam::camera::rh::proj::directx::perspective(2.0 * tan_wide.atan(), 1.0, far, near);
    let nearest = nearest_m.max(near);
    GpuShadowView {
        view_proj: (projection * view).to_cols_array_2d(),
        texel: [2.0 * tan_wide / size, 0.0, 1.0, 0.0],
        eye: eye.extend(1.0).to_array(),
        depth_range: [near, far, size, nearest],
        atlas: [0.0; 4],
    }
}

/// An orthographic view along `direction` covering the scene's bounding sphere.
fn orthographic_view(direction: Vec3, centre: Vec3, radius: f32, size: u32) -> GpuShadowView {
    let up = if direction.y.abs() > 0.9 { Vec3::X } else { Vec3::Y };
    let eye = centre - direction * (radius * 1.01 + 1e-3);
    let view = glam::camera::rh::view::look_at_mat4(eye, centre, up);
    let depth = 2.0 * (radius * 1.01 + 1e-3);
    // Reversed like the perspective views' (1 nearest the sun), so one comparison serves both.
    let projection = glam::camera::rh::proj::directx::orthographic(-radius, radius, -radius, radius, depth, 0.0);
    GpuShadowView {
        view_proj: (projection * view).to_cols_array_2d(),
        texel: [0.0, 2.0 * radius / size.max(1) as f32, 0.0, 0.0],
        eye: direction.extend(0.0).to_array(),
        depth_range: [0.0, depth, size.max(1) as f32, 0.0],
        atlas: [0.0; 4],
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

#[cfg(test)]
mod tests {
    use bytemuck::Zeroable;
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
            locked: false,
        });
        light.shadow_path = super::super::gpu_types::SHADOW_PATH_MAP;
        light.first_shadow_view = 0;
        light.shadow_view_count = view_count(&light, Vec3::ZERO, 0.0).unwrap_or(0) as u32;
        light
    }

    fn clip(view: &GpuShadowView, p: Vec3) -> Vec3 {
        let c = Mat4::from_cols_array_2d(&view.view_proj) * p.extend(1.0);
        c.truncate() / c.w
    }

    #[test]
    fn the_finest_texel_on_a_box_is_a_cube_faces_at_its_nearest_point_or_a_suns_everywhere() {
        let bounds = Aabb::from_points(&[Vec3::splat(-8.0), Vec3::splat(8.0)]);
        let lamp = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
        let views = shadow_views(&[lamp], &bounds, 512);
        // A box whose nearest point lies 4 m from the lamp: a 90° face of 512 texels is
        // 2 tan 45° / 512 wide per metre there (its margin widens it a little).
        let far_box = Aabb::from_points(&[Vec3::new(4.0, -1.0, -1.0), Vec3::new(5.0, 1.0, 1.0)]);
        let lamp_texel = views.finest_texel_m(&far_box);
        let nominal = 2.0 * 4.0 / 512.0;
        assert!(
            (nominal..1.1 * nominal).contains(&lamp_texel),
            "{lamp_texel} against {nominal}"
        );
        // A box holding the lamp: no finer texel than at the eye itself.
        assert_eq!(views.finest_texel_m(&bounds), 0.0);
        let sun = mapped(
            crate::scene::LightKind::Directional,
            Vec3::ZERO,
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        let sun_views = shadow_views(&[sun], &bounds, 1024);
        let texel = sun_views.finest_texel_m(&far_box);
        assert_eq!(texel, sun_views.views[0].texel[1]);
        assert!(texel > 0.0 && texel < 1.0);
        assert_eq!(ShadowViews::default().finest_texel_m(&far_box), f32::INFINITY);
        // A zeroed slot stands for no view.
        let mut with_empty_slot = views.clone();
        with_empty_slot.views.push(GpuShadowView::zeroed());
        assert_eq!(with_empty_slot.finest_texel_m(&far_box), lamp_texel);
    }

    #[test]
    fn a_point_lights_faces_see_each_direction_in_the_face_cube_face_picks() {
        let light = mapped(crate::scene::LightKind::Point, Vec3::new(0.5, 1.0, -0.25), Vec3::NEG_Y);
        let bounds = Aabb::from_points(&[Vec3::splat(-3.0), Vec3::splat(3.0)]);
        let views = shadow_views(&[light], &bounds, 256).views;
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
    fn a_lamps_faces_end_at_its_range_and_keep_its_reach_as_fine_as_the_scene() {
        // A lamp of 1 m range inside a scene of radius 5√3 m ≈ 8.7 m: its faces halve while
        // a texel at 1 m stays no wider than a 1024² face's at 8.7 m (1024/8 = 128 ≥ 118).
        let mut lamp = mapped(crate::scene::LightKind::Point, Vec3::new(1.0, 0.5, 0.0), Vec3::NEG_Y);
        lamp.direction_range[3] = 1.0;
        let bounds = Aabb::from_points(&[Vec3::splat(-5.0), Vec3::splat(5.0)]);
        let ranged = shadow_views(&[lamp], &bounds, 1024);
        assert_eq!(ranged.atlas.view_size(0), 128);
        let texel_at_range = ranged.views[0].texel[0] * 1.0;
        let full_face_at_radius = 2.0 / 1024.0 * bounds.radius();
        assert!(
            texel_at_range <= full_face_at_radius,
            "{texel_at_range} > {full_face_at_radius}"
        );
        for view in &ranged.views {
            let far = view.depth_range[1];
            assert!((1.0..1.02).contains(&far), "far plane at {far} m, not at the range");
        }
        // Depth still falls with distance, and a point past the range is past the far plane.
        let eye = Vec3::new(1.0, 0.5, 0.0);
        let (inside, past) = (
            clip(&ranged.views[0], eye + Vec3::new(0.9, 0.0, 0.0)).z,
            clip(&ranged.views[0], eye + Vec3::new(1.5, 0.0, 0.0)).z,
        );
        assert!(inside > 0.0 && past < 0.0, "{inside} {past}");
        // Without the range: full faces to the scene's far side.
        lamp.direction_range[3] = 0.0;
        let unranged = shadow_views(&[lamp], &bounds, 1024);
        assert_eq!(unranged.atlas.view_size(0), 1024);
        assert!(unranged.views[0].depth_range[1] > 8.0);
    }

    #[test]
    fn depth_falls_with_distance_along_a_view() {
        let light = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
        let bounds = Aabb::from_points(&[Vec3::splat(-2.0), Vec3::splat(2.0)]);
        let views = shadow_views(&[light], &bounds, 512).views;
        let near = clip(&views[0], Vec3::new(0.5, 0.0, 0.0)).z;
        let far = clip(&views[0], Vec3::new(2.5, 0.0, 0.0)).z;
        assert!(1.0 > near && near > far && far > 0.0, "{near} {far}");
    }

    /// The distance a perspective view's depth stands for, as shadow_lookup.wgsl's
    /// view_distance inverts it: d = near·far / (near + z·(far − near)).
    fn view_distance(view: &GpuShadowView, depth: f32) -> f32 {
        let [near, far, ..] = view.depth_range;
        near * far / (near + depth * (far - near))
    }

    #[test]
    fn depth_steps_stay_a_small_share_of_the_distance() {
        // A light inside the scene: the near plane at a millimetre. One float step of the
        // stored depth must stand for far less than a 4096² map's texel (about 0.05 % of
        // the distance for a 90° face) at any distance in the scene.
        let light = mapped(crate::scene::LightKind::Point, Vec3::ZERO, Vec3::NEG_Y);
        let bounds = Aabb::from_points(&[Vec3::splat(-10.0), Vec3::splat(10.0)]);
        let view = shadow_views(&[light], &bounds, 4096).views[0];
        for distance in [0.05_f32, 0.5, 2.0, 5.0, 12.0, 17.0] {
            let z = clip(&view, Vec3::new(distance, 0.0, 0.0)).z;
            let round_trip = view_distance(&view, z);
            assert!(
                (round_trip - distance).abs() < 1e-4 * distance,
                "{distance} → {round_trip}"
            );
            let step = view_distance(&view, z - z * f32::EPSILON) - distance;
            assert!(step.abs() < 2e-5 * distance, "a depth step at {distance} m is {step} m");
        }
    }

    /// Every corner of `bounds` lands inside `view`'s clip volume.
    fn assert_sees_every_corner(view: &GpuShadowView, bounds: &Aabb) {
        for p in bounds.corners() {
            let q = clip(view, p);
            assert!(
                q.x.abs() <= 1.0 && q.y.abs() <= 1.0 && (0.0..=1.0).contains(&q.z),
                "{p} → {q}"
            );
        }
    }

    #[test]
    fn the_suns_view_covers_the_scene() {
        let light = mapped(
            crate::scene::LightKind::Directional,
            Vec3::ZERO,
            Vec3::new(0.3, -1.0, 0.2).normalize(),
        );
        let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
        let view = shadow_views(&[light], &bounds, 1024).views[0];
        assert_sees_every_corner(&view, &bounds);
        // Depth is reversed: nearer the sun is deeper.
        assert!(clip(&view, Vec3::new(0.0, 3.0, 0.0)).z > clip(&view, Vec3::ZERO).z);
    }

    #[test]
    fn a_light_far_outside_the_scene_sees_it_in_one_view_and_a_near_one_in_a_cube() {
        let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
        let (centre, radius) = bounding_sphere(&bounds);
        let sun_like = |position: Vec3| {
            let mut light = mapped(crate::scene::LightKind::Sphere { radius_m: 0.5 }, position, Vec3::NEG_Y);
            light.shadow_view_count = view_count(&light, centre, radius).unwrap_or(0) as u32;
            light
        };
        let far = sun_like(Vec3::new(30.0, 60.0, -20.0));
        assert_eq!(far.shadow_view_count, 1);
        let view = shadow_views(&[far], &bounds, 1024).views[0];
        assert_sees_every_corner(&view, &bounds);
        // A spot wider than 60° that far out: one view aimed at the scene, not its cone.
        let mut wide_spot = mapped(
            crate::scene::LightKind::Spot {
                inner_cone_rad: 1.0,
                outer_cone_rad: 1.3,
            },
            Vec3::new(30.0, 60.0, -20.0),
            Vec3::new(-0.4, -0.8, 0.3).normalize(),
        );
        wide_spot.shadow_view_count = view_count(&wide_spot, centre, radius).unwrap_or(0) as u32;
        assert_eq!(wide_spot.shadow_view_count, 1);
        let spot_view = shadow_views(&[wide_spot], &bounds, 1024).views[0];
        assert_sees_every_corner(&spot_view, &bounds);
        assert!(
            spot_view.texel[0] < view.texel[0] * 1.01,
            "no coarser than the fitted view"
        );
        // Inside the scene's sphere: a cube.
        assert_eq!(sun_like(Vec3::new(3.0, 2.0, 1.0)).shadow_view_count, 6);
        // Too wide at the centre (a 1 m sphere 2 m away is 30° in radius): no maps.
        let wide = mapped(
            crate::scene::LightKind::Sphere { radius_m: 1.0 },
            centre + Vec3::Y * 2.0,
            Vec3::NEG_Y,
        );
        assert_eq!(view_count(&wide, centre, radius), None);
    }

    #[test]
    fn a_moved_single_view_is_drafted_until_drawn_at_rest_and_faces_never_are() {
        let bounds = Aabb::from_points(&[Vec3::new(-4.0, 0.0, -2.0), Vec3::new(4.0, 3.0, 2.0)]);
        let spot = |x: f32| {
            let mut light = mapped(
                crate::scene::LightKind::Spot {
                    inner_cone_rad: 0.3,
                    outer_cone_rad: 0.4,
                },
                Vec3::new(x, 2.5, 1.0),
                Vec3::NEG_Y,
            );
            light.first_shadow_view = 0;
            light
        };
        let mut point = mapped(crate::scene::LightKind::Point, Vec3::new(1.0, 2.0, 0.0), Vec3::NEG_Y);
        point.first_shadow_view = 1;
        let at_rest = shadow_views(&[spot(0.0), point], &bounds, 512);
        let moved = shadow_views(&[spot(0.1), point], &bounds, 512);
        let dragged = moved.drafted_where_moved(&at_rest.views);
        let draft = dragged.views[0];
        assert_eq!(draft.atlas, [0.0, 0.0, 0.5, moved.views[0].atlas[3]]);
        assert_eq!(draft.depth_range[2], moved.views[0].depth_range[2] / 2.0);
        assert_eq!(draft.texel[0], 2.0 * moved.views[0].texel[0]);
        assert_eq!(
            &dragged.views[1..],
            &moved.views[1..],
            "the point light's faces did not move"
        );
        // Held still while dragging: the draft is kept, not drawn again in full.
        assert_eq!(moved.drafted_where_moved(&dragged.views), dragged);
        // An unmoved light is drawn in full.
        assert_eq!(at_rest.drafted_where_moved(&at_rest.views), at_rest);
    }
}
