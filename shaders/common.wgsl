// Shared WGSL: the structs mirrored by Rust twins in src/shading/gpu_types.rs (layouts
// asserted by tests), and the colour pipeline of docs/architecture.md. Imported by every
// shader module that needs them (src/shading/wgsl/compose.rs); never copied.

const PI: f32 = 3.14159265358979;

const LIGHT_POINT: u32 = 0u;
const LIGHT_SPOT: u32 = 1u;
const LIGHT_DIRECTIONAL: u32 = 2u;
// One-sided Lambertian emitter: intensity_rgb is luminance × area, falling as cos θ.
const LIGHT_AREA: u32 = 3u;

// How many lights, blockers and blocker groups the uniform arrays of scene.wgsl and
// logsh.wgsl hold (64 KiB each at most, wgpu's default limit; render::gpu_types has the
// Rust side). Frames with more also read the rest from storage buffers.
const UNIFORM_LIGHT_CAPACITY: u32 = 682u;
const UNIFORM_BLOCKER_CAPACITY: u32 = 2048u;
// Views of the shadow-map array (src/shading/gpu_types.rs MAX_SHADOW_VIEWS).
const MAX_SHADOW_VIEWS: u32 = 384u;
// Light.shadow_path values and the first_shadow_view of a light without maps.
const SHADOW_PATH_SH: u32 = 0u;
const SHADOW_PATH_EXACT: u32 = 1u;
const SHADOW_PATH_MAP: u32 = 2u;
const NO_SHADOW_VIEW: u32 = 0xffffffffu;
// A spot whose cos(outer cone) is at least this has one shadow-map view, a wider one a
// cube of six (src/shading/shadow_maps.rs SINGLE_VIEW_SPOT_MIN_COS).
const SINGLE_VIEW_SPOT_MIN_COS: f32 = 0.5;

// Per-frame constants.
struct Frame {
    view_proj: mat4x4<f32>,
    // xyz = camera position (world, metres).
    camera_position: vec4<f32>,
    // Linear multiplier 2^EV applied before tone mapping.
    exposure: f32,
    light_count: u32,
    // The angle one pixel subtends at the image centre, 2 tan(yfov/2) / height (radians).
    pixel_angle_rad: f32,
    // Lights from this index on take the exact shadow path (render::shading_lights
    // decides per light for the frame; the upload puts them last).
    first_exact_light: u32,
    // Lights from this index to first_exact_light are shadowed by their shadow maps.
    first_mapped_light: u32,
    // The background as the sRGB target stores it (bytes r, g, b, 255 from the low end).
    background_srgb8: u32,
    _pad1: u32,
    _pad2: u32,
    // The camera's ray through normalised device coordinates (x, y) is view_ray[2] +
    // x·view_ray[0] + y·view_ray[1] (xyz): its point at view depth z (along the forward
    // axis) is camera_position + z times it (shading::gpu_types::view_ray).
    view_ray: array<vec4<f32>, 3>,
    // Order-3 SH of the environment's irradiance E(n) = ∫ L max(n·ω, 0) dω (rgb), world
    // axes, polar axis +z (shading-model.md §3).
    environment_irradiance: array<vec4<f32>, 9>,
    // The lights' grid (shading::light_grid): xyz its first box's corner (world,
    // metres), w one over a box's side (1/metres).
    light_grid_origin: vec4<f32>,
    // Boxes along x, y, z; w their count, the index of the outside box.
    light_grid_boxes: vec4<u32>,
};

// One light. Units: point/spot radiant intensity in candela, directional illuminance in lux
// (KHR_lights_punctual), area lights luminance × area (cd along the normal), times the
// linear RGB colour. Sphere lights arrive as points with a source_size.
struct Light {
    // xyz = world position; w unused.
    position: vec4<f32>,
    // xyz = unit direction the light travels (area lights: the emitting normal);
    // w = range in metres (0 = unlimited).
    direction_range: vec4<f32>,
    // rgb = colour × intensity; w unused.
    intensity_rgb: vec4<f32>,
    // x = cos(outer cone), y = 1 / (cos(inner) − cos(outer)); zw unused.
    spot_cone: vec4<f32>,
    kind: u32,
    // Sphere lights (kind LIGHT_POINT): radius in metres; area lights: emitting area in m²;
    // 0 for point-like lights.
    source_size: f32,
    // SHADOW_PATH_SH, SHADOW_PATH_EXACT or SHADOW_PATH_MAP (decided per light for the
    // frame by shading::shading_lights; the shaders read Frame.first_mapped_light and
    // first_exact_light).
    shadow_path: u32,
    // The first of the light's shadow-map views (NO_SHADOW_VIEW: none).
    first_shadow_view: u32,
    // 6: a cube of views (+x, −x, +y, −y, +z, −z); 1: one view; 0: no maps.
    shadow_view_count: u32,
    // Rect lights: half the width along the width axis, metres (three floats: a vec3
    // would be aligned to 16 bytes); zero for other kinds (disks: area_frame's axes).
    area_half_width_x: f32,
    area_half_width_y: f32,
    area_half_width_z: f32,
};

