// The full-resolution frame of deferred reduced shading on single-sampled targets
// (src/render/passes/full_resolution.rs), in compute passes over the surface buffer:
//
// 1. cs_upsample_blocks: each invocation takes the d × d pixels that share their 2 × 2
//    nearest samples (d the samples' spacing), reads and unpacks those four samples once
//    and blends them for each of its pixels (reduced_shading.wgsl's quad_lighting, as a
//    fragment would for itself: the same pixel gets the same colour). Pixels the samples
//    match are written to the frame's colours, and those without a surface the
//    background; those they do not match, or where they disagree, go on a list.
// 2. cs_shade_listed_sharp (two-level shading): a listed pixel takes the soft light at
//    the samples (the soft layer upsampled to them, or shaded there in full: the finest
//    soft light there is) upsampled to it, as its share of the unshadowed light times
//    the pixel's own (low_resolution.wgsl's soft_share), plus the sharp lights shaded
//    at the pixel;
//    where that soft light does not match or disagrees, it goes on a second list. With
//    one level every listed pixel goes straight to the second list.
// 3. cs_shade_listed_full: the pixels on the second list shaded in full; the light of
//    the SH path at such a pixel is kept (kept_harmonic_light) and read again by the
//    next frames while their surfaces and that light's inputs are the same (a stroke on
//    lights of the other paths), as the soft layer is.
// 4. The colours are copied into the frame's image (full_resolution.rs): every pixel
//    of it has been written.
//
// Why: a fragment pass reads the four samples for every pixel (a fetch and an unpack
// each, nine pixels reading the same four at the default spacing), and the pixels the
// samples leave (about 3 % of the studio's frame: the edges of hard shadows, rims,
// silhouettes) lie scattered along lines, where a software GPU, which shades a fragment
// pass in blocks of pixels, paid the full shading for whole blocks around one or two of
// them. Listed, they are shaded 64 at a time (docs/performance.md).
// #import low_resolution reduced_shading logsh slots

// How many pixels each list holds (cleared before the upsampling).
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
// Every pixel's colour, tone-mapped and sRGB-encoded in 8 bits per channel (the bytes a
// fragment shader's output would leave in the frame's sRGB target; packed by
// store_colour) or the background, copied into the frame's image after the passes above
// (through a buffer: full_resolution.rs). One word a pixel: lavapipe stored an
// rgba32float texel at several times the cost (the studio's upsampling took 18.8 ms with
// them, 12.9 with words), and the full-screen pass that drew such an image into the
// frame took 4–5 ms where the copies take a fraction (docs/performance.md). Rounded to
// nearest here, where lavapipe's own encoding approximates: up to 1/255 apart.
@group(PASS_GROUP) @binding(FRAME_COLOURS_BINDING) var frame_colours: texture_storage_2d<r32uint, write>;
// The exposed light of the SH path (the environment and the SH lights through the
// blockers) at the pixels shaded in full, as pack_lighting's two words, and the
// generation of the inputs it was shaded with (0: none): a pixel whose stamp is
// kept_harmonic_generation.x (low_resolution.wgsl) reads it instead of walking the
// blockers. The generation changes whenever the surfaces or the soft light's inputs do
// (render/passes/kept_harmonic.rs); these images are as large as the frame.
@group(PASS_GROUP) @binding(KEPT_HARMONIC_X_BINDING) var kept_harmonic_x: texture_storage_2d<r32uint, read_write>;
@group(PASS_GROUP) @binding(KEPT_HARMONIC_Y_BINDING) var kept_harmonic_y: texture_storage_2d<r32uint, read_write>;
@group(PASS_GROUP) @binding(KEPT_HARMONIC_STAMP_BINDING) var kept_harmonic_stamp: texture_storage_2d<r32uint, read_write>;
// The workgroup counts of the two shading passes' indirect dispatches: sharp xyz, full xyz.
@group(PASS_GROUP) @binding(DISPATCH_ARGS_BINDING) var<storage, read_write> dispatch_args: array<u32, 6>;

