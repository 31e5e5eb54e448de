//! Rust twins of the WGSL structs in `shaders/common.wgsl` (`#[repr(C)]`, bytemuck).
//! `tests/wgsl_layout.rs` checks each size and field offset against naga's layout of the
//! WGSL source, so the two cannot drift apart.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

use crate::scene::{Camera, Environment, Light, LightKind, Material};

/// Light kind tags shared with WGSL (`LIGHT_POINT`, `LIGHT_SPOT`, `LIGHT_DIRECTIONAL`).
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_SPOT: u32 = 1;
pub const LIGHT_DIRECTIONAL: u32 = 2;
pub const LIGHT_AREA: u32 = 3;

/// Shadow paths shared with WGSL (`GpuLight::shadow_path`): through the log-SH
/// visibility, the exact share of the light's disc the sphere blockers hide, or a shadow
/// map of the real triangles rasterised from the light.
pub const SHADOW_PATH_SH: u32 = 0;
pub const SHADOW_PATH_EXACT: u32 = 1;
pub const SHADOW_PATH_MAP: u32 = 2;

/// `GpuLight::first_shadow_view` of a light without a shadow map.
pub const NO_SHADOW_VIEW: u32 = u32::MAX;

/// How many shadow-map views (squares of the map array, WGSL `MAX_SHADOW_VIEWS`) a frame
/// has at most: a point light takes six (a cube), a spot or the sun one. 384 (64 cubes,
/// 48 KiB of uniform views): a room lit by a dozen ceiling lights, a few spots and the sun
/// (the interior sample, 77 views) or by 30 lamps (the lamp room, 180) maps every light,
/// rather than leave some to the SH path, where the room's own walls and ceiling, as disc
/// blockers, would hide them; the atlas sizes the squares to fit its memory
/// (`shading::shadow_atlas`).
pub const MAX_SHADOW_VIEWS: usize = 384;

/// How many lights the uniform array `lights` of scene.wgsl holds (WGSL
/// `UNIFORM_LIGHT_CAPACITY`): as many as fit in wgpu's default 64 KiB uniform binding.
/// lavapipe reads a uniform array several times faster than a storage buffer; a frame with
/// more lights also reads the rest from a storage buffer (`LIGHT_OVERFLOW`).
pub const UNIFORM_LIGHT_CAPACITY: usize = 682;

/// How many blockers and blocker groups the uniform arrays `blockers` and `groups` of
/// logsh.wgsl hold (WGSL `UNIFORM_BLOCKER_CAPACITY`); as [`UNIFORM_LIGHT_CAPACITY`], with
/// `BLOCKER_OVERFLOW`. Groups and clusters together never outnumber blockers (a group holds
/// at least four spheres once there are nine; with fewer, one group and one cluster),
/// so one capacity serves both.
pub const UNIFORM_BLOCKER_CAPACITY: usize = 2048;

/// wgpu's default `max_uniform_buffer_binding_size`.
const MAX_UNIFORM_BINDING_BYTES: usize = 64 << 10;
const _: () = assert!(UNIFORM_LIGHT_CAPACITY * std::mem::size_of::<GpuLight>() <= MAX_UNIFORM_BINDING_BYTES);
const _: () = assert!(UNIFORM_BLOCKER_CAPACITY * std::mem::size_of::<GpuBlockerGroup>() <= MAX_UNIFORM_BINDING_BYTES);
const _: () = assert!(UNIFORM_BLOCKER_CAPACITY * std::mem::size_of::<GpuBlocker>() <= MAX_UNIFORM_BINDING_BYTES);

/// Vertex buffer element: position, normal (world space) and UV set 0 (locations 0–2 of
/// scene.wgsl's vertex stage; `render::resources::vertex_layout`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

