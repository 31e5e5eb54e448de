// Shadow maps of the real triangles (src/shading/shadow_maps.rs): the lookup that turns
// a light's maps into the share of it a surface point sees.

// #import shadow_bindings scene

// false: no light of the frame has a shadow map (shading::compiled_paths).
override SHADOW_MAPS: bool = true;
// false: every light with maps is of no size, and the penumbra filter is left out
// (shading::compiled_paths).
override SOFT_SHADOW_MAPS: bool = true;

// false: every light with shadow maps has a cube of six views (shading::compiled_paths):
// a face's tap is worked out from the light's position (cube_face_tap) instead of read
// through the view's matrix, which lavapipe gathers lane by lane.
override SINGLE_VIEW_MAPS: bool = true;

// Taps of the blocker search and of the penumbra filter each (a Vogel spiral:
// shading::cpu::vogel_point). 48 against 32 took the study's meshes under a 5° light
// from penumbra RMS 0.044 to 0.031 (docs/speed-accuracy.md) for 7 % more on the
// terrain sample's frame.
const PENUMBRA_TAPS: u32 = 48u;
const GOLDEN_ANGLE: f32 = 2.3999632;
// The blocker search looks at most this many light radii (as seen from the receiver)
// around the receiver's direction: blockers nearer the light than a fifth of the way
// from it are missed when the light is inside the scene's bounds.
const MAX_SEARCH_RADII: f32 = 4.0;
// How far a tap's plane point is lifted toward the light per metre from the receiver:
// a curved receiver (a valley in a terrain) rises above its tangent plane about that
// much within a penumbra's width without shadowing itself.
const PLANE_SLACK: f32 = 0.1;

// The share of `light` (seen as `inc`) that reaches s through its shadow maps: the view
// that sees s (a cube's face by the largest component of s − light), the receiver pushed
// a quarter of a texel along its normal and 1 + 2 tan θ texels toward the light (θ the
// light's incidence): no self-shadowing where a texel spans depths of the surface, which
// it does by tan θ per texel. A push along the light's ray reads the same texel, so only
// the normal push moves a shadow's outline: a texel and a half along the normal and one
// toward the light, as before 2026-12-04, had moved every outline by as much (the
// sample's key light: shadowed pixels' RMSE against the path tracer 0.063 → 0.043 with
// every pixel shaded at 480 × 270), and half a texel without the slope term had striped
// walls the lights graze. A light of no size: one comparison read
// that filters the 2 × 2 texels around (percentage-closer, bilinear); wider filters of
// offset reads, tried against tests/shadow_maps.rs, lost much of the shadow of bars a
// few texels wide, so hard edges stay one texel soft. A sphere or area light:
// soft_shadow_map_visibility. Outside its views a light is unshadowed. shading::cpu takes
// the exact visibility by rays instead (shading::cpu::mapped_visibility), which this
// approaches as the maps grow.
fn shadow_map_visibility(light: Light, inc: Incidence, s: Surface) -> f32 {
    if light.first_shadow_view == NO_SHADOW_VIEW {
        return 1.0;
    }
    let view_index = shadow_view_index(light, s.position);
    let view = shadow_views[view_index];
    let perspective = !SINGLE_VIEW_MAPS || view.texel.z > 0.5;
    let distance = length(s.position - select(light.position.xyz, view.eye.xyz, SINGLE_VIEW_MAPS));
    let texel = select(view.texel.y, view.texel.x * distance, perspective);
    let cos_incidence = max(abs(dot(s.normal, inc.to_light)), 0.1);
    let tan_incidence = sqrt(1.0 - cos_incidence * cos_incidence) / cos_incidence;
    let p = s.position + s.normal * (0.25 * texel) + inc.to_light * (texel * (1.0 + 2.0 * tan_incidence));
    if SOFT_SHADOW_MAPS && inc.cap_ratio > 0.0 && perspective {
        return soft_shadow_map_visibility(light, p, s.normal, inc.cap_ratio);
    }
    let tap = light_view_tap(light, view_index, p);
    if tap.off {
        return 1.0;
    }
    return textureSampleCompareLevel(shadow_maps, shadow_map_sampler, tap.uv, tap.layer, tap.depth);
}