// Invocations per workgroup of the listed pixels' shading passes, and their workgroups
// per row of a dispatch: a list's workgroups are dispatched in rows of at most this many,
// as a dispatch may have at most 65 535 along each side (one row would cap a list at 4.2
// million pixels; these rows reach 536 million, past a 16384² frame).
const LISTED_WORKGROUP_SIZE: u32 = 64u;
const LISTED_WORKGROUPS_PER_ROW: u32 = 128u;

// Set by full_resolution.rs: the samples' spacing d in pixels (each upsampling invocation
// takes d × d pixels), the side of the upsampling's square workgroups, and whether the
// pixels the samples leave go to the sharp list (two-level shading) or the full one.
override BLOCK_PX: u32;
override BLOCK_WORKGROUP_SIDE: u32;
override LIST_FOR_SHARP: bool;

// The sRGB transfer function (IEC 61966-2-1), per channel on [0, 1].
fn srgb_from_linear(linear: vec3<f32>) -> vec3<f32> {
    let c = clamp(linear, vec3<f32>(0.0), vec3<f32>(1.0));
    return select(1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3<f32>(0.0031308));
}

// A tone-mapped colour as the sRGB target would store it, in one word.
fn colour_word(colour: vec3<f32>) -> u32 {
    return pack4x8unorm(vec4<f32>(srgb_from_linear(colour), 1.0));
}

// A pixel's tone-mapped colour into frame_colours.
fn store_colour(pixel: vec2<i32>, colour: vec3<f32>) {
    store_word(pixel, colour_word(colour));
}

fn store_word(pixel: vec2<i32>, word: u32) {
    textureStore(frame_colours, pixel, vec4<u32>(word));
}

fn packed_pixel(pixel: vec2<u32>) -> u32 {
    return pixel.x | (pixel.y << 16u);
}

fn unpacked_pixel(packed: u32) -> vec2<i32> {
    return vec2<i32>(i32(packed & 0xffffu), i32((packed >> 16u) & 0x7fffu));
}

// Where entry `entry` of a list `width` texels wide sits.
fn entry_texel(entry: u32, width: u32) -> vec2<u32> {
    return vec2<u32>(entry % width, entry / width);
}

// The word entry `entry` of `list` holds: the pixel (packed_pixel; rows below 32 768) and,
// on the full list, in bit 31 whether its blocker walk may be shared (SHARES_WALK_BIT).
fn listed_word(list: texture_2d<u32>, entry: u32) -> u32 {
    return textureLoad(list, entry_texel(entry, textureDimensions(list).x), 0).x;
}

fn listed_pixel(list: texture_2d<u32>, entry: u32) -> vec2<i32> {
    return unpacked_pixel(listed_word(list, entry));
}

// A pixel on the full list whose samples did not disagree (it was left for too few of
// them on its surface: a rim, a silhouette, a sliver) may stand its blocker walk in for
// a neighbour's (shared_walk_logs); one whose samples disagree lies where the light
// changes within their spacing, and walks at its own point.
const SHARES_WALK_BIT: u32 = 0x80000000u;

// This workgroup's entries on the list it appends to (one list per pass): how many its
// invocations take, and where they start. Each invocation adds its count, then one
// invocation reserves the workgroup's run of entries with one global atomic, so that a
// workgroup's pixels — neighbours on the screen — lie together on the list. Appended one
// atomic at a time, the pixels of the two rasteriser threads' workgroups interleaved, and
// the lanes of the next pass, shading a run of the list together, took walks through
// blockers far apart (its pixels shaded in full cost 30 % more thread time on two
// threads than on one).
var<workgroup> workgroup_listed: atomic<u32>;
var<workgroup> workgroup_first_entry: u32;

// The first of `count` consecutive entries of the sharp list (`sharp`) or the full list
// reserved for this invocation, the workgroup's together. Every invocation of the
// workgroup calls it, in uniform control flow (it holds barriers).
fn reserve_entries(count: u32, lane: u32, sharp: bool) -> u32 {
    let offset = atomicAdd(&workgroup_listed, count);
    workgroupBarrier();
    if lane == 0u {
        let total = atomicLoad(&workgroup_listed);
        if sharp {
            workgroup_first_entry = atomicAdd(&list_counts.sharp, total);
        } else {
            workgroup_first_entry = atomicAdd(&list_counts.full, total);
        }
    }
    return workgroupUniformLoad(&workgroup_first_entry) + offset;
}

