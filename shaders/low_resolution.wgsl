// Reduced-resolution shading deferred (src/render/passes/reduced_shading.rs): the meshes
// are rasterised once, at full resolution, into a surface buffer by a cheap shader
// (fs_surface_buffer), and the costly work runs in full-screen passes that read it — the
// samples' shading at low resolution (each sample the surface of one pixel of the
// buffer: `level_pixel`), the upsampling and the full shading of the pixels it leaves at
// full resolution. lavapipe runs a fragment shader over blocks of pixels per triangle, so
// a mesh whose triangles are smaller than the samples' spacing (a figure's limbs at a
// third of the resolution, a fine terrain at full resolution) had the shading run once
// per triangle for a pixel or less; a full-screen pass runs it once per pixel. Taking
// the samples' surfaces from the full-resolution buffer also spares a second geometry
// pass at low resolution, and each sample is exactly the surface of the pixel it sits
// on.
//
// The buffer, two Rgba32Uint texels per pixel:
//   a: x view depth (f32 bits, 0 where no surface was drawn), y the octahedral normal
//      (two snorm16), zw k_d (pack_lighting);
//   b: xy the emission — the material's own and the baked indirect light —
//      (pack_lighting), z k_s (three unorm10), w the Phong exponent (f32 bits).
// The samples carry the light of the lights alone; each pixel adds its own emission.
// #import reduced_shading logsh shadow_lookup slots full_screen

@group(MATERIAL_GROUP) @binding(SURFACE_BUFFER_A_BINDING) var surface_buffer_a: texture_2d<u32>;
@group(MATERIAL_GROUP) @binding(SURFACE_BUFFER_B_BINDING) var surface_buffer_b: texture_2d<u32>;

// The factors of each light on the shadow-map path at each low-resolution sample
// (mapped_light_factors: its diffuse and glossy lobes at unit intensity, times its
// falloff and its maps' visibility), written by
// fs_mark_surface_samples_keeping_visibility when the surfaces, those lights' geometry or
// their maps changed since the last frame (reduced_shading::MappedVisibilityKey), and
// read by the shading passes: a frame after an edit of the lights' intensities alone (a
// stroke) reads no map and evaluates no lobe at the samples, only intensity × factors.
// Entry k·n + j holds the factors of light frame.first_mapped_light + k at sample j
// (row-major, n samples). Shorter than the frame's lights need (past its memory budget):
// the passes read the maps themselves.
@group(MATERIAL_GROUP) @binding(KEPT_MAPPED_FACTORS_BINDING) var<storage, read> kept_mapped_factors: array<vec2<f32>>;
@group(PASS_GROUP) @binding(MAPPED_FACTORS_OUT_BINDING) var<storage, read_write> mapped_factors_out: array<vec2<f32>>;
// 1 for each mapped light whose factors fs_mark_surface_samples_keeping_visibility
// writes (its geometry or maps changed), 0 for each whose entries hold.
@group(PASS_GROUP) @binding(STALE_LIGHTS_BINDING) var<storage, read> stale_lights: array<u32>;

// The number of low-resolution samples and the index of sample `texel`, samples spaced
// LEVEL_STRIDE_PX pixels apart (reduced_shading::low_resolution_size).
fn sample_count_and_index(texel: vec2<i32>) -> vec2<u32> {
    let size = (textureDimensions(surface_buffer_a) + vec2<u32>(LEVEL_STRIDE_PX - 1u)) / LEVEL_STRIDE_PX;
    return vec2<u32>(size.x * size.y, u32(texel.y) * size.x + u32(texel.x));
}

// Whether a buffer of `length` entries holds every mapped light at `samples` samples.
fn holds_mapped_lights(length: u32, samples: u32) -> bool {
    return (frame.first_exact_light - frame.first_mapped_light) * samples <= length;
}

// mapped_lights_radiance at low-resolution sample `texel` (surface s), each light's
// factors read from kept_mapped_factors (the same sum, so the same bytes, either way).
fn kept_mapped_lights_radiance(s: Surface, texel: vec2<i32>) -> vec3<f32> {
    var radiance = vec3<f32>(0.0);
    if SHADOW_MAPS {
        let at = sample_count_and_index(texel);
        if !holds_mapped_lights(arrayLength(&kept_mapped_factors), at.x) {
            return mapped_lights_radiance(s);
        }
        let run = mapped_lights_at(s.position);
        for (var k = run.first; k < run.end; k++) {
            let i = run_light(k);
            let entry = at.y + (i - frame.first_mapped_light) * at.x;
            radiance += mapped_light_radiance(light_at(i).intensity_rgb.rgb, s, kept_mapped_factors[entry]);
        }
    }
    return radiance;
}

