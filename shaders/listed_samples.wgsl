// Two-level reduced shading's low-resolution samples that the soft layer does not serve
// (src/render/passes/listed_samples.rs): fs_shade_sharp_marking leaves them without a
// surface in the samples' image (view depth 0; y: whether their soft samples agreed)
// where the surface buffer has one; here they are listed and shaded in full in compute
// passes, as the full-resolution pixels the upsampling leaves are (full_resolution.wgsl).
//
// Why: they lie scattered along silhouettes and small objects (about one sample in nine
// on the large sample), and a full-screen fragment pass behind the depth test made
// lavapipe shade whole blocks of samples around each of them: their blocker walks cost
// about four times a soft-layer point's, each (docs/performance.md). Listed, every lane
// of a workgroup shades one of them, and a workgroup's samples are neighbours.
// #import low_resolution full_resolution slots

// The listed samples, each x | y << 16 (packed_pixel), entry i at texel
// (i mod width, i / width) of an image of the samples' size: written by the listing,
// read by the shading.
@group(PASS_GROUP) @binding(LISTED_SAMPLES_OUT_BINDING) var listed_samples_out: texture_storage_2d<r32uint, write>;
@group(PASS_GROUP) @binding(LISTED_SAMPLES_BINDING) var listed_samples: texture_2d<u32>;
// How many samples are listed (cleared before the listing), and the shading's workgroup
// counts (cs_listed_samples_dispatch_args; a buffer of their own, which the shading's
// dispatch reads as its arguments).
@group(PASS_GROUP) @binding(LISTED_SAMPLES_COUNT_BINDING) var<storage, read_write> listed_samples_count: atomic<u32>;
@group(PASS_GROUP) @binding(LISTED_SAMPLES_ARGS_BINDING) var<storage, read_write> listed_samples_args: array<u32, 3>;
// The samples (fs_shade_low's first target) and the SH path's light at them kept for the
// next frames (its second: the image of kept_at_samples this frame writes).
@group(PASS_GROUP) @binding(LOW_SAMPLES_OUT_BINDING) var low_samples_out: texture_storage_2d<rgba32uint, write>;
@group(PASS_GROUP) @binding(KEPT_AT_SAMPLES_OUT_BINDING) var kept_at_samples_out: texture_storage_2d<rgba32uint, write>;

// The side of the listing's square workgroups.
const LISTING_SIDE: u32 = 8u;

// Lists the samples on a surface (fs_mark_surface_samples' test) that the sharp pass
// left without one in the samples' image (low_samples: the samples as that pass left them),
// each with one atomic on the count (a workgroup's samples, neighbours, mostly lie
// together on the list: the lanes of a workgroup run together). (Read from the
// low-resolution depth instead, a depth texture loaded in a compute shader, lavapipe
// corrupted its heap in about one test run in three, even with the pass never run.)
@compute @workgroup_size(LISTING_SIDE, LISTING_SIDE)
fn cs_list_unshaded_samples(@builtin(global_invocation_id) id: vec3<u32>) {
    let texel = vec2<i32>(id.xy);
    if any(id.xy >= textureDimensions(low_samples))
        || textureLoad(surface_buffer_a, level_pixel(texel, LEVEL_STRIDE_PX), 0).x == 0u {
        return;
    }
    // fs_shade_sharp_marking's marker: x 0 where it left the sample, y its soft samples'
    // agreement.
    let marker = textureLoad(low_samples, texel, 0);
    if marker.x != 0u {
        return;
    }
    let entry = atomicAdd(&listed_samples_count, 1u);
    let kept_current = kept_harmonic_generation.y != 0u;
    let may_share = marker.y != 0u;
    let word = packed_pixel(id.xy) | select(0u, KEPT_CURRENT_BIT, kept_current) | select(0u, SAMPLE_SHARES_WALK_BIT, may_share);
    textureStore(listed_samples_out, entry_texel(entry, textureDimensions(listed_samples_out).x), vec4<u32>(word));
}

// Bit 31 of a listed sample's word: the SH path's light kept at it by the last frame is
// this frame's (kept_harmonic_generation.y, the same for every entry). Carried through
// the list rather than read by the shading from the uniform: with a branch on that
// uniform around the blocker walk, compiling cs_shade_listed_samples corrupted
// lavapipe's heap (Mesa 22.3.6) in about one test run in three (docs/performance.md).
const KEPT_CURRENT_BIT: u32 = 0x80000000u;
// Bit 15 (the top of x's half: a column below 32 768): the soft samples on the sample's
// surface agreed (fs_shade_sharp_marking left it for want of them), so its blocker walk
// may be shared (sample_walk_representative).
const SAMPLE_SHARES_WALK_BIT: u32 = 0x8000u;