// The layer of `light`'s maps that sees the point p.
fn shadow_view_index(light: Light, p: vec3<f32>) -> u32 {
    var index = light.first_shadow_view;
    if light.shadow_view_count == 6u {
        index += cube_face(p - light.position.xyz);
    }
    return min(index, MAX_SHADOW_VIEWS - 1u);
}

// The cube face a receiver at `offset` from a point light reads: 2·axis of the largest
// component (ties to the earlier axis), plus 1 on the negative side
// (shadow_maps::cube_face).
fn cube_face(offset: vec3<f32>) -> u32 {
    let a = abs(offset);
    if a.x >= a.y && a.x >= a.z {
        return select(0u, 1u, offset.x < 0.0);
    }
    if a.y >= a.z {
        return select(2u, 3u, offset.y < 0.0);
    }
    return select(4u, 5u, offset.z < 0.0);
}

// Where a map tap lands: its view, its layer, texture coordinates in the layer and
// depth; off: outside its view.
struct ShadowTap {
    view: u32,
    layer: i32,
    uv: vec2<f32>,
    depth: f32,
    off: bool,
};

// The tap at world point q of `light`'s maps.
fn shadow_tap(light: Light, q: vec3<f32>) -> ShadowTap {
    return light_view_tap(light, shadow_view_index(light, q), q);
}

// The tap at world point q of `light`'s view `index` (shadow_view_index): through the
// view's matrix, or where every light's maps are a cube, worked out from the light's
// position (a constant: the other is not compiled).
fn light_view_tap(light: Light, index: u32, q: vec3<f32>) -> ShadowTap {
    if SINGLE_VIEW_MAPS {
        return view_tap(index, q);
    }
    return cube_face_tap(index, index - light.first_shadow_view, q - light.position.xyz);
}

// A receiver at `offset` from a point light in the frame of cube face `face` (the face
// that sees it is cube_face(offset); a tap pushed past the edge of its receiver's face
// still reads that face, within its margin): right, up, and the distance along the
// face's axis (shadow_maps::cube_face_coordinates, the faces' look-to frames).
fn cube_face_coordinates(offset: vec3<f32>, face: u32) -> vec3<f32> {
    let o = offset;
    let negative = (face & 1u) == 1u;
    let z_face = select(vec3<f32>(o.x, -o.y, o.z), vec3<f32>(-o.x, -o.y, -o.z), negative);
    let y_face = select(vec3<f32>(o.x, o.z, o.y), vec3<f32>(o.x, -o.z, -o.y), negative);
    let x_face = select(vec3<f32>(-o.z, -o.y, o.x), vec3<f32>(o.z, -o.y, -o.x), negative);
    return select(select(z_face, y_face, face / 2u == 1u), x_face, face / 2u == 0u);
}

// view_tap for view `index`, cube face `face` of the light at `offset` from q: its
// projection (h·x/d, h·y/d) with h = 1 / tan of the face's widened half-angle (the
// view's texel width per metre is 2 tan / size), and its reversed depth
// near·(far − d) / (d·(far − near)), from the receiver's face coordinates — what the
// face's matrix gives (tests in shading::shadow_maps) with four of the view's values
// read instead of its matrix.
fn cube_face_tap(index: u32, face: u32, offset: vec3<f32>) -> ShadowTap {
    let view = shadow_views[index];
    let v = cube_face_coordinates(offset, face);
    let near = view.depth_range.x;
    let far = view.depth_range.y;
    let h = 2.0 / (view.texel.x * view.depth_range.z);
    let d = v.z;
    let ndc = vec3<f32>(h * v.xy / d, near * (far - d) / (d * (far - near)));
    return atlas_tap(index, view, ndc, d <= 0.0);
}