struct SurfaceTexels {
    @location(0) a: vec4<u32>,
    @location(1) b: vec4<u32>,
};

@fragment
fn fs_surface_buffer(in: VertexOut, @builtin(front_facing) front_facing: bool) -> SurfaceTexels {
    let s = surface(in, front_facing);
    return surface_texels(s, view_depth_of(s.position));
}

// The surface buffer's vertex stage for an untextured object without baked indirect
// light (GpuObject::baked_light): its view depth and normal are all
// fs_plain_surface_buffer needs. lavapipe sets up every varying of each triangle, and the
// large sample's triangles cover a pixel or two each: with these 4 floats instead of
// VertexOut's 11 its surfaces pass took 44.5 instead of 49.9 ms (docs/performance.md).
struct PlainSurfaceVertex {
    @builtin(position) @invariant clip: vec4<f32>,
    // signed_view_depth of the vertex, in metres.
    @location(0) view_depth: f32,
    @location(1) normal: vec3<f32>,
};

@vertex
fn vs_plain_surface(v: VertexIn) -> PlainSurfaceVertex {
    return PlainSurfaceVertex(frame.view_proj * vec4<f32>(v.position, 1.0), signed_view_depth(v.position), v.normal);
}

@fragment
fn fs_plain_surface_buffer(in: PlainSurfaceVertex, @builtin(front_facing) front_facing: bool) -> SurfaceTexels {
    // Untextured and without baked light: no texture coordinates or irradiance to read.
    let s = material_surface(in.normal, vec2<f32>(0.0), vec3<f32>(0.0), front_facing);
    return surface_texels(s, max(in.view_depth, 1e-30));
}

// The surface buffer's two texels of s at view depth `view_depth` (view_depth_of; s's
// position is not read).
fn surface_texels(s: Surface, view_depth: f32) -> SurfaceTexels {
    let k_d = pack_lighting(s.k_d);
    let emission = pack_lighting(s.emissive);
    let k_s = vec3<u32>(round(clamp(s.k_s, vec3<f32>(0.0), vec3<f32>(1.0)) * 1023.0));
    return SurfaceTexels(
        vec4<u32>(bitcast<u32>(view_depth), pack2x16snorm(octahedral_from_unit(s.normal)), k_d.x, k_d.y),
        vec4<u32>(emission.x, emission.y, k_s.r | (k_s.g << 10u) | (k_s.b << 20u), bitcast<u32>(s.phong_exponent)),
    );
}

// Full-resolution pixels per sample along each side in the image a full-screen pass draws
// (1: the full-resolution frame; the shading downsample d for the low-resolution
// samples; 2d for the soft layer).
override LEVEL_STRIDE_PX: u32 = 1u;

// The pixel of the surface buffer that sample `texel` of an image of samples spaced
// `stride_px` pixels apart shades: the middle pixel of its block (the left or upper of
// the two middle ones for even strides), clamped into the buffer where the last block
// runs past the frame's edge. UpsampleParams.sample_pixel says the same to the samples'
// readers.
fn level_pixel(texel: vec2<i32>, stride_px: u32) -> vec2<i32> {
    let last = vec2<i32>(textureDimensions(surface_buffer_a)) - vec2<i32>(1);
    let stride = i32(stride_px);
    return min(texel * stride + vec2<i32>(stride / 2), last);
}

// The surface the buffer holds at `texel`, and whether one was drawn there.
struct BufferedSurface {
    s: Surface,
    drawn: bool,
};

fn buffered_surface(texel: vec2<i32>) -> BufferedSurface {
    let a = textureLoad(surface_buffer_a, texel, 0);
    let b = textureLoad(surface_buffer_b, texel, 0);
    let size = vec2<f32>(textureDimensions(surface_buffer_a));
    let view_depth = bitcast<f32>(a.x);
    let ndc = vec2<f32>(2.0, -2.0) * (vec2<f32>(texel) + vec2<f32>(0.5)) / size + vec2<f32>(-1.0, 1.0);
    let ray = frame.view_ray[2].xyz + ndc.x * frame.view_ray[0].xyz + ndc.y * frame.view_ray[1].xyz;
    var s: Surface;
    s.position = frame.camera_position.xyz + ray * view_depth;
    s.normal = unit_from_octahedral(unpack2x16snorm(a.y));
    s.k_d = unpack_lighting(a.zw);
    s.k_s = vec3<f32>(vec3<u32>(b.z, b.z >> 10u, b.z >> 20u) & vec3<u32>(0x3ffu)) / 1023.0;
    s.phong_exponent = bitcast<f32>(b.w);
    s.emissive = unpack_lighting(b.xy);
    s.mirrored_view = reflect(-normalize(frame.camera_position.xyz - s.position), s.normal);
    return BufferedSurface(s, view_depth > 0.0);
}