/// WGSL `Frame`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    pub view_proj: [[f32; 4]; 4],
    pub camera_position: [f32; 4],
    pub exposure: f32,
    pub light_count: u32,
    /// The angle one pixel subtends at the image centre (see [`pixel_angle_rad`]).
    pub pixel_angle_rad: f32,
    /// Lights from this index on take the exact shadow path (see
    /// [`order_by_shadow_path`]).
    pub first_exact_light: u32,
    /// Lights from this index to `first_exact_light` are shadowed by their shadow maps.
    pub first_mapped_light: u32,
    /// The frame's background as the sRGB target stores it: r | g << 8 | b << 16 |
    /// 255 << 24 ([`srgb8_word`]; the deferred frame writes it where there is no surface).
    pub background_srgb8: u32,
    pub _pad: [u32; 2],
    /// The camera's ray through a point of normalised device coordinates (x, y) is
    /// `view_ray[2] + x·view_ray[0] + y·view_ray[1]` (xyz; w unused): the forward axis plus
    /// the right and up axes scaled by the tangents of the half fields of view, so the
    /// ray's point at view depth z (along the forward axis) is the camera position plus z
    /// times it (see [`view_ray`]).
    pub view_ray: [[f32; 4]; 3],
    /// Order-3 SH of the environment's irradiance (rgb; a unused), world axes.
    pub environment_irradiance: [[f32; 4]; 9],
    /// The lights' grid ([`super::light_grid::LightGrid`]): its first box's corner (xyz,
    /// world metres) and one over a box's side (w, 1/metres).
    pub light_grid_origin: [f32; 4],
    /// Boxes along x, y and z, and their count (w: the outside box's index).
    pub light_grid_boxes: [u32; 4],
}

impl GpuFrame {
    /// The frame of `camera` drawn into `size_px` (width, height) pixels.
    pub fn new(
        camera: &Camera,
        size_px: [u32; 2],
        exposure_ev: f32,
        light_count: usize,
        [first_mapped_light, first_exact_light]: [usize; 2],
        environment_irradiance: [[f32; 4]; 9],
    ) -> GpuFrame {
        let [width, height] = size_px.map(|v| v.max(1) as f32);
        GpuFrame {
            view_proj: camera.view_projection(width / height).to_cols_array_2d(),
            camera_position: camera.position.extend(1.0).to_array(),
            exposure: exposure_ev.exp2(),
            light_count: light_count as u32,
            pixel_angle_rad: pixel_angle_rad(camera, size_px[1]) as f32,
            first_exact_light: first_exact_light.min(light_count) as u32,
            first_mapped_light: first_mapped_light.min(first_exact_light).min(light_count) as u32,
            background_srgb8: srgb8_word([0.0; 3]),
            _pad: [0; 2],
            view_ray: view_ray(camera, width / height),
            environment_irradiance,
            light_grid_origin: [0.0; 4],
            light_grid_boxes: [0; 4],
        }
    }

    pub fn view_projection(&self) -> Mat4 {
        Mat4::from_cols_array_2d(&self.view_proj)
    }
}

