// Shared by every pass that draws the scene's meshes: the frame and material bindings,
// the vertex stage, a light's incidence at a point, and the surface seen by a fragment
// (material mapped to diffuse + normalised Phong, docs/architecture.md "Materials").
// Radiance leaving a surface toward the eye, per light:
//   E_l · [ k_d/π · (n·l) + k_s · (r+1)/(2π) · max(ρ·l, 0)^r ]
// where E_l is the light's irradiance on a plane facing it and ρ the mirrored view vector.
// #import common slots

@group(FRAME_GROUP) @binding(FRAME_BINDING) var<uniform> frame: Frame;
// The lights, read through light_at: the first UNIFORM_LIGHT_CAPACITY from a uniform
// array, the rest (when there are more) from every_light. lavapipe gathers a uniform
// array's values in registers, but reads a storage buffer lane by lane through memory,
// which made the light loop cost several times more.
@group(FRAME_GROUP) @binding(LIGHTS_BINDING) var<uniform> lights: array<Light, UNIFORM_LIGHT_CAPACITY>;
@group(FRAME_GROUP) @binding(EVERY_LIGHT_BINDING) var<storage, read> every_light: array<Light>;
// Baked indirect irradiance (linear RGB, 3 floats per vertex) of every object's vertices,
// one object after another; zeros when there is none. A draw's first instance is its
// object's first vertex here (render::gpu_scene).
@group(FRAME_GROUP) @binding(BAKED_INDIRECT_BINDING) var<storage, read> baked_indirect: array<f32>;
// The lights on the SH and shadow-map paths that can reach each box of a grid over the
// scene (shading::light_grid has the layout): per box three words — its SH-path lights'
// first entry, its mapped lights' first, the end — then the entries, light indices.
@group(FRAME_GROUP) @binding(LIGHT_GRID_BINDING) var<storage, read> light_grid: array<u32>;

@group(MATERIAL_GROUP) @binding(MATERIAL_BINDING) var<uniform> material: Material;
@group(MATERIAL_GROUP) @binding(BASE_COLOR_TEXTURE_BINDING) var base_color_texture: texture_2d<f32>;
@group(MATERIAL_GROUP) @binding(BASE_COLOR_SAMPLER_BINDING) var base_color_sampler: sampler;

// false: the frame has at most UNIFORM_LIGHT_CAPACITY lights, and every_light is never
// read (shading::compiled_paths; set at pipeline creation). Lights past the capacity then
// shade nothing.
override LIGHT_OVERFLOW: bool = true;

// Light i of the frame (i < frame.light_count).
fn light_at(i: u32) -> Light {
    if LIGHT_OVERFLOW {
        if i >= UNIFORM_LIGHT_CAPACITY {
            return every_light[i];
        }
    }
    var light = lights[min(i, UNIFORM_LIGHT_CAPACITY - 1u)];
    light.intensity_rgb *= select(1.0, 0.0, i >= UNIFORM_LIGHT_CAPACITY);
    return light;
}

// true: a point walks the lights of its box of the grid (light_grid) on the SH and
// shadow-map paths, false: every one of them (shading::compiled_paths decides, for frames
// with enough lights whose reach ends; lavapipe pays for every light of a loop whether
// it adds anything or not). The same frame either way: a light left out of a box adds
// exactly 0 there.
override LIGHT_GRID: bool = false;

// The lights a point walks on one path: entries first..end of light_grid (LIGHT_GRID),
// or the light indices first..end; run_light gives entry k's light.
struct LightRun {
    first: u32,
    end: u32,
};

// The box of the grid holding p, or the outside box (frame.light_grid_boxes.w) for a
// point beyond it (shading::light_grid::LightGrid::box_of is the twin).
fn light_box(p: vec3<f32>) -> u32 {
    let q = (p - frame.light_grid_origin.xyz) * frame.light_grid_origin.w;
    let boxes = frame.light_grid_boxes;
    if !(all(q >= vec3<f32>(0.0)) && all(q < vec3<f32>(boxes.xyz))) {
        return boxes.w;
    }
    let c = min(vec3<u32>(q), boxes.xyz - vec3<u32>(1u));
    return c.x + boxes.x * (c.y + boxes.y * c.z);
}

