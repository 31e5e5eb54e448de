// Reduced-resolution shading (src/render/passes/reduced_shading.rs): one sample in every
// d × d block of pixels is shaded with the full log-SH shading of logsh.wgsl, and every
// pixel blends the samples that lie on its own surface (a joint bilateral upsampling
// guided by position and normal, Kopf et al. 2007). Both are deferred on single-sampled
// targets (low_resolution.wgsl, full_resolution.wgsl). With two-level
// shading the light of soft shadows is shaded at every other sample only and upsampled
// to the rest by the same function (upsampled_lighting), as its share of the same light
// unshadowed (low_resolution.wgsl's soft_share), which each reader multiplies its own
// unshadowed light by.
//
// The samples carry the exposed light of the lights with the material divided out,
//   lighting = 2^EV · (L − emission) / (k_d + k_s),
// clamped where the tone curve is long saturated; each pixel multiplies its own k_d + k_s
// back in and adds its own emission (the material's and the baked indirect light):
// texture detail and material edges stay sharp at full resolution while only the smooth
// lighting is interpolated. Pixels that no sample matches (thin objects, silhouettes),
// and those whose nearest samples on their surface disagree (an edge of the light runs
// between them) or are fewer than two, are left by the upsampling and shaded in full
// (full_resolution.wgsl lists them and shades them densely: a fallback branch inside the
// upsampling would cost every pixel the full shading on a software GPU, which runs both
// sides of a divergent branch). Multisampled targets use the rasterised fs_upsample,
// where such pixels take the best-matching sample nearby.
// #import scene slots

// One texel per sample, so that the upsampling reads each with one texel fetch (on
// lavapipe the fetches were most of its cost; two images took two):
//   x: the view depth of the shaded point (f32 bits; metres along the camera's forward
//      axis; 0, the clear value, where no surface was shaded) — the point is rebuilt on
//      the ray through the sample's pixel centre (Frame.view_ray), exact in f32;
//   y, z: lighting = 2^EV · (radiance − emission) / reflectance, rgb, each the
//      top 21 bits of its f32 (pack_lighting: a relative step of 2⁻¹³; half floats
//      would need a capability not every device has) — in the soft light's images
//      (two-level shading) its share of the unshadowed light instead (soft_share);
//   w: the unit shading normal, octahedral, two snorm16.
@group(PASS_GROUP) @binding(UPSAMPLE_BINDING) var<uniform> upsample: UpsampleParams;
@group(PASS_GROUP) @binding(LOW_SAMPLES_BINDING) var low_samples: texture_2d<u32>;

// The octahedral map of a unit vector into [-1, 1]²: the upper half projected onto the
// octahedron |x| + |y| + |z| = 1, the lower half folded over its diagonals.
fn octahedral_from_unit(n: vec3<f32>) -> vec2<f32> {
    let p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    let signs = select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
    return select(p, (vec2<f32>(1.0) - abs(p.yx)) * signs, n.z < 0.0);
}

fn unit_from_octahedral(e: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let fold = max(-n.z, 0.0);
    n.x += select(fold, -fold, n.x >= 0.0);
    n.y += select(fold, -fold, n.y >= 0.0);
    return normalize(n);
}

// What divides out of a surface's shading per channel: k_d + k_s, kept above 1e-3 so a
// black material divides safely (what it reflects is as small).
fn reflectance(s: Surface) -> vec3<f32> {
    return max(s.k_d + s.k_s, vec3<f32>(1e-3));
}

// Lighting this bright is white after the tone curve even on the darkest reflectance
// (1e-3 × 6e4 = 60, where the curve is saturated); the clamp keeps infinities out.
const MAX_LIGHTING: f32 = 6e4;

// The texel of a low-resolution sample of surface s with exposed `lighting` per unit
// reflectance.
fn low_sample_texel(s: Surface, lighting: vec3<f32>) -> vec4<u32> {
    let packed_lighting = pack_lighting(min(lighting, vec3<f32>(MAX_LIGHTING)));
    return vec4<u32>(
        bitcast<u32>(view_depth_of(s.position)),
        packed_lighting.x,
        packed_lighting.y,
        pack2x16snorm(octahedral_from_unit(s.normal)),
    );
}

// Non-negative rgb in 63 bits: each channel's f32 without its sign bit and lowest 10
// mantissa bits (8 exponent and 13 mantissa bits), r in bits 0–20 of x, g in bits 21–31
// of x and 0–9 of y, b in bits 10–30 of y.
fn pack_lighting(rgb: vec3<f32>) -> vec2<u32> {
    let bits = bitcast<vec3<u32>>(max(rgb, vec3<f32>(0.0))) >> vec3<u32>(10u);
    return vec2<u32>(bits.r | (bits.g << 21u), (bits.g >> 11u) | (bits.b << 10u));
}