// The surface of sample `texel` of an image of samples spaced `stride_px` pixels apart
// (level_pixel's pixel), with the diffuse reflectance k_d averaged over the
// `span_px` × `span_px` pixels around it that lie on its surface (normals within about
// 2° in the octahedral map, view depths within 10 %: a cheap test, as this runs span_px²
// times a sample). The samples carry their lighting divided by k_d + k_s, which each
// pixel multiplies by its own: exact where the two reflectances' diffuse and glossy
// shares agree, so a sample on one texel of a texture (a black stripe, whose light is
// mostly the glossy lobe's) would carry its texel's shares to its neighbours. The mean
// over the d × d pixels a low-resolution sample stands for is what a texture filtered
// over its footprint gives (the mip level rasterising the samples at their own
// resolution would pick); tests/texture_filtering.rs measures the striped floor's mean.
fn sample_surface(texel: vec2<i32>, stride_px: u32, span_px: u32) -> BufferedSurface {
    let centre = level_pixel(texel, stride_px);
    var buffered = buffered_surface(centre);
    let centre_texel = textureLoad(surface_buffer_a, centre, 0);
    let centre_normal = unpack2x16snorm(centre_texel.y);
    let centre_depth = bitcast<f32>(centre_texel.x);
    let last = vec2<i32>(textureDimensions(surface_buffer_a)) - vec2<i32>(1);
    let first = centre - vec2<i32>(i32(span_px / 2u));
    var k_d_sum = vec3<f32>(0.0);
    var count = 0.0;
    for (var k = 0u; k < span_px * span_px; k++) {
        let pixel = clamp(first + vec2<i32>(i32(k % span_px), i32(k / span_px)), vec2<i32>(0), last);
        let a = textureLoad(surface_buffer_a, pixel, 0);
        let on_surface = all(abs(unpack2x16snorm(a.y) - centre_normal) < vec2<f32>(0.03))
            && abs(bitcast<f32>(a.x) - centre_depth) < 0.1 * centre_depth;
        k_d_sum += select(vec3<f32>(0.0), unpack_lighting(a.zw), on_surface);
        count += select(0.0, 1.0, on_surface);
    }
    if count > 0.0 {
        buffered.s.k_d = k_d_sum / count;
    }
    return buffered;
}

// A triangle covering the target, at depth 1: with the depth test "greater" it reaches
// only the samples fs_mark_surface_samples marked (depth 0: a surface was drawn there).
struct FullScreen {
    @builtin(position) clip: vec4<f32>,
};

@vertex
fn vs_full_screen(@builtin(vertex_index) index: u32) -> FullScreen {
    return FullScreen(vec4<f32>(full_screen_corner(index) * 2.0 - vec2<f32>(1.0), 1.0, 1.0));
}

// Marks the low-resolution samples that lie on a surface: depth 0 there (the low
// depth is cleared to 1), so that the shading passes' triangle at depth 1 with the test
// "greater" reaches only them.
@fragment
fn fs_mark_surface_samples(in: FullScreen) -> @builtin(frag_depth) f32 {
    if textureLoad(surface_buffer_a, level_pixel(vec2<i32>(in.clip.xy), LEVEL_STRIDE_PX), 0).x == 0u {
        discard;
    }
    return 0.0;
}