// The lights on the SH path that may reach p.
fn harmonic_lights_at(p: vec3<f32>) -> LightRun {
    if !LIGHT_GRID {
        return LightRun(0u, frame.first_mapped_light);
    }
    let header = 3u * light_box(p);
    return LightRun(light_grid[header], light_grid[header + 1u]);
}

// The lights on the shadow-map path that may reach p.
fn mapped_lights_at(p: vec3<f32>) -> LightRun {
    if !LIGHT_GRID {
        return LightRun(frame.first_mapped_light, frame.first_exact_light);
    }
    let header = 3u * light_box(p);
    return LightRun(light_grid[header + 1u], light_grid[header + 2u]);
}

// The light of entry k of a LightRun.
fn run_light(k: u32) -> u32 {
    if LIGHT_GRID {
        return light_grid[k];
    }
    return k;
}

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @builtin(vertex_index) index: u32,
    // The object's first vertex in `baked_indirect`.
    @builtin(instance_index) first_vertex: u32,
};

struct VertexOut {
    // Invariant: a depth pre-pass and the shading pass must produce the same depths.
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // Baked indirect irradiance at the vertex (linear RGB, lux), interpolated.
    @location(3) indirect_irradiance: vec3<f32>,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return transform_vertex(v);
}

fn transform_vertex(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.world_position = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    let b = 3u * (v.first_vertex + v.index);
    out.indirect_irradiance = vec3<f32>(baked_indirect[b], baked_indirect[b + 1u], baked_indirect[b + 2u]);
    return out;
}

// The fragment stage of a depth pre-pass into a pass with a colour target it leaves alone
// (its pipeline writes no channel): nothing to compute, where running fs_surface would
// sample the material's texture at every fragment for nothing.
@fragment
fn fs_depth_only() {}

// Irradiance (per unit area facing diffuse_to_light), the unit direction toward the
// light's centre (shadows are looked up that way), and the sine of the half-angle of the
// cap the light subtends (0 for point-like lights).
struct Incidence {
    irradiance: vec3<f32>,
    to_light: vec3<f32>,
    // Whose cosine with a receiver's normal scales `irradiance` to the receiver's:
    // to_light, except near area lights (their vector irradiance's direction).
    diffuse_to_light: vec3<f32>,
    cap_ratio: f32,
    // Distance to the light (the largest f32 for directional lights).
    distance: f32,
};

fn incidence(light: Light, p: vec3<f32>) -> Incidence {
    var result: Incidence;
    result.cap_ratio = 0.0;
    if light.kind == LIGHT_DIRECTIONAL {
        result.to_light = -light.direction_range.xyz;
        result.diffuse_to_light = result.to_light;
        result.irradiance = light.intensity_rgb.rgb;
        result.distance = 3.4e38;
        return result;
    }
    let offset = light.position.xyz - p;
    let distance2 = max(dot(offset, offset), 1e-8);
    result.distance = sqrt(distance2);
    result.to_light = offset * inverseSqrt(distance2);
    result.diffuse_to_light = result.to_light;
    var falloff = 1.0 / distance2;
    let range = light.direction_range.w;
    if range > 0.0 {
        // KHR_lights_punctual's recommended smooth window to zero at `range`.
        let ratio2 = distance2 / (range * range);
        let window = clamp(1.0 - ratio2 * ratio2, 0.0, 1.0);
        falloff *= window * window;
    }
    if light.kind == LIGHT_POINT && light.source_size > 0.0 {
        // A sphere light: its cap has sin(half-angle) = radius / distance.
        result.cap_ratio = min(light.source_size * inverseSqrt(distance2), 1.0);
    }
    if (RECT_LIGHTS || DISK_LIGHTS) && light.kind == LIGHT_AREA {
        let cos_emitter = max(dot(-result.to_light, light.direction_range.xyz), 0.0);
        // The cap of the same solid angle Ω = A·cos θ/d²: 1 − cos(half-angle) = Ω/(2π).
        let u = min(light.source_size * cos_emitter / distance2 / (2.0 * PI), 1.0);
        result.cap_ratio = sqrt(u * (2.0 - u));
        // intensity = L·A; on the plane facing Φ the irradiance is L·|Φ|.
        let phi = area_vector_irradiance(light, p);
        let length_phi = length(phi);
        falloff *= distance2 * length_phi / max(light.source_size, 1e-30);
        if length_phi > 0.0 {
            result.diffuse_to_light = phi / length_phi;
        }
    }
    if light.kind == LIGHT_SPOT {
        let cos_angle = dot(-result.to_light, light.direction_range.xyz);
        let t = clamp((cos_angle - light.spot_cone.x) * light.spot_cone.y, 0.0, 1.0);
        falloff *= t * t;
    }
    result.irradiance = light.intensity_rgb.rgb * falloff;
    return result;
}

