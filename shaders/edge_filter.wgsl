// Edge antialiasing of a single-sample frame (src/render/target/edge_filter.rs), after the
// idea of FXAA (Lottes 2009): a pixel on a contrast edge takes the image sampled a
// fraction of a pixel across the edge. The fraction grows toward the end of the edge's run
// nearer the pixel (a staircase step of a slanted edge gets the coverage a multisampled
// edge would), and a pixel much unlike its 3 × 3 neighbourhood (a one-pixel-wide feature)
// is blended at least by how much it stands out. Works on the stored sRGB-encoded values,
// which are close to perceived lightness.
//
// Two draws of a full-screen triangle: fs_keep_flat copies the pixels without contrast
// and marks them in the depth buffer, discarding the rest; fs_edge_filter then runs only
// on those (its depth test rejects the marked ones before the shader). On a software GPU,
// which runs both sides of a branch at every pixel, a single draw would pay the edge
// search at every pixel.
// #import slots full_screen

// The frame as drawn, read raw (sRGB-encoded values).
@group(IMAGE_GROUP) @binding(FRAME_IMAGE_BINDING) var frame_image: texture_2d<f32>;
// Bilinear, clamped at the border.
@group(IMAGE_GROUP) @binding(FRAME_SAMPLER_BINDING) var frame_sampler: sampler;
// The frame's depth as rasterised (1: no surface; an image filtered without surfaces is
// all 1).
@group(IMAGE_GROUP) @binding(FRAME_DEPTH_BINDING) var frame_depth: texture_depth_2d;

// Contrast (in encoded luma) below which a pixel is left alone: an absolute floor for
// dark regions, and a share of the neighbourhood's brightest luma.
const EDGE_CONTRAST_FLOOR: f32 = 0.0312;
const EDGE_CONTRAST_SHARE: f32 = 0.125;
// How much of the one-pixel-feature blend applies (1: all of it).
const SUBPIXEL_BLEND: f32 = 0.75;
// Steps of the search along an edge for its ends, and their lengths in pixels (the later
// ones longer: an end found far away needs no exact position).
const EDGE_SEARCH_STEPS: u32 = 8u;

fn edge_search_step_px(i: u32) -> f32 {
    return select(1.0, select(2.0, 4.0, i >= 6u), i >= 4u);
}

// A triangle covering the viewport at depth 0: no overdraw, no vertex buffer.
@vertex
fn vs_full_screen(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(full_screen_corner(index) * 2.0 - 1.0, 0.0, 1.0);
}

fn luma(color: vec3<f32>) -> f32 {
    return dot(color, vec3<f32>(0.299, 0.587, 0.114));
}

fn luma_at_pixel(pixel: vec2<i32>) -> f32 {
    let last = vec2<i32>(textureDimensions(frame_image)) - vec2<i32>(1);
    return luma(textureLoad(frame_image, clamp(pixel, vec2<i32>(0), last), 0).rgb);
}

fn luma_at_uv(uv: vec2<f32>) -> f32 {
    return luma(textureSampleLevel(frame_image, frame_sampler, uv, 0.0).rgb);
}

// The luma of a pixel's four edge neighbours (north, south, east, west; y grows down).
struct Cross {
    n: f32,
    s: f32,
    e: f32,
    w: f32,
};

fn cross_at(pixel: vec2<i32>) -> Cross {
    return Cross(
        luma_at_pixel(pixel + vec2<i32>(0, -1)),
        luma_at_pixel(pixel + vec2<i32>(0, 1)),
        luma_at_pixel(pixel + vec2<i32>(1, 0)),
        luma_at_pixel(pixel + vec2<i32>(-1, 0)),
    );
}

// Luma range over the pixel (luma m) and its cross.
fn contrast_of(m: f32, c: Cross) -> f32 {
    return max(m, max(max(c.n, c.s), max(c.e, c.w))) - min(m, min(min(c.n, c.s), min(c.e, c.w)));
}