// The tap at world point q of view `index`: its coordinates within the view mapped into
// the view's square of the array (shading::shadow_atlas), kept half a texel inside the
// square so that a filtered read never blends in a neighbouring quadrant's texels (on a
// whole layer the same as the sampler's clamp to its edge).
fn view_tap(index: u32, q: vec3<f32>) -> ShadowTap {
    let view = shadow_views[index];
    let clip = view.view_proj * vec4<f32>(q, 1.0);
    return atlas_tap(index, view, clip.xyz / clip.w, clip.w <= 0.0);
}

// The tap of view `index` (`view`) at normalised device coordinates ndc, off where
// `behind` the eye or outside the view.
fn atlas_tap(index: u32, view: ShadowView, ndc: vec3<f32>, behind: bool) -> ShadowTap {
    let uv = vec2<f32>(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y);
    let off = behind || any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || ndc.z < 0.0;
    let half_texel = 0.5 / view.depth_range.z;
    let inside = clamp(uv, vec2<f32>(half_texel), vec2<f32>(1.0 - half_texel));
    return ShadowTap(index, i32(view.atlas.w), view.atlas.xy + inside * view.atlas.z, min(ndc.z, 1.0), off);
}

// The point of the receiver's tangent plane (through p, normal n) seen from the light's
// centre `eye` in the direction `ray` (not unit): each tap compares the map with the
// receiver's own plane there, not with p's depth, so a tilted receiver does not shadow
// itself across a wide filter (receiver-plane depth, as in Isidoro 2006). Where the
// plane is seen edge-on the tap keeps p's distance.
fn tap_on_plane(eye: vec3<f32>, ray: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let to_p = p - eye;
    let nominal = length(to_p) / length(ray);
    let t = dot(to_p, n) / dot(ray, n);
    let on_plane = t > 0.5 * nominal && t < 2.0 * nominal;
    return eye + ray * select(nominal, t, on_plane);
}

// The distance along a perspective view's axis of a depth the map holds (reversed: near
// → 1, far → 0, so d = near·far / (near + z·(far − near))).
fn view_distance(view: ShadowView, depth: f32) -> f32 {
    let near = view.depth_range.x;
    let far = view.depth_range.y;
    return near * far / (near + depth * (far - near));
}