// Whether `light` adds anything at p as far as its range and its cone say: the window
// and the cone factor of incidence above 0, written as incidence computes them
// (light_windows::light_reaches is the twin).
fn light_reaches(light: Light, p: vec3<f32>) -> bool {
    if light.kind == LIGHT_DIRECTIONAL {
        return true;
    }
    let offset = light.position.xyz - p;
    let distance2 = max(dot(offset, offset), 1e-8);
    let range = light.direction_range.w;
    var reaches = !(range > 0.0) || distance2 / (range * range) < 1.0;
    if light.kind == LIGHT_SPOT {
        let cos_angle = dot(-offset * inverseSqrt(distance2), light.direction_range.xyz);
        reaches = reaches && (cos_angle - light.spot_cone.x) * light.spot_cone.y > 0.0;
    }
    return reaches;
}

// false: no environment lights the frame (shading::compiled_paths), and its light through
// the visibility — a product of SH at every point shaded — is left out (logsh.wgsl), as
// is its own log-visibility beside the lights' (light_windows.wgsl).
override ENVIRONMENT_LIGHT: bool = true;

// false: no light of the frame is a rect (a disk), and the vector irradiance of its
// polygon is left out (shading::compiled_paths; lavapipe pays for a branch's body whether
// or not a pixel takes it).
override RECT_LIGHTS: bool = true;
override DISK_LIGHTS: bool = true;

// Sides of the regular polygon of equal area a disk light is taken as
// (shading::cpu::area::DISK_LIGHT_SIDES).
const DISK_LIGHT_SIDES: u32 = 8u;
// area_vector_irradiance writes the eight corners out.
const_assert DISK_LIGHT_SIDES == 8u;

// The emitting plane's unit width axis for an emitting normal: reference × normal, the
// reference +y, or +z within 8° of ±y (shading::cpu::area::area_frame).
fn area_width_axis(normal: vec3<f32>) -> vec3<f32> {
    let reference = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0), abs(normal.y) > 0.99);
    return normalize(cross(reference, normal));
}

// An edge's share of a polygon's vector form factor seen from the origin: the angle the
// edge a → b subtends times the unit normal of the plane through the origin and the edge
// (blockers::disc::edge_form_factor); atan2 rather than acos, exact for the small angles
// of distant polygons. Area lights here, disc blockers in logsh.wgsl.
fn edge_form_factor(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let plane = cross(a, b);
    let plane_length = length(plane);
    return atan2(plane_length, dot(a, b)) * plane / max(plane_length, 1e-30);
}

// A light's area_half_width as a vector (zero for a disk).
fn area_half_width(light: Light) -> vec3<f32> {
    return vec3<f32>(light.area_half_width_x, light.area_half_width_y, light.area_half_width_z);
}

// A rect light's half extent along its height axis, normal × width, as a vector: area /
// (4 · |half width|) (cpu::area::emitter).
fn rect_half_height(light: Light, half_width: vec3<f32>) -> vec3<f32> {
    return normalize(cross(light.direction_range.xyz, half_width)) * (light.source_size / (4.0 * length(half_width)));
}