fn is_edge(m: f32, c: Cross) -> bool {
    let highest = max(m, max(max(c.n, c.s), max(c.e, c.w)));
    return contrast_of(m, c) >= max(EDGE_CONTRAST_FLOOR, highest * EDGE_CONTRAST_SHARE);
}

fn depth_at(pixel: vec2<i32>) -> f32 {
    let last = vec2<i32>(textureDimensions(frame_depth)) - vec2<i32>(1);
    return textureLoad(frame_depth, clamp(pixel, vec2<i32>(0), last), 0);
}

// How far the depth along a row or column may bend at a pixel, as a share of its steepest
// step there, before the surfaces count as folding or breaking: within one plane the
// rasterised depth is affine in the screen's coordinates (its second difference is only
// rounding), across a silhouette it jumps, and across a crease its slope turns. A
// tessellated curve bends by about its pixel's share of the curve's radius on the screen.
const DEPTH_BEND_SHARE: f32 = 0.25;
// And in absolute terms: a few units in the last place of depths near 1.
const DEPTH_BEND_FLOOR: f32 = 4.0e-7;

// Whether the surfaces fold or break at `pixel` (a silhouette, a crease), or no surface
// is there or beside it (a frame's background, or an image filtered without its
// surfaces, judged by its colours alone). Contrast elsewhere lies within one surface —
// a texture already filtered over each pixel's footprint, a shadow's outline, a
// highlight — which the edge filter would only blur: on the lamp room's checkered floor
// the frame came closer to the path tracer without the filter than with it
// (docs/speed-accuracy.md).
fn surfaces_break(pixel: vec2<i32>) -> bool {
    // Two gathers of 2 × 2 texels, (w, c, n, nw) about the pixel's top-left corner and
    // (s, se, e, c) about its bottom-right one (WGSL orders a gather i0j1, i1j1, i1j0,
    // i0j0), clamped at the border as the sampler addresses.
    let size = vec2<f32>(textureDimensions(frame_depth));
    let top_left = textureGather(frame_depth, frame_sampler, vec2<f32>(pixel) / size);
    let bottom_right = textureGather(frame_depth, frame_sampler, (vec2<f32>(pixel) + 1.0) / size);
    let c = top_left.y;
    let n = top_left.z;
    let w = top_left.x;
    let e = bottom_right.z;
    let s = bottom_right.x;
    let nothing_drawn = min(c, min(min(n, s), min(e, w))) >= 1.0;
    // At the image's border the neighbour beyond is the pixel itself (clamped), which
    // would read as a fold: no bend is measured across that side.
    let last = vec2<i32>(textureDimensions(frame_depth)) - vec2<i32>(1);
    let across_x = pixel.x > 0 && pixel.x < last.x;
    let across_y = pixel.y > 0 && pixel.y < last.y;
    let bend = max(select(0.0, abs(e + w - 2.0 * c), across_x), select(0.0, abs(n + s - 2.0 * c), across_y));
    let step = max(max(abs(e - c), abs(c - w)), max(abs(n - c), abs(c - s)));
    return nothing_drawn || bend > DEPTH_BEND_SHARE * step + DEPTH_BEND_FLOOR;
}

// First draw: a pixel without contrast, or whose contrast lies within one surface, keeps
// its colour (and its depth, written 0, keeps fs_edge_filter away); a pixel on an edge
// of the surfaces is discarded, for fs_edge_filter.
@fragment
fn fs_keep_flat(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(position.xy);
    let centre = textureLoad(frame_image, pixel, 0);
    // Nested, so that blocks of pixels without contrast (most of a frame) skip the depth
    // reads (a software GPU runs a branch only where some lane takes it).
    if is_edge(luma(centre.rgb), cross_at(pixel)) {
        if surfaces_break(pixel) {
            discard;
        }
    }
    return centre;
}