fn list_on_sharp(pixel: vec2<u32>, entry: u32) {
    textureStore(sharp_pixels_out, entry_texel(entry, textureDimensions(sharp_pixels_out).x), vec4<u32>(packed_pixel(pixel)));
}

fn list_on_full(pixel: vec2<u32>, entry: u32, shares_walk: bool) {
    let word = packed_pixel(pixel) | select(0u, SHARES_WALK_BIT, shares_walk);
    textureStore(full_pixels_out, entry_texel(entry, textureDimensions(full_pixels_out).x), vec4<u32>(word));
}

// Block (i, j) holds the pixels whose nearest samples' corner is (i − 1, j − 1): with the
// samples at pixels d·k + ⌊d/2⌋ (low_resolution.wgsl's level_pixel), pixels d·(i − 1) +
// ⌊d/2⌋ up to d more along each axis (reduced_shading.rs tests the mapping). Block 0
// holds the pixels before the first sample, whose corner −1 clamps to sample 0.
@compute @workgroup_size(BLOCK_WORKGROUP_SIDE, BLOCK_WORKGROUP_SIDE)
fn cs_upsample_blocks(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let size = vec2<i32>(textureDimensions(surface_buffer_a));
    let d = i32(BLOCK_PX);
    let corner = vec2<i32>(id.xy) - vec2<i32>(1);
    let first = d * corner + vec2<i32>(d / 2);
    // Bit k: pixel k of the block goes on the list (no early return: reserve_entries
    // holds barriers).
    var listed = 0u;
    // Bit k: pixel k's samples did not disagree (SHARES_WALK_BIT).
    var sharing = 0u;
    if all(first < size) {
        let quad = sample_quad(corner);
        for (var k = 0u; k < BLOCK_PX * BLOCK_PX; k++) {
            let pixel = first + vec2<i32>(i32(k % BLOCK_PX), i32(k / BLOCK_PX));
            if all(pixel >= vec2<i32>(0)) && all(pixel < size) {
                let buffered = buffered_surface(pixel);
                let s = buffered.s;
                // The pixel's place among the samples, as sample_place gives a fragment at
                // its centre, from the block's corner.
                let at = sample_coordinates(vec2<f32>(pixel) + vec2<f32>(0.5));
                let up = quad_lighting(quad, at - vec2<f32>(corner), s);
                // One store for the background and the upsampled colour (lavapipe runs
                // both sides of a branch, a store on each side twice).
                let colour = tonemap_aces_fit(frame.exposure * s.emissive + reflectance(s) * up.lighting);
                let word = select(frame.background_srgb8, colour_word(colour), buffered.drawn);
                if !buffered.drawn || up.matches {
                    store_word(pixel, word);
                } else {
                    listed |= 1u << k;
                    sharing |= select(0u, 1u << k, up.agrees);
                }
            }
        }
    }
    var entry = reserve_entries(countOneBits(listed), lane, LIST_FOR_SHARP);
    while listed != 0u {
        let k = firstTrailingBit(listed);
        listed &= listed - 1u;
        let pixel = vec2<u32>(first + vec2<i32>(i32(k % BLOCK_PX), i32(k / BLOCK_PX)));
        if LIST_FOR_SHARP {
            list_on_sharp(pixel, entry);
        } else {
            list_on_full(pixel, entry, (sharing & (1u << k)) != 0u);
        }
        entry += 1u;
    }
}

// The shading passes' workgroup counts from the lists' lengths: rows of
// LISTED_WORKGROUPS_PER_ROW workgroups (fewer where one row holds the list).
@compute @workgroup_size(1)
fn cs_dispatch_args() {
    let groups = (vec2<u32>(atomicLoad(&list_counts.sharp), atomicLoad(&list_counts.full)) + vec2<u32>(LISTED_WORKGROUP_SIZE - 1u)) / LISTED_WORKGROUP_SIZE;
    let per_row = min(groups, vec2<u32>(LISTED_WORKGROUPS_PER_ROW));
    let rows = (groups + vec2<u32>(LISTED_WORKGROUPS_PER_ROW - 1u)) / LISTED_WORKGROUPS_PER_ROW;
    dispatch_args = array<u32, 6>(per_row.x, rows.x, 1u, per_row.y, rows.y, 1u);
}