// One view of a light's shadow maps: a layer of the array or a quadrant of one (src/shading/shadow_maps.rs).
struct ShadowView {
    // World to clip space, depth reversed (1 near, 0 far: shading::shadow_maps).
    view_proj: mat4x4<f32>,
    // x: a texel's width per metre of distance from the eye (perspective), y: a texel's
    // width in metres (orthographic), z: 1 for perspective views, 0 for orthographic.
    texel: vec4<f32>,
    // xyz: the eye (perspective) or the forward axis (orthographic).
    eye: vec4<f32>,
    // x: near plane, y: far plane (perspective), z: the map's size in texels, w: the
    // distance to the scene's bounding sphere (perspective).
    depth_range: vec4<f32>,
    // Where the view lies in the map array: xy its square's corner in texture coordinates
    // of its layer, z the square's side (1 or ½), w the layer.
    atlas: vec4<f32>,
};

// Parameters of the log-SH shadow pass (logsh.wgsl).
struct ShadowParams {
    // ln ε: the log-visibility of a blocked direction (shading-model.md §4).
    ln_epsilon: f32,
    // Blockers whose sin(cap half-angle) = r/d is below this are skipped (too far to matter).
    min_cap_ratio: f32,
    blocker_count: u32,
    // 1: scale each blocker's log-visibility by r/d (Ren's ratio attenuation).
    ratio_attenuation: u32,
    // Number of BlockerGroups (src/shading/blocker_groups.rs), after the clusters.
    group_count: u32,
    // Discs in `discs`: open and thin meshes' planar patches, shaded in their own loop.
    disc_count: u32,
    // Clusters of groups at the start of `groups` (blocker_groups::BlockerCluster).
    cluster_count: u32,
    _pad: u32,
    // k(s) at s = i/31, four to a vec4: the scale of a cap's log-visibility that keeps
    // the light it blocks through the band limit (src/sh/cap_mass.rs; all 1 when off).
    cap_mass_scale: array<vec4<f32>, 8>,
    discs: array<Blocker, 64>,
};

// Parameters of the reduced-resolution shading's upsampling (reduced_shading.wgsl).
struct UpsampleParams {
    // Sample texels per pixel of the reader's image along x and y (1/d for the
    // full-resolution frame reading the low-resolution samples, 1/2 for those reading
    // the soft layer).
    full_to_low: vec2<f32>,
    // A sample counts as on this pixel's surface within this many full-resolution pixel
    // footprints of its tangent plane (Gaussian falloff).
    plane_tolerance_px: f32,
    // Below this share of the bilinear weight matching, the pixel is shaded in full.
    min_matched_weight: f32,
    // The nearest samples on the pixel's surface disagree, and the pixel is shaded in
    // full, where the brightest one's lighting luminance exceeds this many times the
    // darkest one's plus lighting_floor.
    max_lighting_ratio: f32,
    lighting_floor: f32,
    // Where a sample sits, in sample texels, for the reader's pixel centre p (in its own
    // image's pixels): sample texel p · full_to_low − sample_offset (integers at the
    // samples).
    sample_offset: vec2<f32>,
    // Sample texel (i, j) is the surface of full-resolution pixel
    // min((i, j) · x + y, zw) (low_resolution.wgsl's level_pixel: x the samples'
    // spacing in pixels, y the offset of its middle pixel, zw the last pixel).
    sample_pixel: vec4<f32>,
    // Full-resolution pixel (i, j)'s centre lies on the camera's ray through normalised
    // device coordinates (i, j) · xy + zw.
    pixel_to_ndc: vec4<f32>,
};

