// Reduced-resolution shading deferred (src/render/passes/reduced_shading.rs): the meshes
// are rasterised once into a surface buffer by a cheap shader (fs_surface_buffer), and
// the costly work runs in full-screen passes that read it — the samples' shading at low
// resolution, and on single-sampled targets the upsampling and the full shading of the
// pixels it leaves at full resolution. lavapipe runs a fragment shader over blocks of
// pixels per triangle, so a mesh whose triangles are smaller than the samples' spacing
// (a figure's limbs at a third of the resolution, a fine terrain at full resolution) had
// the shading run once per triangle for a pixel or less; a full-screen pass runs it once
// per pixel. Appended after reduced_shading.wgsl.
//
// The buffer, two Rgba32Uint texels per pixel:
//   a: x view depth (f32 bits, 0 where no surface was drawn), y the octahedral normal
//      (two snorm16), zw k_d (pack_lighting);
//   b: xy the emission — the material's own and the baked indirect light —
//      (pack_lighting), z k_s (three unorm10), w the Phong exponent (f32 bits).
// The samples carry the light of the lights alone; each pixel adds its own emission.

@group(1) @binding(8) var surface_buffer_a: texture_2d<u32>;
@group(1) @binding(9) var surface_buffer_b: texture_2d<u32>;

struct SurfaceTexels {
    @location(0) a: vec4<u32>,
    @location(1) b: vec4<u32>,
};

@fragment
fn fs_surface_buffer(in: VertexOut, @builtin(front_facing) front_facing: bool) -> SurfaceTexels {
    let s = surface(in, front_facing);
    let k_d = pack_lighting(s.k_d);
    let emission = pack_lighting(s.emissive);
    let k_s = vec3<u32>(round(clamp(s.k_s, vec3<f32>(0.0), vec3<f32>(1.0)) * 1023.0));
    return SurfaceTexels(
        vec4<u32>(
            bitcast<u32>(view_depth_of(s.position)),
            pack2x16snorm(octahedral_from_unit(s.normal)),
            k_d.x,
            k_d.y,
        ),
        vec4<u32>(emission.x, emission.y, k_s.r | (k_s.g << 10u) | (k_s.b << 20u), bitcast<u32>(s.phong_exponent)),
    );
}

// The depth of p along the camera's forward axis, kept above 0 (the mark of a drawn
// surface: points in view lie past the near plane).
fn view_depth_of(p: vec3<f32>) -> f32 {
    return max(dot(p - frame.camera_position.xyz, frame.view_ray[2].xyz), 1e-30);
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

// A triangle covering the target, at depth 1: with the depth test "greater" it reaches
// only the samples where the surface buffer's pass drew something (depth < 1), and
// those a marking pass has not yet set to 1.
struct FullScreen {
    @builtin(position) clip: vec4<f32>,
};

@vertex
fn vs_full_screen(@builtin(vertex_index) index: u32) -> FullScreen {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return FullScreen(vec4<f32>(corner * 2.0 - vec2<f32>(1.0), 1.0, 1.0));
}

// A low-resolution sample shaded in full.
@fragment
fn fs_shade_low(in: FullScreen) -> @location(0) vec4<u32> {
    let s = buffered_surface(vec2<i32>(in.clip.xy)).s;
    return low_sample_texel(s, frame.exposure * (shadowed_radiance(s) - s.emissive) / reflectance(s));
}

// The soft layer's samples (two-level shading): the light of soft shadows alone — the
// environment's and the SH path's lights through the blockers' visibility — of the
// low-resolution surface at the top-left of each 2 × 2 block (UpsampleParams.
// sample_offset and texel_to_ndc say so to its readers).
@fragment
fn fs_shade_soft(in: FullScreen) -> @location(0) vec4<u32> {
    let last = vec2<i32>(textureDimensions(surface_buffer_a)) - vec2<i32>(1);
    let buffered = buffered_surface(min(2 * vec2<i32>(in.clip.xy), last));
    let s = buffered.s;
    let texel = low_sample_texel(s, frame.exposure * harmonic_radiance(s) / reflectance(s));
    return select(vec4<u32>(0u), texel, buffered.drawn);
}

// A low-resolution sample from the soft layer upsampled to it (group 3 then holds the
// soft layer) plus the lights of sharp shadows, the shadow-map and exact paths, shaded
// here. Samples the soft layer does not match, or whose soft samples disagree, are
// discarded, and fs_shade_low shades them in full right after: this pass writes depth 1
// where it shades (its pipeline's depth write), which fs_shade_low's test then skips.
@fragment
fn fs_shade_sharp_marking(in: FullScreen) -> @location(0) vec4<u32> {
    let s = buffered_surface(vec2<i32>(in.clip.xy)).s;
    let soft = upsampled_lighting(in.clip.xy, s, false);
    if !soft.matches {
        discard;
    }
    let sharp = mapped_lights_radiance(s) + exact_path_radiance(s);
    return low_sample_texel(s, soft.lighting + frame.exposure * sharp / reflectance(s));
}

// The full-resolution frame deferred too (single-sampled targets): the surface buffer at
// full resolution, then the upsampling and the full shading of the pixels it leaves as
// full-screen passes, as at low resolution. A mesh of triangles a few pixels wide (a
// terrain) had each rasterised pass pay per triangle.

// A pixel from the low-resolution samples (group 3), or discarded for fs_logsh_deferred
// where they do not match or disagree; writes depth 1 where it shades (its pipeline).
@fragment
fn fs_upsample_deferred_marking(in: FullScreen) -> @location(0) vec4<f32> {
    let s = buffered_surface(vec2<i32>(in.clip.xy)).s;
    let up = upsampled_lighting(in.clip.xy, s, false);
    if !up.matches {
        discard;
    }
    return vec4<f32>(tonemap_aces_fit(frame.exposure * s.emissive + reflectance(s) * up.lighting), 1.0);
}

// A pixel shaded in full: fs_logsh from the surface buffer.
@fragment
fn fs_logsh_deferred(in: FullScreen) -> @location(0) vec4<f32> {
    let s = buffered_surface(vec2<i32>(in.clip.xy)).s;
    return vec4<f32>(tonemap_aces_fit(frame.exposure * shadowed_radiance(s)), 1.0);
}