// The circumradius of a disk light's regular polygon of equal area, A = ½·N·ρ²·sin(2π/N)
// (cpu::area::emitter).
fn disk_circumradius_m(light: Light) -> f32 {
    let n = f32(DISK_LIGHT_SIDES);
    return sqrt(light.source_size / (0.5 * n * sin(2.0 * PI / n)));
}

// The radius (metres) of the smallest sphere about a light's centre that holds its
// emitter (cpu::area::bounding_radius_m): a rect's half diagonal, the circumradius of a
// disk's polygon, a sphere light's radius, 0 for point-like lights.
fn light_bounding_radius_m(light: Light) -> f32 {
    if light.kind == LIGHT_AREA {
        let half_width_m = length(area_half_width(light));
        if half_width_m > 0.0 {
            let half_height_m = light.source_size / (4.0 * half_width_m);
            return sqrt(half_width_m * half_width_m + half_height_m * half_height_m);
        }
        return disk_circumradius_m(light);
    }
    return select(0.0, light.source_size, light.kind == LIGHT_POINT);
}

// How far a light's emitter reaches from its centre along unit `axis` (cpu::area::emitter,
// penumbra::Emitter::support_m): a rect's |w·a| + |h·a|, a disk's circumradius times
// √(1 − (n·a)²), a sphere light's radius, 0 for point-like lights; −1 for the sun, at
// infinity.
fn emitter_support_m(light: Light, axis: vec3<f32>) -> f32 {
    if light.kind == LIGHT_DIRECTIONAL {
        return -1.0;
    }
    if light.kind == LIGHT_AREA {
        let half_width = area_half_width(light);
        if dot(half_width, half_width) > 0.0 {
            return abs(dot(half_width, axis)) + abs(dot(rect_half_height(light, half_width), axis));
        }
        let along = dot(light.direction_range.xyz, axis);
        return disk_circumradius_m(light) * sqrt(max(1.0 - along * along, 0.0));
    }
    return select(0.0, light.source_size, light.kind == LIGHT_POINT);
}

// Whether `light`'s emitter lies wholly on p's side of a plane with unit `normal`, p
// `side_p` in front of it, the light seen toward `to_light`, `distance` away, of sine
// `sin_light` (the sun: its distance stands for infinity, its sine for its extent): then
// a disc blocker in that plane cannot hide it (blockers::disc::disc_plane_between is
// the twin, negated). The exact path's discs and the SH lights' windows ask it.
fn emitter_beside_plane(light: Light, side_p: f32, normal: vec3<f32>, to_light: vec3<f32>, distance: f32, sin_light: f32) -> bool {
    let support = emitter_support_m(light, normal);
    let side_light = side_p + distance * dot(to_light, normal);
    let extent = select(support, sin_light * distance, support < 0.0);
    return side_light * side_p > 0.0 && abs(side_light) > extent;
}