// A height-field terrain for terrain.wgsl (src/render/resources/terrain.rs fills it).
struct TerrainParams {
    // 0: the scene has no terrain.
    present: u32,
    // W: marching directions per receiver.
    azimuths: u32,
    // Pyramid levels read while marching.
    levels: u32,
    // Samples per azimuth, at t_i = first_step_m · 2^(i/4).
    sample_count: u32,
    first_step_m: f32,
    // Index in terrain_heights of the surface cache: n² values per finest sample.
    surface_first: u32,
    // Receivers at most this far above the terrain (metres) read the surface cache.
    surface_tolerance_m: f32,
    _pad0: f32,
    // Per level: world x and z of sample (0, 0), spacing along x and z (metres).
    level_frame: array<vec4<f32>, 12>,
    // Per level: columns, rows, index of sample (0, 0) in terrain_heights, unused.
    level_size: array<vec4<u32>, 12>,
    // M_lin, n² rows × 2n columns row-major, four to a vec4 (room for order 8).
    wedge: array<vec4<f32>, 256>,
};

// Consecutive blockers first..first + count culled together: every sphere lies within
// center_extent.w of center_extent.xyz, and one sphere at the centre (radius
// stand_in_radius_m: the area the spheres cover together; its log-visibility weighed
// stand_in_depth, Σ r² over its radius squared) stands in for them between half
// hand_over_m and hand_over_m, and alone beyond it. A cluster has the same layout: its
// groups are first..first + count of `groups` (src/shading/blocker_groups.rs). As stored
// (PackedBlockerGroup), first and count share one u32: first in the low GROUP_FIRST_BITS
// bits; group_at unpacks it.
struct BlockerGroup {
    center_extent: vec4<f32>,
    hand_over_m: f32,
    first: u32,
    count: u32,
    stand_in_radius_m: f32,
    stand_in_depth: f32,
};

struct PackedBlockerGroup {
    center_extent: vec4<f32>,
    hand_over_m: f32,
    first_count: u32,
    stand_in_radius_m: f32,
    stand_in_depth: f32,
};

const GROUP_FIRST_BITS: u32 = 26u;

// A blocker: xyz = centre (world, metres), w = radius in metres; a sphere, or a flat disc
// facing disc_normal.xyz when that is not zero (src/blockers/surface.rs).
struct Blocker {
    center_radius: vec4<f32>,
    disc_normal: vec4<f32>,
};

// A material, mapped from glTF metallic-roughness (see Material in src/scene/material.rs).
struct Material {
    // Linear RGBA base colour factor.
    base_color: vec4<f32>,
    // x = metallic, y = KHR specular factor, z = Phong exponent, w = 1 if textured.
    params: vec4<f32>,
    // rgb = emitted radiance.
    emissive: vec4<f32>,
};

// Filmic tone curve of Narkowicz (2015), an analytic fit of the ACES reference rendering
// transform, applied per channel: t(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14),
// clamped to [0, 1]. The sRGB encode is done by the render target's format.
fn tonemap_aces_fit(x: vec3<f32>) -> vec3<f32> {
    let c = max(x, vec3<f32>(0.0));
    return clamp(c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

// Order-3 real SH (Condon–Shortley phase, polar axis +z) of `coefficients` at unit `d`:
// the first 9 of the unrolled Cartesian polynomials of src/sh/basis.rs.
fn sh3_eval(coefficients: array<vec4<f32>, 9>, d: vec3<f32>) -> vec3<f32> {
    let x = d.x;
    let y = d.y;
    let z = d.z;
    var sum = coefficients[0].rgb * 0.28209479;
    sum += coefficients[1].rgb * (-0.48860251 * y);
    sum += coefficients[2].rgb * (0.48860251 * z);
    sum += coefficients[3].rgb * (-0.48860251 * x);
    sum += coefficients[4].rgb * (1.09254843 * x * y);
    sum += coefficients[5].rgb * (-1.09254843 * y * z);
    sum += coefficients[6].rgb * (0.31539157 * (3.0 * z * z - 1.0));
    sum += coefficients[7].rgb * (-1.09254843 * x * z);
    sum += coefficients[8].rgb * (0.54627422 * (x * x - y * y));
    return sum;
}