// fs_mark_surface_samples, and each marked sample's factors of the mapped lights that
// stale_lights marks written to mapped_factors_out (mapped_light_factors at the surface
// of the sample's pixel, whose position, normal and gloss sample_surface gives the
// shading passes; they average k_d alone, which the factors leave out).
@fragment
fn fs_mark_surface_samples_keeping_visibility(in: FullScreen) -> @builtin(frag_depth) f32 {
    let texel = vec2<i32>(in.clip.xy);
    let buffered = buffered_surface(level_pixel(texel, LEVEL_STRIDE_PX));
    if !buffered.drawn {
        discard;
    }
    let at = sample_count_and_index(texel);
    if SHADOW_MAPS && holds_mapped_lights(arrayLength(&mapped_factors_out), at.x) {
        // Only the lights that may reach the sample (the others' entries go unread).
        let run = mapped_lights_at(buffered.s.position);
        for (var e = run.first; e < run.end; e++) {
            let i = run_light(e);
            let k = i - frame.first_mapped_light;
            if k >= arrayLength(&stale_lights) || stale_lights[k] != 0u {
                let light = light_at(i);
                mapped_factors_out[at.y + k * at.x] = mapped_light_factors(light, buffered.s);
            }
        }
    }
    return 0.0;
}

// x: the generation of the SH path's light kept where it was shaded in full (never 0),
// which changes whenever the surfaces or the soft light's inputs do (render/passes/
// kept_harmonic.rs), so light kept with this generation is this frame's; y: 1 where the
// last frame had this generation too, so the samples fs_shade_low shades now are those it
// shaded then (they depend on the surfaces and the soft layer alone) and their light
// kept then is this frame's.
@group(PASS_GROUP) @binding(KEPT_HARMONIC_GENERATION_BINDING) var<uniform> kept_harmonic_generation: vec4<u32>;
// The soft light at the samples in the last frame, a sample texel each (view depth, its
// share of the unshadowed light — soft_share —, normal: reduced_shading.wgsl), of which
// fs_shade_low reads the SH path's light at those it shades. fs_shade_low reads last frame's image and writes the other
// (a fragment shader writing storage would run before its depth test: every sample, not
// only those left, would pay).
@group(PASS_GROUP) @binding(KEPT_HARMONIC_READ_BINDING) var kept_harmonic_read: texture_2d<u32>;

// The soft light's share of its unshadowed light, which two-level shading's soft samples
// carry in place of their lighting: per channel, the SH path's light through the
// blockers' and the terrain's visibility (`harmonic`) over the same light unblocked
// (`unshadowed`, unshadowed_harmonic_radiance). Each reader multiplies its own unshadowed
// light back in, so the light's turn with the normal and its reflectance's texture are
// the reader's own and only the visibility is interpolated: with one light, or the
// environment alone, the share is that light's visibility (the separate BRDF's clamped
// mean of the visibility SH over it, or the cosine-weighted environment through it over
// the unblocked). A channel no unshadowed light reaches takes the luminance's share;
// `known` is false where no light reaches at all (the sample then says nothing of the
// visibility). Against interpolating the soft light itself, on the large sample at
// 480 × 270 the frame's relative L1 to the path tracer went 0.0551 → 0.0546
// (docs/performance.md).
struct SoftShare {
    share: vec3<f32>,
    known: bool,
};

fn soft_share(harmonic: vec3<f32>, unshadowed: vec3<f32>) -> SoftShare {
    let luminance = vec3<f32>(0.2126, 0.7152, 0.0722);
    let unshadowed_luminance = dot(unshadowed, luminance);
    let mean = dot(harmonic, luminance) / max(unshadowed_luminance, 1e-30);
    let per_channel = harmonic / max(unshadowed, vec3<f32>(1e-30));
    let share = select(vec3<f32>(mean), per_channel, unshadowed > vec3<f32>(1e-6 * unshadowed_luminance));
    return SoftShare(min(share, vec3<f32>(MAX_LIGHTING)), unshadowed_luminance > 0.0);
}

// A sample texel (reduced_shading.wgsl) of surface s carrying `share` in place of the
// lighting, and no surface (view depth 0) where the share is not known, so that readers
// do not count it.
fn soft_share_texel(s: Surface, share: SoftShare) -> vec4<u32> {
    let texel = low_sample_texel(s, share.share);
    return select(vec4<u32>(0u, texel.yzw), texel, share.known);
}

// A sample shaded in full, and the SH path's light at it as a sample of its share
// (soft_share; kept for the next frames; with two levels the listed pixels upsample it
// with the soft layer's share at the other samples).
struct ShadedLowSample {
    @location(0) texel: vec4<u32>,
    @location(1) soft: vec4<u32>,
};

// A low-resolution sample shaded in full (one level: every sample on a surface).
@fragment
fn fs_shade_low(in: FullScreen) -> ShadedLowSample {
    return low_sample_in_full(vec2<i32>(in.clip.xy), kept_harmonic_generation.y != 0u);
}

