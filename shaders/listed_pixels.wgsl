// The pixels the upsampling leaves, gathered into lists and shaded densely
// (src/render/passes/listed_pixels.rs). They are few (about 3 % of the studio's frame:
// the edges of hard shadows, rims, silhouettes) and scattered along lines, and a
// software GPU shades a fragment pass in blocks of pixels: a full-screen pass over them,
// its depth test leaving one or two live pixels in a block, paid the full shading for the
// whole block (the studio's 3.0 % took 14 ms; shaded densely, about 3 ms). So a compute
// pass lists them from the frame's depth (the upsampling wrote depth 1 where it drew),
// compute passes shade each list densely, 64 at a time, into an image, and a last
// full-screen pass copies that image into the frame at the listed pixels.
//
// With two-level shading a listed pixel first takes the soft layer upsampled to it plus
// the sharp lights shaded at the pixel (cs_shade_listed_sharp); where the soft layer does
// not match or its samples disagree, the pixel goes on a second list and is shaded in full
// (cs_shade_listed_full). With one level every listed pixel is shaded in full.
// #import low_resolution reduced_shading logsh slots

// The frame's depth after the upsampling: below 1 at the surface pixels it left.
@group(PASS_GROUP) @binding(FRAME_DEPTH_BINDING) var frame_depth: texture_depth_2d;

// How many pixels each list holds (cleared before the listing).
struct ListCounts {
    sharp: atomic<u32>,
    full: atomic<u32>,
};
@group(PASS_GROUP) @binding(LIST_COUNTS_BINDING) var<storage, read_write> list_counts: ListCounts;
// The pixels to shade from the soft layer and the sharp lights, and those to shade in full,
// each x | y << 16 (frames are below 65 536 pixels on a side): entry i of a list at texel
// (i mod width, i / width) of an image of the frame's size, written by one pass and read
// by the next. (Images of the frame's size fit every device that draws the frame; a
// storage buffer of 4 bytes a pixel passed the binding limit of some.)
@group(PASS_GROUP) @binding(SHARP_PIXELS_OUT_BINDING) var sharp_pixels_out: texture_storage_2d<r32uint, write>;
@group(PASS_GROUP) @binding(SHARP_PIXELS_BINDING) var sharp_pixels: texture_2d<u32>;
@group(PASS_GROUP) @binding(FULL_PIXELS_OUT_BINDING) var full_pixels_out: texture_storage_2d<r32uint, write>;
@group(PASS_GROUP) @binding(FULL_PIXELS_BINDING) var full_pixels: texture_2d<u32>;
// The listed pixels' colours, at their pixels (written only there).
@group(PASS_GROUP) @binding(LISTED_COLOURS_BINDING) var listed_colours: texture_storage_2d<rgba32float, write>;
// The workgroup counts of the two shading passes' indirect dispatches: sharp xyz, full xyz.
@group(PASS_GROUP) @binding(DISPATCH_ARGS_BINDING) var<storage, read_write> dispatch_args: array<u32, 6>;
// The same colours read by the pass that copies them into the frame.
@group(PASS_GROUP) @binding(LISTED_COLOURS_READ_BINDING) var listed_colours_read: texture_2d<f32>;

// Invocations per workgroup of the shading passes.
const LISTED_WORKGROUP_SIZE: u32 = 64u;

// Two-level shading: listed pixels go to the sharp list first (else straight to the full one).
override LIST_FOR_SHARP: bool = true;

fn packed_pixel(pixel: vec2<u32>) -> u32 {
    return pixel.x | (pixel.y << 16u);
}

fn unpacked_pixel(packed: u32) -> vec2<i32> {
    return vec2<i32>(i32(packed & 0xffffu), i32(packed >> 16u));
}

// Where entry `entry` of a list `width` texels wide sits.
fn entry_texel(entry: u32, width: u32) -> vec2<u32> {
    return vec2<u32>(entry % width, entry / width);
}