/// Linear RGB `linear` (clamped to [0, 1]) as the four bytes an sRGB target stores for it,
/// opaque, in one little-endian word: each channel encoded (IEC 61966-2-1) and rounded.
pub fn srgb8_word(linear: [f64; 3]) -> u32 {
    let [r, g, b] = linear.map(|c| (crate::scene::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u32);
    r | (g << 8) | (b << 16) | (255 << 24)
}

/// `lights` in the order the shaders take them: those on the SH path first, then those
/// with a shadow map, then those on the exact path (each in scene order), with the index
/// of the first mapped and of the first exact one. The shaders walk each range in its own
/// loop: lavapipe runs both sides of a branch at every
/// pixel, so a per-light choice inside one loop would cost both paths for every light.
pub fn order_by_shadow_path(lights: &[GpuLight]) -> (Vec<GpuLight>, [usize; 2]) {
    let on = |path: u32| lights.iter().filter(move |light| light.shadow_path == path).copied();
    let mut ordered: Vec<GpuLight> = on(SHADOW_PATH_SH).collect();
    let first_mapped = ordered.len();
    ordered.extend(on(SHADOW_PATH_MAP));
    let first_exact = ordered.len();
    ordered.extend(
        lights
            .iter()
            .filter(|l| !matches!(l.shadow_path, SHADOW_PATH_SH | SHADOW_PATH_MAP))
            .copied(),
    );
    (ordered, [first_mapped, first_exact])
}

/// `Frame::view_ray` of `camera` seen at `aspect` (width over height): right × tan(xfov/2),
/// up × tan(yfov/2), forward (wgpu's normalised device coordinates: x right, y up).
pub fn view_ray(camera: &Camera, aspect: f32) -> [[f32; 4]; 3] {
    let forward = camera.forward.normalize_or(Vec3::NEG_Z);
    let right = forward.cross(camera.up).normalize_or(Vec3::X);
    let up = right.cross(forward);
    let tan_y = (0.5 * camera.yfov_rad).tan();
    [
        (right * tan_y * aspect).extend(0.0).to_array(),
        (up * tan_y).extend(0.0).to_array(),
        forward.extend(0.0).to_array(),
    ]
}

/// The angle (radians) one pixel subtends at the centre of an image `height_px` tall seen
/// through `camera`: 2 tan(yfov/2) / height. Times a point's distance from the eye, it is
/// the width of a pixel there (shaders: `pixel_footprint`).
pub fn pixel_angle_rad(camera: &Camera, height_px: u32) -> f64 {
    2.0 * (0.5 * camera.yfov_rad as f64).tan() / height_px.max(1) as f64
}

/// The environment's irradiance SH in the layout of `Frame::environment_irradiance`
/// (zeros without an environment).
pub fn environment_irradiance(environment: Option<&Environment>) -> [[f32; 4]; 9] {
    let mut out = [[0.0; 4]; 9];
    if let Some(environment) = environment {
        let irradiance = crate::scene::environment::irradiance_sh(&environment.world_radiance_sh());
        for (slot, rgb) in out.iter_mut().zip(irradiance) {
            *slot = [rgb[0] as f32, rgb[1] as f32, rgb[2] as f32, 0.0];
        }
    }
    out
}

/// Whether `environment` lights anything: its irradiance SH (as the frame carries them)
/// are not all zero. A frame without is lit by its lights alone (`light_windows`).
pub fn environment_lights(environment: Option<&Environment>) -> bool {
    irradiance_lights(&environment_irradiance(environment))
}

/// Whether irradiance SH as the frame carries them (`Frame::environment_irradiance`)
/// light anything: not all zero.
pub fn irradiance_lights(irradiance: &[[f32; 4]; 9]) -> bool {
    irradiance.iter().any(|c| c[..3].iter().any(|&x| x != 0.0))
}

/// WGSL `Light`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    pub position: [f32; 4],
    pub direction_range: [f32; 4],
    pub intensity_rgb: [f32; 4],
    pub spot_cone: [f32; 4],
    pub kind: u32,
    /// Sphere lights: radius in metres; area lights: emitting area in m²; otherwise 0.
    pub source_size: f32,
    /// [`SHADOW_PATH_SH`], [`SHADOW_PATH_EXACT`] or [`SHADOW_PATH_MAP`] (decided for the
    /// frame by `shading::shading_lights`; [`GpuLight::new`] sets the SH path).
    pub shadow_path: u32,
    /// The first of the light's shadow-map views ([`NO_SHADOW_VIEW`]: none).
    pub first_shadow_view: u32,
    /// How many views its maps take (`shading::shadow_maps::view_count`): 6 for a cube
    /// (+x, −x, +y, −y, +z, −z), 1 for one view; 0 without maps.
    pub shadow_view_count: u32,
    /// Rect lights: half the width along the width axis (`Light::area_axes`), metres;
    /// zero for every other kind (a disk's polygon lies on `cpu::area::area_frame`).
    pub area_half_width_m: [f32; 3],
}

impl GpuLight {
    /// An area light whose polygon is a rect (its half width is not zero), as the shaders
    /// tell it; the other area lights are disks.
    pub fn is_rect(&self) -> bool {
        self.area_half_width_m.iter().map(|c| c * c).sum::<f32>() > 0.0
    }