// Second draw, at the pixels on an edge.
@fragment
fn fs_edge_filter(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(frame_image));
    let texel = 1.0 / size;
    let pixel = vec2<i32>(position.xy);
    let uv = position.xy * texel;
    let m = luma(textureLoad(frame_image, pixel, 0).rgb);
    let around = cross_at(pixel);
    let n = around.n;
    let s = around.s;
    let e = around.e;
    let w = around.w;
    let contrast = contrast_of(m, around);

    let nw = luma_at_pixel(pixel + vec2<i32>(-1, -1));
    let ne = luma_at_pixel(pixel + vec2<i32>(1, -1));
    let sw = luma_at_pixel(pixel + vec2<i32>(-1, 1));
    let se = luma_at_pixel(pixel + vec2<i32>(1, 1));
    // A horizontal edge changes luma along y: compare second differences across rows and
    // across columns.
    let across_rows = abs(nw + sw - 2.0 * w) + 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e);
    let across_columns = abs(nw + ne - 2.0 * n) + 2.0 * abs(w + e - 2.0 * m) + abs(sw + se - 2.0 * s);
    let horizontal = across_rows >= across_columns;

    // The side of the edge with the steeper change, and one pixel toward it.
    let before = select(w, n, horizontal);
    let after = select(e, s, horizontal);
    let toward_before = abs(before - m) >= abs(after - m);
    let side_luma = select(after, before, toward_before);
    let across_px = select(1.0, -1.0, toward_before);
    let across = select(vec2<f32>(across_px * texel.x, 0.0), vec2<f32>(0.0, across_px * texel.y), horizontal);
    let along = select(vec2<f32>(0.0, texel.y), vec2<f32>(texel.x, 0.0), horizontal);
    // Half-way between the pixel and its neighbour across the edge, the edge's luma.
    let edge_luma = 0.5 * (m + side_luma);
    let gradient = 0.25 * max(abs(before - m), abs(after - m));
    let start = uv + 0.5 * across;

    // Walk along the edge both ways until its luma leaves the edge's (an end of the run).
    var back = start - along;
    var forth = start + along;
    var back_delta = luma_at_uv(back) - edge_luma;
    var forth_delta = luma_at_uv(forth) - edge_luma;
    var back_done = abs(back_delta) >= gradient;
    var forth_done = abs(forth_delta) >= gradient;
    for (var i = 0u; i < EDGE_SEARCH_STEPS && !(back_done && forth_done); i++) {
        let stride = along * edge_search_step_px(i);
        if !back_done {
            back -= stride;
            back_delta = luma_at_uv(back) - edge_luma;
            back_done = abs(back_delta) >= gradient;
        }
        if !forth_done {
            forth += stride;
            forth_delta = luma_at_uv(forth) - edge_luma;
            forth_done = abs(forth_delta) >= gradient;
        }
    }
    let to_back = select(uv.y - back.y, uv.x - back.x, horizontal);
    let to_forth = select(forth.y - uv.y, forth.x - uv.x, horizontal);
    let nearer_back = to_back < to_forth;
    let run = max(to_back + to_forth, 1e-6);
    // Only where the nearer end turns the way that makes this pixel part of the step.
    let end_delta = select(forth_delta, back_delta, nearer_back);
    let turns_right = (end_delta < 0.0) != (m < edge_luma);
    let run_offset = select(0.0, 0.5 - min(to_back, to_forth) / run, turns_right);

    let neighbourhood = (2.0 * (n + s + e + w) + nw + ne + sw + se) / 12.0;
    let stand_out = clamp(abs(neighbourhood - m) / max(contrast, 1e-6), 0.0, 1.0);
    let smooth_out = (3.0 - 2.0 * stand_out) * stand_out * stand_out;
    let subpixel_offset = smooth_out * smooth_out * SUBPIXEL_BLEND;

    let offset = max(run_offset, subpixel_offset);
    return textureSampleLevel(frame_image, frame_sampler, uv + offset * across, 0.0);
}