// The vector irradiance at p of an area light of unit radiance, Φ = ½ Σ_edges γ·n̂
// (Lambert's formula; Arvo 1994): E = L·Φ·n for a receiver whose horizon the light is
// wholly above. Its polygon: a rect's 4 corners, or for a disk the regular polygon of
// DISK_LIGHT_SIDES sides and equal area, on the ellipse centre + cos θ·U + sin θ·V
// (shading::cpu::area: area_light_corners, polygon_vector_irradiance). Zero behind the
// emitting side.
fn area_vector_irradiance(light: Light, p: vec3<f32>) -> vec3<f32> {
    let normal = light.direction_range.xyz;
    let centre = light.position.xyz - p;
    if dot(centre, normal) >= 0.0 {
        return vec3<f32>(0.0);
    }
    let half_width = area_half_width(light);
    let rect = dot(half_width, half_width) > 0.0;
    // The polygons' edges written out, corners without a sine or cosine: a loop over
    // them, with a sine and a cosine a corner, cost lavapipe about twice as much.
    var sum = vec3<f32>(0.0);
    if RECT_LIGHTS && rect {
        // Corners at 45° + k·90° on the ellipse of semi-axes √2·(half extents).
        let half_height = rect_half_height(light, half_width);
        let c0 = centre + half_width + half_height;
        let c1 = centre - half_width + half_height;
        let c2 = centre - half_width - half_height;
        let c3 = centre + half_width - half_height;
        sum = edge_form_factor(c0, c1) + edge_form_factor(c1, c2) + edge_form_factor(c2, c3) + edge_form_factor(c3, c0);
    }
    if DISK_LIGHTS && !rect {
        // DISK_LIGHT_SIDES (8) corners at k·45° on the circle of the circumradius.
        let circumradius = disk_circumradius_m(light);
        let width = area_width_axis(normal);
        let u = width * circumradius;
        let v = cross(normal, width) * circumradius;
        let r = 0.70710678;
        let c0 = centre + u;
        let c1 = centre + r * (u + v);
        let c2 = centre + v;
        let c3 = centre + r * (v - u);
        let c4 = centre - u;
        let c5 = centre - r * (u + v);
        let c6 = centre - v;
        let c7 = centre + r * (u - v);
        sum = edge_form_factor(c0, c1) + edge_form_factor(c1, c2) + edge_form_factor(c2, c3) + edge_form_factor(c3, c4)
            + edge_form_factor(c4, c5) + edge_form_factor(c5, c6) + edge_form_factor(c6, c7) + edge_form_factor(c7, c0);
    }
    let phi = 0.5 * sum;
    return select(phi, -phi, dot(phi, centre) < 0.0);
}

// What the shading of a fragment needs to know about its surface.
struct Surface {
    position: vec3<f32>,
    // Unit shading normal, turned toward the viewer on back faces.
    normal: vec3<f32>,
    k_d: vec3<f32>,
    k_s: vec3<f32>,
    phong_exponent: f32,
    // Light leaving the surface that no shadow or light sample changes: emission plus the
    // baked indirect light reflected diffusely, k_d/π · E_indirect.
    emissive: vec3<f32>,
    // The view direction mirrored about the normal, the Phong lobe's axis (computed once
    // here rather than per light: the shader compiler does not hoist it out of the loop).
    mirrored_view: vec3<f32>,
};

// false: the pipeline draws only untextured materials and samples no base colour
// texture (lavapipe samples it at every pixel whether a material has one or not, and a
// trilinear sample is much of what the upsampling costs a pixel). Set at pipeline
// creation (src/render/passes/logsh.rs).
override BASE_COLOR_TEXTURE: bool = true;

// The base colour texture filtered over the pixel's footprint. The footprint is the
// parallelogram spanned by the uv derivatives; a plain trilinear sample sizes its filter
// by the long side, so a floor seen at a grazing angle is blurred across the short side
// too and its pattern washes out where a path tracer's samples, spread over the pixel,
// keep it. Here one trilinear tap whose filter keeps the footprint's area: the long side
// shortened to √(long · short) (the level a filter of the footprint's area would pick),
// the short side as it is. Measured on the studio and the sample against the path tracer
// at 480×270 (2026-12-04): whole-image RMSE 0.0151 → 0.0125 and 0.0184 → 0.0157, for
// 3 / 5 ms more a frame at 960×540 (`render --time-frames`); lavapipe's anisotropic
// sampler reached 0.0123 / 0.0154 for 6 / 15 ms more, four taps along the long side
// 0.0118 / 0.0147 for 11 / 21 ms more.
fn sample_base_color(uv: vec2<f32>) -> vec4<f32> {
    let along_x = dpdx(uv);
    let along_y = dpdy(uv);
    let length_x = length(along_x);
    let length_y = length(along_y);
    let x_is_long = length_x >= length_y;
    let long_side = select(along_y, along_x, x_is_long);
    let short_side = select(along_x, along_y, x_is_long);
    let short_over_long = max(min(length_x, length_y), 1e-12) / max(max(length_x, length_y), 1e-12);
    return textureSampleGrad(base_color_texture, base_color_sampler, uv, long_side * sqrt(short_over_long), short_side);
}