    /// This light without its intensity and colour: what its reach, its windows on the
    /// blockers and its shadow maps depend on (a stroke changes only what this leaves out).
    pub fn geometry(&self) -> GpuLight {
        GpuLight {
            intensity_rgb: [0.0; 4],
            ..*self
        }
    }

    pub fn new(light: &Light) -> GpuLight {
        // A sphere lights like a point at its centre (exact for unshadowed receivers it is
        // wholly above the horizon of); an area light carries L·A, its shape (area and
        // width axis) giving its exact vector irradiance (`cpu::area`).
        let mut intensity_scale = 1.0;
        let mut source_size = 0.0;
        let (kind, spot_cone) = match light.kind {
            LightKind::Point => (LIGHT_POINT, [0.0; 4]),
            LightKind::Sphere { radius_m } => {
                source_size = radius_m;
                (LIGHT_POINT, [0.0; 4])
            }
            LightKind::Rect { .. } | LightKind::Disk { .. } => {
                intensity_scale = light.kind.emitting_area_m2().unwrap_or(0.0);
                source_size = intensity_scale;
                (LIGHT_AREA, [0.0; 4])
            }
            LightKind::Directional => (LIGHT_DIRECTIONAL, [0.0; 4]),
            LightKind::Spot { .. } => {
                let (cos_outer, inverse_transition) = light.kind.spot_cone().unwrap_or((-1.0, 1.0));
                (LIGHT_SPOT, [cos_outer, inverse_transition, 0.0, 0.0])
            }
        };
        let intensity: Vec3 = light.color * light.intensity * intensity_scale;
        GpuLight {
            position: light.position.extend(1.0).to_array(),
            direction_range: light.direction.extend(light.range.unwrap_or(0.0)).to_array(),
            intensity_rgb: intensity.extend(0.0).to_array(),
            spot_cone,
            kind,
            source_size,
            shadow_path: SHADOW_PATH_SH,
            first_shadow_view: NO_SHADOW_VIEW,
            shadow_view_count: 0,
            area_half_width_m: match light.kind {
                LightKind::Rect { width_m, .. } => (light.area_width_axis() * (0.5 * width_m)).to_array(),
                _ => [0.0; 3],
            },
        }
    }
}

/// WGSL `ShadowView`: one view of a light's shadow maps, a layer of the map array or a quadrant of one.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuShadowView {
    /// World to clip space of the light's view (depth 0 near, 1 far).
    pub view_proj: [[f32; 4]; 4],
    /// x: a texel's width per metre of distance from the light (perspective views),
    /// y: a texel's width in metres (orthographic views), z: the light's position for
    /// the distance (perspective: 1; orthographic: 0), w unused.
    pub texel: [f32; 4],
    /// xyz: the view's eye (perspective) or its forward axis (orthographic); w unused.
    pub eye: [f32; 4],
    /// x: the near plane's distance, y: the far plane's (perspective views: a depth read
    /// from the map turns back into a distance along the view's axis), z: the map's size
    /// in texels, w: the distance from the light to the scene's bounding sphere (0 inside
    /// it; perspective views), within which nothing casts a shadow.
    pub depth_range: [f32; 4],
    /// Where the view lies in the map array (`shading::shadow_maps`, the atlas): xy the
    /// corner of its square in texture coordinates of its layer, z the square's side as a
    /// share of the layer's (1: the whole layer; ½: a quadrant), w the layer's index.
    pub atlas: [f32; 4],
}

/// WGSL `Material`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    pub base_color: [f32; 4],
    pub params: [f32; 4],
    pub emissive: [f32; 4],
}

impl GpuMaterial {
    pub fn new(material: &Material, textured: bool) -> GpuMaterial {
        GpuMaterial {
            base_color: material.base_color.to_array(),
            params: [
                material.metallic,
                material.specular,
                material.phong_exponent(),
                if textured { 1.0 } else { 0.0 },
            ],
            emissive: material.emissive.extend(0.0).to_array(),
        }
    }
}

