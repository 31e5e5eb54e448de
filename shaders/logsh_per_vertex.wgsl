// Per-vertex log-SH shadows: a compute pass exponentiates every vertex's log-visibility
// (log_visibility of logsh.wgsl at the vertex position and normal) into a buffer that the
// shading pass reads as vertex attributes; the rasteriser interpolates the visibility SH
// and each fragment shades its lights through it exactly as fs_logsh does. Shading cost
// follows the vertex count instead of the pixel count. Composed with logsh.wgsl for the
// orders whose visibility fits the varyings (wgsl_sh::supports_per_vertex).
// #import logsh slots

// GpuVertex as plain floats (position xyz, normal xyz, uv): 8 per vertex.
@group(PASS_GROUP) @binding(VERTEX_DATA_BINDING) var<storage, read> vertex_data: array<f32>;
// The visibility SH of every vertex, as consecutive Sh.
@group(PASS_GROUP) @binding(VERTEX_VISIBILITY_BINDING) var<storage, read_write> vertex_visibility: array<Sh>;

@compute @workgroup_size(64)
fn cs_vertex_visibility(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&vertex_data) / 8u {
        return;
    }
    let b = 8u * i;
    let p = vec3<f32>(vertex_data[b], vertex_data[b + 1u], vertex_data[b + 2u]);
    let n = normalize(vec3<f32>(vertex_data[b + 3u], vertex_data[b + 4u], vertex_data[b + 5u]));
    vertex_visibility[i] = sh_exp(log_visibility(p, n));
}

@vertex
fn vs_per_vertex(v: VertexIn, visibility: Visibility) -> VertexOutWithVisibility {
    return with_visibility(transform_vertex(v), visibility);
}

@fragment
fn fs_per_vertex(
    in: VertexOut,
    visibility: Visibility,
    @builtin(front_facing) front_facing: bool,
) -> @location(0) vec4<f32> {
    let s = surface(in, front_facing);
    let radiance = radiance_through(s, lobes_through(s, sh_from_visibility(visibility)));
    return vec4<f32>(tonemap_aces_fit(frame.exposure * radiance), 1.0);
}