fn surface(in: VertexOut, front_facing: bool) -> Surface {
    var s = material_surface(in.normal, in.uv, in.indirect_irradiance, front_facing);
    s.position = in.world_position;
    s.mirrored_view = reflect(-normalize(frame.camera_position.xyz - s.position), s.normal);
    return s;
}

// A Surface but for its position and mirrored view: the material's colours and
// exponent, the normal (`normal` as interpolated, turned toward the viewer on a back
// face), and the emission with the baked indirect irradiance at the point.
fn material_surface(normal: vec3<f32>, uv: vec2<f32>, indirect_irradiance: vec3<f32>, front_facing: bool) -> Surface {
    var base = material.base_color;
    if BASE_COLOR_TEXTURE && material.params.w > 0.5 {
        base *= sample_base_color(uv);
    }
    let metallic = material.params.x;
    let dielectric_specular = 0.04 * material.params.y;
    var s: Surface;
    s.normal = normalize(normal);
    if !front_facing {
        s.normal = -s.normal;
    }
    s.k_d = base.rgb * (1.0 - metallic) * (1.0 - dielectric_specular);
    s.k_s = mix(vec3<f32>(dielectric_specular), base.rgb, metallic);
    s.phong_exponent = material.params.z;
    s.emissive = material.emissive.rgb + s.k_d / PI * max(indirect_irradiance, vec3<f32>(0.0));
    return s;
}

// The width (metres) of one pixel at p: its distance from the eye times the angle a pixel
// subtends at the image centre (without the surface's slant).
fn pixel_footprint(p: vec3<f32>) -> f32 {
    return distance(frame.camera_position.xyz, p) * frame.pixel_angle_rad;
}

// A light's unshadowed diffuse and glossy factors, n·l_d/π and (r+1)/(2π)·max(ρ·l, 0)^r
// with l_d = diffuse_to_light and l = to_light (both 0 below the horizon of l_d).
fn direct_lobes(s: Surface, inc: Incidence) -> vec2<f32> {
    let n_dot_l = dot(s.normal, inc.diffuse_to_light);
    if n_dot_l <= 0.0 {
        return vec2<f32>(0.0);
    }
    let cos_mirror = max(dot(s.mirrored_view, inc.to_light), 1e-8);
    // exp2(r·log2 c) rather than pow: equals 1 at r = 0 even where c underflows.
    let glossy = (s.phong_exponent + 1.0) / (2.0 * PI) * exp2(s.phong_exponent * log2(cos_mirror));
    return vec2<f32>(n_dot_l / PI, glossy);
}

// Unshadowed radiance toward the eye from one light (0 when the light is below the horizon).
fn direct_radiance(s: Surface, inc: Incidence) -> vec3<f32> {
    let lobes = direct_lobes(s, inc);
    return inc.irradiance * (s.k_d * lobes.x + s.k_s * lobes.y);
}

// The environment's irradiance on s's tangent plane (clamped at 0 against ringing).
fn environment_irradiance_at(s: Surface) -> vec3<f32> {
    return max(sh3_eval(frame.environment_irradiance, s.normal), vec3<f32>(0.0));
}

// Diffuse light of the environment from its irradiance SH (clamped at 0 against ringing).
fn environment_radiance(s: Surface) -> vec3<f32> {
    return s.k_d / PI * environment_irradiance_at(s);
}

// The depth of p along the camera's forward axis, kept above 0 (the mark of a drawn
// surface: points in view lie past the near plane).
fn view_depth_of(p: vec3<f32>) -> f32 {
    return max(signed_view_depth(p), 1e-30);
}

// The depth of p along the camera's forward axis: affine in p, so a vertex stage may
// pass it for the rasteriser to interpolate as it would p.
fn signed_view_depth(p: vec3<f32>) -> f32 {
    return dot(p - frame.camera_position.xyz, frame.view_ray[2].xyz);
}