/// WGSL `ShadowParams`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuShadowParams {
    pub ln_epsilon: f32,
    pub min_cap_ratio: f32,
    pub blocker_count: u32,
    pub ratio_attenuation: u32,
    /// Groups in `groups`, after the clusters.
    pub group_count: u32,
    /// Discs in `discs` (open and thin meshes' planar patches, shaded in their own loop).
    pub disc_count: u32,
    /// Clusters at the start of `groups` (`blocker_groups::BlockerCluster`).
    pub cluster_count: u32,
    pub _pad: u32,
    /// k(s) at s = i/31 (`sh::cap_mass_scales`), four to a vec4; all 1 when the
    /// settings do not preserve the shadow mass.
    pub cap_mass_scale: [[f32; 4]; crate::sh::CAP_MASS_ENTRIES / 4],
    pub discs: [GpuBlocker; crate::blockers::MAX_DISCS],
}

impl GpuShadowParams {
    /// The table `cap_mass_scale` for `settings` (`ShadowSettings::cap_mass_table`).
    pub fn cap_mass_scale_for(
        settings: &crate::shading::ShadowSettings,
    ) -> [[f32; 4]; crate::sh::CAP_MASS_ENTRIES / 4] {
        let table = settings.cap_mass_table();
        let mut packed = [[1.0; 4]; crate::sh::CAP_MASS_ENTRIES / 4];
        for (i, k) in table.iter().enumerate() {
            packed[i / 4][i % 4] = *k as f32;
        }
        packed
    }
}

/// WGSL `UpsampleParams` (see `reduced_shading`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuUpsampleParams {
    pub full_to_low: [f32; 2],
    pub plane_tolerance_px: f32,
    pub min_matched_weight: f32,
    pub max_lighting_ratio: f32,
    pub lighting_floor: f32,
    /// A reader's pixel centre p lies at sample texel p · full_to_low − sample_offset.
    pub sample_offset: [f32; 2],
    /// Sample texel (i, j) is the surface of full-resolution pixel min((i, j) · x + y, zw).
    pub sample_pixel: [f32; 4],
    /// Full-resolution pixel (i, j)'s centre lies on the camera's ray through normalised
    /// device coordinates (i, j) · xy + zw.
    pub pixel_to_ndc: [f32; 4],
}

/// Levels of the terrain pyramid the GPU can hold (WGSL `TerrainParams`).
pub const GPU_TERRAIN_LEVELS: usize = 12;

/// WGSL `TerrainParams` (see `gpu_terrain`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuTerrainParams {
    pub present: u32,
    pub azimuths: u32,
    pub levels: u32,
    pub sample_count: u32,
    pub first_step_m: f32,
    pub surface_first: u32,
    pub surface_tolerance_m: f32,
    pub _pad: f32,
    pub level_frame: [[f32; 4]; GPU_TERRAIN_LEVELS],
    pub level_size: [[u32; 4]; GPU_TERRAIN_LEVELS],
    pub wedge: [[f32; 4]; 256],
}

/// WGSL `PackedBlockerGroup` (see `blocker_groups`), which blockers.wgsl's `group_at`
/// unpacks into a `BlockerGroup`: `first_count` holds the first blocker (or, for a
/// cluster, group) in its low [`GROUP_FIRST_BITS`] bits and the count above them (at
/// most 32 groups or 16 spheres; the layout has room for no more 4-byte fields at
/// [`UNIFORM_BLOCKER_CAPACITY`] groups).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuBlockerGroup {
    pub center_extent: [f32; 4],
    pub hand_over_m: f32,
    pub first_count: u32,
    pub stand_in_radius_m: f32,
    pub stand_in_depth: f32,
}

/// Bits of `GpuBlockerGroup::first_count` that hold the first index (WGSL
/// `GROUP_FIRST_BITS`): 67 million, where the sphere budget stops at 100,000
/// (`blockers::SphereBudget`, `--blockers`); the count (≤ 32) takes the other 6.
pub const GROUP_FIRST_BITS: u32 = 26;

