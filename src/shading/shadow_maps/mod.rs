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

/// The views of a cube of maps (a point light's, `GpuLight::shadow_view_count`).
pub const CUBE_VIEW_COUNT: u32 = 6;

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
        let cube_face = light.shadow_view_count == CUBE_VIEW_COUNT;
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

/// A receiver at `offset` from a point light in the frame of cube face `face` (the one
/// that sees it is [`cube_face`]; a tap pushed past a face's edge still reads the
/// receiver's face, within its margin): its right and up coordinates and its distance
/// along the face's axis, from the face's forward axis and up vector (`CUBE_FACES`,
/// `look_to`). A face's view then projects it to (h·x/d, h·y/d) with h = 1 / tan of its
/// widened half-angle, and to the depth near·(far − d) / (d·(far − near)) (reversed):
/// shadow_lookup.wgsl's cube_face_tap works a face's tap out so rather than reading its
/// matrix.
pub fn cube_face_coordinates(offset: Vec3, face: usize) -> Vec3 {
    let o = offset;
    match face {
        0 => Vec3::new(-o.z, -o.y, o.x),
        1 => Vec3::new(o.z, -o.y, -o.x),
        2 => Vec3::new(o.x, o.z, o.y),
        3 => Vec3::new(o.x, -o.z, -o.y),
        4 => Vec3::new(o.x, -o.y, o.z),
        _ => Vec3::new(-o.x, -o.y, -o.z),
    }
}

#[cfg(test)]
mod tests;