fn list_on_sharp(pixel: vec2<u32>) {
    let entry = atomicAdd(&list_counts.sharp, 1u);
    textureStore(sharp_pixels_out, entry_texel(entry, textureDimensions(sharp_pixels_out).x), vec4<u32>(packed_pixel(pixel)));
}

fn list_on_full(pixel: vec2<u32>) {
    let entry = atomicAdd(&list_counts.full, 1u);
    textureStore(full_pixels_out, entry_texel(entry, textureDimensions(full_pixels_out).x), vec4<u32>(packed_pixel(pixel)));
}

// The listing's workgroup is LIST_WORKGROUP_SIDE² invocations, each looking at
// LIST_RUN_PX pixels side by side along a row (four at a time listed the studio's frame
// in 1.3–1.6 ms, one at a time in 1.8: lavapipe's cost per invocation outweighed the
// depth reads). Set by listed_pixels.rs, which dispatches the workgroups.
override LIST_WORKGROUP_SIDE: u32;
override LIST_RUN_PX: u32;

// Lists every surface pixel the upsampling left.
@compute @workgroup_size(LIST_WORKGROUP_SIDE, LIST_WORKGROUP_SIDE)
fn cs_list_unshaded(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(frame_depth);
    for (var k = 0u; k < LIST_RUN_PX; k++) {
        let pixel = vec2<u32>(id.x * LIST_RUN_PX + k, id.y);
        if all(pixel < size) && textureLoad(frame_depth, vec2<i32>(pixel), 0) < 1.0 {
            if LIST_FOR_SHARP {
                list_on_sharp(pixel);
            } else {
                list_on_full(pixel);
            }
        }
    }
}

// The shading passes' workgroup counts from the lists' lengths.
@compute @workgroup_size(1)
fn cs_dispatch_args() {
    let groups = (vec2<u32>(atomicLoad(&list_counts.sharp), atomicLoad(&list_counts.full)) + vec2<u32>(LISTED_WORKGROUP_SIZE - 1u)) / LISTED_WORKGROUP_SIZE;
    dispatch_args = array<u32, 6>(groups.x, 1u, 1u, groups.y, 1u, 1u);
}

// A listed pixel from the soft layer upsampled to it (group 3's samples) plus the sharp
// lights shaded here, or put on the full list where the soft layer does not match it or
// disagrees.
@compute @workgroup_size(LISTED_WORKGROUP_SIZE)
fn cs_shade_listed_sharp(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= atomicLoad(&list_counts.sharp) {
        return;
    }
    let pixel = unpacked_pixel(textureLoad(sharp_pixels, entry_texel(id.x, textureDimensions(sharp_pixels).x), 0).x);
    let s = buffered_surface(pixel).s;
    // The pixel's centre, as a fragment's position is.
    let soft = upsampled_lighting(vec2<f32>(pixel) + vec2<f32>(0.5), s, false);
    if soft.matches {
        let sharp = mapped_lights_radiance(s) + exact_path_radiance(s);
        let colour = tonemap_aces_fit(frame.exposure * (s.emissive + sharp) + reflectance(s) * soft.lighting);
        textureStore(listed_colours, pixel, vec4<f32>(colour, 1.0));
    } else {
        list_on_full(vec2<u32>(pixel));
    }
}

// A listed pixel shaded in full.
@compute @workgroup_size(LISTED_WORKGROUP_SIZE)
fn cs_shade_listed_full(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= atomicLoad(&list_counts.full) {
        return;
    }
    let pixel = unpacked_pixel(textureLoad(full_pixels, entry_texel(id.x, textureDimensions(full_pixels).x), 0).x);
    let s = buffered_surface(pixel).s;
    textureStore(listed_colours, pixel, vec4<f32>(tonemap_aces_fit(frame.exposure * shadowed_radiance(s)), 1.0));
}

// The listed pixels' colours into the frame: drawn where the upsampling left the depth
// below 1, which is where the listing found them.
@fragment
fn fs_listed_colour(in: FullScreen) -> @location(0) vec4<f32> {
    return textureLoad(listed_colours_read, vec2<i32>(in.clip.xy), 0);
}