fn unpack_lighting(packed: vec2<u32>) -> vec3<f32> {
    let r = packed.x & 0x1fffffu;
    let g = (packed.x >> 21u) | ((packed.y & 0x3ffu) << 11u);
    let b = packed.y >> 10u;
    return bitcast<vec3<f32>>(vec3<u32>(r, g, b) << vec3<u32>(10u));
}

// A low-resolution sample read back: whether a surface was shaded there, its point
// (rebuilt from its view depth on the ray through its pixel's centre), normal and lighting.
struct LowSample {
    shaded: bool,
    position: vec3<f32>,
    normal: vec3<f32>,
    lighting: vec3<f32>,
};

fn low_sample(texel: vec2<i32>) -> LowSample {
    let packed = textureLoad(low_samples, texel, 0);
    let view_depth = bitcast<f32>(packed.x);
    // The full-resolution pixel the sample shaded (low_resolution.wgsl's level_pixel).
    let pixel = min(vec2<f32>(texel) * upsample.sample_pixel.x + upsample.sample_pixel.y, upsample.sample_pixel.zw);
    let ndc = pixel * upsample.pixel_to_ndc.xy + upsample.pixel_to_ndc.zw;
    let ray = frame.view_ray[2].xyz + ndc.x * frame.view_ray[0].xyz + ndc.y * frame.view_ray[1].xyz;
    let lighting = unpack_lighting(packed.yz);
    return LowSample(
        view_depth > 0.0,
        frame.camera_position.xyz + ray * view_depth,
        unit_from_octahedral(unpack2x16snorm(packed.w)),
        lighting,
    );
}

fn pow2(x: f32) -> f32 {
    return x * x;
}

// The lighting (exposed, per unit reflectance; from the soft light's samples, its share
// of the unshadowed light) the samples give a pixel, and whether they matched its
// surface and agreed.
struct UpsampledLighting {
    lighting: vec3<f32>,
    matches: bool,
    // false: the nearest samples on the surface disagree (blend_agrees' ratio: the light
    // changes within their spacing), whatever else left the pixel unmatched.
    agrees: bool,
};

// A full-resolution pixel rebuilt from the samples (the best match nearby where none
// matches its surface: `ring`), rasterised.
fn upsampled(in: VertexOut, front_facing: bool, ring: bool) -> vec4<f32> {
    let s = surface(in, front_facing);
    let up = upsampled_lighting(in.clip.xy, s, ring);
    return vec4<f32>(tonemap_aces_fit(frame.exposure * s.emissive + reflectance(s) * up.lighting), 1.0);
}

// The running sums of a pixel's blend of samples (blend_sample).
struct Blend {
    lighting: vec3<f32>,
    matched: f32,
    // The darkest and brightest lighting among the 2 × 2 nearest samples on the surface,
    // and how many lie on it.
    darkest: f32,
    brightest: f32,
    on_surface: u32,
};

fn empty_blend() -> Blend {
    return Blend(vec3<f32>(0.0), 0.0, 3.0e38, 0.0, 0u);
}

// How well sample `low` lies on surface s: 0 where the low-resolution pixel saw no surface.
fn sample_geometry(low: LowSample, s: Surface, tolerance_m: f32) -> f32 {
    let off_plane = dot(low.position - s.position, s.normal) / tolerance_m;
    // (n·n')¹⁶: a sample whose normal is 15° off weighs 0.57, 30° off 0.1 (the
    // lighting of the rim of a curved object changes fast with its normal; so, if less
    // fast, does the soft light's share of its unshadowed light, as the part of the sky
    // and of the blockers a point faces turns with it).
    let facing2 = pow2(max(dot(low.normal, s.normal), 0.0));
    let facing16 = pow2(pow2(pow2(facing2)));
    return select(0.0, exp(-off_plane * off_plane) * facing16, low.shaded);
}

// `b` with sample `low` of geometry `geometry` at `step` from the corner added, for a
// pixel at `t` from the corner (in samples).
fn blend_sample(b: Blend, low: LowSample, geometry: f32, step: vec2<i32>, t: vec2<f32>) -> Blend {
    // Bilinear weights of the 2 × 2 nearest samples; a ring around them only stands in
    // for the best match.
    let tent = max(vec2<f32>(1.0) - abs(vec2<f32>(step) - t), vec2<f32>(0.0));
    let weight = tent.x * tent.y * geometry;
    let nearest = all(step >= vec2<i32>(0)) && all(step <= vec2<i32>(1));
    let counted = nearest && geometry > 0.5;
    let brightness = dot(low.lighting, vec3<f32>(0.2126, 0.7152, 0.0722));
    return Blend(
        b.lighting + weight * low.lighting,
        b.matched + weight,
        select(b.darkest, min(b.darkest, brightness), counted),
        select(b.brightest, max(b.brightest, brightness), counted),
        b.on_surface + select(0u, 1u, counted),
    );
}

// Samples on the surface that disagree straddle an edge of the light (a hard shadow's,
// a rim's) that interpolation would blur and misplace, and a lone one on the surface
// (a limb a few pixels wide) cannot tell: such pixels are shaded in full too.
fn blend_agrees(b: Blend) -> bool {
    return b.on_surface >= 2u && lighting_agrees(b);
}