// The list entry an invocation of a shading pass takes (cs_dispatch_args' rows).
fn listed_entry(workgroup: vec3<u32>, lane: u32) -> u32 {
    return (workgroup.y * LISTED_WORKGROUPS_PER_ROW + workgroup.x) * LISTED_WORKGROUP_SIZE + lane;
}

// A listed pixel from the soft light at the samples upsampled to it (group 3's samples)
// plus the sharp lights shaded here, or put on the full list where that soft light does
// not match it or disagrees.
@compute @workgroup_size(LISTED_WORKGROUP_SIZE)
fn cs_shade_listed_sharp(@builtin(workgroup_id) workgroup: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let entry = listed_entry(workgroup, lane);
    var to_full = false;
    var shares_walk = false;
    var pixel = vec2<i32>(0);
    if entry < atomicLoad(&list_counts.sharp) {
        pixel = listed_pixel(sharp_pixels, entry);
        let s = buffered_surface(pixel).s;
        // The soft light's share of the unshadowed light at the samples (soft_share),
        // upsampled to the pixel's centre, as a fragment's position is.
        let share = upsampled_lighting(vec2<f32>(pixel) + vec2<f32>(0.5), s, false);
        if share.matches {
            let soft = share.lighting * unshadowed_harmonic_radiance(s);
            let sharp = mapped_lights_radiance(s) + exact_path_radiance(s);
            let colour = tonemap_aces_fit(frame.exposure * (s.emissive + soft + sharp));
            store_colour(pixel, colour);
        } else {
            to_full = true;
            shares_walk = share.agrees;
        }
    }
    // No early return above: reserve_entries holds barriers.
    let full_entry = reserve_entries(select(0u, 1u, to_full), lane, false);
    if to_full {
        list_on_full(vec2<u32>(pixel), full_entry, shares_walk);
    }
}

// A listed pixel shaded in full. Its SH path's light is kept from an earlier frame of
// this generation, or shaded through the blockers' log-visibility at its walk's
// representative (shared_walk_logs) where the walk is shared, else at the pixel itself
// (kept_harmonic_light).
@compute @workgroup_size(LISTED_WORKGROUP_SIZE)
fn cs_shade_listed_full(@builtin(workgroup_id) workgroup: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let entry = listed_entry(workgroup, lane);
    let listed = entry < atomicLoad(&list_counts.full);
    var pixel = vec2<i32>(0);
    var may_share = false;
    if listed {
        let word = listed_word(full_pixels, entry);
        pixel = unpacked_pixel(word);
        may_share = (word & SHARES_WALK_BIT) != 0u;
    }
    let s = buffered_surface(pixel).s;
    var harmonic = vec3<f32>(0.0);
    if shares_walks() {
        // Every invocation, in uniform control flow (barriers).
        let kept = listed && kept_harmonic_stamped(pixel);
        let walked = shared_walk_logs(lane, listed_pixel_walk(listed && !kept, may_share, pixel, s));
        if kept {
            harmonic = kept_harmonic(pixel);
        } else if listed {
            let radiance = harmonic_radiance_through(s, lobes_from_log_visibility(s, walked));
            harmonic = keep_harmonic(pixel, frame.exposure * radiance);
        }
    } else if listed {
        harmonic = kept_harmonic_light(pixel, s);
    }
    if listed {
        let others = s.emissive + exact_path_radiance(s) + mapped_lights_radiance(s);
        store_colour(pixel, tonemap_aces_fit(frame.exposure * others + harmonic));
    }
}

// Whether the SH path's light kept at `pixel` is this generation's.
fn kept_harmonic_stamped(pixel: vec2<i32>) -> bool {
    return textureLoad(kept_harmonic_stamp, pixel).x == kept_harmonic_generation.x;
}