fn first_count(first: usize, count: usize) -> u32 {
    debug_assert!(first < 1 << GROUP_FIRST_BITS && count < 1 << (32 - GROUP_FIRST_BITS));
    (first as u32 & ((1 << GROUP_FIRST_BITS) - 1)) | ((count as u32) << GROUP_FIRST_BITS)
}

impl GpuBlockerGroup {
    pub fn new(group: &super::blocker_groups::BlockerGroup) -> GpuBlockerGroup {
        GpuBlockerGroup {
            center_extent: group.center.extend(group.extent_m).to_array(),
            // f32::MAX rather than infinity: squared in the shader, it still compares.
            hand_over_m: group.hand_over_m.min(1e18),
            first_count: first_count(group.first, group.count),
            stand_in_radius_m: group.stand_in_radius_m,
            stand_in_depth: group.stand_in_depth,
        }
    }

    /// A cluster in the same layout, its groups at `first_group_index..` of the array
    /// (the clusters come first).
    pub fn cluster(cluster: &super::blocker_groups::BlockerCluster, first_group_index: usize) -> GpuBlockerGroup {
        GpuBlockerGroup {
            center_extent: cluster.center.extend(cluster.extent_m).to_array(),
            hand_over_m: cluster.hand_over_m.min(1e18),
            first_count: first_count(first_group_index, cluster.group_count),
            stand_in_radius_m: cluster.stand_in_radius_m,
            stand_in_depth: cluster.stand_in_depth,
        }
    }
}

/// WGSL `Blocker`: centre xyz and radius w, world metres; a disc's unit normal in
/// `disc_normal.xyz` (zero for a sphere; w unused).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuBlocker {
    pub center_radius: [f32; 4],
    pub disc_normal: [f32; 4],
}

impl GpuBlocker {
    pub fn new(sphere: &crate::blockers::Sphere) -> GpuBlocker {
        GpuBlocker {
            center_radius: sphere.center.extend(sphere.radius_m).to_array(),
            disc_normal: sphere.disc_normal.extend(0.0).to_array(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_srgb_byte_decoded_comes_back_as_itself_in_the_background_word() {
        for byte in 0..=255u32 {
            let linear = crate::scene::srgb_to_linear(f64::from(byte) / 255.0);
            assert_eq!(srgb8_word([linear; 3]), byte | (byte << 8) | (byte << 16) | (255 << 24));
        }
        // Out of range and NaN: clamped, NaN to black, always opaque.
        assert_eq!(srgb8_word([f64::NAN, 2.0, -1.0]), 0xff00_ff00);
    }

    #[test]
    fn a_point_is_rebuilt_from_its_device_coordinates_and_view_depth() {
        // What the upsampling does with each low-resolution sample: the point the
        // projection puts at (x, y), at its depth along the forward axis.
        let camera = Camera {
            position: Vec3::new(1.0, 2.0, 3.0),
            forward: Vec3::new(-0.3, -0.4, -1.0).normalize(),
            up: Vec3::Y,
            yfov_rad: 0.8,
            znear: 0.05,
            zfar: None,
        };
        let aspect = 16.0 / 9.0;
        let camera = Camera {
            up: camera.forward.cross(Vec3::Y).cross(camera.forward).normalize(),
            ..camera
        };
        let view_proj = camera.view_projection(aspect);
        let [right, up, forward] = view_ray(&camera, aspect).map(|v| Vec3::from_slice(&v[..3]));
        for p in [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(-2.0, 0.5, -4.0),
            Vec3::new(0.7, 1.9, 2.0),
            Vec3::new(-40.0, -10.0, -90.0),
        ] {
            let clip = view_proj * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{p} is in view: {ndc}");
            let depth = (p - camera.position).dot(camera.forward);
            let rebuilt = camera.position + (forward + ndc.x * right + ndc.y * up) * depth;
            assert!((rebuilt - p).length() < 1e-5 * (1.0 + depth), "{p} → {rebuilt}");
        }
    }
}