// Low-resolution sample `texel` shaded in full (fs_shade_low; with two levels the
// samples the soft layer does not serve, listed_samples.wgsl); the SH path's light (the
// blocker walk) as its share of the unshadowed light (soft_share), read from the last
// frame's kept image where `kept_current` (that frame had this one's generation:
// kept_harmonic_generation.y). Always through pack_lighting, so that a frame reading it
// is the frame shading it anew.
fn low_sample_in_full(texel: vec2<i32>, kept_current: bool) -> ShadedLowSample {
    let s = sample_surface(texel, LEVEL_STRIDE_PX, LEVEL_STRIDE_PX).s;
    let unshadowed = unshadowed_harmonic_radiance(s);
    var kept = textureLoad(kept_harmonic_read, texel, 0);
    // The same for every sample (a condition per sample would not spare lavapipe the
    // walk: it runs a branch for a block of samples, those the depth test left out too).
    if !kept_current {
        kept = soft_share_texel(s, soft_share(harmonic_radiance(s), unshadowed));
    }
    return low_sample_with_soft(texel, s, unshadowed, kept);
}

// Low-resolution sample `texel` (surface s, whose SH path's light unshadowed is
// `unshadowed`) shaded in full with the SH path's light `kept` (soft_share_texel).
fn low_sample_with_soft(texel: vec2<i32>, s: Surface, unshadowed: vec3<f32>, kept: vec4<u32>) -> ShadedLowSample {
    let harmonic_lighting = frame.exposure * unpack_lighting(kept.yz) * unshadowed / reflectance(s);
    let others = exact_path_radiance(s) + kept_mapped_lights_radiance(s, texel);
    let lighting = frame.exposure * others / reflectance(s) + harmonic_lighting;
    return ShadedLowSample(low_sample_texel(s, lighting), kept);
}

// The soft layer's samples (two-level shading): the light of soft shadows alone — the
// environment's and the SH path's lights through the blockers' visibility — as its share
// of the same light unshadowed (soft_share), at twice the low-resolution samples'
// spacing (LEVEL_STRIDE_PX is 2d here).
@fragment
fn fs_shade_soft(in: FullScreen) -> @location(0) vec4<u32> {
    // The soft samples' k_d averaged over the d × d pixels around them, as the
    // low-resolution samples' (fewer fetches; the soft light is smooth).
    let buffered = sample_surface(vec2<i32>(in.clip.xy), LEVEL_STRIDE_PX, LEVEL_STRIDE_PX / 2u);
    let s = buffered.s;
    let texel = soft_share_texel(s, soft_share(harmonic_radiance(s), unshadowed_harmonic_radiance(s)));
    return select(vec4<u32>(0u), texel, buffered.drawn);
}

// A low-resolution sample from the soft layer upsampled to it (group 3 then holds the
// soft layer) plus the lights of sharp shadows, the shadow-map and exact paths, shaded
// here, and that soft light's share alone as a sample (its second target: with the
// samples the listed samples' passes shade, the soft light's share at every sample, which
// the listed pixels upsample). Samples the soft layer does not match, or whose soft
// samples disagree, it leaves without a surface, marked for the listed samples' passes
// (listed_samples.wgsl), which shade them in full right after.
@fragment
fn fs_shade_sharp_marking(in: FullScreen) -> ShadedLowSample {
    let s = sample_surface(vec2<i32>(in.clip.xy), LEVEL_STRIDE_PX, LEVEL_STRIDE_PX).s;
    // The soft light's share (soft_share), upsampled.
    let share = upsampled_lighting(in.clip.xy, s, false);
    if !share.matches {
        // Left for the listed samples' passes (listed_samples.wgsl) to shade in full: no
        // surface (view depth 0), and y 1 where the soft samples on its surface agreed
        // (too few of them lay on it: its blocker walk may be shared).
        return ShadedLowSample(vec4<u32>(0u, select(0u, 1u, share.agrees), 0u, 0u), vec4<u32>(0u));
    }
    let soft = share.lighting * unshadowed_harmonic_radiance(s);
    let sharp = kept_mapped_lights_radiance(s, vec2<i32>(in.clip.xy)) + exact_path_radiance(s);
    return ShadedLowSample(
        low_sample_texel(s, frame.exposure * (soft + sharp) / reflectance(s)),
        soft_share_texel(s, SoftShare(share.lighting, true)),
    );
}