fn kept_harmonic(pixel: vec2<i32>) -> vec3<f32> {
    return unpack_lighting(vec2<u32>(textureLoad(kept_harmonic_x, pixel).x, textureLoad(kept_harmonic_y, pixel).x));
}

// The exposed light of the SH path `exposed` kept at `pixel` with this generation, and
// returned as a frame reading it back would read it (pack_lighting's 13-bit mantissas,
// non-negative, clamped where the tone curve is long saturated).
fn keep_harmonic(pixel: vec2<i32>, exposed: vec3<f32>) -> vec3<f32> {
    let packed = pack_lighting(min(exposed, vec3<f32>(MAX_LIGHTING)));
    textureStore(kept_harmonic_x, pixel, vec4<u32>(packed.x));
    textureStore(kept_harmonic_y, pixel, vec4<u32>(packed.y));
    textureStore(kept_harmonic_stamp, pixel, vec4<u32>(kept_harmonic_generation.x));
    return unpack_lighting(packed);
}

// The exposed light of the SH path at `pixel` (surface s): kept from an earlier frame of
// this generation, else shaded (harmonic_radiance: the blocker walk) and kept, so that a
// frame reading it is the frame shading it anew.
fn kept_harmonic_light(pixel: vec2<i32>, s: Surface) -> vec3<f32> {
    if kept_harmonic_stamped(pixel) {
        return kept_harmonic(pixel);
    }
    return keep_harmonic(pixel, frame.exposure * harmonic_radiance(s));
}

// The blocker walk shared between neighbouring listed pixels. The pixels shaded in full
// lie along rims, silhouettes and contact shadows, in short runs of neighbours, and each
// walked the blockers itself: most of this pass's time. Where a pixel was listed only
// because too few samples lay on its surface (a rim, a silhouette: SHARES_WALK_BIT), the
// visibility — not the light, which turns with the normal — of a pixel of its block on
// its surface hardly differs from its own, so that pixel's walk stands for its own
// (walk_representative: the same whichever frame or workgroup asks), the workgroup walks
// each representative once, and each pixel shades through that log-visibility with its
// own surface (normal, material, lights). Where its samples disagree (the light changes
// within their spacing: a contact shadow's edge) a pixel walks at its own point.
//
// Only without light windows: the windowed walk's sums are each light's and are opened
// per point, and are not shared.
fn shares_walks() -> bool {
    return SH_VISIBILITY && LIGHT_WINDOWS == 0u;
}

// Walks per round (workgroup memory for their log-visibility: 8 KB at order 8).
const SHARED_WALKS_PER_ROUND: u32 = 32u;
// A lane's representative pixel (packed_pixel), NO_WALK where it walks nothing.
const NO_WALK: u32 = 0xffffffffu;
var<workgroup> walk_pixel: array<u32, LISTED_WORKGROUP_SIZE>;
// A walking lane's slot among the workgroup's walks, and each slot's pixel.
var<workgroup> walk_slot: array<u32, LISTED_WORKGROUP_SIZE>;
var<workgroup> slot_pixel: array<u32, LISTED_WORKGROUP_SIZE>;
var<workgroup> walk_count: atomic<u32>;
var<workgroup> walked_logs: array<Sh, SHARED_WALKS_PER_ROUND>;

// How far from a pixel's tangent plane, in pixel footprints, and how far turned its
// normal (cosine: 46°) may be the surface of the pixel whose walk stands for its own.
// Measured on the large sample at 960 × 540 (docs/performance.md): at 0.5 footprints and
// 0.97 the pass was no faster than walking every pixel; at these, 74 → 63 ms, with the
// frame against the path tracer as it was (480 × 270).
const WALK_PLANE_TOLERANCE_PX: f32 = 2.0;
const WALK_MIN_FACING: f32 = 0.7;