// The sample of a listed sample's word, without its bits.
fn listed_sample(word: u32) -> vec2<i32> {
    return vec2<i32>(i32(word & 0x7fffu), i32((word >> 16u) & 0x7fffu));
}

// The shading's workgroup counts from the list's length, in rows as cs_dispatch_args'.
@compute @workgroup_size(1)
fn cs_listed_samples_dispatch_args() {
    let groups = (atomicLoad(&listed_samples_count) + LISTED_WORKGROUP_SIZE - 1u) / LISTED_WORKGROUP_SIZE;
    listed_samples_args = array<u32, 3>(
        min(groups, LISTED_WORKGROUPS_PER_ROW),
        (groups + LISTED_WORKGROUPS_PER_ROW - 1u) / LISTED_WORKGROUPS_PER_ROW,
        1u,
    );
}

// Each listed sample shaded in full (low_sample_in_full, fs_shade_low's), into the
// samples and the kept soft light. Without light windows a sample the soft layer left
// for want of soft samples on its surface (a rim, a small object) shares its blocker walk
// with the samples of its 2 × 2 block whose representative is the same
// (sample_walk_representative), as the full-resolution rims do (shared_walk_logs).
@compute @workgroup_size(LISTED_WORKGROUP_SIZE)
fn cs_shade_listed_samples(@builtin(workgroup_id) workgroup: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let entry = listed_entry(workgroup, lane);
    let listed = entry < atomicLoad(&listed_samples_count);
    var word = 0u;
    if listed {
        word = listed_word(listed_samples, entry);
    }
    let texel = listed_sample(word);
    let walks = listed && (word & KEPT_CURRENT_BIT) == 0u;
    let s = sample_surface(texel, LEVEL_STRIDE_PX, LEVEL_STRIDE_PX).s;
    let unshadowed = unshadowed_harmonic_radiance(s);
    var kept = textureLoad(kept_harmonic_read, texel, 0);
    if shares_walks() {
        var representative = NO_WALK;
        if walks {
            var stand_in = texel;
            if (word & SAMPLE_SHARES_WALK_BIT) != 0u {
                stand_in = sample_walk_representative(texel, s);
            }
            representative = packed_pixel(vec2<u32>(level_pixel(stand_in, LEVEL_STRIDE_PX)));
        }
        // Every invocation, in uniform control flow (barriers).
        let walked = shared_walk_logs(lane, representative);
        if walks {
            let harmonic = harmonic_radiance_through(s, lobes_from_log_visibility(s, walked));
            kept = soft_share_texel(s, soft_share(harmonic, unshadowed));
        }
    } else if walks {
        kept = soft_share_texel(s, soft_share(harmonic_radiance(s), unshadowed));
    }
    if listed {
        let shaded = low_sample_with_soft(texel, s, unshadowed, kept);
        textureStore(low_samples_out, texel, shaded.texel);
        textureStore(kept_at_samples_out, texel, shaded.soft);
    }
}

// The sample whose blocker walk stands for sample `texel`'s (surface s): the first of its
// 2 × 2 block of samples (the soft layer's spacing) whose surface lies on s's tangent
// plane within WALK_PLANE_TOLERANCE_PX footprints with a normal within WALK_MIN_FACING
// (stands_for_walk, walk_representative's test), which may be the sample itself. It
// depends on the surface buffer alone, so every workgroup holding a sample of the block
// picks the same.
fn sample_walk_representative(texel: vec2<i32>, s: Surface) -> vec2<i32> {
    let size = vec2<i32>(textureDimensions(low_samples_out));
    let first = 2 * (texel / 2);
    let tolerance_m = walk_plane_tolerance_m(s);
    for (var k = 0; k < 4; k++) {
        let candidate = first + vec2<i32>(k % 2, k / 2);
        if all(candidate == texel) {
            break;
        }
        if all(candidate < size) && stands_for_walk(level_pixel(candidate, LEVEL_STRIDE_PX), s, tolerance_m) {
            return candidate;
        }
    }
    return texel;
}

