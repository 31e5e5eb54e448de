// Reduced-resolution shading (src/render/passes/reduced_shading.rs): one sample in every
// d × d block of pixels is shaded with the full log-SH shading of logsh.wgsl, and every
// pixel blends the samples that lie on its own surface (a joint bilateral upsampling
// guided by position and normal, Kopf et al. 2007). Both are deferred on single-sampled
// targets (low_resolution.wgsl: surface buffers, full-screen passes). With two-level
// shading the light of soft shadows is shaded at every other sample only and upsampled
// to the rest by the same function (upsampled_lighting).
//
// The samples carry the exposed light of the lights with the material divided out,
//   lighting = 2^EV · (L − emission) / (k_d + k_s),
// clamped where the tone curve is long saturated; each pixel multiplies its own k_d + k_s
// back in and adds its own emission (the material's and the baked indirect light):
// texture detail and material edges stay sharp at full resolution while only the smooth
// lighting is interpolated. Pixels that no sample matches (thin objects, silhouettes),
// and those whose nearest samples on their surface disagree (an edge of the light runs
// between them) or are fewer than two, are discarded by the upsampling and shaded in
// full right after: the upsampling writes depth 1 where it draws, so the depth test
// leaves only the discarded ones to the full shading. (A fallback branch inside the upsampling would cost every pixel the full
// shading on a software GPU, which runs both sides of a divergent branch.) Multisampled
// targets use the rasterised fs_upsample, where such pixels take the best-matching
// sample nearby: lavapipe tests their depth after the fragment shader, so a full shading
// pass would shade every fragment.
// #import scene slots

// One texel per sample, so that the upsampling reads each with one texel fetch (on
// lavapipe the fetches were most of its cost; two images took two):
//   x: the view depth of the shaded point (f32 bits; metres along the camera's forward
//      axis; 0, the clear value, where no surface was shaded) — the point is rebuilt on
//      the ray through the sample's pixel centre (Frame.view_ray), exact in f32;
//   y, z: lighting = 2^EV · (radiance − emission) / reflectance, rgb, each the
//      top 21 bits of its f32 (pack_lighting: a relative step of 2⁻¹³; half floats
//      would need a capability not every device has);
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

// The lighting (exposed, per unit reflectance) the samples give a pixel, and whether they
// matched its surface and agreed.
struct UpsampledLighting {
    lighting: vec3<f32>,
    matches: bool,
};

// A full-resolution pixel rebuilt from the samples (the best match nearby where none
// matches its surface: `ring`), rasterised.
fn upsampled(in: VertexOut, front_facing: bool, ring: bool) -> vec4<f32> {
    let s = surface(in, front_facing);
    let up = upsampled_lighting(in.clip.xy, s, ring);
    return vec4<f32>(tonemap_aces_fit(frame.exposure * s.emissive + reflectance(s) * up.lighting), 1.0);
}

// `ring`: also look at the ring of 12 samples around the 2 × 2 nearest for the best match
// of a pixel they do not match (without it, such a pixel's colour is left undefined: the
// caller discards it). A constant at each call, so the compiler drops the unused half.
// `pixel`: the pixel's centre in its own image's pixels (in.clip.xy), which
// upsample.full_to_low maps to the samples' image; s: its surface.
fn upsampled_lighting(pixel: vec2<f32>, s: Surface, ring: bool) -> UpsampledLighting {
    let low_size = vec2<f32>(textureDimensions(low_samples));
    let last = vec2<i32>(low_size) - vec2<i32>(1);
    let tolerance_m = max(upsample.plane_tolerance_px * pixel_footprint(s.position), 1e-6);
    // in.clip is the pixel centre in framebuffer pixels here; low-resolution texel centres
    // sit at integer + 0.5 in texel units.
    let at = pixel * upsample.full_to_low - upsample.sample_offset;
    let corner = floor(at);
    let t = at - corner;
    var lighting = vec3<f32>(0.0);
    var matched = 0.0;
    // The best-matching sample (by score), for pixels the 2 × 2 nearest do not match.
    var best_lighting = vec3<f32>(0.0);
    var best_match = 0.0;
    // The darkest and brightest lighting among the 2 × 2 nearest samples on the surface,
    // and how many lie on it.
    var darkest = 3.0e38;
    var brightest = 0.0;
    var on_surface = 0u;
    let side = select(2u, 4u, ring);
    let first = select(0, -1, ring);
    for (var k = 0u; k < side * side; k++) {
        let step = vec2<i32>(i32(k % side), i32(k / side)) + vec2<i32>(first);
        let texel = clamp(vec2<i32>(corner) + step, vec2<i32>(0), last);
        let low = low_sample(texel);
        let sample = low.lighting;
        let shaded = low.shaded;
        let normal = low.normal;
        let off_plane = dot(low.position - s.position, s.normal) / tolerance_m;
        // (n·n')¹⁶: a sample whose normal is 15° off weighs 0.57, 30° off 0.1 (the
        // lighting of the rim of a curved object changes fast with its normal).
        let facing2 = pow2(max(dot(normal, s.normal), 0.0));
        let facing16 = pow2(pow2(pow2(facing2)));
        // 0 where the low-resolution pixel saw no surface.
        let geometry = select(0.0, exp(-off_plane * off_plane) * facing16, shaded);
        // Any surface beats none, the nearer the better, when no sample matches (a sliver
        // such as the top face of a wall takes its neighbour's light rather than none).
        if ring {
            let distance2 = dot(vec2<f32>(step) - t, vec2<f32>(step) - t);
            let score = geometry + select(0.0, 1e-3 / (1.0 + distance2), shaded);
            let better = score > best_match;
            best_match = select(best_match, score, better);
            best_lighting = select(best_lighting, sample, better);
        }
        // Bilinear weights of the 2 × 2 nearest samples; the ring around them only stands
        // in for the best match.
        let tent = max(vec2<f32>(1.0) - abs(vec2<f32>(step) - t), vec2<f32>(0.0));
        let weight = tent.x * tent.y * geometry;
        let nearest = all(step >= vec2<i32>(0)) && all(step <= vec2<i32>(1));
        let counted = nearest && geometry > 0.5;
        let brightness = dot(sample, vec3<f32>(0.2126, 0.7152, 0.0722));
        darkest = select(darkest, min(darkest, brightness), counted);
        on_surface += select(0u, 1u, counted);
        brightest = select(brightest, max(brightest, brightness), counted);
        lighting += weight * sample;
        matched += weight;
    }
    // Samples on the surface that disagree straddle an edge of the light (a hard shadow's,
    // a rim's) that interpolation would blur and misplace, and a lone one on the surface
    // (a limb a few pixels wide) cannot tell: such pixels are shaded in full too. (Not
    // when taking the best match: those pixels have no full shading to fall back on.)
    let agree = on_surface >= 2u
        && brightest <= upsample.max_lighting_ratio * darkest + upsample.lighting_floor;
    let matches = matched >= upsample.min_matched_weight && (ring || agree);
    if ring && !matches {
        lighting = best_lighting;
        matched = 1.0;
    }
    return UpsampledLighting(lighting / matched, matches);
}

// Upsampling into a multisampled target.
@fragment
fn fs_upsample(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return upsampled(in, front_facing, true);
}