// The pixel whose blocker walk stands for pixel's (surface s): the first of its d × d
// block (cs_upsample_blocks' block) whose surface lies on s's tangent plane within
// WALK_PLANE_TOLERANCE_PX footprints with a normal within WALK_MIN_FACING, which may be
// the pixel itself. It depends on the surface buffer alone, so every frame of these
// surfaces, and every workgroup holding a pixel of the block, picks the same.
fn walk_representative(pixel: vec2<i32>, s: Surface) -> vec2<i32> {
    let d = i32(BLOCK_PX);
    let size = vec2<i32>(textureDimensions(surface_buffer_a));
    // Block corner k holds pixels d·k + ⌊d/2⌋ up to d more (cs_upsample_blocks).
    let corner = (pixel - vec2<i32>(d / 2) + vec2<i32>(d)) / d - vec2<i32>(1);
    let first = d * corner + vec2<i32>(d / 2);
    let tolerance_m = walk_plane_tolerance_m(s);
    for (var k = 0; k < d * d; k++) {
        let candidate = first + vec2<i32>(k % d, k / d);
        if all(candidate == pixel) {
            break;
        }
        if all(candidate >= vec2<i32>(0)) && all(candidate < size) && stands_for_walk(candidate, s, tolerance_m) {
            return candidate;
        }
    }
    return pixel;
}

// How far from surface s's tangent plane a surface standing for its walk may lie (m).
fn walk_plane_tolerance_m(s: Surface) -> f32 {
    return max(WALK_PLANE_TOLERANCE_PX * pixel_footprint(s.position), 1e-6);
}

// Whether the surface drawn at buffer pixel `pixel` may stand for s's blocker walk: it
// lies within tolerance_m of s's tangent plane with a normal within WALK_MIN_FACING of s's.
fn stands_for_walk(pixel: vec2<i32>, s: Surface, tolerance_m: f32) -> bool {
    let c = buffered_surface(pixel);
    let off_plane = abs(dot(c.s.position - s.position, s.normal));
    return c.drawn && off_plane <= tolerance_m && dot(c.s.normal, s.normal) >= WALK_MIN_FACING;
}

// The packed pixel (packed_pixel) whose walk stands for listed pixel `pixel`'s (surface
// s): its representative where `may_share` (walk_representative), else itself; NO_WALK
// where it needs no walk (`walks` false).
fn listed_pixel_walk(walks: bool, may_share: bool, pixel: vec2<i32>, s: Surface) -> u32 {
    var representative = NO_WALK;
    if walks {
        var stand_in = pixel;
        if may_share {
            stand_in = walk_representative(pixel, s);
        }
        representative = packed_pixel(vec2<u32>(stand_in));
    }
    return representative;
}

// The blockers' and the terrain's log-visibility at the surface of full-resolution pixel
// `representative` (packed_pixel; NO_WALK: this lane needs no walk), walked once per
// representative by the workgroup, the walks packed into the first lanes (lanes past the
// walks skip the walk's loop as whole vectors, which a lane merely not walking would
// not). Every invocation calls it, in uniform control flow (it holds barriers).
fn shared_walk_logs(lane: u32, representative: u32) -> Sh {
    let walks = representative != NO_WALK;
    walk_pixel[lane] = representative;
    if lane == 0u {
        atomicStore(&walk_count, 0u);
    }
    workgroupBarrier();
    // The first lane with this representative walks it.
    var walker = lane;
    if walks {
        for (var j = 0u; j < lane; j++) {
            if walk_pixel[j] == representative {
                walker = j;
                break;
            }
        }
        if walker == lane {
            let slot = atomicAdd(&walk_count, 1u);
            walk_slot[lane] = slot;
            slot_pixel[slot] = representative;
        }
    }
    let count = workgroupUniformLoad(&walk_count);
    var slot = 0u;
    if walks {
        slot = walk_slot[walker];
    }
    var logs = sh_zero();
    for (var first = 0u; first < count; first += SHARED_WALKS_PER_ROUND) {
        if lane < SHARED_WALKS_PER_ROUND && first + lane < count {
            let at = buffered_surface(unpacked_pixel(slot_pixel[first + lane])).s;
            walked_logs[lane] = log_visibility(at.position, at.normal);
        }
        workgroupBarrier();
        if walks && slot >= first && slot < first + SHARED_WALKS_PER_ROUND {
            logs = walked_logs[slot - first];
        }
        workgroupBarrier();
    }
    return logs;
}