// Percentage-closer soft shadows (Fernando 2005) for a sphere or area light whose disc
// has sine `cap_ratio` seen from the receiver p, in tangents of angles seen from the
// light's centre. A blocker at distance d_b along the view's axis, seen ρ away from p's
// direction, hides part of the light from p only if ρ < tan θ_light · (d_r − d_b) / d_b
// (similar triangles: it lies in the cone from p to the light's disc). The blocker
// search spreads PENUMBRA_TAPS reads from half a texel out to where a blocker at the
// scene's nearest point could still be in that cone (radii spaced geometrically, so near
// blockers, the common case, are found as reliably as at a hard edge), keeps those in
// their cone, and takes their mean distance d_b; a planar blocker there hides the light
// from p over a disc of tan θ_light · (d_r − d_b) / d_b around it, which PENUMBRA_TAPS
// comparison reads average (equal areas). Each read compares with the receiver's plane
// (tap_on_plane) lifted toward the light by a texel, more on surfaces the light grazes
// (slope-scaled), and PLANE_SLACK of the tap's distance from p, so neither tilted nor
// curved receivers shadow themselves. Taps pick their own cube face, so
// a penumbra may span faces. What it cannot know: blockers at several depths (one mean
// for all) and bars thinner than the filter taps' spacing.
fn soft_shadow_map_visibility(light: Light, p: vec3<f32>, n: vec3<f32>, cap_ratio: f32) -> f32 {
    let eye = light.position.xyz;
    let axis = normalize(p - eye);
    let sine = min(cap_ratio, 0.999);
    let tan_light = sine / sqrt(1.0 - sine * sine);
    let t1 = normalize(cross(axis, select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(axis.y) > 0.9)));
    let t2 = cross(axis, t1);
    let turn = mat2x2<f32>(cos(GOLDEN_ANGLE), sin(GOLDEN_ANGLE), -sin(GOLDEN_ANGLE), cos(GOLDEN_ANGLE));
    let view = shadow_views[shadow_view_index(light, p)];
    var receiver_distance = cube_face_coordinates(p - eye, cube_face(p - eye)).z;
    if SINGLE_VIEW_MAPS {
        receiver_distance = (view.view_proj * vec4<f32>(p, 1.0)).w;
    }
    let nearest_m = max(view.depth_range.w, view.depth_range.x);
    let search_tan = tan_light * min(max(receiver_distance - nearest_m, 0.0) / nearest_m, MAX_SEARCH_RADII);
    let innermost_tan = 0.5 * view.texel.x;
    let growth = max(search_tan / innermost_tan, 1.0);
    // Slope-scaled: a read up to a texel and a half from its tap sees the receiver's
    // plane tan(incidence) texels deeper per texel, so taps are lifted by that too.
    let cos_incidence = max(abs(dot(n, axis)), 0.1);
    let lift_texels = 1.0 + 1.5 * sqrt(1.0 - cos_incidence * cos_incidence) / cos_incidence;

    var blockers = 0.0;
    var blocker_distance = 0.0;
    var spiral = vec2<f32>(1.0, 0.0);
    for (var k = 0u; k < PENUMBRA_TAPS; k++) {
        let radius = min(innermost_tan * pow(growth, (f32(k) + 0.5) / f32(PENUMBRA_TAPS)), search_tan);
        let q = lifted(eye, tap_on_plane(eye, axis + (t1 * spiral.x + t2 * spiral.y) * radius, p, n), p, view, lift_texels);
        let tap = shadow_tap(light, q);
        spiral = turn * spiral;
        if tap.off {
            continue;
        }
        let size = vec2<f32>(textureDimensions(shadow_maps));
        let texel = min(vec2<i32>(tap.uv * size), vec2<i32>(size) - 1);
        let stored = textureLoad(shadow_maps, texel, tap.layer, 0);
        let distance = view_distance(shadow_views[tap.view], stored);
        // In front of the receiver's plane and inside the cone to the light's disc, give or
        // take a texel (a penumbra narrower than a texel is the hard edge's).
        if stored > tap.depth && (radius - view.texel.x) * distance < tan_light * (receiver_distance - distance) {
            blockers += 1.0;
            blocker_distance += distance;
        }
    }
    if blockers == 0.0 {
        return 1.0;
    }
    let mean_blocker = blocker_distance / blockers;
    let filter_tan = tan_light * max(receiver_distance - mean_blocker, 0.0) / max(mean_blocker, 1e-6);

    var lit = 0.0;
    spiral = vec2<f32>(1.0, 0.0);
    for (var k = 0u; k < PENUMBRA_TAPS; k++) {
        let radius = sqrt((f32(k) + 0.5) / f32(PENUMBRA_TAPS)) * filter_tan;
        let q = lifted(eye, tap_on_plane(eye, axis + (t1 * spiral.x + t2 * spiral.y) * radius, p, n), p, view, lift_texels);
        let tap = shadow_tap(light, q);
        spiral = turn * spiral;
        if tap.off {
            lit += 1.0;
        } else {
            lit += textureSampleCompareLevel(shadow_maps, shadow_map_sampler, tap.uv, tap.layer, tap.depth);
        }
    }
    return lit / f32(PENUMBRA_TAPS);
}

// The tap point q moved toward the light's centre `eye` (along its own ray, so it reads
// the same texel) by `texels` texels and PLANE_SLACK of its distance from the receiver p.
fn lifted(eye: vec3<f32>, q: vec3<f32>, p: vec3<f32>, view: ShadowView, texels: f32) -> vec3<f32> {
    let to_eye = eye - q;
    let distance = length(to_eye);
    let slack = texels * view.texel.x * distance + PLANE_SLACK * length(q - p);
    return q + to_eye * (min(slack, 0.5 * distance) / distance);
}
