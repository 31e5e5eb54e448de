// The editor's viewport image drawn into egui's frame (src/ui/viewport_image.rs): a
// triangle covering the viewport that egui sets for the paint callback, each pixel the
// frame's texel. egui's own image shader costs lavapipe about 14 ms for a 960 × 540
// image (it carries a second, bilinear path of four texel loads and wrap arithmetic that
// a software GPU runs beside the first); this one fetches one texel. Standalone.
// #import slots full_screen

@group(IMAGE_GROUP) @binding(FRAME_IMAGE_BINDING) var frame_image: texture_2d<f32>;
@group(IMAGE_GROUP) @binding(FRAME_SAMPLER_BINDING) var frame_sampler: sampler;

// 1: the surface egui draws into is sRGB-encoding, so the frame's sRGB bytes are decoded
// before the store encodes them again; 0: they are stored as they are.
override SRGB_TARGET: bool = false;

struct Covering {
    @builtin(position) clip: vec4<f32>,
    // The image's coordinates, (0, 0) top-left and (1, 1) bottom-right of the viewport.
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_viewport(@builtin(vertex_index) index: u32) -> Covering {
    let corner = full_screen_corner(index);
    return Covering(vec4<f32>(corner * 2.0 - vec2<f32>(1.0), 0.0, 1.0), vec2<f32>(corner.x, 1.0 - corner.y));
}

fn stored(rgba: vec4<f32>) -> vec4<f32> {
    if SRGB_TARGET {
        let c = rgba.rgb;
        let linear = select(pow((c + vec3<f32>(0.055)) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
        return vec4<f32>(linear, 1.0);
    }
    return vec4<f32>(rgba.rgb, 1.0);
}

// The image as large as the viewport in pixels: its texel under the pixel.
@fragment
fn fs_texel(in: Covering) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(frame_image));
    let texel = min(vec2<i32>(in.uv * size), vec2<i32>(size) - vec2<i32>(1));
    return stored(textureLoad(frame_image, texel, 0));
}

// An image of another size (the half-resolution frame while the camera moves, a
// resolution scale below 1): filtered bilinearly.
@fragment
fn fs_filtered(in: Covering) -> @location(0) vec4<f32> {
    return stored(textureSampleLevel(frame_image, frame_sampler, in.uv, 0.0));
}