// Whether the nearest samples on the surface lie within upsample.max_lighting_ratio (and
// lighting_floor) of each other: vacuously so with fewer than two.
fn lighting_agrees(b: Blend) -> bool {
    return b.brightest <= upsample.max_lighting_ratio * b.darkest + upsample.lighting_floor;
}

// Where a pixel centre `pixel` (in its own image's pixels, which upsample.full_to_low maps
// to the samples' image) lies among the samples: the nearest samples' corner, and the
// pixel's place from it in samples.
struct SamplePlace {
    corner: vec2<i32>,
    t: vec2<f32>,
};

// Where pixel centre `pixel` lies in the samples' image, in samples (texel centres at
// integer + 0.5 in texel units map to integers).
fn sample_coordinates(pixel: vec2<f32>) -> vec2<f32> {
    return pixel * upsample.full_to_low - upsample.sample_offset;
}

fn sample_place(pixel: vec2<f32>) -> SamplePlace {
    let at = sample_coordinates(pixel);
    let corner = floor(at);
    return SamplePlace(vec2<i32>(corner), at - corner);
}

// The sample at `corner` + `step`, clamped into the image.
fn low_sample_near(corner: vec2<i32>, step: vec2<i32>) -> LowSample {
    let last = vec2<i32>(textureDimensions(low_samples)) - vec2<i32>(1);
    return low_sample(clamp(corner + step, vec2<i32>(0), last));
}

// The 2 × 2 nearest samples blended for surface s at `t` from their corner: the lighting
// (exposed, per unit reflectance) and whether they matched its surface and agreed.
fn quad_lighting(quad: array<LowSample, 4>, t: vec2<f32>, s: Surface) -> UpsampledLighting {
    let tolerance_m = max(upsample.plane_tolerance_px * pixel_footprint(s.position), 1e-6);
    var b = empty_blend();
    for (var k = 0u; k < 4u; k++) {
        let step = vec2<i32>(i32(k % 2u), i32(k / 2u));
        b = blend_sample(b, quad[k], sample_geometry(quad[k], s, tolerance_m), step, t);
    }
    let matches = b.matched >= upsample.min_matched_weight && blend_agrees(b);
    return UpsampledLighting(b.lighting / b.matched, matches, lighting_agrees(b));
}

// The 2 × 2 samples around `corner`, in quad_lighting's order.
fn sample_quad(corner: vec2<i32>) -> array<LowSample, 4> {
    return array<LowSample, 4>(
        low_sample_near(corner, vec2<i32>(0, 0)),
        low_sample_near(corner, vec2<i32>(1, 0)),
        low_sample_near(corner, vec2<i32>(0, 1)),
        low_sample_near(corner, vec2<i32>(1, 1)),
    );
}

// The lighting the samples give the pixel whose centre is `pixel` on surface s (in
// its own image's pixels; in.clip.xy for a fragment), and whether they matched its
// surface and agreed. `ring`: where the 2 × 2 nearest do not, the best match among them
// and the ring of 12 around them (matches is then true: such pixels have no full shading
// to fall back on). A constant at each call, so the compiler drops the unused half.
fn upsampled_lighting(pixel: vec2<f32>, s: Surface, ring: bool) -> UpsampledLighting {
    let place = sample_place(pixel);
    if !ring {
        return quad_lighting(sample_quad(place.corner), place.t, s);
    }
    let tolerance_m = max(upsample.plane_tolerance_px * pixel_footprint(s.position), 1e-6);
    var b = empty_blend();
    // The best-matching sample (by score), for pixels the 2 × 2 nearest do not match.
    var best_lighting = vec3<f32>(0.0);
    var best_match = 0.0;
    for (var k = 0u; k < 16u; k++) {
        let step = vec2<i32>(i32(k % 4u), i32(k / 4u)) - vec2<i32>(1);
        let low = low_sample_near(place.corner, step);
        let geometry = sample_geometry(low, s, tolerance_m);
        // Any surface beats none, the nearer the better, when no sample matches (a sliver
        // such as the top face of a wall takes its neighbour's light rather than none).
        let distance2 = dot(vec2<f32>(step) - place.t, vec2<f32>(step) - place.t);
        let score = geometry + select(0.0, 1e-3 / (1.0 + distance2), low.shaded);
        let better = score > best_match;
        best_match = select(best_match, score, better);
        best_lighting = select(best_lighting, low.lighting, better);
        b = blend_sample(b, low, geometry, step, place.t);
    }
    if b.matched < upsample.min_matched_weight {
        return UpsampledLighting(best_lighting, true, true);
    }
    return UpsampledLighting(b.lighting / b.matched, true, true);
}

// Upsampling into a multisampled target.
@fragment
fn fs_upsample(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return upsampled(in, front_facing, true);
}
